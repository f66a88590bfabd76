#!/usr/bin/env python3
"""Counts what the last `meson test` run executed, from build/meson-logs/testlog.json.

Prints one line per test program (its meson result and its doctest counts,
then the names of its skipped test cases) and a closing 'N passed, N failed,
N skipped' line, doctest test cases summed over every program. Passed and
failed come from doctest's summary line; skipped counts the cases the test
mains name ("[doctest] skipped: NAME", tests/support/run_summary.hpp): those
that could not run here (a missing asset, backend or Embree, or a whole
program without a GL context), not those a filter left to another run.
A program that exits 77 (meson: SKIP) is not a failure. Exits 1 when a
program failed, when no test program ran or when no test case passed: a
build that silently dropped its suites (a missing dependency) must not look
green. Used by .ci/run.
"""
import json
import re
import sys

log = sys.argv[1] if len(sys.argv) > 1 else "build/meson-logs/testlog.json"
try:
    with open(log, encoding="utf-8") as f:
        runs = [json.loads(line) for line in f if line.strip()]
except FileNotFoundError:
    print(f"{log}: no test log: meson test ran no test")
    sys.exit(1)

summary = re.compile(r"\[doctest\] test cases:\s*(\d+)\s*\|\s*(\d+) passed\s*\|\s*(\d+) failed")
skipped_case = re.compile(r"^\[doctest\] skipped: (.*)$", re.M)
passed = failed = skipped = 0
programs_ok = programs_skipped = 0
for run in runs:
    stdout = run.get("stdout", "") or ""
    match = summary.search(stdout)
    run_passed, run_failed = (int(match.group(2)), int(match.group(3))) if match else (0, 0)
    run_skipped = skipped_case.findall(stdout)
    passed, failed, skipped = passed + run_passed, failed + run_failed, skipped + len(run_skipped)
    result = run.get("result")
    programs_ok += result in ("OK", "EXPECTEDFAIL")
    programs_skipped += result == "SKIP"
    print(f"{run['name']}: {result}, {run_passed} passed, {run_failed} failed, {len(run_skipped)} skipped")
    for name in run_skipped:
        print(f"  skipped: {name}")

print(f"{programs_ok} of {len(runs)} test programs OK, {programs_skipped} skipped (exit 77)")
print(f"{passed} passed, {failed} failed, {skipped} skipped")
if not runs or passed == 0:
    print("error: the test run executed no test case")
    sys.exit(1)
sys.exit(0 if failed == 0 and programs_ok + programs_skipped == len(runs) else 1)
