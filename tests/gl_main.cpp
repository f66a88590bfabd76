// doctest's main for the GL suites. The backend comes from the environment
// (HEADLIGHT_TEST_BACKEND = egl | osmesa | auto). If no context of that kind
// can be made at all the suite exits 77, which meson reports as skipped; any
// other failure is a failure.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <iostream>

#include "headlight/error.hpp"
#include "support/gl.hpp"

int main(int argc, char** argv) {
  try {
    headlight::test::sharedContext();
  } catch (const headlight::ContextError& error) {
    std::cerr << "skipping: " << error.what() << "\n";
    return 77;
  }
  std::cerr << "GL tests on " << headlight::test::sharedContext().description() << ": "
            << headlight::test::sharedContext().renderer() << "\n";
  doctest::Context context(argc, argv);
  return context.run();
}
