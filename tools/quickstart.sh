#!/bin/sh
# README command 1: on a fresh Debian 12 machine, install what is missing,
# build, and render the built-in default scene (builtin:cornell) into ./out.
# Extra arguments go to `headlight render` (e.g. --width 1280 --height 720).
set -eu
cd "$(dirname "$0")/.."

missing=""
for package in $(sed 's/#.*//' tools/debian-packages.txt); do
  dpkg -s "$package" >/dev/null 2>&1 || missing="$missing $package"
done
if [ -n "$missing" ]; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $missing
fi

[ -f build/build.ninja ] || meson setup build
ninja -C build
build/headlight render --out out "$@"
