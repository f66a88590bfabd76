// Hostile inputs for alphaMode BLEND (the blend pass): factors out of range
// or not finite, and a flood of blended instances against the draw budget.
#include <doctest/doctest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "hostile_cli.hpp"
#include "hostile_inputs.hpp"
#include "support/encoding.hpp"
#include "support/process.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace headlight::test;

namespace {

// The base triangle with one BLEND material of base colour alpha `alpha`
// (written as is, so "1e39" stays text that overflows a float).
std::string blendedTriangle(const std::string& alpha) {
  json document = hostile::triangleScene();
  document["materials"] =
      json::array({{{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 1.0, 1.0, 0.125}}}}}});
  document["meshes"][0]["primitives"][0]["material"] = 0;
  std::string text = document.dump();
  const std::string placeholder = "0.125";
  text.replace(text.find(placeholder), placeholder.size(), alpha);
  return text;
}

// 1,000 blended primitives of alpha 0.5 in one mesh, placed by `nodes`
// nodes a little apart: 1,000 x nodes layers over one triangle.
json layeredTriangles(int nodes) {
  json document = json::parse(blendedTriangle("0.5"));
  json primitive = document["meshes"][0]["primitives"][0];
  document["meshes"][0]["primitives"] = json::array();
  for (int i = 0; i < 1000; ++i) document["meshes"][0]["primitives"].push_back(primitive);
  document["nodes"] = json::array();
  document["scenes"][0]["nodes"] = json::array();
  for (int node = 0; node < nodes; ++node) {
    document["nodes"].push_back({{"mesh", 0}, {"translation", {0.01 * node, 0, -0.01 * node}}});
    document["scenes"][0]["nodes"].push_back(node);
  }
  return document;
}

// The smallest and largest value of the one-channel EXR at `path`.
std::pair<float, float> channelRange(const fs::path& path) {
  auto input = OIIO::ImageInput::open(path.string());
  REQUIRE(input);
  const OIIO::ImageSpec& spec = input->spec();
  std::vector<float> pixels(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels));
  REQUIRE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  const auto [low, high] = std::minmax_element(pixels.begin(), pixels.end());
  return {*low, *high};
}

}  // namespace

TEST_SUITE("hostile") {
  TEST_CASE("blend: a BLEND material with an overflowing alpha factor is refused, naming the material") {
    TempFolder folder("hostile-blend");
    const fs::path scene = folder.write("inf.gltf", blendedTriangle("1e39"));
    const ProcessResult run = renderSmall(scene, folder.path() / "out");
    INFO(run.output);
    CHECK(run.exitCode == 1);
    CHECK(run.output.find("material 0") != std::string::npos);
    CHECK(run.output.find("non-finite factor") != std::string::npos);
    CHECK((!fs::exists(folder.path() / "out") || fs::is_empty(folder.path() / "out")));
  }

  TEST_CASE("blend: alpha factors outside 0..1 render with coverage kept inside 0..1") {
    TempFolder folder("hostile-blend");
    for (const char* alpha : {"-3", "7"}) {
      CAPTURE(alpha);
      const fs::path scene = folder.write(std::string("alpha") + alpha + ".gltf", blendedTriangle(alpha));
      const fs::path out = folder.path() / (std::string("out") + alpha);
      const ProcessResult run = renderSmall(scene, out, "--strict");
      INFO(run.output);
      REQUIRE(run.exitCode == 0);
      const auto [low, high] = channelRange(out / "coverage.exr");
      CHECK(low >= 0.0f);
      CHECK(high <= 1.0f);
      CHECK(high == (alpha[0] == '-' ? 0.0f : 1.0f));  // clamped: all or nothing
    }
  }

  TEST_CASE("blend: coverage keeps growing under hundreds of faint layers (issue 32)") {
    TempFolder folder("hostile-blend");
    json document = json::parse(blendedTriangle("0.03"));
    document["nodes"] = json::array();
    document["scenes"][0]["nodes"] = json::array();
    for (int node = 0; node < 300; ++node) {  // each nearer than the last, all over the image's middle
      document["nodes"].push_back({{"mesh", 0}, {"translation", {0, 0, 0.0005 * node}}});
      document["scenes"][0]["nodes"].push_back(node);
    }
    const fs::path scene = folder.write("faint.gltf", document.dump());
    const ProcessResult run = renderSmall(scene, folder.path() / "out", "--no-ssgi --strict");
    INFO(run.output);
    REQUIRE(run.exitCode == 0);
    // 1 - 0.97^300 = 0.99989; a half-float accumulator stopped near 0.976.
    const auto [low, high] = channelRange(folder.path() / "out" / "coverage.exr");
    CHECK(high > 0.999f);
    CHECK(high <= 1.0f);
  }

  TEST_CASE("blend: the pixels blended layers cover, times the antialias views, meet --max-blended-fragments") {
    TempFolder folder("hostile-blend-fill");
    // 10,000 layers of one triangle over much of the image (12 s at 64x48
    // with 15,000 and the default antialiasing before the budget counted them).
    const fs::path scene = folder.write("layers.gltf", layeredTriangles(10).dump());
    const ProcessResult refused = renderSmall(scene, folder.path() / "refused", "--max-blended-fragments 20000000");
    INFO(refused.output);
    CHECK(refused.exitCode == 1);
    CHECK(refused.output.find("10000 alphaMode BLEND instances covering") != std::string::npos);
    CHECK(refused.output.find("x 9 views: the pixel centre and 8 antialias samples") != std::string::npos);
    CHECK(refused.output.find("raise --max-blended-fragments, or lower --antialias") != std::string::npos);
    CHECK(folderEmptyOrAbsent(folder.path() / "refused"));
    // One view shades a ninth of it, within the same budget.
    const ProcessResult drawn =
        renderSmall(scene, folder.path() / "drawn", "--max-blended-fragments 20000000 --antialias 1 --no-ssgi");
    INFO(drawn.output);
    CHECK(drawn.exitCode == 0);
    CHECK(fs::exists(folder.path() / "drawn" / "coverage.exr"));
  }

  TEST_CASE("blend: 100,000 blended instances count against --max-draws, and render within a raised budget") {
    TempFolder folder("hostile-blend");
    const fs::path scene = folder.write("flood.gltf", layeredTriangles(100).dump());
    // Counted as every instance is (instances x passes): a bound on the
    // blend pass's one draw per blended instance.
    const ProcessResult refused = renderSmall(scene, folder.path() / "refused");
    INFO(refused.output);
    CHECK(refused.exitCode == 1);
    CHECK(refused.output.find("100000 instances x (1 shadow view + the view)") != std::string::npos);
    CHECK(refused.output.find("--max-draws") != std::string::npos);
    // Each antialias sample draws the view again (the blend pass too): the
    // raised budget covers one view, not nine (16 s at 32x24 when it was not counted).
    const ProcessResult antialiased = renderSmall(scene, folder.path() / "antialiased", "--max-draws 200000 --no-ssgi");
    INFO(antialiased.output);
    CHECK(antialiased.exitCode == 1);
    CHECK(antialiased.output.find("x (1 shadow view + 9 views: the pixel centre and 8 antialias samples) = 1000000 "
                                  "draws") != std::string::npos);
    CHECK(antialiased.output.find("raise --max-draws, or lower --antialias") != std::string::npos);
    CHECK(folderEmptyOrAbsent(folder.path() / "antialiased"));
    const ProcessResult drawn =
        renderSmall(scene, folder.path() / "drawn", "--max-draws 200000 --antialias 1 --no-ssgi --strict --verbose");
    INFO(drawn.output);
    CHECK(drawn.exitCode == 0);
    CHECK(drawn.output.find("pass blend") != std::string::npos);
    const auto [low, high] = channelRange(folder.path() / "drawn" / "coverage.exr");
    CHECK(high > 0.99f);  // 100 layers of alpha 0.5 at the triangle's middle
    CHECK(low == 0.0f);   // and background around it
  }
}
