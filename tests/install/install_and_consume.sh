#!/bin/sh
# Installs the build into a temporary DESTDIR, then, with nothing but what
# was installed and pkg-config:
#  1. compiles one translation unit that includes every installed public
#     header, and fails if any of them pulls in glad, EGL, OSMesa, GL,
#     tinygltf, Embree or OpenImageIO (compiler's dependency list, -M), or
#     if any names an internal function or type (the CLI parser, bench rows,
#     test hooks, GPU formats, locks);
#  2. builds examples/embed.cpp with `pkg-config --cflags --libs headlight`
#     and runs it (it renders builtin:cornell, then a textured glTF file from
#     ../shared/gltf-conformance, into memory and checks their pixels);
#  3. imports the Python module; 4. renders and diffs with the installed CLI;
#  5. finds the thumbnailer's freedesktop entry and runs the installed thumbnailer.
# Usage: install_and_consume.sh BUILD_DIR SOURCE_DIR PREFIX LIBDIR CXX...
set -eu
build="$1"; source="$2"; prefix="$3"; libdir="$4"; shift 4
case "$libdir" in /*) ;; *) libdir="$prefix/$libdir" ;; esac
dest=$(mktemp -d)
trap 'rm -rf "$dest"' EXIT

meson install -C "$build" --no-rebuild --quiet --destdir "$dest" >/dev/null
include="$dest$prefix/include"
test -f "$include/headlight/renderer.hpp" || { echo "no headers under $include/headlight"; exit 1; }
test -f "$dest$libdir/pkgconfig/headlight.pc" || { echo "no headlight.pc under $dest$libdir/pkgconfig"; exit 1; }
ls "$dest$libdir"/libheadlight.so.* >/dev/null || { echo "no libheadlight.so.* under $dest$libdir"; exit 1; }

# pkg-config reads the installed .pc; the sysroot maps its /usr/local paths
# into the temporary folder.
export PKG_CONFIG_PATH="$dest$libdir/pkgconfig"
export PKG_CONFIG_SYSROOT_DIR="$dest"
flags=$(pkg-config --cflags --libs headlight)
echo "pkg-config --cflags --libs headlight: $flags"

# 1. Every public header, with only the installed include path.
tu="$dest/all_headers.cpp"
for header in "$include"/headlight/*.hpp; do
  echo "#include <headlight/$(basename "$header")>" >> "$tu"
done
echo 'int main() { return 0; }' >> "$tu"
"$@" -std=c++20 $(pkg-config --cflags headlight) -M "$tu" > "$dest/deps.txt"
"$@" -std=c++20 -Wall -Wextra -Werror $(pkg-config --cflags headlight) -c "$tu" -o "$dest/all_headers.o"
if grep -E -i 'glad|/EGL/|/GL/|/KHR/|tiny_gltf|tinygltf|embree|OpenImageIO|nlohmann' "$dest/deps.txt"; then
  echo "public headers include the files above"
  exit 1
fi
echo "$(ls "$include"/headlight/*.hpp | wc -l) public headers compile alone; they include no GL, EGL, OSMesa, glad, tinygltf, Embree or OpenImageIO header"
# The public API is what an embedder needs: the CLI's parser and help, bench
# rows, test hooks, GPU formats and locks live in the internal libraries.
internal='parseCommandLine|optionHelp|helpLine|matchFlag|splitFlag|BenchRow|writeBenchCsv|writeBenchJson|maskedError'
internal="$internal|paretoFront|fileFingerprint|textFingerprint|removeStaleTemporaries|tonemapAces|tonemapReinhard"
internal="$internal|pendingErrorCount|lockBackend|unique_lock|mutex|GpuFormat|gpuFormat|bindOption|actionOption|liftOptions"
if grep -n -w -E "$internal" "$include"/headlight/*.hpp || grep -n -F 'see headlight' "$include"/headlight/*.hpp; then
  echo "public headers expose the internal names above"
  exit 1
fi
echo "no public header names the CLI parser, bench rows, test hooks, GPU formats or locks"

# 2. The example, built and run against the installed library: the built-in
# scene, then a textured glTF file (a consumer once failed on any file:
# libheadlight.so listed libdraco, which carries a tinygltf of its own,
# before libtinygltf). The file is a shared conformance model; without
# ../shared the case says it is skipped.
"$@" -std=c++20 "$source/examples/embed.cpp" $flags -o "$dest/embed"
LD_LIBRARY_PATH="$dest$libdir" "$dest/embed"
model="$source/../shared/gltf-conformance/NormalTangentTest/glTF/NormalTangentTest.gltf"
if [ -f "$model" ]; then
  LD_LIBRARY_PATH="$dest$libdir" "$dest/embed" auto "$model"
else
  echo "SKIPPED: the glTF consumer case ($model is absent)"
fi

# 3. The Python module, where one was built: imported from where it was
# installed, by the interpreter it was built for.
module=$(find "$dest" -name 'headlight.cpython-*.so' | head -n 1)
if [ -n "$module" ]; then
  PYTHONPATH=$(dirname "$module") /usr/bin/python3 -c '
import headlight
r = headlight.Renderer()
r.set_scene("builtin:cornell")
lit = r.render(width=32, height=24, ssgi_samples=4)["lit"]
assert lit.shape == (24, 32, 4) and lit[12, 16, 3] == 1.0, lit[12, 16]
print("installed Python module:", headlight.__file__)'
fi

# 4. The installed CLI writes and diffs images: the image module
# (OpenImageIO, loaded on first use) is found from the binary's own place,
# ../<libdir>/headlight/, wherever the tree was copied.
bindir="$dest$prefix/bin"
test -f "$dest$libdir/headlight/libheadlight-image-io.so" || { echo "no image module under $dest$libdir/headlight"; exit 1; }
"$bindir/headlight" render builtin:cornell --width 16 --height 16 --out "$dest/out" --quiet
"$bindir/headlight" diff "$dest/out/lit.exr" "$dest/out/lit.exr" --quiet
echo "installed CLI wrote $(ls "$dest/out" | wc -l) files and diffed one"

# 5. The thumbnailer and its freedesktop entry, where file managers look for them.
entry="$dest$prefix/share/thumbnailers/headlight.thumbnailer"
test -f "$entry" || { echo "no thumbnailer entry at $entry"; exit 1; }
grep -q '^Exec=headlight-thumbnailer %i %o %s$' "$entry" || { echo "$entry: unexpected Exec line"; exit 1; }
"$bindir/headlight-thumbnailer" builtin:cornell "$dest/thumbnail.png" 64
test -s "$dest/thumbnail.png" || { echo "the installed thumbnailer wrote no PNG"; exit 1; }
echo "installed thumbnailer: $entry and a 64 px thumbnail"
