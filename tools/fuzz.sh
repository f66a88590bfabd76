#!/usr/bin/env bash
# Builds the glTF loader's libFuzzer target with clang-14 (ASan + UBSan) into
# build-fuzz/ and runs it on the seed corpus made by the tests.
#
#   tools/fuzz.sh [SECONDS] [SEED_DIR [SEED_MAKER]]   # default 3600 s; corpus kept in $FUZZ_OUT/corpus
#
# SEED_MAKER (build/tests/make-fuzz-seeds) writes the tests' scenes into
# SEED_DIR first. FUZZ_OUT: where to build and keep the corpus (build-fuzz).
#
# meson test --suite fuzz runs it for 60 s (see tests/meson.build). Exit 77
# (skipped) when clang++-14 or libFuzzer (libclang-rt-14-dev) is missing.
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
mkdir -p "$out/obj" "$out/corpus"
flags=(-std=c++20 -O1 -gline-tables-only -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
       -Ilib/include -Ilib -Iglsl -DHEADLIGHT_VERSION='"fuzz"' -DHEADLIGHT_HAS_EMBREE=0)
# Only what the loader needs: no GL, no context.
sources=(lib/scene/gltf_loader.cpp lib/scene/gltf_prescan.cpp lib/scene/limits.cpp lib/scene/scene.cpp
         lib/scene/shapes.cpp lib/scene/builtin_scenes.cpp lib/scene/scene_builder.cpp lib/settings/options.cpp
         lib/output/fingerprint.cpp lib/output/bounded_read.cpp lib/image_io/texture_decode.cpp tests/fuzz/gltf_loader_fuzz.cpp)
objects=()
for source in "${sources[@]}"; do
  object="$out/obj/$(basename "$source" .cpp).o"
  if [[ ! -f "$object" || "$source" -nt "$object" || lib/include/headlight/limits.hpp -nt "$object" ]]; then
    "$cxx" "${flags[@]}" -c "$source" -o "$object"
  fi
  objects+=("$object")
done
"$cxx" -fsanitize=fuzzer,address,undefined "${objects[@]}" $(pkg-config --libs OpenImageIO libxxhash) -ltinygltf \
  -o "$out/gltf-loader-fuzz"
[[ -n "$maker" ]] && "$maker" "$seeds"
dirs=("$out/corpus")
[[ -n "$seeds" ]] && dirs+=("$seeds")
# One worker; findings (crash-*, leak-*, timeout-*) land in $out/. A finding
# exits 1: libFuzzer's own default (77) would read as "skipped" to meson.
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
# Function names in reports (and for the suppressions) need a symbolizer;
# Debian's clang-14 puts llvm-14's beside it, not on PATH.
[[ -z "${ASAN_SYMBOLIZER_PATH:-}" && -x /usr/lib/llvm-14/bin/llvm-symbolizer ]] &&
  export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer
exec "$out/gltf-loader-fuzz" -error_exitcode=1 -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 -timeout=20 \
  -artifact_prefix="$out/" -print_final_stats=1 "${dirs[@]}"
