// Hostile inputs for issue 17's texture sets, KHR_texture_transform and
// KHR_materials_unlit: generated here, run through the CLI. A value that
// cannot be rendered gives exit 1, a message naming the file, the material,
// the texture and the value, and no output; a texture set that is not
// rendered draws and is named.
#include <doctest/doctest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "hostile_cli.hpp"
#include "hostile_inputs.hpp"
#include "support/process.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace headlight::test;

namespace {

// The hostile base triangle with a 1x1 texture on material 0's base colour,
// the texture reference being `textureInfo`, and the material `extensions`.
json texturedTriangle(const json& textureInfo, const json& extensions = json::object()) {
  json document = hostile::triangleScene();
  document["images"] = {{{"uri", hostile::kOnePixelPng}}};
  document["textures"] = {{{"source", 0}}};
  document["materials"] = {{{"name", "Painted"}, {"pbrMetallicRoughness", {{"baseColorTexture", textureInfo}}}}};
  if (!extensions.empty()) document["materials"][0]["extensions"] = extensions;
  document["meshes"][0]["primitives"][0]["material"] = 0;
  return document;
}

json transformed(const json& transform) {
  return texturedTriangle({{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}});
}

void expectRefused(const TempFolder& folder, const std::string& text, const std::vector<std::string>& fragments) {
  const fs::path scene = folder.write("scene.gltf", text);
  const fs::path out = folder.path() / "out";
  const ProcessResult run = renderSmall(scene, out);
  INFO(run.output);
  CHECK(run.exitCode == 1);
  CHECK(run.output.find(scene.string()) != std::string::npos);
  for (const std::string& fragment : fragments) CHECK(run.output.find(fragment) != std::string::npos);
  CHECK((!fs::exists(out) || fs::is_empty(out)));
}

}  // namespace

TEST_SUITE("hostile") {
  TEST_CASE("texture transform, texture sets, unlit: the generated valid files render") {
    TempFolder folder("hostile-uv");
    const json valid[] = {
        transformed({{"offset", {0.5, -0.25}}, {"rotation", 3.0}, {"scale", {-2, 1e-30}}, {"texCoord", 1}}),
        texturedTriangle({{"index", 0}, {"texCoord", 1}}, {{"KHR_materials_unlit", json::object()}}),
    };
    for (const json& document : valid) {
      const fs::path scene = folder.write("scene.gltf", document.dump());
      const ProcessResult run = renderSmall(scene, folder.path() / "out");
      INFO(run.output);
      CHECK(run.exitCode == 0);
      fs::remove_all(folder.path() / "out");
    }
  }

  TEST_CASE("a KHR_texture_transform value beyond float, or not a number, is refused naming it") {
    TempFolder folder("hostile-uv");
    const std::string where = "material 0 baseColorTexture (texture 0) KHR_texture_transform ";
    expectRefused(folder, transformed({{"offset", {1e39, 0}}}).dump(),
                  {where + "offset[0] is 1e+39, expected a finite number"});
    expectRefused(folder, transformed({{"scale", {1, -3.5e38 * 10}}}).dump(),
                  {where + "scale[1] is -3.5e+39, expected a finite number"});
    expectRefused(folder, transformed({{"rotation", 1e300}}).dump(), {where + "rotation is 1e+300"});
    // JSON has no NaN or infinity: such a literal is not a number at all.
    std::string nan = transformed({{"rotation", 12345}}).dump();
    nan.replace(nan.find("12345"), 5, "NaN");
    expectRefused(folder, nan, {"is not valid JSON"});
    // A literal past double's range: refused by the JSON parser.
    std::string huge = transformed({{"offset", {0, 12345}}}).dump();
    huge.replace(huge.find("12345"), 5, "1e400");
    expectRefused(folder, huge, {"number overflow parsing '1e400'"});
    expectRefused(folder, transformed({{"offset", "far"}}).dump(), {where + "offset is not an array of 2 numbers"});
    expectRefused(folder, transformed({{"texCoord", -2}}).dump(), {where + "texCoord is not an integer >= 0"});
  }

  TEST_CASE("a texCoord past the rendered sets draws TEXCOORD_0 and is named") {
    TempFolder folder("hostile-uv");
    const fs::path scene = folder.write("scene.gltf", texturedTriangle({{"index", 0}, {"texCoord", 7}}).dump());
    const ProcessResult run = renderSmall(scene, folder.path() / "out");
    INFO(run.output);
    CHECK(run.exitCode == 0);
    CHECK(run.output.find("TEXCOORD_7 on 1 material (first: material 0 'Painted') is not rendered") !=
          std::string::npos);
  }
}
