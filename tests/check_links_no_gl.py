#!/usr/bin/env python3
"""Checks that a linked program has no GL in it: no GL, EGL, GLX, OSMesa or
GBM library among its direct dependencies (readelf -d, NEEDED) and no glad,
EGL or OSMesa symbol (nm). Exits 0 when clean, 1 naming what it found.
Used by tests/meson.build on the unit program (which must be clean) and on
the gl program (which must not be, to show the check can fail).

Direct dependencies only, as the link line has them: `ldd` also lists
libGLX, which Debian's OpenImageIO (linked by the diff tests to write their
images) reaches through OpenCV; that is OpenImageIO's, not a GL of ours.
"""
import re
import subprocess
import sys

GL_LIBRARY = re.compile(r"^lib(GL|EGL|GLX|GLdispatch|OpenGL|OSMesa|gbm)\b")
GL_SYMBOL = re.compile(r"^(glad|GLAD_|egl[A-Z]|OSMesa)")


def needed(program):
    dynamic = subprocess.run(["readelf", "-d", program], check=True, capture_output=True, text=True).stdout
    return re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", dynamic)


def symbols(program):
    table = subprocess.run(["nm", "--defined-only", program], check=True, capture_output=True, text=True).stdout
    undefined = subprocess.run(["nm", "-D", "--undefined-only", program], check=True, capture_output=True, text=True)
    table += undefined.stdout
    return [line.split()[-1] for line in table.splitlines() if line.split()]


program = sys.argv[1]
libraries = [name for name in needed(program) if GL_LIBRARY.match(name)]
gl_symbols = sorted({name for name in symbols(program) if GL_SYMBOL.match(name)})
for name in libraries:
    print(f"{program}: links {name}")
if gl_symbols:
    print(f"{program}: holds {len(gl_symbols)} GL symbols, e.g. {', '.join(gl_symbols[:5])}")
if libraries or gl_symbols:
    sys.exit(1)
print(f"{program}: no GL library, no glad, EGL or OSMesa symbol")
