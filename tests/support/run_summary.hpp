#pragma once
// What every test program's main does after doctest has run: names each
// skipped test case on stdout ("[doctest] skipped: NAME (FILE:LINE)"), and
// turns a run in which no test case could run into exit status 77, which
// meson reports as SKIP. doctest's own summary line ("test cases: N | N
// passed | N failed | N skipped") counts cases left out by a filter as
// skipped too; tools/count_tests.py counts the named lines instead, so that
// a case excluded from one run because another runs it is not a skip.
#include <string>
#include <vector>

namespace headlight::test {

// `doctestStatus` is doctest::Context::run()'s result. Returns it, or 77
// when the run executed no test case although the program has some (every
// one skipped or filtered out).
int exitStatus(int doctestStatus);

// For a program that cannot run any of its cases (no GL context at all):
// names each of `testCaseNames` as skipped, prints doctest's summary line
// with every case skipped, and returns 77.
int skipWholeProgram(const std::vector<std::string>& testCaseNames);

}  // namespace headlight::test
