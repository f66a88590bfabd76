#!/usr/bin/env python3
"""Counts what the last `meson test` run executed, from build/meson-logs/testlog.json.

Prints one line per suite and a closing 'N passed, N failed, N skipped' line
(doctest test cases, summed over every test program). Exits 1 when no test
program ran or no test case passed: a build that silently dropped its suites
(a missing dependency) must not look green. Used by .ci/run.
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

summary = re.compile(r"\[doctest\] test cases:\s*(\d+)\s*\|\s*(\d+) passed\s*\|\s*(\d+) failed\s*\|\s*(\d+) skipped")
passed = failed = skipped = 0
programs_ok = 0
for run in runs:
    match = summary.search(run.get("stdout", "") or "")
    counts = tuple(int(g) for g in match.groups()[1:]) if match else (0, 0, 0)
    passed, failed, skipped = passed + counts[0], failed + counts[1], skipped + counts[2]
    programs_ok += run.get("result") == "OK"
    print(f"{run['name']}: {run.get('result')}, {counts[0]} passed, {counts[1]} failed, {counts[2]} skipped")

print(f"{programs_ok} of {len(runs)} test programs OK")
print(f"{passed} passed, {failed} failed, {skipped} skipped")
if not runs or passed == 0:
    print("error: the test run executed no test case")
    sys.exit(1)
sys.exit(0 if failed == 0 and programs_ok == len(runs) else 1)
