#!/usr/bin/env bash
# The batch and start-up benchmark of docs/BENCHMARKS.md ("Batches, start-up
# and output"): headlight against F3D (the yardstick, under Xvfb) side by
# side in one hyperfine run, then in-process batches read from
# `headlight render --json`. Prints every number the page records.
#
#   tools/bench_batch.sh            # from the source root, after ninja -C build
#   RUNS=3 VIEWS=20 tools/bench_batch.sh   # quicker, noisier
#
# Needs: hyperfine, f3d, xvfb-run (Debian packages; tools/debian-packages-bench.txt).
set -euo pipefail
HEADLIGHT=${HEADLIGHT:-build/headlight}
RUNS=${RUNS:-7}
VIEWS=${VIEWS:-100}
SIZE=${SIZE:-512}
work=$(mktemp -d /tmp/headlight-bench-batch.XXXXXX)
trap 'rm -rf "$work"' EXIT
scene="$work/cornell.gltf"
python3 "$(dirname "$0")/make_cornell_gltf.py" "$scene"

echo "== machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores"
"$HEADLIGHT" render "$scene" --width 64 --height 64 --out "$work/probe" --verbose 2>&1 >/dev/null | grep GL_RENDERER
echo "== f3d: $(f3d --version 2>&1 | head -1)"

# 1. Cold start and --version, alternating, under one X server (F3D needs
#    one; its start is not F3D's cost).
echo "== cold start (${SIZE}x${SIZE}, every file written) and --version, $RUNS runs each"
xvfb-run -a -s "-screen 0 1280x1024x24" hyperfine -N --warmup 1 --runs "$RUNS" --export-json "$work/cold.json" \
  --command-name headlight-render "$HEADLIGHT render $scene --width $SIZE --height $SIZE --out $work/cold --quiet" \
  --command-name f3d-ssao "f3d --ssao --resolution $SIZE,$SIZE --output $work/f3d.png $scene" \
  --command-name headlight-version "$HEADLIGHT --version" \
  --command-name f3d-version "f3d --version" >/dev/null
python3 - "$work/cold.json" <<'PY'
import json, sys
r = {x["command"]: x for x in json.load(open(sys.argv[1]))["results"]}
for name, x in r.items():
    print(f"  {name:18s} median {x['median']*1000:8.1f} ms  (min {x['min']*1000:.1f}, max {x['max']*1000:.1f})")
print(f"  cold start ratio headlight/f3d: {r['headlight-render']['median']/r['f3d-ssao']['median']:.2f}x (target <= 0.6x)")
print(f"  --version ratio headlight/f3d:  {r['headlight-version']['median']/r['f3d-version']['median']:.2f}x (target <= 0.8x)")
PY

# 2. One process, VIEWS orbit views: per-view wall time against the
#    in-process pipeline time (every pass + readback) of a view.
echo "== batch: $VIEWS orbit views at ${SIZE}x${SIZE} in one process"
start=$(date +%s.%N)
"$HEADLIGHT" render "$scene" --views "$VIEWS" --orbit --width "$SIZE" --height "$SIZE" --out "$work/orbit" --json \
  >"$work/orbit.json"
end=$(date +%s.%N)
python3 - "$work/orbit.json" "$start" "$end" <<'PY'
import json, statistics, sys
j = json.load(open(sys.argv[1])); wall = float(sys.argv[3]) - float(sys.argv[2])
rs = [x for x in j["results"] if x["status"] == "rendered"]
pipeline = [sum(x["passes_ms"].values()) for x in rs]
steady = statistics.median(pipeline[1:] if len(pipeline) > 1 else pipeline)
print(f"  process wall {wall:.2f} s for {len(rs)} views: {wall/len(rs)*1000:.1f} ms/view; in-batch wall {j['wall_ms']/len(rs):.1f} ms/view")
print(f"  pipeline (passes + readback) median {steady:.1f} ms/view; write median {statistics.median(x['write_ms'] for x in rs):.1f} ms (overlapped)")
print(f"  ratio per-view wall / pipeline: {wall/len(rs)*1000/steady:.2f}x (target <= 1.15x)")
rss = [x["peak_rss_kb"] for x in rs]
if len(rss) >= 10:
    a, b = rss[9], rss[-1]
    print(f"  peak RSS after view 10: {a/1024:.1f} MiB, after view {len(rss)}: {b/1024:.1f} MiB ({(b-a)/a*100:+.1f}%; target within 5%)")
PY

# 3. Per-view time against pixel count, in one process per size.
echo "== per-view time against pixel count (10 orbit views per size)"
for s in 128 256 512 1024; do
  "$HEADLIGHT" render "$scene" --views 10 --orbit --width $s --height $s --out "$work/px$s" --json >"$work/px$s.json"
done
python3 - "$work" <<'PY'
import json, math, statistics, sys
xs, ys, ps = [], [], []
for s in (128, 256, 512, 1024):
    j = json.load(open(f"{sys.argv[1]}/px{s}.json"))
    rs = [x for x in j["results"] if x["status"] == "rendered"]
    # Steady state: views 2..10 (the first pays the shadow maps and variants).
    per = (j["wall_ms"] - rs[0]["render_ms"]) / (len(rs) - 1)
    pipe = statistics.median(sum(x["passes_ms"].values()) for x in rs[1:])
    xs.append(math.log(s * s)); ys.append(math.log(per)); ps.append(math.log(pipe))
    print(f"  {s:5d}^2: {per:8.1f} ms/view in the batch, pipeline {pipe:8.1f} ms")
def slope(x, y):
    mx, my = sum(x) / len(x), sum(y) / len(y)
    return sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x)
print(f"  log-log slope 128^2..1024^2: batch wall {slope(xs, ys):.2f}, pipeline {slope(xs, ps):.2f}; "
      f"256^2..1024^2: {slope(xs[1:], ys[1:]):.2f} (target 1.0 +- 0.15)")
PY

# 4. EXR compression: write time (one process, the set written on the
#    main thread's pool) and bytes of the eight targets.
echo "== OpenEXR lossless compression at ${SIZE}x${SIZE} (median of $RUNS)"
for mode in none rle zips zip piz; do
  for i in $(seq "$RUNS"); do
    "$HEADLIGHT" render "$scene" --width "$SIZE" --height "$SIZE" --exr-compression $mode --out "$work/c$mode" \
      --targets position,normal,albedo,material,depth,emissive,ssgi,lit --json >"$work/c$mode.$i.json"
  done
done
python3 - "$work" "$RUNS" <<'PY'
import json, statistics, sys
for mode in ("none", "rle", "zips", "zip", "piz"):
    js = [json.load(open(f"{sys.argv[1]}/c{mode}.{i}.json")) for i in range(1, int(sys.argv[2]) + 1)]
    w = statistics.median(j["results"][0]["write_ms"] for j in js)
    b = sum(f["bytes"] for f in js[0]["results"][0]["files"])
    print(f"  {mode:5s} write {w:7.1f} ms  {b/1024:8.1f} KiB")
PY
