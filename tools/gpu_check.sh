#!/bin/sh
# Issue 29's GPU targets in one short run, for a machine with a GPU (through
# ../shared/gpu/bundle.sh: `bash .device/run.sh sh tools/gpu_check.sh`) or any
# other: builtin:cornell and builtin:spheres at 1920x1080 and 3840x2160, both
# fullscreen forms, no reference traced; prints each configuration's median
# frame and SSGI time, wall (glFinish-bounded) and GPU (GL_TIME_ELAPSED), and
# the forms the passes ran in. bench.json beside it has every pass's times.
# Usage: tools/gpu_check.sh [OUT_DIR]   (HEADLIGHT=path/to/headlight to choose the binary)
set -eu
out=${1:-gpu-check}
headlight=${HEADLIGHT:-headlight}
command -v "$headlight" >/dev/null 2>&1 || headlight=build/headlight
"$headlight" bench builtin:cornell builtin:spheres --resolutions 1920x1080,3840x2160 --no-reference --quiet \
  --repetitions 9 --warmup 3 --sweep fullscreen-form=fragment,compute --out "$out"
python3 - "$out/bench.json" <<'PY'
import json, sys
rows = json.load(open(sys.argv[1]))["rows"]
print(f"renderer: {rows[0]['renderer']}")
print("| scene | size | configuration | frame ms | frame GPU ms | SSGI ms | SSGI GPU ms | forms |")
print("|---|---|---|---:|---:|---:|---:|---|")
for r in rows:
    label = "seed (hemisphere 64, no blur)" if r["seed_default"] else r["label"]
    print(f"| {r['scene']} | {r['width']}x{r['height']} | {label} | {r['frame_ms']['median']:.2f} | "
          f"{r['frame_gpu_ms']['median']:.2f} | {r['ssgi_ms']['median']:.2f} | {r['ssgi_gpu_ms']['median']:.2f} | "
          f"{r['forms']} |")
PY
