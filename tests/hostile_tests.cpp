// Hostile inputs (issue 10): files made to crash, exhaust or fool the
// loader and the renderer. Each is generated here, run through the CLI and
// must give exit 1, a message naming the file, the element and the rule, and
// no output; the limits a user sets are checked through the library.
#include <doctest/doctest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include <glm/glm.hpp>

#include "headlight/error.hpp"
#include "headlight/finite.hpp"
#include "headlight/limits.hpp"
#include "headlight/output.hpp"
#include "headlight/scene_loader.hpp"
#include "hostile_cli.hpp"
#include "hostile_inputs.hpp"
#include "support/encoding.hpp"
#include "support/process.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace headlight;
using namespace headlight::test;

TEST_SUITE("hostile") {
  TEST_CASE("the generated base scene renders (so each refusal below is the mutation's)") {
    TempFolder folder("hostile");
    const fs::path scene = writeGltf(folder, hostile::triangleScene());
    const ProcessResult run =
        runHostile("render " + quote(scene) + " --width 32 --height 24 --out " + quote(folder.path() / "out"));
    INFO(run.output);
    CHECK(run.exitCode == 0);
    CHECK(fs::exists(folder.path() / "out" / "lit.exr"));
  }

  TEST_CASE("JSON nested 20,000 levels in extras or extensions is refused before tinygltf parses it") {
    TempFolder folder("hostile");
    for (const char* where : {"extras", "extensions"}) {
      json document = hostile::triangleScene();
      document["nodes"][0][where] = json::object();
      std::string text = document.dump();
      const std::string marker = std::string("\"") + where + "\":{}";
      const auto at = text.find(marker);
      REQUIRE(at != std::string::npos);
      text.replace(at, marker.size(), std::string("\"") + where + "\":" + hostile::nestedArrays(20000));
      CAPTURE(where);
      expectRefused(folder.write(std::string(where) + ".gltf", text), {"nests deeper than 64 levels"});
    }
    // The same in a GLB's JSON chunk.
    std::string text = hostile::triangleScene().dump();
    text.insert(text.size() - 1, ",\"extras\":" + hostile::nestedArrays(20000));
    expectRefused(folder.write("deep.glb", hostile::glb(text, {}, 2)), {"nests deeper than 64 levels"});
  }

  TEST_CASE("transforms, light colours and cameras that overflow float are refused, naming the element") {
    TempFolder folder("hostile");
    {
      json document = hostile::triangleScene();
      document["nodes"][0]["translation"] = {1e39, 0, 0};
      expectRefused(writeGltf(folder, document, "translation.gltf"), {"node 0", "world transform entry", "1e+39"});
    }
    {
      json document = hostile::triangleScene();  // nested 1e20 x 1e20: each node alone is already too large
      document["nodes"] = json::array(
          {{{"scale", {1e20, 1e20, 1e20}}, {"children", {1}}}, {{"scale", {1e20, 1e20, 1e20}}, {"mesh", 0}}});
      expectRefused(writeGltf(folder, document, "scales.gltf"), {"node 0", "world transform entry"});
    }
    {
      json document = hostile::triangleScene();  // 1e6 x 1e6 per node: only the product is too large
      document["nodes"] =
          json::array({{{"scale", {1e7, 1e7, 1e7}}, {"children", {1}}}, {{"scale", {1e7, 1e7, 1e7}}, {"mesh", 0}}});
      expectRefused(writeGltf(folder, document, "product.gltf"), {"node 1", "its own and its ancestors'"});
    }
    {
      json document = hostile::withLight(hostile::triangleScene(), {1e39, 1, 1}, 1.0);
      expectRefused(writeGltf(folder, document, "light.gltf"), {"light 0", "colour", "channel 0"});
    }
    {
      json document = hostile::withLight(hostile::triangleScene(), {1, 1, 1}, 1e30);
      expectRefused(writeGltf(folder, document, "intensity.gltf"), {"light 0", "colour x intensity"});
    }
    {
      json document = hostile::triangleScene();
      document["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
      document["nodes"].push_back({{"camera", 0}, {"scale", {1e20, 1e20, 1e20}}, {"translation", {0, 0, 3}}});
      document["scenes"][0]["nodes"].push_back(1);
      expectRefused(writeGltf(folder, document, "camera.gltf"), {"node 1", "world transform entry"});
    }
    {
      json document = hostile::triangleScene();
      document["nodes"][0]["scale"] = {1e19, 1e19, 1e19};
      expectRefused(writeGltf(folder, document, "nocamera.gltf"), {"node 0", "world transform entry"});
    }
    {
      json document = hostile::triangleScene();
      document["cameras"] = {
          {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}, {"zfar", 1e39}}}}};
      document["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 3}}});
      document["scenes"][0]["nodes"].push_back(1);
      expectRefused(writeGltf(folder, document, "zfar.gltf"), {"camera 0", "zfar"});
    }
  }

  TEST_CASE("small files that ask for huge allocations are refused before allocating") {
    TempFolder folder("hostile");
    {
      json document = hostile::triangleScene();
      document["accessors"][0].erase("bufferView");
      document["accessors"][0]["count"] = std::int64_t(1) << 31;
      expectRefused(writeGltf(folder, document, "count31.gltf"), {"accessor 0", "--max-triangles"});
    }
    {
      json document = hostile::triangleScene();
      document["accessors"][0].erase("bufferView");
      document["accessors"][0]["count"] = 3 * (std::int64_t(1) << 24);
      expectRefused(writeGltf(folder, document, "count24.gltf"), {"accessor 0", "--max-triangles"});
    }
    {
      // 300 morph targets over 3M vertices, accessors without bufferViews: 9e8
      // deltas. Before, 300 x 30M took 38 s and 1.8 GB (issue 32).
      json document = hostile::triangleScene();
      document["accessors"][0].erase("bufferView");
      document["accessors"][0]["count"] = 3000000;
      document["meshes"][0]["primitives"][0].erase("indices");
      json& primitive = document["meshes"][0]["primitives"][0];
      for (int target = 0; target < 300; ++target) {
        primitive["targets"].push_back({{"POSITION", document["accessors"].size()}});
        document["accessors"].push_back(
            {{"componentType", 5126}, {"count", 3000000}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {0, 0, 0}}});
      }
      document["meshes"][0]["weights"] = std::vector<double>(300, 0.5);
      expectRefused(
          writeGltf(folder, document, "morphs.gltf"),
          {"mesh 0 primitive 0's morph targets move 3000000 vertices by 900000000 deltas", "--max-triangles"});
    }
    {
      json document = hostile::triangleScene();  // a 1,000-node chain, its root listed 100,000 times
      document["nodes"] = json::array();
      for (int node = 0; node < 1000; ++node) {
        json entry = {{"mesh", 0}};
        if (node + 1 < 1000) entry["children"] = {node + 1};
        document["nodes"].push_back(entry);
      }
      document["scenes"][0]["nodes"] = std::vector<int>(100000, 0);
      expectRefused(writeGltf(folder, document, "roots.gltf"), {"scene 0", "lists node 0 more than once"});
    }
    {
      // 2,000 images that cannot be decoded and one structural error: the
      // structural error is reported, so no image was decoded before it.
      json document = hostile::triangleScene();
      document["images"] = json::array();
      for (int image = 0; image < 2000; ++image) {
        document["images"].push_back({{"uri", "data:image/png;base64,AAAA"}});
      }
      document["meshes"][0]["primitives"][0]["mode"] = 7;
      expectRefused(writeGltf(folder, document, "images.gltf"), {"mesh 0 primitive 0", "has mode 7, expected 0..6"});
    }
  }

  TEST_CASE("invalid values tinygltf would accept are refused, naming the rule") {
    TempFolder folder("hostile");
    {
      json document = hostile::triangleScene();
      document["asset"]["version"] = "3.0";
      expectRefused(writeGltf(folder, document, "version.gltf"), {"asset.version", "\"3.0\"", "glTF 2.x"});
    }
    expectRefused(folder.write("v1.glb", hostile::glb(hostile::triangleScene().dump(), {}, 1)),
                  {"GLB header version is 1", "expected 2"});
    {
      json document = hostile::triangleScene();
      document["bufferViews"][0]["byteOffset"] = -4;
      expectRefused(writeGltf(folder, document, "viewoffset.gltf"),
                    {"bufferView 0 byteOffset is -4", "expected an integer"});
    }
    {
      json document = hostile::triangleScene();
      document["accessors"][0]["byteOffset"] = -4;
      expectRefused(writeGltf(folder, document, "accoffset.gltf"), {"accessor 0 byteOffset is -4"});
    }
    {
      json document = hostile::triangleScene();
      document["accessors"][0]["byteOffset"] = "12";
      expectRefused(writeGltf(folder, document, "stringoffset.gltf"), {"accessor 0 byteOffset is \"12\" (a string)"});
    }
    {
      json document = hostile::triangleScene();
      document["bufferViews"][0]["byteStride"] = -12;
      expectRefused(writeGltf(folder, document, "stride.gltf"), {"bufferView 0 byteStride is -12"});
    }
    {
      json document = hostile::triangleScene();
      document["accessors"][0]["bufferView"] = -5;
      expectRefused(writeGltf(folder, document, "negindex.gltf"), {"accessor 0 bufferView is -5"});
    }
  }

  TEST_CASE("absolute URIs: refused naming the rule, and loaded with --allow-external-paths") {
    TempFolder folder("hostile");
    TempFolder elsewhere("hostile-external");
    const fs::path buffer = elsewhere.write("triangle.bin", hostile::trianglePositions());
    json document = hostile::triangleScene();
    document["buffers"][0]["uri"] = buffer.string();
    const fs::path scene = writeGltf(folder, document);
    expectRefused(scene, {"outside the asset folder", "pass --allow-external-paths"});

    const ProcessResult run =
        runHostile("render " + quote(scene) + " --allow-external-paths --width 32 --height 24 --out " +
                   quote(folder.path() / "out"));
    INFO(run.output);
    CHECK(run.exitCode == 0);
    CHECK(fs::exists(folder.path() / "out" / "lit.exr"));
  }

  TEST_CASE("limits a user sets: triangles, instances and texels") {
    TempFolder folder("hostile");
    const fs::path scene = writeGltf(folder, hostile::triangleScene());
    ResourceLimits limits;
    CHECK_NOTHROW(loadGltf(scene, {}, limits));
    limits.maxTriangles = 0;  // below the row's minimum, but the struct takes it: no triangle fits
    CHECK_THROWS_WITH_AS(loadGltf(scene, {}, limits), doctest::Contains("raise max-triangles"), LimitError);
    limits = {};
    limits.maxInstances = 0;
    CHECK_THROWS_WITH_AS(loadGltf(scene, {}, limits), doctest::Contains("raise max-instances"), LimitError);

    json textured = hostile::triangleScene();
    textured["images"] = {{{"uri", hostile::kOnePixelPng}}, {{"uri", hostile::kOnePixelPng}}};
    const fs::path texturedScene = writeGltf(folder, textured, "textured.gltf");
    limits = {};
    CHECK(loadGltf(texturedScene, {}, limits).images.size() == 2);
    limits.maxTexels = 1;
    CHECK_THROWS_WITH_AS(loadGltf(texturedScene, {}, limits), doctest::Contains("image 1"), LimitError);

    limits = {};
    limits.maxMemoryMiB = 64;
    CHECK_NOTHROW(checkFrameFits(64, 64, 0, ResourceLimits{}));
    CHECK_THROWS_WITH_AS(checkFrameFits(8192, 8192, 0, limits), doctest::Contains("raise max-memory"), LimitError);
  }

  TEST_CASE("an image declaring 16383^2 is refused by max-memory from its header, before a pixel is decoded") {
    // The one-pixel PNG with its IHDR patched to 16383 x 16383 (and its CRC
    // made again): a few bytes that decoded would reach 2.75 GB at the peak
    // (as a 10 KB WebP of one colour did, issue 32). Refused from the header.
    std::vector<unsigned char> png = hostile::onePixelPngBytes();
    const auto bigEndian = [&](std::size_t at, std::uint32_t value) {
      for (int i = 0; i < 4; ++i) png[at + std::size_t(i)] = (unsigned char)(value >> (24 - 8 * i));
    };
    bigEndian(16, 16383);  // IHDR width
    bigEndian(20, 16383);  // IHDR height
    std::uint32_t crc = 0xffffffffu;
    for (std::size_t i = 12; i < 29; ++i) {  // "IHDR" and its 13 data bytes
      crc ^= png[i];
      for (int bit = 0; bit < 8; ++bit) crc = crc & 1 ? (crc >> 1) ^ 0xedb88320u : crc >> 1;
    }
    bigEndian(29, ~crc);
    TempFolder folder("hostile-declared-image");
    json textured = hostile::triangleScene();
    textured["images"] = {{{"uri", "data:image/png;base64," + base64(png)}}};
    const fs::path scene = writeGltf(folder, textured, "declared.gltf");
    expectRefused(scene, {"image 0", "16383x16383", "MiB to decode and keep", "--max-memory"}, "--max-memory 1024");
  }

  TEST_CASE(
      "a file of 4,000 point lights: past --max-lights, and with shadows their maps against max-memory, before any is "
      "made") {
    // Each point light's depth cube is 6 x 512^2 x 4 bytes at this size's
    // auto map size (1024): 6 MiB, 24000 MiB for the lot; with a transmissive
    // material, 30 MiB each (the transmittance cubes). Before the maps were
    // counted, a render started allocating them.
    TempFolder folder("hostile-many-lights");
    json lit = hostile::triangleScene();
    lit["extensionsUsed"] = {"KHR_lights_punctual"};
    json lights = json::array();
    for (int i = 0; i < 4000; ++i) {
      lights.push_back({{"type", "point"}, {"intensity", 1.0}});
      lit["nodes"].push_back({{"translation", {0, 0, 2}}, {"extensions", {{"KHR_lights_punctual", {{"light", i}}}}}});
      lit["scenes"][0]["nodes"].push_back(lit["nodes"].size() - 1);
    }
    lit["extensions"]["KHR_lights_punctual"]["lights"] = lights;
    const fs::path scene = writeGltf(folder, lit, "lights.gltf");
    expectRefused(scene, {"4000 shadow-casting lights (4000 point", "24000 MiB at 1024", "--shadow-map-size"},
                  "--max-memory 4096 --max-lights 4096");
    // Without shadows each light is still evaluated at every pixel of every
    // view: past --max-lights (1024) the file is refused while it loads.
    expectRefused(scene, {"node 1025 places light 1024, one more than the 1024 punctual lights", "--max-lights"},
                  "--no-shadows");
    const ProcessResult raised = runHostile("render " + quote(scene) +
                                            " --no-shadows --max-lights 4000 --width 32 "
                                            "--height 24 --out " +
                                            quote(folder.path() / "raised"));
    INFO(raised.output);
    CHECK(raised.exitCode == 0);
  }

  TEST_CASE("finite checks count, name and clamp non-finite values") {
    Frame frame;
    frame.sceneSource = "test.gltf";
    frame.depth = ImageF{2, 1, {"depth.Z"}, {1.0f, std::numeric_limits<float>::quiet_NaN()}};
    frame.lit = ImageF{1, 1, {"R", "G", "B", "A"}, {std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 1.0f}};
    const std::vector<TargetNonFinite> counts = countNonFinite(frame);
    REQUIRE(counts.size() == 2);
    CHECK(counts[0].target == "depth");
    CHECK(counts[0].count == 1);
    CHECK(counts[0].firstX == 1);
    CHECK(counts[0].firstChannel == "depth.Z");
    CHECK(counts[1].count == 1);
    CHECK_THROWS_WITH_AS(requireFinite(frame), doctest::Contains("depth 1 of 2 (first at 1,0 depth.Z)"),
                         NonFiniteError);
    CHECK(clampNonFinite(frame) == 2);
    CHECK_NOTHROW(requireFinite(frame));
  }

  // Never silent (issue 17): a feature that is not rendered is a warning,
  // once per scene, and is recorded with the outputs; --strict-gltf makes it
  // an error with nothing written.
  TEST_CASE("a glTF feature that is not rendered is named once; --strict-gltf refuses the file") {
    TempFolder folder("hostile");
    json document = hostile::triangleScene();
    document["materials"] = {{{"name", "Cloth"}, {"extensions", {{"KHR_materials_dispersion", json::object()}}}},
                             {{"extensions", {{"KHR_materials_dispersion", json::object()}}}}};
    document["meshes"][0]["primitives"][0]["material"] = 0;
    document["extensionsUsed"] = {"KHR_materials_dispersion"};
    const fs::path scene = writeGltf(folder, document, "dispersion.gltf");
    const std::string warning = "warning: " + scene.string() +
                                ": KHR_materials_dispersion on 2 materials (first: material 0 'Cloth') is not rendered";
    const fs::path out = folder.path() / "out";
    const ProcessResult run =
        runHostile("render " + quote(scene) + " --width 32 --height 24 --views 2 --orbit --out " + quote(out));
    INFO(run.output);
    CHECK(run.exitCode == 0);
    const auto first = run.output.find(warning);
    CHECK(first != std::string::npos);
    CHECK(run.output.find(warning, first + 1) == std::string::npos);  // two views, one scene: once
    std::ifstream manifestFile(out / "view_000" / "frame.json");
    const json manifest = json::parse(manifestFile);
    CHECK(manifest["ignored"] == json::array({warning.substr(warning.find("KHR_"))}));
    auto exr = OIIO::ImageInput::open((out / "view_000" / "lit.exr").string());
    REQUIRE(exr);
    CHECK(exr->spec().get_string_attribute("headlight:ignored") == warning.substr(warning.find("KHR_")));

    const fs::path strictScene = writeGltf(folder, document, "strict/dispersion.gltf");  // its own, empty out/
    expectRefused(strictScene, {"--strict-gltf: KHR_materials_dispersion on 2 materials"}, "--strict-gltf");
  }

  // The static pose (issue 17 item 2): morph targets, skins and
  // EXT_mesh_gpu_instancing are applied at load; their inputs are checked.
  TEST_CASE("the posed scene loads as hand-computed: morphed, skinned, instanced") {
    TempFolder folder("hostile");
    const fs::path path = writeGltf(folder, hostile::posedScene(), "posed.gltf");
    const Scene scene = loadGltf(path);
    REQUIRE(scene.instances.size() == 4);
    CHECK(scene.ignored.empty());
    auto positions = [&](std::size_t instance) {
      return scene.primitives[scene.instances[instance].primitive].positions;
    };
    auto near = [](const std::vector<glm::vec3>& actual, const std::vector<glm::vec3>& expected) {
      if (actual.size() != expected.size()) return false;
      for (std::size_t v = 0; v < actual.size(); ++v)
        if (glm::length(actual[v] - expected[v]) > 1e-5f) return false;
      return true;
    };
    // Morph: base + 0.5 x (0, 0, 1).
    CHECK(near(positions(0), {{-1, -1, 0.5f}, {1, -1, 0.5f}, {0, 1, 0.5f}}));
    // Skin: (x, y) -> (-y, x) by the joint, in world space (identity instance).
    CHECK(near(positions(1), {{1, -1, 0}, {1, 1, 0}, {-1, 0, 0}}));
    CHECK(scene.instances[1].worldFromLocal == glm::mat4(1.0f));
    // Instancing: two placements of mesh 0.
    CHECK(glm::vec3(scene.instances[2].worldFromLocal[3]) == glm::vec3(0, 0, 0));
    CHECK(glm::vec3(scene.instances[3].worldFromLocal[3]) == glm::vec3(3, 0, 0));
    ResourceLimits limits;
    limits.maxInstances = 3;
    CHECK_THROWS_WITH_AS(loadGltf(path, {}, limits), doctest::Contains("max-instances 3"), LimitError);
    const ProcessResult run =
        runHostile("render " + quote(path) + " --width 32 --height 24 --out " + quote(folder.path() / "out"));
    INFO(run.output);
    CHECK(run.exitCode == 0);
  }

  // Issue 32: each joint's world transform is composed once, not up its
  // whole chain again (a 20,000-joint chain took 12.5 s, 100,000 past 120 s).
  TEST_CASE("a skin whose 50,000 joints are one chain loads within the hostile budget, each joint placed") {
    TempFolder folder("hostile");
    json document = hostile::posedScene();
    constexpr int kChain = 50000, kFirst = 4;
    for (int i = 0; i < kChain; ++i) {
      json node = {{"translation", {0.0001, 0, 0}}};
      if (i + 1 < kChain) node["children"] = {kFirst + i + 1};
      document["nodes"].push_back(node);
    }
    document["scenes"][0]["nodes"].push_back(kFirst);
    // Joint 0, the one every vertex follows, is the chain's deepest node: 50,000 x 0.0001 along x.
    json joints = json::array();
    for (int i = kChain - 1; i >= 0; --i) joints.push_back(kFirst + i);
    document["skins"][0] = {{"joints", joints}};  // no inverse bind matrices: identity
    const fs::path path = writeGltf(folder, document, "chain.gltf");
    const auto start = std::chrono::steady_clock::now();
    const Scene scene = loadGltf(path);
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));  // the hostile budget
    const auto& positions = scene.primitives[scene.instances[1].primitive].positions;
    REQUIRE(positions.size() == 3);
    const glm::vec3 expected[] = {{4, -1, 0}, {6, -1, 0}, {5, 1, 0}};
    for (std::size_t v = 0; v < 3; ++v) CHECK(glm::length(positions[v] - expected[v]) < 1e-4f);
  }

  TEST_CASE("instancing's count meets max-instances before any placement is read (issue 32)") {
    TempFolder folder("hostile");
    json document = hostile::posedScene();
    // Two billion placements of zeros (no bufferView): 24 GB of translations had they been read first.
    document["accessors"].push_back({{"componentType", 5126}, {"type", "VEC3"}, {"count", 2000000000}});
    document["nodes"][3]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["TRANSLATION"] =
        document["accessors"].size() - 1;
    const fs::path path = writeGltf(folder, document, "placements.gltf");
    CHECK_THROWS_WITH_AS(loadGltf(path), doctest::Contains("as instance 2000000002, more than max-instances 1000000"),
                         LimitError);
  }

  TEST_CASE("bad skins, morph targets and instancing attributes are refused, naming the element") {
    TempFolder folder("hostile");
    {
      json document = hostile::posedScene();
      document["skins"][0]["joints"] = {2, 2, 2};  // 3 joints, 1 inverse bind matrix
      expectRefused(writeGltf(folder, document, "ibm.gltf"),
                    {"skin 0 inverseBindMatrices accessor 4 has 1 matrix, but the skin has 3 joints"});
    }
    {
      json document = hostile::posedScene();
      document["skins"][0]["joints"] = {7};
      expectRefused(writeGltf(folder, document, "joint-node.gltf"), {"skin 0 joint 0 refers to node 7"});
    }
    {
      json document = hostile::posedScene();
      document["skins"][0]["skeleton"] = 12345;  // not read, but no node of the file (issue 32)
      expectRefused(writeGltf(folder, document, "skeleton-node.gltf"), {"skin 0 skeleton refers to node 12345"});
    }
    {
      json document = hostile::posedScene();
      document["skins"][0].erase("inverseBindMatrices");
      document["meshes"][2]["primitives"][0]["attributes"]["JOINTS_0"] = 3;  // float weights as joints
      expectRefused(writeGltf(folder, document, "joint-format.gltf"),
                    {"mesh 2 primitive 0 JOINTS_0 accessor 3 is FLOAT VEC4, expected UNSIGNED_BYTE VEC4"});
    }
    {
      json document = hostile::posedScene();
      document["accessors"][2]["bufferView"] = 3;  // WEIGHTS_0's float 1.0 (00 00 80 3f) from byte 2: joint 128
      document["accessors"][2]["byteOffset"] = 2;
      expectRefused(writeGltf(folder, document, "joint-range.gltf"),
                    {"mesh 2 primitive 0 JOINTS_0 accessor 2 names joint 128 at vertex 0, but the skin has 1 joint"});
    }
    {
      json document = hostile::posedScene();
      document["meshes"][1]["weights"] = {0.5, 0.25};
      expectRefused(writeGltf(folder, document, "weights.gltf"),
                    {"mesh 1 primitive 0 has 1 morph target, but its weights have 2 values"});
    }
    {
      json document = hostile::posedScene();
      document["accessors"][1]["count"] = 2;
      expectRefused(writeGltf(folder, document, "target-count.gltf"),
                    {"target 0 POSITION accessor 1 has 2 elements, but POSITION accessor 0 has 3"});
    }
    {
      json document = hostile::posedScene();
      document["nodes"][3]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["SCALE"] = 0;  // 3 elements
      expectRefused(
          writeGltf(folder, document, "instances.gltf"),
          {"node 3 EXT_mesh_gpu_instancing SCALE accessor 0 has 3 elements, but the other attributes have 2"});
    }
  }

  TEST_CASE("a normal-mapped triangle without tangents and with zero UV area still renders finite") {
    TempFolder folder("hostile");
    json document = hostile::triangleScene();
    const std::vector<unsigned char> uvs(24, 0);  // three (0, 0): no UV area, no tangent direction
    document["buffers"].push_back(
        {{"byteLength", uvs.size()}, {"uri", "data:application/octet-stream;base64," + base64(uvs)}});
    document["bufferViews"].push_back({{"buffer", 1}, {"byteLength", uvs.size()}});
    document["accessors"].push_back({{"bufferView", 1}, {"componentType", 5126}, {"type", "VEC2"}, {"count", 3}});
    document["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 1;
    document["meshes"][0]["primitives"][0]["material"] = 0;
    document["images"] = {{{"uri", hostile::kOnePixelPng}}};
    document["textures"] = {{{"source", 0}}};
    document["materials"] = {{{"normalTexture", {{"index", 0}}}}};
    const fs::path path = writeGltf(folder, document, "flat-uv.gltf");
    const Scene scene = loadGltf(path);
    REQUIRE(scene.primitives[0].tangents.size() == 3);
    for (const glm::vec4& tangent : scene.primitives[0].tangents)
      CHECK(std::abs(glm::length(glm::vec3(tangent)) - 1.0f) < 1e-5f);
    const ProcessResult run =
        runHostile("render " + quote(path) + " --width 32 --height 24 --out " + quote(folder.path() / "out"));
    INFO(run.output);
    CHECK(run.exitCode == 0);  // exit 1 if any target held NaN or inf
  }
}
