#pragma once
// What a failing regression test leaves for a person to look at: per
// target, the golden, the actual render and the error heatmap as PNGs, with
// the numbers, in one HTML page.
#include <filesystem>

#include "headlight/diff.hpp"

namespace headlight::test {

// Writes <folder>/report.html (and the PNGs it shows) for `diff`, whose A is
// the golden folder and B the actual one. Returns the page's path.
std::filesystem::path writeRegressionReport(const DirectoryDiff& diff, const std::string& name,
                                            const std::filesystem::path& folder);

}  // namespace headlight::test
