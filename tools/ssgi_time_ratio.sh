#!/bin/bash
# The bitmask SSGI's time as a ratio to hemisphere-64's (issue 16's time
# measure), for variants side by side: each round runs every variant once, in
# turn, and each run is one `headlight bench` of both methods in the same
# process. A run's ratio is the two rows' ssgi_ms_min (the fastest of 11
# frames: on a shared 2-core machine the median drifts with other load, the
# minimum far less; docs/BENCHMARKS.md, "Session 11"). Prints each variant's
# median ratio over the rounds, the medians of its two minima, and every
# round's ratio. Never run in CI.
# Usage: tools/ssgi_time_ratio.sh ROUNDS SCENE 'BINARY|FLAGS' ['BINARY|FLAGS' ...]
#   e.g. tools/ssgi_time_ratio.sh 5 builtin:cornell 'build/headlight|' 'build/headlight|--ssgi-far-slices 1'
set -eu
[ $# -ge 3 ] || { sed -n '2,12p' "$0" >&2; exit 2; }
rounds=$1 scene=$2
shift 2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
declare -A ratios
for ((round = 0; round < rounds; ++round)); do
  for variant in "$@"; do
    binary=${variant%%|*} flags=${variant#*|}
    # shellcheck disable=SC2086  # flags are words on purpose
    "$binary" bench "$scene" --resolutions 256x256 --sweep ssgi-method=hemisphere,bitmask --ssgi-samples 64 \
      --repetitions 11 --warmup 1 --reference-samples 16 --no-chart --quiet --out "$out" $flags >/dev/null
    ratios[$variant]+=" $(/usr/bin/python3 - "$out/bench.csv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
method = {r["ssgi-method"]: float(r["ssgi_ms_min"]) for r in rows if r["label"].startswith("ssgi-method=")}
print("%.4f/%.2f/%.2f" % (method["bitmask"] / method["hemisphere"], method["bitmask"], method["hemisphere"]))
EOF
)"
  done
done
for variant in "$@"; do
  /usr/bin/python3 - "$variant" "${ratios[$variant]}" <<'EOF'
import statistics, sys
runs = [tuple(map(float, r.split("/"))) for r in sys.argv[2].split()]
median = lambda i: statistics.median(r[i] for r in runs)
print("%-60s %.3fx  (bitmask %.1f ms, hemisphere-64 %.1f ms)  rounds: %s"
      % (sys.argv[1], median(0), median(1), median(2), " ".join("%.2f" % r[0] for r in runs)))
EOF
done
