#include "support/run_summary.hpp"

#include <doctest/doctest.h>

#include <iostream>

namespace headlight::test {

namespace {

constexpr int kMesonSkip = 77;

struct RunTally {
  bool ran = false;  // doctest reached the end of a run (not --help, --list-...)
  unsigned caseCount = 0;
  unsigned casesRun = 0;
};

RunTally& tally() {
  static RunTally value;
  return value;
}

void printSkipped(const std::string& testCaseName) { std::cout << "[doctest] skipped: " << testCaseName << "\n"; }

// A listener: reports nothing of its own but skipped cases, and keeps the
// run's counts for exitStatus.
class SkipReporter : public doctest::IReporter {
 public:
  explicit SkipReporter(const doctest::ContextOptions&) {}

  void test_case_skipped(const doctest::TestCaseData& test) override {
    // Cases left out by a filter (-tc, -ts, --test-suite-exclude) were not
    // asked for; those skipped by their own decorator (a missing asset,
    // backend or Embree) are named.
    if (test.m_skip) printSkipped(test.m_name);
  }
  void test_run_end(const doctest::TestRunStats& stats) override {
    tally() = RunTally{true, stats.numTestCases, stats.numTestCasesPassingFilters};
  }

  void report_query(const doctest::QueryData&) override {}
  void test_run_start() override {}
  void test_case_start(const doctest::TestCaseData&) override {}
  void test_case_reenter(const doctest::TestCaseData&) override {}
  void test_case_end(const doctest::CurrentTestCaseStats&) override {}
  void test_case_exception(const doctest::TestCaseException&) override {}
  void subcase_start(const doctest::SubcaseSignature&) override {}
  void subcase_end() override {}
  void log_assert(const doctest::AssertData&) override {}
  void log_message(const doctest::MessageData&) override {}
};

}  // namespace

// Registered here, beside exitStatus, so that linking a main that calls it
// links the listener too (a static library drops objects nothing calls).
REGISTER_LISTENER("skips", 1, SkipReporter);

int exitStatus(int doctestStatus) {
  const RunTally& run = tally();
  if (doctestStatus != 0 || !run.ran) return doctestStatus;
  if (run.caseCount > 0 && run.casesRun == 0) {
    std::cout << "[doctest] every test case was skipped: exit " << kMesonSkip << " (meson: SKIP)\n";
    return kMesonSkip;
  }
  return doctestStatus;
}

int skipWholeProgram(const std::vector<std::string>& testCaseNames) {
  for (const std::string& name : testCaseNames) printSkipped(name);
  std::cout << "[doctest] test cases: " << testCaseNames.size() << " | 0 passed | 0 failed | "
            << testCaseNames.size() << " skipped\n";
  return kMesonSkip;
}

}  // namespace headlight::test
