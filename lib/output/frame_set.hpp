#pragma once
// The frame.json protocol of writeFrame (headlight/output.hpp): an
// "incomplete" manifest before the first file is touched, the complete one
// (each file's size and hash, the settings hash) after the last.
#include <cstddef>
#include <filesystem>
#include <vector>

#include "headlight/output.hpp"

namespace headlight::detail {

// Replaces frame.json with one that says a write is under way.
void beginFrameSet(const Frame& frame, const std::filesystem::path& folder, const OutputOptions& options);
// Hashes the written files and writes frame.json with "complete": true.
void finishFrameSet(const Frame& frame, const std::filesystem::path& folder, const OutputOptions& options,
                    const std::vector<WrittenFile>& files);

}  // namespace headlight::detail

namespace headlight {

// Removes <folder>/.*.<pid>-<n>.tmp files whose process <pid> no longer
// runs (left by a killed writer). Returns how many were removed.
std::size_t removeStaleTemporaries(const std::filesystem::path& folder);

}  // namespace headlight
