#pragma once
// The process's address-space limit, for bounds that an explicit
// --max-memory must not outgrow (lib/scene/limits.cpp).
#include <cstdint>

namespace headlight {

// RLIMIT_AS (`ulimit -v`) in bytes; 0 when there is none.
std::uint64_t addressSpaceLimitBytes();

}  // namespace headlight
