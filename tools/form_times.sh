#!/bin/sh
# Each fullscreen pass's time as a fragment shader and as a compute dispatch
# on this machine (docs/BENCHMARKS.md, "Fullscreen forms"): headlight bench
# --no-reference sweeps fullscreen-form over both forms, ROUNDS times with
# the order swapped every round, and the table gives each pass's median time
# per form over the rounds' medians, and their ratio. TIME=wall (default:
# glFinish-bounded, what llvmpipe must be judged by, since its
# GL_TIME_ELAPSED counts a compute dispatch as 0) or TIME=gpu (timer queries:
# the measure on a hardware GPU).
# Usage: tools/form_times.sh [ROUNDS] [WxH,...] [SCENE...]   (extra bench
# flags through BENCH_FLAGS, e.g. BENCH_FLAGS="--ssgi-frames 4")
set -eu
cd "$(dirname "$0")/.."
rounds=${1:-3}
sizes=${2:-256x256,640x480}
shift 2 2>/dev/null || shift $#
scenes=${*:-builtin:cornell builtin:spheres}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
round=0
while [ "$round" -lt "$rounds" ]; do
  if [ $((round % 2)) -eq 0 ]; then order=fragment,compute; else order=compute,fragment; fi
  # shellcheck disable=SC2086
  build/headlight bench $scenes --resolutions "$sizes" --no-reference --quiet --repetitions 7 --warmup 2 \
    --sweep fullscreen-form=$order ${BENCH_FLAGS:-} --out "$work/round$round"
  round=$((round + 1))
done
/usr/bin/python3 - "$work" "$rounds" "${TIME:-wall}" <<'PY'
import json, statistics, sys, collections
work, rounds, kind = sys.argv[1], int(sys.argv[2]), sys.argv[3]
key = "gpu_ms" if kind == "gpu" else "ms"
times = collections.defaultdict(list)  # (scene, size, pass, form) -> [median per round]
renderer = ""
for r in range(rounds):
    for row in json.load(open(f"{work}/round{r}/bench.json"))["rows"]:
        if row["seed_default"]:
            continue
        form = row["settings"]["fullscreen-form"]
        renderer = row["renderer"]
        for name, t in row["passes"].items():
            if key in t:
                times[(row["scene"], f'{row["width"]}x{row["height"]}', name, form)].append(t[key]["median"])
what = "GPU ms (GL_TIME_ELAPSED)" if kind == "gpu" else "wall ms (glFinish-bounded)"
print(f"renderer: {renderer}; {rounds} rounds, medians of 7 frames each; {what}\n")
print("| scene | size | pass | fragment ms | compute ms | compute / fragment |")
print("|---|---|---|---:|---:|---:|")
keys = sorted({k[:3] for k in times})
for scene, size, name in keys:
    f = times.get((scene, size, name, "fragment"))
    c = times.get((scene, size, name, "compute"))
    if not f or not c or name in ("shadows", "readback", "gbuffer", "virtual-lights"):
        continue
    fm, cm = statistics.median(f), statistics.median(c)
    print(f"| {scene} | {size} | {name} | {fm:.3f} | {cm:.3f} | {cm / fm:.2f} |")
PY
