#pragma once
// The KHR_materials_* lobes, by name: a bit of a variant's lobe set
// (frame_plan.hpp lobeDefines), a slot of the reference's Surface
// (reference/surface.hpp). What each is made of: frame_plan.cpp kLobeRows,
// docs/PIPELINE.md "What a lobe is made of".
#include <cstddef>
#include <cstdint>

namespace headlight {

enum class Lobe { Specular, Clearcoat, Sheen, Anisotropy, Iridescence, Count };
inline constexpr std::size_t kLobeCount = std::size_t(Lobe::Count);
constexpr std::uint32_t lobeBit(Lobe lobe) { return std::uint32_t{1} << unsigned(lobe); }

}  // namespace headlight
