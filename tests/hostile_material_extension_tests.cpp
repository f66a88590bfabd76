// Hostile inputs for issue 18 item 4, the material extensions: a value
// outside its extension's range refuses the file through the CLI (exit 1,
// the file, material, extension, property and value named, nothing written).
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "hostile_cli.hpp"
#include "hostile_inputs.hpp"

using nlohmann::json;
using namespace headlight::test;

namespace {

json withMaterialExtensions(const json& extensions) {
  json document = hostile::triangleScene();
  document["materials"] = {{{"name", "Glass"}, {"extensions", extensions}}};
  document["meshes"][0]["primitives"][0]["material"] = 0;
  return document;
}

}  // namespace

TEST_SUITE("hostile") {
  TEST_CASE("material extensions: values outside their ranges refuse the file, naming the value") {
    TempFolder folder("hostile-material-extensions");
    expectRefused(writeGltf(folder, withMaterialExtensions({{"KHR_materials_ior", {{"ior", 0.5}}}})),
                  {"material 0 KHR_materials_ior ior is 0.5", "expected a number >= 1 or 0"});
    expectRefused(writeGltf(folder, withMaterialExtensions({{"KHR_materials_volume", {{"thicknessFactor", -3}}}})),
                  {"KHR_materials_volume thicknessFactor is -3", "expected a number >= 0"});
    expectRefused(writeGltf(folder, withMaterialExtensions({{"KHR_materials_volume", {{"attenuationDistance", -1}}}})),
                  {"KHR_materials_volume attenuationDistance is -1", "expected a number > 0"});
    expectRefused(writeGltf(folder, withMaterialExtensions({{"KHR_materials_sheen", {{"sheenColorFactor", {1, 1}}}}})),
                  {"KHR_materials_sheen sheenColorFactor is not 3 numbers"});
    expectRefused(writeGltf(folder, withMaterialExtensions({{"KHR_materials_clearcoat", {{"clearcoatFactor", 1e40}}}})),
                  {"KHR_materials_clearcoat clearcoatFactor is 1e+40"});
  }

  TEST_CASE(
      "extension integers outside 32 bits, and extensions that are not objects, refuse the file, naming the value as "
      "written (issue 32)") {
    // The glTF parser keeps JSON integers as int: these read as 1 and as -2147483648 before the check.
    TempFolder folder("hostile-extension-integers");
    expectRefused(writeGltf(folder, withMaterialExtensions(
                                        {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4294967297}}}})),
                  {"materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength is 4294967297",
                   "outside -2147483648..2147483647", "4294967297.0"});
    json transformed = withMaterialExtensions(json::object());
    transformed["materials"][0]["pbrMetallicRoughness"] = {
        {"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 2147483648}}}}}}}};
    expectRefused(writeGltf(folder, transformed, "texcoord.gltf"), {"KHR_texture_transform.texCoord is 2147483648"});
    json below = withMaterialExtensions({{"KHR_materials_volume", {{"thicknessFactor", -2147483649}}}});
    expectRefused(writeGltf(folder, below, "below.gltf"), {"thicknessFactor is -2147483649"});
    // An extension that is not an object: the glTF parser dropped it in silence (exit 0, untransformed).
    json arrayed = withMaterialExtensions(json::object());
    arrayed["materials"][0]["pbrMetallicRoughness"] = {
        {"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {1, 2}}}}}}};
    expectRefused(writeGltf(folder, arrayed, "arrayed.gltf"),
                  {"materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform is an array, "
                   "expected an object"});
    json notObject = withMaterialExtensions(json::object());
    notObject["materials"][0]["extensions"] = "KHR_materials_ior";
    expectRefused(writeGltf(folder, notObject, "string.gltf"),
                  {"materials[0].extensions is \"KHR_materials_ior\" (a string), expected an object"});
    // Extras are the file's own: not read, not checked.
    json extras = withMaterialExtensions(json::object());
    extras["materials"][0]["extras"] = {{"extensions", {{"counter", 4294967297}}}};
    const auto scene = writeGltf(folder, extras, "extras.gltf");
    const ProcessResult run =
        runHostile("render " + quote(scene) + " --width 32 --height 24 --out " + quote(folder.path() / "out"));
    INFO(run.output);
    CHECK(run.exitCode == 0);
  }

  TEST_CASE("material extensions: valid values at the ends of their ranges render") {
    TempFolder folder("hostile-material-extensions-valid");
    const auto scene =
        writeGltf(folder, withMaterialExtensions({{"KHR_materials_ior", {{"ior", 0}}},
                                                  {"KHR_materials_volume", {{"thicknessFactor", 0.5}}}}));
    const auto out = folder.path() / "out";
    const ProcessResult run = runHostile("render " + quote(scene) + " --width 32 --height 24 --out " + quote(out));
    INFO(run.output);
    CHECK(run.exitCode == 0);
    CHECK(std::filesystem::exists(out / "lit.exr"));
  }

  TEST_CASE("a volume thicker than half float holds renders, its path length kept in a float transmission.exr") {
    // thicknessFactor has no upper bound in KHR_materials_volume: 1e20 made the
    // path length inf (length()'s squares overflow, and the half target), so no
    // set could be written (issue 32).
    TempFolder folder("hostile-thick-volume");
    const auto scene =
        writeGltf(folder, withMaterialExtensions({{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
                                                  {"KHR_materials_volume", {{"thicknessFactor", 1e20}}}}));
    const auto out = folder.path() / "out";
    const ProcessResult run = runHostile("render " + quote(scene) + " --width 32 --height 24 --out " + quote(out));
    INFO(run.output);
    CHECK(run.exitCode == 0);
    CHECK(run.output.find("transmission.exr: 32x24 float ") != std::string::npos);
    CHECK(run.output.find("transmission.thickness [0, 1e+20]; non-finite 0") != std::string::npos);
    // A volume within half's range keeps the half file.
    const auto thin = writeGltf(folder,
                                withMaterialExtensions({{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
                                                        {"KHR_materials_volume", {{"thicknessFactor", 0.5}}}}),
                                "thin.gltf");
    const ProcessResult half =
        runHostile("render " + quote(thin) + " --width 32 --height 24 --out " + quote(folder.path() / "thin"));
    INFO(half.output);
    CHECK(half.exitCode == 0);
    CHECK(half.output.find("transmission.exr: 32x24 half ") != std::string::npos);
  }
}
