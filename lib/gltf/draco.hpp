#pragma once
// KHR_draco_mesh_compression: primitives whose attributes and indices are a
// Draco stream (libdraco-dev). Each stream is decoded, before any accessor is
// read, into buffers of the model that the primitive's accessors are pointed
// at, in the accessors' own component types; the accessors then go through
// the same checks (gltf_accessors, gltf_geometry) as plain ones.
//
// The stream's header states its point (or vertex) and face counts; they are
// counted against max-triangles before Draco allocates anything.
#include <cstdint>
#include <span>
#include <string>

#include "gltf/common.hpp"
#include "headlight/limits.hpp"

namespace headlight::gltf {

// True when built with Draco (HEADLIGHT_HAS_DRACO).
bool dracoDecoding();

// The counts a Draco mesh stream's header states: faces, and the points (the
// sequential coder) or encoded vertices (edgebreaker) that bound its points.
struct DracoCounts {
  std::uint64_t faces = 0;
  std::uint64_t vertices = 0;
};

// Reads the header and connectivity counts of a Draco mesh stream without
// decoding it; returns the problem ("" when read).
std::string peekDracoCounts(std::span<const unsigned char> stream, DracoCounts& counts);

// Decodes every primitive that carries KHR_draco_mesh_compression (mode
// TRIANGLES) and points its indices and the attributes the extension lists at
// the decoded data. Throws SceneError or LimitError naming the mesh and
// primitive.
void decodeDracoPrimitives(tinygltf::Model& model, const Source& source, const ResourceLimits& limits);

}  // namespace headlight::gltf
