#pragma once
// EXT_meshopt_compression: bufferViews whose bytes are meshoptimizer streams
// (libmeshoptimizer-dev). Each is decoded, before any accessor is read, into
// a buffer of its own that the bufferView is pointed at, so the accessors
// over it go through the same checks (gltf_accessors) as plain ones.
//
// A file that requires the extension may give its bufferViews a placeholder
// buffer with no uri (the spec's "fallback buffer"), which tinygltf cannot
// read: gltf_stand_ins gives it a stand-in and keeps its index.
#include <cstdint>
#include <vector>

#include "gltf/common.hpp"
#include "headlight/limits.hpp"

namespace headlight::gltf {

// True when built with meshoptimizer (HEADLIGHT_HAS_MESHOPT).
bool meshoptDecoding();

// Decodes every bufferView that carries EXT_meshopt_compression into a new
// buffer of `model` and points the view at it. Checks the extension object
// (buffer, range, mode, filter, byteStride, count, the parent's byteLength
// and byteStride) and counts the decoded bytes against max-memory before
// allocating them; a bufferView that refers to a placeholder without the
// extension is refused. Throws SceneError or LimitError naming the bufferView.
void decodeMeshoptViews(tinygltf::Model& model, const Source& source, const std::vector<int>& placeholders,
                        const ResourceLimits& limits);

}  // namespace headlight::gltf
