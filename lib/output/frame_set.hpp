#pragma once
// The frame.json protocol of writeFrame (headlight/output.hpp): an
// "incomplete" manifest before the first file is touched, the complete one
// (each file's size and hash, the settings hash) after the last.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "headlight/output.hpp"

namespace headlight::detail {

// The names of files Headlight sets wrote into `folder`, as its frame.json
// lists them (a finished set's files, an interrupted one's planned files);
// empty without a frame.json. Only these may be removed or replaced without
// --force. Throws IoError for a frame.json that is not a Headlight manifest.
std::vector<std::string> ownedFileNames(const std::filesystem::path& folder);

// Replaces frame.json with one that says a write is under way; it names
// `planned` and the names the previous manifest owned, so that an
// interrupted write's files stay Headlight's.
void beginFrameSet(const Frame& frame, const std::filesystem::path& folder, const OutputOptions& options,
                   const std::vector<std::string>& planned);
// Hashes the written files and writes frame.json with "complete": true.
void finishFrameSet(const Frame& frame, const std::filesystem::path& folder, const OutputOptions& options,
                    const std::vector<WrittenFile>& files);

}  // namespace headlight::detail

namespace headlight {

// Removes <folder>/.*.<pid>-<n>.tmp files whose process <pid> no longer
// runs (left by a killed writer). Returns how many were removed.
std::size_t removeStaleTemporaries(const std::filesystem::path& folder);

}  // namespace headlight
