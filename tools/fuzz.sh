#!/usr/bin/env bash
# Builds a libFuzzer target with clang-14 (ASan + UBSan) into build-fuzz/ and
# runs it on its seed corpus. Targets (FUZZ_TARGET):
#   gltf-loader  the glTF loader (default); seeds made by the tests
#   job-file     render --jobs' job-line parser and out-folder clash check
#   settings     the settings-file parser (render --settings, tune's output)
#
#   tools/fuzz.sh [SECONDS] [SEED_DIR [SEED_MAKER]]   # default 3600 s; corpus kept in $FUZZ_OUT/corpus[-TARGET]
#
# SEED_MAKER (build/tests/make-fuzz-seeds) writes the tests' scenes into
# SEED_DIR first (gltf-loader). FUZZ_OUT: where to build and keep the corpus
# (build-fuzz).
#
# meson test --suite fuzz runs the loader for 60 s (see tests/meson.build).
# Exit 77 (skipped) when clang++-14 or libFuzzer (libclang-rt-14-dev) is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-3600}
seeds=${2:-}
maker=${3:-}
out=${FUZZ_OUT:-build-fuzz}
cxx=${FUZZ_CXX:-clang++-14}
if ! command -v "$cxx" >/dev/null; then
  echo "skipping: $cxx not found (Debian: clang-14)"; exit 77
fi
if ! echo 'extern "C" int LLVMFuzzerTestOneInput(const char*, unsigned long) { return 0; }' |
    "$cxx" -x c++ -fsanitize=fuzzer - -o /dev/null 2>/dev/null; then
  echo "skipping: $cxx cannot link -fsanitize=fuzzer (Debian: libclang-rt-14-dev)"; exit 77
fi
target=${FUZZ_TARGET:-gltf-loader}
corpus="$out/corpus"
[[ "$target" != gltf-loader ]] && corpus="$out/corpus-$target"
mkdir -p "$out/obj" "$corpus"
flags=(-std=c++20 -O1 -gline-tables-only -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
       -Ilib/include -Ilib -Iglsl -Itools -DHEADLIGHT_VERSION='"fuzz"' -DHEADLIGHT_HAS_EMBREE=0
       -DHEADLIGHT_HAS_DRACO=1 -DHEADLIGHT_HAS_MESHOPT=1)
# The library's GL-free part, the sources of meson's headlight-no-gl target
# (meson.build lists them once; read back from the configured build), as an
# archive from which each target's link takes what it calls: no GL, no context.
build=${HEADLIGHT_BUILD_DIR:-build}
if [[ ! -f "$build/meson-info/intro-targets.json" ]]; then
  echo "fuzz.sh: no configured meson build in '$build' (HEADLIGHT_BUILD_DIR); run tools/quickstart.sh first" >&2; exit 2
fi
mapfile -t library < <(python3 -c '
import json, os, sys
for target in json.load(open(sys.argv[1])):
    if target["name"] == "headlight-no-gl":
        for group in target["target_sources"]:
            for source in group.get("sources", []):
                if source.endswith(".cpp"): print(os.path.relpath(source))
' "$build/meson-info/intro-targets.json")
if (( ${#library[@]} == 0 )); then echo "fuzz.sh: headlight-no-gl has no sources in '$build'" >&2; exit 2; fi
case "$target" in
  # The image module's decoders linked directly, not through dlopen.
  gltf-loader) sources=(lib/image_io/texture_decode.cpp lib/image_io/environment_decode.cpp tests/fuzz/gltf_loader_fuzz.cpp) ;;
  job-file) sources=(lib/tooling/command_line.cpp tools/job_file.cpp tools/scene_catalogue.cpp tools/batch_plan.cpp
              tests/fuzz/job_file_fuzz.cpp) ;;
  settings) sources=(tests/fuzz/settings_fuzz.cpp) ;;
  *) echo "fuzz.sh: unknown FUZZ_TARGET '$target' (gltf-loader, job-file, settings)" >&2; exit 2 ;;
esac
libs=($(pkg-config --libs OpenImageIO libxxhash draco) -ltinygltf -lmeshoptimizer)
# One object per source, named by its path (lib/gltf/materials.cpp and
# lib/scene/... never meet), rebuilt when older than its source or the limits.
object_of() { local path=${1%.cpp}; echo "$out/obj/${path//\//_}.o"; }
compile() {
  local object
  object=$(object_of "$1")
  if [[ ! -f "$object" || "$1" -nt "$object" || lib/include/headlight/limits.hpp -nt "$object" ]]; then
    "$cxx" "${flags[@]}" -c "$1" -o "$object"
  fi
}
pending=0
for source in "${library[@]}" "${sources[@]}"; do
  compile "$source" &
  if (( ++pending >= $(nproc) )); then wait -n; ((pending--)); fi
done
while (( pending > 0 )); do wait -n; ((pending--)); done
archive_objects=()
for source in "${library[@]}"; do archive_objects+=("$(object_of "$source")"); done
rm -f "$out/headlight-no-gl.a"
ar qc "$out/headlight-no-gl.a" "${archive_objects[@]}"
objects=()
for source in "${sources[@]}"; do objects+=("$(object_of "$source")"); done
"$cxx" -fsanitize=fuzzer,address,undefined "${objects[@]}" "$out/headlight-no-gl.a" "${libs[@]}" -o "$out/$target-fuzz"
[[ -n "$maker" ]] && "$maker" "$seeds"
dirs=("$corpus")
[[ -n "$seeds" ]] && dirs+=("$seeds")
# One worker; findings (crash-*, leak-*, timeout-*) land in $out/$target-. A finding
# exits 1: libFuzzer's own default (77) would read as "skipped" to meson.
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
# Function names in reports (and for the suppressions) need a symbolizer;
# Debian's clang-14 puts llvm-14's beside it, not on PATH.
[[ -z "${ASAN_SYMBOLIZER_PATH:-}" && -x /usr/lib/llvm-14/bin/llvm-symbolizer ]] &&
  export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer
exec "$out/$target-fuzz" -error_exitcode=1 -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 -timeout=20 \
  -artifact_prefix="$out/$target-" -print_final_stats=1 "${dirs[@]}"
