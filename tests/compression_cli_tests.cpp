// Compressed glTF drawn through the CLI (issue 17): the Draco and meshopt
// files of the known torus render, at 64 px, as its uncompressed file does,
// within the codecs' quantisation; and the scene-load flags' help.
#include <doctest/doctest.h>

#include <OpenImageIO/imagebuf.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "compressed_inputs.hpp"
#include "support/process.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using namespace headlight::test;

namespace {

// Renders `scene` at 64x64 and returns its lit.exr.
OIIO::ImageBuf renderLit(const fs::path& scene) {
  const fs::path out = scene.parent_path() / (scene.stem().string() + "-out");
  const ProcessResult run = runHeadlight("render " + shellQuote(scene.string()) + " --width 64 --height 64 --out " +
                                         shellQuote(out.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK(run.output.find("warning") == std::string::npos);  // nothing named as not rendered
  OIIO::ImageBuf image((out / "lit.exr").string());
  REQUIRE(image.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  return image;
}

struct Difference {
  double meanAbs = 0;        // over pixels and RGB
  double differing = 0;      // fraction of pixels with a channel off by more than 0.05 x the reference's peak
  double referencePeak = 0;  // the reference's largest RGB value
  double covered = 0;        // fraction of the reference's pixels not equal to its corner (the torus drawn)
};

Difference compare(const OIIO::ImageBuf& reference, const OIIO::ImageBuf& other) {
  Difference result;
  const int width = reference.spec().width, height = reference.spec().height;
  REQUIRE(other.spec().width == width);
  REQUIRE(other.spec().height == height);
  float corner[3];
  reference.getpixel(0, 0, corner, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float a[3];
      reference.getpixel(x, y, a, 3);
      for (int c = 0; c < 3; ++c) result.referencePeak = std::max(result.referencePeak, double(a[c]));
    }
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float a[3], b[3];
      reference.getpixel(x, y, a, 3);
      other.getpixel(x, y, b, 3);
      bool off = false, drawn = false;
      for (int c = 0; c < 3; ++c) {
        result.meanAbs += std::abs(double(a[c]) - double(b[c]));
        off = off || std::abs(double(a[c]) - double(b[c])) > 0.05 * result.referencePeak;
        drawn = drawn || a[c] != corner[c];
      }
      result.differing += off ? 1 : 0;
      result.covered += drawn ? 1 : 0;
    }
  }
  const double pixels = double(width) * height;
  result.meanAbs /= pixels * 3;
  result.differing /= pixels;
  result.covered /= pixels;
  return result;
}

void checkLikePlain(const OIIO::ImageBuf& plain, const OIIO::ImageBuf& compressed) {
  const Difference difference = compare(plain, compressed);
  CAPTURE(difference.meanAbs);
  CAPTURE(difference.differing);
  CAPTURE(difference.referencePeak);
  CHECK(difference.covered > 0.1);  // the torus fills part of the frame
  // Quantised positions move a silhouette by well under a pixel: at most 2%
  // of pixels differ by more than 5% of the peak, and the mean by 0.5% of it.
  CHECK(difference.differing <= 0.02);
  CHECK(difference.meanAbs <= 0.005 * difference.referencePeak);
}

}  // namespace

TEST_CASE("a Draco file renders as its uncompressed file does (64 px)" * doctest::skip(!compressed::kDracoAvailable)) {
  TempFolder folder("draco-render");
  const compressed::KnownMesh mesh = compressed::torus();
  const OIIO::ImageBuf plain = renderLit(folder.write("plain.gltf", compressed::plainGltf(mesh).dump()));
  checkLikePlain(plain, renderLit(folder.write("draco.gltf", compressed::dracoGltf(mesh).dump())));
}

TEST_CASE("a meshopt file renders as its uncompressed file does (64 px)" *
          doctest::skip(!compressed::kMeshoptAvailable)) {
  TempFolder folder("meshopt-render");
  const compressed::KnownMesh mesh = compressed::torus();
  const OIIO::ImageBuf plain = renderLit(folder.write("plain.gltf", compressed::plainGltf(mesh).dump()));
  checkLikePlain(plain, renderLit(folder.write("meshopt.glb", compressed::meshoptGlb(mesh))));
}

TEST_CASE("render --help: --scene and --material-variant say their defaults, no empty [default: ]") {
  const ProcessResult run = runHeadlight("render --help");
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK(run.output.find("[default: ]") == std::string::npos);
  CHECK(run.output.find("(default: the file's `scene`, else 0)") != std::string::npos);
  CHECK(run.output.find("--material-variant NAME") != std::string::npos);
  CHECK(run.output.find("(default: the file's default materials") != std::string::npos);
}

TEST_CASE("--verbose lists a file's material variants; without the flag nothing is warned") {
  TempFolder folder("variants-verbose");
  nlohmann::json document = compressed::plainGltf(compressed::torus());
  document["materials"] = {nlohmann::json::object({{"name", "a"}}), nlohmann::json::object({{"name", "b"}})};
  document["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = {
      {{"material", 1}, {"variants", {0}}}};
  document["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "Night"}}, {{"name", "Day"}}};
  document["extensionsUsed"] = {"KHR_materials_variants"};
  const fs::path scene = folder.write("variants.gltf", document.dump());
  const std::string base = "render " + shellQuote(scene.string()) + " --width 16 --height 16 --out ";
  const ProcessResult quiet = runHeadlight(base + shellQuote((folder.path() / "a").string()));
  INFO(quiet.output);
  CHECK(quiet.exitCode == 0);
  CHECK(quiet.output.find("warning") == std::string::npos);
  const ProcessResult verbose =
      runHeadlight(base + shellQuote((folder.path() / "b").string()) + " --verbose --material-variant Day");
  INFO(verbose.output);
  CHECK(verbose.exitCode == 0);
  CHECK(verbose.output.find("material variants (--material-variant; default: the file's default materials): "
                            "'Night' 'Day'") != std::string::npos);
}

TEST_CASE("a job file's material_variant picks the variant for its job only") {
  TempFolder folder("variants-jobs");
  nlohmann::json document = compressed::plainGltf(compressed::torus());
  document["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}},
                           {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 1, 0, 1}}}}}};
  document["meshes"][0]["primitives"][0]["material"] = 0;
  document["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = {
      {{"material", 1}, {"variants", {0}}}};
  document["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "Green"}}};
  document["extensionsUsed"] = {"KHR_materials_variants"};
  const fs::path scene = folder.write("variants.gltf", document.dump());
  const fs::path a = folder.path() / "a", b = folder.path() / "b", c = folder.path() / "c";
  auto job = [&](const fs::path& out, const std::string& variant) {
    nlohmann::json line = {{"scene", scene.string()}, {"out", out.string()}, {"size", "32x32"}};
    if (!variant.empty()) line["material_variant"] = variant;
    return line.dump() + "\n";
  };
  const fs::path jobs = folder.write("jobs.jsonl", job(a, "") + job(b, "Green") + job(c, "Blue"));
  const ProcessResult run = runHeadlight("render --jobs " + shellQuote(jobs.string()));
  INFO(run.output);
  CHECK(run.exitCode == 1);
  CHECK(run.output.find("3 jobs: 2 rendered, 0 skipped, 1 failed") != std::string::npos);
  CHECK(run.output.find("material variant 'Blue' is not in the file: its variants are 'Green'") != std::string::npos);
  // Summed over the frame, the default draws red and the variant green.
  auto redMinusGreen = [](const fs::path& out) {
    OIIO::ImageBuf albedo((out / "albedo.exr").string());
    REQUIRE(albedo.read(0, 0, true, OIIO::TypeDesc::FLOAT));
    double sum = 0;
    for (int y = 0; y < albedo.spec().height; ++y)
      for (int x = 0; x < albedo.spec().width; ++x) sum += albedo.getchannel(x, y, 0, 0) - albedo.getchannel(x, y, 0, 1);
    return sum;
  };
  CHECK(redMinusGreen(a) > 1.0);
  CHECK(redMinusGreen(b) < -1.0);
}
