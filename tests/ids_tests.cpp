// The ids target (Frame::ids, ids.exr): every pixel's ids are those of an
// instance the scene has, agree with the other G-buffer targets drawn by the
// same fragment, name what the file names, and survive the EXR as integers.
#include <doctest/doctest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>

#include "headlight/diff.hpp"
#include "headlight/output.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "support/assets.hpp"
#include "support/gl.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
using headlight::test::conformanceGltf;
namespace fs = std::filesystem;

namespace {

using Ids = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>;

Ids idsAt(const ImageF& ids, std::size_t pixel) {
  const float* p = &ids.pixels[pixel * 4];
  return {std::uint32_t(p[0]), std::uint32_t(p[1]), std::uint32_t(p[2]), std::uint32_t(p[3])};
}

// The ids each instance of `scene` is drawn with (1 + the table index; the
// default material after the scene's).
std::set<Ids> instanceIds(const Scene& scene) {
  std::set<Ids> ids;
  for (const Instance& i : scene.instances)
    ids.insert({std::uint32_t(i.meshInstance + 1), std::uint32_t(i.mesh + 1),
                std::uint32_t((i.material >= 0 ? std::size_t(i.material) : scene.materials.size()) + 1),
                std::uint32_t(i.meshPrimitive + 1)});
  return ids;
}

// Every geometry pixel shows ids of an instance of the scene, every
// background pixel zeros; returns how many geometry pixels there are.
std::size_t checkIdsBelongToScene(const Frame& frame, const Scene& scene) {
  REQUIRE(frame.ids.channels == std::vector<std::string>{"instance.id", "mesh.id", "material.id", "primitive.id"});
  const std::set<Ids> known = instanceIds(scene);
  std::size_t geometry = 0, unknown = 0, backgroundWithIds = 0;
  for (std::size_t p = 0; p < std::size_t(frame.ids.width) * std::size_t(frame.ids.height); ++p) {
    const Ids ids = idsAt(frame.ids, p);
    if (frame.position.pixels[p * 4 + 3] > 0.0f) {
      ++geometry;
      unknown += !known.count(ids);
    } else {
      backgroundWithIds += ids != Ids{0, 0, 0, 0};
    }
  }
  CHECK(unknown == 0);
  CHECK(backgroundWithIds == 0);
  return geometry;
}

}  // namespace

TEST_CASE("ids: cornell's pixels show their instance, and its material is the albedo drawn there") {
  const Scene scene = loadScene("builtin:cornell");
  const Frame frame = test::renderFresh(scene, test::smallSettings(96, 72));
  REQUIRE(!frame.ids.empty());
  REQUIRE(frame.idNames);
  CHECK(checkIdsBelongToScene(frame, scene) > 96 * 72 / 2);
  // The ids and the albedo come from one fragment (no antialiasing in the
  // G-buffer): the material an id names has the pixel's base colour.
  std::size_t wrongAlbedo = 0;
  std::set<std::string> seen;
  for (std::size_t p = 0; p < std::size_t(96 * 72); ++p) {
    const auto [instance, mesh, material, primitive] = idsAt(frame.ids, p);
    if (instance == 0) continue;
    REQUIRE(material >= 1);
    REQUIRE(material <= frame.idNames->materials.size());
    const int index = frame.idNames->materials[material - 1].index;
    REQUIRE(index >= 0);
    const glm::vec3 base = glm::vec3(scene.materials[std::size_t(index)].baseColorFactor);
    for (int c = 0; c < 3; ++c) wrongAlbedo += std::abs(frame.albedo.pixels[p * 3 + std::size_t(c)] - base[c]) > 1e-2f;
    seen.insert(frame.idNames->meshInstances.at(instance - 1).name);
  }
  CHECK(wrongAlbedo == 0);
  // Every part of the box the camera sees is named by the ids.
  for (const char* name : {"floor", "ceiling", "back wall", "left wall", "right wall", "tall block", "short block"}) {
    CAPTURE(name);
    CHECK(seen.count(name) == 1);
  }
  // The left wall's pixels are red: its id names it, and its material is cornell red.
  const ImageF& ids = frame.ids;
  const std::size_t leftMiddle = std::size_t(36) * 96 + 16;
  REQUIRE(std::get<0>(idsAt(ids, leftMiddle)) > 0);
  CHECK(frame.idNames->meshInstances[std::get<0>(idsAt(ids, leftMiddle)) - 1].name == "left wall");
  CHECK(frame.idNames->materials[std::get<2>(idsAt(ids, leftMiddle)) - 1].name == "cornell red");
}

TEST_CASE("ids: not asked for, no ids and no names") {
  const Scene scene = loadScene("builtin:cornell");
  Renderer renderer(test::sharedContext());
  renderer.setScene(loadScene("builtin:cornell"));
  const std::vector<std::string> litOnly{"lit"};
  const Frame frame = renderer.render(test::smallSettings(32, 24), nullptr, litOnly);
  CHECK(frame.ids.empty());
  CHECK(!frame.idNames);
}

TEST_CASE("ids: a glTF file's nodes, meshes, materials and primitives, named as the file names them" *
          doctest::skip(!test::haveConformanceModel("MorphPrimitivesTest"))) {
  // One mesh of two primitives with a material each, under a node named "mesh".
  const Scene scene = loadScene(conformanceGltf("MorphPrimitivesTest").string());
  const Frame frame = test::renderFresh(scene, test::smallSettings(96, 96));
  REQUIRE(frame.idNames);
  CHECK(checkIdsBelongToScene(frame, scene) > 96 * 96 / 10);
  REQUIRE(frame.idNames->meshes.size() == 1);
  CHECK(frame.idNames->meshes[0].index == 0);
  REQUIRE(frame.idNames->meshPrimitives.size() == 2);
  CHECK(frame.idNames->meshPrimitives[1].index == 0);     // mesh 0
  CHECK(frame.idNames->meshPrimitives[1].subIndex == 1);  // its primitive 1
  REQUIRE(frame.idNames->meshInstances.size() == 1);
  CHECK(frame.idNames->meshInstances[0].name == "mesh");
  CHECK(frame.idNames->meshInstances[0].subIndex == -1);  // no EXT_mesh_gpu_instancing
  // Both primitives show, each with its own id and its own material.
  std::set<std::uint32_t> primitives, materials;
  for (std::size_t p = 0; p < std::size_t(96 * 96); ++p)
    if (std::get<0>(idsAt(frame.ids, p)) > 0) {
      primitives.insert(std::get<3>(idsAt(frame.ids, p)));
      materials.insert(std::get<2>(idsAt(frame.ids, p)));
    }
  CHECK(primitives == std::set<std::uint32_t>{1, 2});
  CHECK(materials.size() == 2);
}

TEST_CASE("ids: each EXT_mesh_gpu_instancing copy is a mesh instance of its own" *
          doctest::skip(!test::haveConformanceModel("SimpleInstancing"))) {
  const Scene scene = loadScene(conformanceGltf("SimpleInstancing").string());
  REQUIRE(scene.meshInstanceNames.size() == 125);
  for (std::size_t copy = 0; copy < 125; ++copy) {
    CHECK(scene.meshInstanceNames[copy].index == 0);  // node 0
    CHECK(scene.meshInstanceNames[copy].subIndex == int(copy));
  }
  const Frame frame = test::renderFresh(scene, test::smallSettings(128, 128));
  checkIdsBelongToScene(frame, scene);
  std::set<std::uint32_t> instances;
  for (std::size_t p = 0; p < std::size_t(128 * 128); ++p)
    if (const std::uint32_t id = std::get<0>(idsAt(frame.ids, p)); id > 0) instances.insert(id);
  CHECK(instances.size() > 20);  // many copies in view, told apart
}

TEST_CASE("ids: ids.exr holds uint32, frame.json names them, and diff judges a changed label as wrong") {
  Renderer renderer(test::sharedContext());
  renderer.setScene(loadScene("builtin:cornell"));
  const Frame frame = renderer.render(test::smallSettings(64, 48));
  const fs::path folder = test::freshFolder("ids_roundtrip");
  writeFrame(frame, folder);

  auto input = OIIO::ImageInput::open((folder / "ids.exr").string());
  REQUIRE(input);
  CHECK(input->spec().format == OIIO::TypeDesc::UINT);
  std::vector<std::uint32_t> stored(64 * 48 * 4);
  REQUIRE(input->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT, stored.data()));
  input->close();

  std::ifstream manifest(folder / "frame.json");
  const nlohmann::json json = nlohmann::json::parse(manifest);
  REQUIRE(json.contains("ids"));
  CHECK(json["ids"]["background"] == 0);
  CHECK(json["ids"]["instance"].size() == frame.idNames->meshInstances.size());
  CHECK(json["ids"]["material"][1]["name"] == "cornell red");
  CHECK(json["ids"]["material"][1]["id"] == 2);
  CHECK(json["ids"]["material"][1]["material"] == 1);

  // Itself: nothing differs. One pixel's instance changed by one: a wrong
  // pixel (it warns), within the 0.5 % a silhouette may flip; 5 % changed fail.
  CHECK(diffImages(folder / "ids.exr", folder / "ids.exr").status == DiffStatus::Pass);
  const OIIO::ImageSpec spec = input->spec();
  auto writeChanged = [&](const fs::path& path, std::size_t pixels) {
    std::vector<std::uint32_t> changed = stored;
    for (std::size_t p = 0; p < pixels; ++p) changed[p * 37 % (64 * 48) * 4] += 1;
    auto output = OIIO::ImageOutput::create("openexr");
    REQUIRE(output->open(path.string(), spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::UINT, changed.data()));
    output->close();
  };
  writeChanged(folder / "one.exr", 1);
  DiffOptions asIds;
  asIds.target = "ids";
  const DiffResult one = diffImages(folder / "ids.exr", folder / "one.exr", asIds);
  CHECK(one.metric == DiffMetric::Mismatch);
  CHECK(one.status == DiffStatus::Warn);
  CHECK(one.failingPixels == 1);
  writeChanged(folder / "many.exr", 154);
  CHECK(diffImages(folder / "ids.exr", folder / "many.exr", asIds).status == DiffStatus::Fail);
  fs::remove_all(folder);
}
