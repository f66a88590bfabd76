#pragma once
// Cases that trace the reference need Embree: without it they are skipped
// (and counted as such); the refusal has a case of its own
// (reference_tests.cpp).
#include <doctest/doctest.h>

namespace headlight::test {

inline const auto kNeedsEmbree = doctest::skip(!HEADLIGHT_HAS_EMBREE);

}  // namespace headlight::test
