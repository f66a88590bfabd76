// glTF loading without GL: minimal files, buffers and URIs, sparse accessors,
// nodes, cameras and lights, images, alpha modes, COLOR_0, .glb, and the errors
// that name the file, the element and the problem. Files are written by the
// tests themselves into a fresh temporary folder.
#include <doctest/doctest.h>

#include <sys/stat.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "gltf/common.hpp"
#include "gltf_test_files.hpp"
#include "headlight/camera.hpp"
#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "support/assets.hpp"
#include "support/encoding.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using namespace headlight;
using namespace headlight::test;

TEST_CASE("a minimal glTF triangle loads, with generated normals") {
  TempFolder folder;
  const Scene scene = loadGltf(writeTriangleGltf(folder));
  REQUIRE(scene.primitives.size() == 1);
  REQUIRE(scene.instances.size() == 1);
  CHECK(scene.triangleCount() == 1);
  CHECK(scene.instances[0].material == -1);
  CHECK(scene.primitives[0].texcoords.empty());
  CHECK(scene.primitives[0].tangents.empty());
  CHECK(near(scene.primitives[0].normals[0], {0, 0, 1}));
  CHECK(isHex16(scene.sourceHash));
  checkWellFormed(scene);
}

TEST_CASE("glTF: buffers as data URIs, non-indexed primitives") {
  TempFolder folder;
  GltfParts parts;
  parts.bufferUri = "data:application/octet-stream;base64," + base64(triangleBuffer());
  parts.primitive = R"({"attributes":{"POSITION":0}})";
  const Scene scene = loadGltf(folder.write("inline.gltf", gltfJson(parts)));
  REQUIRE(scene.primitives.size() == 1);
  CHECK(scene.primitives[0].indices == std::vector<std::uint32_t>{0, 1, 2});
}

TEST_CASE("glTF: a sparse accessor without a bufferView is zeros plus its substitutions") {
  TempFolder folder;
  std::string json = gltfJson({});
  const std::string dense = R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"})";
  // Positions 0..2 are all substituted: the indices view doubles as the
  // sparse indices (0, 1, 2) and the positions view as the values.
  const std::string sparse = R"({"componentType":5126,"count":3,"type":"VEC3","sparse":{"count":3,)"
                             R"("indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":0}}})";
  json.replace(json.find(dense), dense.size(), sparse);
  folder.write("triangle.bin", triangleBuffer());
  const Scene scene = loadGltf(folder.write("sparse.gltf", json));
  REQUIRE(scene.primitives.size() == 1);
  CHECK(near(scene.primitives[0].positions[1], {1, 0, 0}));
  CHECK(near(scene.primitives[0].positions[2], {0, 1, 0}));

  folder.write("triangle.bin", triangleBuffer({0, 1, 7}));
  CHECK(loadError(folder.path() / "sparse.gltf").find("accessor 0 sparse index 2 is 7, expected < count 3") !=
        std::string::npos);
}

TEST_CASE("glTF: nodes share a mesh, transforms accumulate, camera and light are placed") {
  TempFolder folder;
  GltfParts parts;
  parts.nodes = R"([{"translation":[1,0,0],"children":[1,2,3]},
                    {"mesh":0,"scale":[2,2,2]},
                    {"mesh":0,"matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,3,0,1]},
                    {"camera":0,"translation":[0,0,5],"scale":[3,3,3],
                     "extensions":{"KHR_lights_punctual":{"light":0}}}])";
  parts.extra = R"(,"cameras":[{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1}}],
                   "extensionsUsed":["KHR_lights_punctual"],
                   "extensions":{"KHR_lights_punctual":{"lights":[
                     {"type":"spot","color":[1,0.5,0.25],"intensity":40,"spot":{"outerConeAngle":0.5}}]}})";
  const Scene scene = loadGltf(writeTriangleGltf(folder, parts));
  CHECK(scene.primitives.size() == 1);
  REQUIRE(scene.instances.size() == 2);
  const Bounds bounds = scene.worldBounds();
  CHECK(near(bounds.min, {1, 0, 0}));
  CHECK(near(bounds.max, {3, 4, 0}));
  REQUIRE(scene.cameras.size() == 1);
  CHECK(near(cameraPosition(scene.cameras[0]), {1, 0, 5}));
  CHECK(near(glm::vec3(scene.cameras[0].worldFromCamera[0]), {1, 0, 0}));  // scale removed
  CHECK(scene.cameras[0].zfar == 0.0f);
  REQUIRE(scene.lights.size() == 1);
  CHECK(scene.lights[0].type == Light::Type::Spot);
  CHECK(near(scene.lights[0].position, {1, 0, 5}));
  CHECK(near(scene.lights[0].direction, {0, 0, -1}));
  CHECK(near(scene.lights[0].color, {1, 0.5f, 0.25f}));
  CHECK(scene.lights[0].outerConeAngle == doctest::Approx(0.5f));
}

TEST_CASE(
    "glTF: a WebP data URI decodes though tinygltf knows not its type; an image URI naming a folder or a FIFO is "
    "named (issue 32)") {
  // A 1x1 red lossless WebP: its base64 holds a '+', which tinygltf's URL
  // decoding of a URI it takes for a file name turns into a space; it was
  // refused as "File not found".
  const std::string webp = "UklGRhwAAABXRUJQVlA4TA8AAAAvAAAAAAcQ/Y/+ByKi/wEA";
  REQUIRE(webp.find('+') != std::string::npos);
  TempFolder folder;
  auto withImage = [](const std::string& uri) {
    GltfParts parts;
    parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":0})";
    parts.extra = R"(,"extensionsUsed":["EXT_texture_webp"],"extensionsRequired":["EXT_texture_webp"],
                     "materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],
                     "textures":[{"extensions":{"EXT_texture_webp":{"source":0}}}],
                     "images":[{"uri":")" +
                  uri + R"("}])";
    return parts;
  };
  const Scene scene = loadGltf(writeTriangleGltf(folder, withImage("data:image/webp;base64," + webp)));
  REQUIRE(scene.images.size() == 1);
  CHECK(scene.images[0].width == 1);
  CHECK(scene.images[0].rgba == std::vector<std::uint8_t>{255, 0, 0, 255});
  // A data URI that is not base64, or whose payload is not, is named as such.
  CHECK(loadError(writeTriangleGltf(folder, withImage("data:image/webp," + webp))).find("is not base64") !=
        std::string::npos);
  CHECK(loadError(writeTriangleGltf(folder, withImage("data:image/webp;base64,Ukl*GR")))
            .find("payload that is not base64") != std::string::npos);
  // Bytes that do not decode say what their signature claims: a truncated
  // WebP (20 of its 36 bytes) was "Not a PNG file".
  CHECK(loadError(writeTriangleGltf(folder, withImage("data:image/webp;base64,UklGRhwAAABXRUJQVlA4TA8AAAA=")))
            .find("as the WEBP its signature says it is (truncated: 20 of the 36 bytes") != std::string::npos);
  CHECK(loadError(writeTriangleGltf(folder, withImage("data:image/webp;base64,aGVsbG8sIG5vdCBhbiBpbWFnZQ==")))
            .find("its 19 bytes start with no PNG, JPEG, GIF, BMP or WebP signature") != std::string::npos);
  // A folder or a FIFO where a file should be: named, not "File not found" (and the FIFO never opened).
  std::filesystem::create_directory(folder.path() / "folder.webp");
  const std::string folderError = loadError(writeTriangleGltf(folder, withImage("folder.webp")));
  CHECK(folderError.find("URI 'folder.webp' is a folder") != std::string::npos);
  REQUIRE(::mkfifo((folder.path() / "fifo.webp").c_str(), 0600) == 0);
  const std::string fifoError = loadError(writeTriangleGltf(folder, withImage("fifo.webp")));
  CHECK(fifoError.find("URI 'fifo.webp' is a FIFO") != std::string::npos);
}

TEST_CASE("glTF: an embedded PNG is decoded to RGBA, top row first") {
  // 1x2 RGB PNG: red on top, blue below.
  const std::string png =
      "iVBORw0KGgoAAAANSUhEUgAAAAEAAAACCAIAAAAW4yFwAAAADUlEQVR4nGP4zwAC/wEIAAH/2ZC7NQAAAABJRU5ErkJggg==";
  TempFolder folder;
  GltfParts parts;
  parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":0})";
  parts.extra = R"(,"materials":[{"name":"painted","pbrMetallicRoughness":{"baseColorTexture":{"index":0}},
                     "emissiveFactor":[1,1,1],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":5}}}],
                   "textures":[{"source":0,"sampler":0}],
                   "samplers":[{"magFilter":9728,"wrapS":33071}],
                   "images":[{"uri":"data:image/png;base64,)" +
                png + R"("}])";
  const Scene scene = loadGltf(writeTriangleGltf(folder, parts));
  REQUIRE(scene.images.size() == 1);
  const ImageData& image = scene.images[0];
  CHECK(image.width == 1);
  CHECK(image.height == 2);
  CHECK(image.rgba == std::vector<std::uint8_t>{255, 0, 0, 255, 0, 0, 255, 255});
  REQUIRE(scene.materials.size() == 1);
  const Material& material = scene.materials[0];
  CHECK(material.name == "painted");
  CHECK(material.baseColorTexture.image == 0);
  CHECK(material.baseColorTexture.magFilter == 9728);
  CHECK(material.baseColorTexture.wrapS == 33071);
  CHECK(material.baseColorTexture.wrapT == 10497);
  CHECK(near(material.emissiveFactor, glm::vec3(5.0f)));
  CHECK(scene.hasEmissive());
  // A textured material gets texcoords even where the file has none.
  CHECK(scene.primitives[0].texcoords.size() == 3);
}

TEST_CASE("glTF: alphaMode and alphaCutoff are read; MASK is rendered, BLEND named; bad values are refused") {
  TempFolder folder;
  GltfParts parts;
  parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":0})";
  auto load = [&](const std::string& material) {
    parts.extra = R"(,"materials":[)" + material + "]";
    return loadGltf(writeTriangleGltf(folder, parts));
  };
  const Scene masked = load(R"({"alphaMode":"MASK","alphaCutoff":0.25})");
  CHECK(masked.materials[0].alphaMode == AlphaMode::Mask);
  CHECK(masked.materials[0].alphaCutoff == 0.25f);
  CHECK(masked.ignored.empty());
  const Scene byDefault = load(R"({"alphaMode":"MASK"})");
  CHECK(byDefault.materials[0].alphaCutoff == 0.5f);
  CHECK(load("{}").materials[0].alphaMode == AlphaMode::Opaque);
  const Scene blend = load(R"({"alphaMode":"BLEND"})");
  CHECK(blend.materials[0].alphaMode == AlphaMode::Blend);
  CHECK(blend.ignored.empty());  // rendered by the blend pass
  CHECK_THROWS_WITH_AS(load(R"({"alphaMode":"CUTOUT"})"),
                       doctest::Contains("material 0 has alphaMode 'CUTOUT', expected OPAQUE, MASK or BLEND"),
                       SceneError);
  CHECK_THROWS_WITH_AS(load(R"({"alphaMode":"MASK","alphaCutoff":1.5})"),
                       doctest::Contains("material 0 has alphaCutoff 1.5"), SceneError);
  CHECK_THROWS_WITH_AS(load(R"({"alphaMode":"MASK","alphaCutoff":-0.1})"),
                       doctest::Contains("material 0 has alphaCutoff -0.1"), SceneError);
}

TEST_CASE("glTF: COLOR_0 is read as float or normalized unsigned integers, RGB or RGBA; a wrong one is refused") {
  TempFolder folder;
  GltfParts parts;
  parts.primitive = R"({"attributes":{"POSITION":0,"COLOR_0":2},"indices":1})";
  auto load = [&](const std::string& color) {
    parts.moreAccessors = ",{\"bufferView\":0," + color + "}";
    return loadGltf(writeTriangleGltf(folder, parts));
  };
  // Float RGB: the positions' bytes read as colours, A = 1.
  const Scene rgb = load(R"("componentType":5126,"count":3,"type":"VEC3")");
  REQUIRE(rgb.primitives[0].colors.size() == 3);
  for (std::size_t v = 0; v < 3; ++v)
    CHECK(rgb.primitives[0].colors[v] == glm::vec4(rgb.primitives[0].positions[v], 1.0f));
  CHECK(rgb.ignored.empty());
  // Normalized unsigned bytes and shorts land in 0..1.
  for (const char* color : {R"("componentType":5121,"normalized":true,"count":3,"type":"VEC4")",
                            R"("componentType":5123,"normalized":true,"count":3,"type":"VEC3")"}) {
    CAPTURE(color);
    const Scene scene = load(color);
    REQUIRE(scene.primitives[0].colors.size() == 3);
    for (const glm::vec4& c : scene.primitives[0].colors)
      for (int i = 0; i < 4; ++i) CHECK((c[i] >= 0.0f && c[i] <= 1.0f));
  }
  CHECK_THROWS_WITH_AS(load(R"("componentType":5126,"count":2,"type":"VEC3")"),
                       doctest::Contains("COLOR_0 accessor 2 has 2 elements, but POSITION accessor 0 has 3"),
                       SceneError);
  CHECK_THROWS_WITH_AS(load(R"("componentType":5121,"count":3,"type":"VEC3")"), doctest::Contains("COLOR_0"),
                       SceneError);  // unsigned bytes must be normalized
  // A primitive with COLOR_0 does not share the geometry of one without.
  parts.primitive =
      R"({"attributes":{"POSITION":0,"COLOR_0":2},"indices":1},{"attributes":{"POSITION":0},"indices":1})";
  const Scene both = load(R"("componentType":5126,"count":3,"type":"VEC3")");
  REQUIRE(both.primitives.size() == 2);
  CHECK(both.primitives[0].colors.size() == 3);
  CHECK(both.primitives[1].colors.empty());
  // COLOR_1 stays named as not rendered.
  parts.primitive = R"({"attributes":{"POSITION":0,"COLOR_1":2},"indices":1})";
  const Scene second = load(R"("componentType":5126,"count":3,"type":"VEC3")");
  REQUIRE(second.ignored.size() == 1);
  CHECK(second.ignored[0].feature == "COLOR_1");
}

TEST_CASE("glTF: a .glb with its BIN chunk loads") {
  TempFolder folder;
  GltfParts parts;
  parts.bufferUri = "";
  const Scene scene = loadGltf(folder.write("triangle.glb", makeGlb(gltfJson(parts), triangleBuffer())));
  CHECK(scene.triangleCount() == 1);

  parts.positionCount = "4";
  const fs::path broken = folder.write("broken.glb", makeGlb(gltfJson(parts), triangleBuffer()));
  CHECK(loadError(broken) == broken.string() + ": accessor 0 reads bytes 0..48 of bufferView 0, which has 36");
}

TEST_CASE("glTF errors name the file, the element and the problem") {
  TempFolder folder;

  SUBCASE("missing file") {
    const fs::path missing = folder.path() / "absent.gltf";
    CHECK(loadError(missing) == missing.string() + ": no such file");
  }
  SUBCASE("unknown extension") {
    const std::string message = loadError(folder.write("scene.obj", "o triangle"));
    CHECK(message.find("scene.obj: ") != std::string::npos);
    CHECK(message.find(".gltf or .glb") != std::string::npos);
  }
  SUBCASE("invalid JSON") {
    const fs::path path = folder.write("broken.gltf", R"({"asset": {"version": "2.0"}, "nodes": [)");
    const std::string message = loadError(path);
    CHECK(message.find(path.string() + ": ") == 0);
    CHECK(message.find("is not valid JSON") != std::string::npos);  // checked before tinygltf parses
  }
  SUBCASE("accessor past its bufferView") {
    GltfParts parts;
    parts.positionCount = "4";
    const fs::path path = writeTriangleGltf(folder, parts);
    CHECK(loadError(path) == path.string() + ": accessor 0 reads bytes 0..48 of bufferView 0, which has 36");
  }
  SUBCASE("bufferView past its buffer") {
    GltfParts parts;
    parts.indexView = R"("byteOffset":40,"byteLength":6)";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("scene.gltf: bufferView 1 spans bytes 40..46 of buffer 0, which has 44") != std::string::npos);
  }
  SUBCASE("index beyond the vertices") {
    const fs::path path = writeTriangleGltf(folder, {}, triangleBuffer({0, 1, 3}));
    const std::string message = loadError(path);
    CHECK(message.find(path.string() + ": mesh 0 primitive 0: index 2 of accessor 1 is 3") == 0);
  }
  SUBCASE("unknown primitive mode") {
    GltfParts parts;
    parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"mode":7})";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("scene.gltf: mesh 0 primitive 0 has mode 7, expected 0..6") != std::string::npos);
  }
  SUBCASE("no POSITION") {
    GltfParts parts;
    parts.primitive = R"({"attributes":{"NORMAL":0},"indices":1})";
    CHECK(loadError(writeTriangleGltf(folder, parts)).find("mesh 0 primitive 0 has no POSITION") != std::string::npos);
  }
  SUBCASE("wrong component type") {
    GltfParts parts;
    parts.primitive = R"({"attributes":{"POSITION":0},"indices":0})";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("mesh 0 primitive 0 indices accessor 0 is FLOAT VEC3, expected UNSIGNED_BYTE SCALAR") !=
          std::string::npos);
  }
  SUBCASE("attribute counts differ") {
    GltfParts parts;
    parts.primitive = R"({"attributes":{"POSITION":0,"NORMAL":2},"indices":1})";
    parts.moreAccessors = R"(,{"bufferView":0,"componentType":5126,"count":2,"type":"VEC3"})";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("NORMAL accessor 2 has 2 elements, but POSITION accessor 0 has 3") != std::string::npos);
  }
  SUBCASE("non-finite position") {
    const fs::path path = writeTriangleGltf(folder, {}, triangleBuffer({0, 1, 2}, NAN));
    CHECK(loadError(path).find("accessor 0 (POSITION of mesh 0 primitive 0) has a non-finite value at element 0") !=
          std::string::npos);
  }
  SUBCASE("node cycle") {
    GltfParts parts;
    parts.nodes = R"([{"mesh":0,"children":[1]},{"children":[0]}])";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("scene.gltf: node 1 has child node 0") != std::string::npos);
    CHECK(message.find("cycle") != std::string::npos);
  }
  SUBCASE("external image missing") {
    GltfParts parts;
    parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":0})";
    parts.extra = R"(,"materials":[{"normalTexture":{"index":0}}],"textures":[{"source":0}],
                     "images":[{"uri":"absent.png"}])";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("image 0 (uri 'absent.png') could not be loaded") != std::string::npos);
  }
  SUBCASE("unsupported required extension") {
    GltfParts parts;
    parts.extra = R"(,"extensionsUsed":["EXT_made_up"],"extensionsRequired":["EXT_made_up"])";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("requires extension EXT_made_up, which is not supported") != std::string::npos);
  }
  SUBCASE("every unsupported required extension is named at once") {
    GltfParts parts;
    parts.extra = R"(,"extensionsUsed":["EXT_made_up","KHR_texture_basisu","KHR_texture_transform"],
                    "extensionsRequired":["EXT_made_up","KHR_texture_transform","KHR_texture_basisu"])";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("requires extensions EXT_made_up, KHR_texture_basisu, which are not supported") !=
          std::string::npos);
  }
}

// ---- Never silent: features that are not rendered are named ----------------

TEST_CASE("counted nouns in messages: vertices and indices, not vertexs") {
  using headlight::gltf::countOf;
  CHECK(countOf(1, "vertex") == "1 vertex");
  CHECK(countOf(3, "vertex") == "3 vertices");
  CHECK(countOf(0, "index") == "0 indices");
  CHECK(countOf(2, "node") == "2 nodes");
}
