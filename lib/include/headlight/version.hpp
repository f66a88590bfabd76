#pragma once
namespace headlight {
// From meson's project() version (HEADLIGHT_VERSION is set by meson.build).
inline constexpr const char* kVersion = HEADLIGHT_VERSION;
}  // namespace headlight
