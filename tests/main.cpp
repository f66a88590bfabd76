// doctest's main for the suites that need no GL context. A program whose
// every case is skipped exits 77 (meson: SKIP); skipped cases are named
// (support/run_summary.hpp).
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "support/run_summary.hpp"

int main(int argc, char** argv) {
  doctest::Context context(argc, argv);
  return headlight::test::exitStatus(context.run());
}
