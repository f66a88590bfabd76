// 8-bit PNGs a person looks at: preview.png (lit tone mapped over its
// background) and any frame target by its row's PngLook (render --png).
#pragma once

#include <filesystem>

#include "headlight/output.hpp"
#include "headlight/targets.hpp"

namespace headlight {

// <target>.png: the target's image through its row's look (headlight/targets.hpp).
WrittenFile writeTargetPng(const Frame& frame, const FrameTarget& target, const std::filesystem::path& path);

}  // namespace headlight
