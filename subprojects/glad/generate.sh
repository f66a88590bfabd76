#!/bin/sh
# Usage: generate.sh GLAD OUT_H OUT_C
# Runs glad into a scratch folder and copies the two files meson tracks.
set -eu
glad="$1"; out_h="$2"; out_c="$3"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$glad" --reproducible --quiet --api gl:core=4.5 --extensions GL_KHR_debug \
  --out-path "$tmp" c >/dev/null
cp "$tmp/include/glad/gl.h" "$out_h"
cp "$tmp/src/gl.c" "$out_c"
