#!/usr/bin/env bash
# The unit, gl (EGL), cli, stability and hostile suites again, in an ASan + UBSan
# build of the same sources (a second build folder beside the first). Run by
# `meson test` as the `sanitize` suite (tests/meson.build), so the README's
# test command and CI run it; by hand:
#
#   tools/sanitize.sh [BUILD_DIR]        # default build-sanitize
#
# Only Headlight's code is instrumented; Mesa, LLVM and OpenImageIO are not.
# LeakSanitizer's suppressions (tests/sanitize/lsan.supp) name Mesa's own
# leaks, each with its reason. UBSan findings stop the test (no recovery).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build-sanitize}
if [[ ! -f "$out/build.ninja" ]]; then
  # -O0 -g1 (line tables, no variables): the compile is what this suite
  # spends its time on. -O2 -g took 2.7x longer than -O1 (gltf/loader.cpp:
  # 96 s against 36 s), and -O0 takes half of -O1 (gltf/loader.cpp 5.2 s
  # against 10.9 s, renderer.cpp 4.9 against 9.9, gl_tests.cpp 3.4 against
  # 6.6, one core each); the suites' own run changes little, since the GL
  # work happens in Mesa, which is not instrumented. ASan's documentation
  # recommends -O1 for speed, not for what it finds.
  # A unity build (meson joins up to four sources of a target into one
  # object): each joined file's headers (doctest, nlohmann/json, OpenImageIO,
  # tinygltf) are parsed once, not once a file. These targets built in 289 s
  # on two cores (474 s of CPU) against ~800 s (1597 s of CPU) one file an
  # object (session 24). The main build stays one file an object, so each
  # source is still compiled alone somewhere (its own includes checked).
  # No Python module or install test: they load the library into python3,
  # which is not built with the sanitizer runtime.
  meson setup "$out" -Dbuildtype=plain -Doptimization=0 -Ddebug=false -Dcpp_args=-g1 -Dc_args=-g1 \
    -Db_sanitize=address,undefined -Db_lundef=false -Dpython=disabled -Dunity=on >/dev/null
fi
ninja -C "$out" headlight headlight-thumbnailer libheadlight-image-io.so tests/unit-tests tests/gl-tests tests/cli-tests tests/stability-tests tests/hostile-tests \
  tests/libhostile-null-image-module.so tests/libhostile-wrong-image-module.so
# intercept_tls_get_addr=0: up to GCC 13, ASan's __tls_get_addr interceptor
# takes a dynamic TLS block that happens to sit at a certain page offset for
# a pre-2.25 glibc header and reads two words before it; LeakSanitizer's
# tracer then dies at exit ("Tracer caught signal 11"), at random. Dynamic
# TLS blocks come from libraries loaded with dlopen: OpenImageIO's, since the
# image module (seen once in ~30 cli-suite renders).
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:intercept_tls_get_addr=0${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitize/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
# The gl suite under EGL only: its "backends" cases make an OSMesa context
# too, so the OSMesa context code is instrumented there, and the gl-osmesa
# run repeats the same Headlight code on another Mesa driver (56 s of the
# suite's ~5 min in the fresh-Debian run of session 7).
meson test -C "$out" --no-rebuild --print-errorlogs --suite unit --suite cli --suite stability --suite hostile \
  --timeout-multiplier 3
exec meson test -C "$out" --no-rebuild --print-errorlogs --timeout-multiplier 3 --logbase testlog-gl gl-egl
