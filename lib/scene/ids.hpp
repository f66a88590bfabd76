#pragma once
// The ids target's values (headlight/frame.hpp, Frame::ids): what the
// G-buffer pass writes for each instance, and the names behind them.
#include <cstddef>

#include <glm/glm.hpp>

#include "headlight/frame.hpp"
#include "headlight/scene.hpp"

namespace headlight {

// Frame::ids holds its integers in floats, exact up to here; a scene with
// more of one kind gets no ids target (named, not rounded).
inline constexpr std::size_t kLargestExactId = std::size_t(1) << 24;

// An instance's ids: mesh instance, mesh, material, mesh primitive; each the
// table index + 1, 0 where the instance has none.
glm::uvec4 instanceIds(const Scene& scene, const Instance& instance);

// The largest id any kind can take in `scene` (its longest table).
std::size_t largestId(const Scene& scene);

// The four tables, materials included (glTF's default material last).
IdNames makeIdNames(const Scene& scene);

}  // namespace headlight
