// KHR_materials_variants, EXT_texture_webp and KHR_texture_basisu (issue 17):
// files made here, loaded through the library.
#include <doctest/doctest.h>

#include <OpenImageIO/imageio.h>

#include <cstdlib>
#include <string>

#include "compressed_inputs.hpp"
#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "hostile_inputs.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
using namespace headlight::test;
using nlohmann::json;

namespace {

// The torus with materials 0 red, 1 green, 2 blue; variants 'green' (0) and
// 'blue' (1) map the primitive to materials 1 and 2.
json variantsDocument() {
  json document = compressed::plainGltf(compressed::torus());
  for (const auto& colour : {json{1, 0, 0, 1}, json{0, 1, 0, 1}, json{0, 0, 1, 1}}) {
    document["materials"].push_back({{"pbrMetallicRoughness", {{"baseColorFactor", colour}}}});
  }
  auto& primitive = document["meshes"][0]["primitives"][0];
  primitive["material"] = 0;
  primitive["extensions"]["KHR_materials_variants"]["mappings"] = {{{"material", 1}, {"variants", {0}}},
                                                                   {{"material", 2}, {"variants", {1}}}};
  document["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "green"}}, {{"name", "blue"}}};
  document["extensionsUsed"] = {"KHR_materials_variants"};
  return document;
}

int drawnMaterial(const std::string& path, const std::string& variant) {
  SceneLoadOptions options;
  options.materialVariant = variant;
  const Scene scene = loadScene(path, options);
  REQUIRE(scene.instances.size() == 1);
  CHECK(scene.ignored.empty());  // the default is the file's intent: nothing named
  CHECK(scene.materialVariants == std::vector<std::string>{"green", "blue"});
  return scene.instances[0].material;
}

std::string loadError(const std::string& path, const SceneLoadOptions& options = {}) {
  try {
    (void)loadScene(path, options);
  } catch (const SceneError& error) {
    return error.what();
  }
  return "(loaded)";
}

// A textured torus: texture 0 with `texture` as its JSON, images as given.
json texturedDocument(const json& texture, const json& images) {
  json document = compressed::plainGltf(compressed::torus());
  document["images"] = images;
  document["textures"] = {texture};
  document["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  document["meshes"][0]["primitives"][0]["material"] = 0;
  return document;
}

}  // namespace

TEST_CASE("material variants: default materials, a named variant's, an unknown name listed") {
  TempFolder folder("variants");
  const std::string path = folder.write("variants.gltf", variantsDocument().dump()).string();
  CHECK(drawnMaterial(path, "") == 0);
  CHECK(drawnMaterial(path, "green") == 1);
  CHECK(drawnMaterial(path, "blue") == 2);
  SceneLoadOptions options;
  options.materialVariant = "purple";
  const std::string message = loadError(path, options);
  CHECK(message.find(path) == 0);
  CHECK(message.find("material variant 'purple' is not in the file: its variants are 'green', 'blue'") !=
        std::string::npos);
  // A file without variants says so.
  const std::string plain = folder.write("plain.gltf", compressed::plainGltf(compressed::torus()).dump()).string();
  CHECK(loadError(plain, options).find("it has no KHR_materials_variants") != std::string::npos);
}

TEST_CASE("material variants: mappings indexing out of range are refused, named") {
  TempFolder folder("variants-range");
  json badVariant = variantsDocument();
  badVariant["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"][1]["variants"] = {5};
  CHECK(loadError(folder.write("variant.gltf", badVariant.dump()).string())
            .find("mesh 0 primitive 0 KHR_materials_variants mapping 1 lists variant 5, but the file has 2 variants") !=
        std::string::npos);
  json badMaterial = variantsDocument();
  badMaterial["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"][0]["material"] = 9;
  CHECK(loadError(folder.write("material.gltf", badMaterial.dump()).string())
            .find("mapping 0 refers to material 9, but the file has 3 materials") != std::string::npos);
  json noName = variantsDocument();
  noName["extensions"]["KHR_materials_variants"]["variants"][1]["name"] = 5;
  const std::string unnamed = loadError(folder.write("name.gltf", noName.dump()).string());
  CHECK_MESSAGE(unnamed.find("variant 1 has no name") != std::string::npos, unnamed);
}

TEST_CASE("EXT_texture_webp: the WebP image is decoded and preferred over the source") {
  TempFolder folder("webp");
  const std::string webp = (folder.path() / "colour.webp").string();
  {
    auto output = OIIO::ImageOutput::create(webp);
    const std::string why = "OpenImageIO cannot write WebP: " + OIIO::geterror();
    REQUIRE_MESSAGE(output, why);
    const OIIO::ImageSpec spec(4, 4, 3, OIIO::TypeDesc::UINT8);
    std::vector<unsigned char> pixels(4 * 4 * 3);
    for (std::size_t i = 0; i < pixels.size(); i += 3) pixels[i] = 200, pixels[i + 1] = 40, pixels[i + 2] = 10;
    REQUIRE(output->open(webp, spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    output->close();
  }
  json document = texturedDocument({{"source", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 1}}}}}},
                                   {{{"uri", hostile::kOnePixelPng}}, {{"uri", "colour.webp"}}});
  document["extensionsUsed"] = {"EXT_texture_webp"};
  const Scene scene = loadScene(folder.write("webp.gltf", document.dump()).string());
  CHECK(scene.ignored.empty());
  REQUIRE(scene.materials.size() == 1);
  REQUIRE(scene.materials[0].baseColorTexture.image == 1);
  const ImageData& image = scene.images[1];
  REQUIRE(image.width == 4);
  REQUIRE(image.height == 4);
  // WebP may be lossy: within 12 of 255.
  CHECK(std::abs(int(image.rgba[0]) - 200) <= 12);
  CHECK(std::abs(int(image.rgba[1]) - 40) <= 12);
  CHECK(std::abs(int(image.rgba[2]) - 10) <= 12);
  CHECK(image.rgba[3] == 255);
}

TEST_CASE("KHR_texture_basisu: refused when required or without fallback, the source drawn otherwise") {
  TempFolder folder("basisu");
  const std::string ktx2("\xABKTX 20\xBB\r\n\x1A\n not really a Basis Universal payload", 44);
  folder.write("texture.ktx2", ktx2);
  const json images = {{{"uri", hostile::kOnePixelPng}}, {{"uri", "texture.ktx2"}}};
  const json withFallback = {{"source", 0}, {"extensions", {{"KHR_texture_basisu", {{"source", 1}}}}}};

  json used = texturedDocument(withFallback, images);
  used["extensionsUsed"] = {"KHR_texture_basisu"};
  const Scene scene = loadScene(folder.write("used.gltf", used.dump()).string());
  CHECK(scene.materials[0].baseColorTexture.image == 0);
  REQUIRE(scene.ignored.size() == 1);
  CHECK(scene.ignored[0].describe().find("KHR_texture_basisu on 1 texture (first: texture 0) is not rendered") == 0);
  CHECK(scene.ignored[0].effect.find("core source image is drawn") != std::string::npos);

  json required = used;
  required["extensionsRequired"] = {"KHR_texture_basisu"};
  const std::string refused = loadError(folder.write("required.gltf", required.dump()).string());
  CHECK(refused.find("required.gltf: requires extension KHR_texture_basisu") != std::string::npos);
  CHECK(refused.find("(texture 0)") != std::string::npos);
  CHECK(refused.find("no Debian package decodes Basis Universal") != std::string::npos);

  json only = texturedDocument({{"extensions", {{"KHR_texture_basisu", {{"source", 1}}}}}}, images);
  only["extensionsUsed"] = {"KHR_texture_basisu"};
  const std::string lacking = loadError(folder.write("only.gltf", only.dump()).string());
  CHECK(lacking.find("texture 0 has only a KHR_texture_basisu image (image 1, KTX2 Basis Universal)") !=
        std::string::npos);
}
