#!/bin/sh
# Re-renders every golden listed in reference_images/goldens.txt and prints
# what changed against the current goldens (headlight diff, directory mode),
# then replaces them. An explicit, reviewed step: never run in CI. Review the
# printed diff and the images, then commit reference_images/.
# Usage: tools/update_goldens.sh [NAME...]   (default: all)
set -eu
cd "$(dirname "$0")/.."
[ -x build/headlight ] || { echo "build first: tools/quickstart.sh" >&2; exit 2; }
if [ -n "${CI:-}" ]; then echo "update_goldens.sh does not run in CI" >&2; exit 2; fi

sed 's/#.*//' reference_images/goldens.txt | while read -r name scene flags; do
  [ -n "$name" ] || continue
  if [ $# -gt 0 ] && ! printf '%s\n' "$@" | grep -qx "$name"; then continue; fi
  fresh="reference_images/.$name.new"
  rm -rf "$fresh"
  # shellcheck disable=SC2086  # flags are words on purpose
  # Every EXR target (emissive as zeros where nothing emits: named targets are
  # always written), no preview; frame.json makes the golden a checked set.
  # tests/regression_tests.cpp renders with the same list.
  build/headlight render "$scene" $flags --out "$fresh" --quiet --strict \
    --targets position,normal,albedo,material,depth,emissive,ssgi,lit,ids
  if [ -d "reference_images/$name" ]; then
    echo "== $name: changes against the current golden"
    build/headlight diff "reference_images/$name" "$fresh" || true
  else
    echo "== $name: new golden"
  fi
  rm -rf "reference_images/$name"
  mv "$fresh" "reference_images/$name"
done
