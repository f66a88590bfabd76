// Hostile compressed inputs (issue 17): Draco streams and meshopt views made
// to exhaust or fool the decoders, and material-variant misuse, each run
// through the CLI: exit 1, a message naming the file, the element and the
// problem, and nothing written. The files are made by tests/compressed_inputs.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "compressed_inputs.hpp"
#include "hostile_cli.hpp"
#include "support/process.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using namespace headlight::test;
using nlohmann::json;

namespace {

// The Draco file with `stream` as its bytes.
json withDracoStream(const std::vector<unsigned char>& stream) {
  json document = compressed::dracoGltf(compressed::torus());
  std::string text;
  for (unsigned char byte : stream) text += char(byte);
  document["buffers"][0]["uri"] = "data:application/octet-stream;base64," + [&] {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < stream.size(); i += 3) {
      const unsigned value = unsigned(stream[i]) << 16 | (i + 1 < stream.size() ? unsigned(stream[i + 1]) << 8 : 0u) |
                             (i + 2 < stream.size() ? stream[i + 2] : 0u);
      out += kAlphabet[value >> 18 & 63];
      out += kAlphabet[value >> 12 & 63];
      out += i + 1 < stream.size() ? kAlphabet[value >> 6 & 63] : '=';
      out += i + 2 < stream.size() ? kAlphabet[value & 63] : '=';
    }
    return out;
  }();
  document["buffers"][0]["byteLength"] = stream.size();
  document["bufferViews"][0]["byteLength"] = stream.size();
  return document;
}

}  // namespace

TEST_SUITE("hostile") {
  TEST_CASE("Draco: a stream claiming 2^31 points, a truncated one and garbage are refused before decoding" *
            doctest::skip(!compressed::kDracoAvailable)) {
    TempFolder folder("hostile-draco");
    // Header: DRACO, bitstream 2.2, triangular mesh, sequential, no flags;
    // then varint faces 1, varint points 2^31.
    const std::vector<unsigned char> huge = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 0, 0, 0, 1, 0x80, 0x80, 0x80, 0x80, 0x08};
    expectRefused(folder.write("huge.gltf", withDracoStream(huge).dump()),
                  {"mesh 0 primitive 0 KHR_draco_mesh_compression", "states 1 faces and 2147483648 points",
                   "max-triangles"});
    const std::vector<unsigned char> stream = compressed::dracoStream(compressed::torus(), true);
    const std::vector<unsigned char> truncated(stream.begin(), stream.begin() + std::ptrdiff_t(stream.size() / 2));
    expectRefused(folder.write("truncated.gltf", withDracoStream(truncated).dump()),
                  {"mesh 0 primitive 0 KHR_draco_mesh_compression: bufferView 0 does not decode"});
    expectRefused(folder.write("garbage.gltf", withDracoStream(std::vector<unsigned char>(200, 0x5a)).dump()),
                  {"bufferView 0 is not a Draco stream"});
    // A valid stream whose attribute id names no attribute of it.
    json missing = compressed::dracoGltf(compressed::torus());
    missing["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 7;
    expectRefused(folder.write("attribute.gltf", missing.dump()),
                  {"NORMAL is Draco attribute 7, which the stream lacks"});
    // Accessor counts that disagree with the decoded stream.
    json count = compressed::dracoGltf(compressed::torus());
    count["accessors"][3]["count"] = 9;
    expectRefused(folder.write("count.gltf", count.dump()), {"indices accessor 3 has count 9, but the stream decodes 256 faces"});
  }

  TEST_CASE("meshopt: wrong byteStride, count, truncated streams and placeholder misuse are refused" *
            doctest::skip(!compressed::kMeshoptAvailable)) {
    TempFolder folder("hostile-meshopt");
    const compressed::KnownMesh mesh = compressed::torus();
    json base;
    (void)compressed::meshoptGlb(mesh, &base);
    auto mutated = [&](const std::string& name, const auto& change) {
      json document = base;
      change(document);
      return folder.write(name, compressed::packMeshoptGlb(document, mesh));
    };
    expectRefused(mutated("stride.glb", [](json& d) { d["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 8; }),
                  {"bufferView 1 EXT_meshopt_compression: byteStride 8 differs from the bufferView's byteStride 4"});
    expectRefused(mutated("stride6.glb", [](json& d) {
                    d["bufferViews"][0].erase("byteStride");
                    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 6;
                  }),
                  {"bufferView 0 EXT_meshopt_compression: byteStride 6 for ATTRIBUTES, expected a multiple of 4 in 4..256"});
    expectRefused(mutated("count.glb", [](json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 154; }),
                  {"bufferView 0 EXT_meshopt_compression: count 154 x byteStride 12 is not the bufferView's byteLength 1836"});
    expectRefused(mutated("triangles.glb", [](json& d) {
                    d["bufferViews"][3]["extensions"]["EXT_meshopt_compression"]["count"] = 767;
                    d["bufferViews"][3]["byteLength"] = 767 * 2;
                  }),
                  {"bufferView 3 EXT_meshopt_compression: count 767 for TRIANGLES, expected a multiple of 3"});
    // The index stream's stride must be its accessor's size: 4-byte indices read as UNSIGNED_SHORT were accepted.
    expectRefused(mutated("index-size.glb",
                          [](json& d) {
                            auto& extension = d["bufferViews"][3]["extensions"]["EXT_meshopt_compression"];
                            const int count = extension["count"].get<int>();
                            extension["byteStride"] = 4;
                            d["bufferViews"][3]["byteLength"] = count * 4;
                            for (json& accessor : d["accessors"])
                              if (accessor["bufferView"] == 3) accessor["componentType"] = 5123;  // UNSIGNED_SHORT
                          }),
                  {"bufferView 3 EXT_meshopt_compression: byteStride 4 for TRIANGLES, but accessor",
                   "reads the view as 2-byte components"});
    expectRefused(mutated("short.glb", [](json& d) {
                    auto& extension = d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"];
                    extension["byteLength"] = extension["byteLength"].get<int>() / 2;
                  }),
                  {"bufferView 0 EXT_meshopt_compression: the", "-byte stream does not decode to 153 elements of 12 bytes"});
    expectRefused(mutated("plain.glb", [](json& d) { d["bufferViews"][2].erase("extensions"); }),
                  {"bufferView 2 refers to buffer 1, a placeholder without data (no uri), but has no EXT_meshopt_compression"});
    // (2^24 - 1) x 256 bytes: the most a bufferView's 32-bit byteLength allows.
    expectRefused(mutated("huge.glb", [](json& d) {
                    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = (std::size_t(1) << 24) - 1;
                    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 256;
                    d["bufferViews"][0]["byteLength"] = ((std::size_t(1) << 24) - 1) * 256;
                    d["bufferViews"][0]["byteStride"] = 252;
                    d["bufferViews"][0].erase("byteStride");
                  }),
                  {"bufferView 0 EXT_meshopt_compression decodes to 4294967040 bytes", "max-memory"},
                  "--max-memory 1024");
  }

  TEST_CASE("an unknown --material-variant is refused, listing the file's variants") {
    TempFolder folder("hostile-variant");
    json document = compressed::plainGltf(compressed::torus());
    document["materials"] = {json::object({{"name", "a"}}), json::object({{"name", "b"}})};
    document["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = {
        {{"material", 1}, {"variants", {0}}}};
    document["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "Night"}}};
    const fs::path scene = folder.write("variants.gltf", document.dump());
    expectRefused(scene, {"material variant 'Day' is not in the file: its variants are 'Night'"},
                  "--material-variant Day");
    // 200,000 variants and a 100 KB name: a 3.4 MB message before (issue 32); now 20 names and the name's start.
    json many = document;
    many["extensions"]["KHR_materials_variants"]["variants"] = json::array();
    for (int i = 0; i < 200000; ++i)
      many["extensions"]["KHR_materials_variants"]["variants"].push_back({{"name", "v" + std::to_string(i)}});
    const fs::path manyScene = folder.write("many.gltf", many.dump());
    const ProcessResult longName = runHostile("render " + quote(manyScene) + " --material-variant " +
                                              std::string(100000, 'x') + " --out " + quote(folder.path() / "o"));
    CHECK(longName.exitCode == 1);
    CHECK(longName.output.size() < 2000);
    CHECK(longName.output.find("'v0', 'v1'") != std::string::npos);
    CHECK(longName.output.find("... and 199980 more") != std::string::npos);
    CHECK(longName.output.find("...' (100000 bytes)") != std::string::npos);
    document["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"][0]["variants"] = {3};
    expectRefused(folder.write("range.gltf", document.dump()),
                  {"mesh 0 primitive 0 KHR_materials_variants mapping 0 lists variant 3, but the file has 1 variant"});
  }
}
