// OpenImageIO's colour maps (ImageBufAlgo::color_map: inferno, magma,
// viridis, ...) as a display shows them.
#pragma once

#include <OpenImageIO/imagebuf.h>

#include <string>

namespace headlight {

// Channel 0 of `values` (0..1) through colour map `map`, as display
// (sRGB-encoded) RGB for an 8-bit sRGB file. OpenImageIO's maps give linear
// values: its viridis(1) is (251, 204, 5) in 8 bits where the published
// table is (253, 231, 37), so written as they are every map came out too dark.
// Throws IoError naming the map when OpenImageIO fails.
OIIO::ImageBuf displayColorMap(const OIIO::ImageBuf& values, const std::string& map);

}  // namespace headlight
