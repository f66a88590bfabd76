#!/usr/bin/env python3
"""Checks that the library's rooms (the folders of lib/) include only rooms
on their own floor or below: each quoted include of a file in lib/ that
names another room ("gltf/loader.hpp" from lib/scene/) must name a room
listed before its own in FLOORS. Exits 0 when clean, 1 naming each include
that reaches up, and 2 for a room FLOORS does not list.

  check_include_layers.py SOURCE_ROOT        # checks lib/
  check_include_layers.py SOURCE_ROOT --self-test   # must find a planted upward include

The public headers (lib/include/headlight/) sit below every room; glsl/'s
shared_layout.h is included bare and is not a room.
"""
import pathlib
import re
import sys

# The ground floor first. A room may include the rooms before it.
FLOORS = [
    "io",           # bounded reads, atomic files, fingerprints, folder locks, bounded JSON
    "color",        # sRGB transfer functions
    "settings",     # the settings table
    "scene",        # the scene model, built-in scenes, cameras, limits
    "context",      # EGL and OSMesa contexts
    "gl",           # GL objects, readback, the scene's upload; gpu_format.hpp is GL-free
    "frame",        # the frame plan, GL-free
    "environment",  # equirect and prefilter maths
    "diff",         # FLIP and thresholds
    "output",       # frame sets: manifest and names
    "image_io",     # the OpenImageIO module (dlopen) and its loader
    "gltf",         # the importers: glTF and the environment map file
    "reference",    # the Embree tracer
    "passes",       # the GPU passes
    "renderer",     # lib/renderer.cpp
    "tooling",      # the tools' support library
]
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)


def room_of(path, lib):
    parts = path.relative_to(lib).parts
    return "renderer" if len(parts) == 1 else parts[0]


def upward_includes(lib, extra=()):
    problems, unknown = [], set()
    files = [p for p in sorted(lib.rglob("*")) if p.suffix in (".cpp", ".hpp", ".h") and "include" not in p.parts[:2]]
    sources = [(p, p.read_text(errors="replace")) for p in files] + list(extra)
    for path, text in sources:
        if path.relative_to(lib).parts[0] == "include":
            continue
        room = room_of(path, lib)
        if room not in FLOORS:
            unknown.add(room)
            continue
        for included in INCLUDE.findall(text):
            target = included.split("/")[0]
            if "/" not in included or target == "headlight" or target == room:
                continue
            if target not in FLOORS:
                unknown.add(target)
            elif FLOORS.index(target) > FLOORS.index(room):
                problems.append(f"{path.relative_to(lib.parent)}: includes {included}: {room} sits below {target}")
    return problems, unknown


def main():
    lib = pathlib.Path(sys.argv[1]) / "lib"
    extra = ()
    if "--self-test" in sys.argv:
        extra = [(lib / "io" / "planted.cpp", '#include "gltf/loader.hpp"\n')]
    problems, unknown = upward_includes(lib, extra)
    if unknown:
        print("rooms not in FLOORS (tests/check_include_layers.py): " + ", ".join(sorted(unknown)))
        return 2
    for problem in problems:
        print(problem)
    if "--self-test" in sys.argv:
        return 0 if problems else 1
    print(f"{len(FLOORS)} rooms, no include reaches up" if not problems else f"{len(problems)} includes reach up")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
