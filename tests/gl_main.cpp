// doctest's main for the GL suites. The backend comes from the environment
// (HEADLIGHT_TEST_BACKEND = egl | osmesa | auto). If no context of that kind
// can be made at all the suite exits 77, which meson reports as skipped; any
// other failure is a failure. Before the run, two edits to doctest's list of
// test cases (only this file, which holds doctest's implementation, can
// reach it):
// - a case in the test suite "backends" needs both EGL and OSMesa; where one
//   is missing it is skipped, and counted and named as skipped;
// - every case is wrapped so that, after it (each of its subcase passes),
//   a GL error or KHR_debug error still pending on the shared test context
//   fails it, naming the errors.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstring>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "headlight/error.hpp"
#include "support/gl.hpp"
#include "support/run_summary.hpp"

namespace {

using headlight::Backend;
using doctest::detail::funcType;
using doctest::detail::TestCase;

// ---- Cases that need both backends ---------------------------------------------

void skipCasesWithoutBothBackends() {
  bool probed = false, both = false;
  for (const TestCase& test : doctest::detail::getRegisteredTests()) {
    if (std::strcmp(test.m_test_suite, "backends") != 0 || test.m_skip) continue;
    if (!probed) {
      both = headlight::test::canMakeContext(Backend::Egl) && headlight::test::canMakeContext(Backend::OSMesa);
      probed = true;
    }
    // The set orders by file, line and name, none of which changes here.
    if (!both) const_cast<TestCase&>(test).m_skip = true;
  }
  if (probed && !both) std::cout << "[doctest] EGL or OSMesa is missing: the \"backends\" cases are skipped\n";
}

// ---- No GL error left after a case ---------------------------------------------

std::map<const doctest::TestCaseData*, funcType>& originalBodies() {
  static std::map<const doctest::TestCaseData*, funcType> bodies;
  return bodies;
}

const doctest::TestCaseData* currentCase = nullptr;

// Tells the wrapper which case doctest is running.
class CurrentCase : public doctest::IReporter {
 public:
  explicit CurrentCase(const doctest::ContextOptions&) {}
  void test_case_start(const doctest::TestCaseData& test) override { currentCase = &test; }
  void test_case_end(const doctest::CurrentTestCaseStats&) override { currentCase = nullptr; }

  void report_query(const doctest::QueryData&) override {}
  void test_run_start() override {}
  void test_run_end(const doctest::TestRunStats&) override {}
  void test_case_reenter(const doctest::TestCaseData&) override {}
  void test_case_exception(const doctest::TestCaseException&) override {}
  void subcase_start(const doctest::SubcaseSignature&) override {}
  void subcase_end() override {}
  void log_assert(const doctest::AssertData&) override {}
  void log_message(const doctest::MessageData&) override {}
  void test_case_skipped(const doctest::TestCaseData&) override {}
};
REGISTER_LISTENER("current-case", 0, CurrentCase);

void failOnPendingGlErrors() {
  const std::string errors = headlight::test::takeGlErrors(headlight::test::sharedContext());
  if (errors.empty()) return;
  const std::string message = "GL errors left on the test context after the test case: " + errors;
  FAIL_CHECK(message);
}

void runThenCheckGlErrors() {
  const funcType body = originalBodies().at(currentCase);
  try {
    body();
  } catch (...) {
    failOnPendingGlErrors();
    throw;
  }
  failOnPendingGlErrors();
}

void checkGlErrorsAfterEveryCase() {
  for (const TestCase& test : doctest::detail::getRegisteredTests()) {
    originalBodies()[&test] = test.m_test;
    const_cast<TestCase&>(test).m_test = &runThenCheckGlErrors;
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    headlight::test::sharedContext();
  } catch (const headlight::ContextError& error) {
    std::cerr << "skipping: " << error.what() << "\n";
    std::vector<std::string> names;
    for (const TestCase& test : doctest::detail::getRegisteredTests()) names.emplace_back(test.m_name);
    return headlight::test::skipWholeProgram(names);
  }
  std::cerr << "GL tests on " << headlight::test::sharedContext().description() << ": "
            << headlight::test::sharedContext().renderer() << "\n";
  doctest::Context context(argc, argv);
  skipCasesWithoutBothBackends();
  checkGlErrorsAfterEveryCase();
  return headlight::test::exitStatus(context.run());
}
