#pragma once
// libheadlight is built with -fvisibility=hidden: only what the public headers
// declare is exported from the shared library. Each public header opens its
// namespace as `namespace headlight HEADLIGHT_PUBLIC {`, which gives that
// namespace body (and nothing else in namespace headlight) default visibility.
#if defined(__GNUC__) || defined(__clang__)
#define HEADLIGHT_PUBLIC __attribute__((visibility("default")))
#else
#define HEADLIGHT_PUBLIC
#endif
