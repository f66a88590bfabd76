#!/usr/bin/env python3
"""Writes a Cornell box as one self-contained .gltf (buffer embedded as a data
URI), so headlight and other viewers (F3D) can render the same file in
tools/bench_batch.sh. The layout follows builtin:cornell: x -1..1, y 0..2,
z -1..1, open at +Z, red wall at -X, green at +X, two blocks, a ceiling light.
Usage: make_cornell_gltf.py OUT.gltf"""
import base64
import json
import struct
import sys


def quad(p0, p1, p2, p3, n):
    return [p0, p1, p2, p3], [n] * 4, [0, 1, 2, 0, 2, 3]


def box(cx, cz, sx, sy, sz):
    """An axis-aligned block standing on the floor: five visible faces + bottom."""
    x0, x1, y0, y1, z0, z1 = cx - sx, cx + sx, 0.0, sy, cz - sz, cz + sz
    faces = [
        quad((x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0), (0, 1, 0)),
        quad((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1), (0, 0, 1)),
        quad((x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (0, 0, -1)),
        quad((x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (1, 0, 0)),
        quad((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0), (-1, 0, 0)),
    ]
    return faces


def main(out):
    parts = {  # material -> list of faces
        "white": [
            quad((-1, 0, 1), (1, 0, 1), (1, 0, -1), (-1, 0, -1), (0, 1, 0)),  # floor
            quad((-1, 2, -1), (1, 2, -1), (1, 2, 1), (-1, 2, 1), (0, -1, 0)),  # ceiling
            quad((-1, 0, -1), (1, 0, -1), (1, 2, -1), (-1, 2, -1), (0, 0, 1)),  # back
        ] + box(0.33, 0.3, 0.3, 0.6, 0.3) + box(-0.35, -0.3, 0.3, 1.2, 0.3),
        "red": [quad((-1, 0, 1), (-1, 0, -1), (-1, 2, -1), (-1, 2, 1), (1, 0, 0))],
        "green": [quad((1, 0, -1), (1, 0, 1), (1, 2, 1), (1, 2, -1), (-1, 0, 0))],
    }
    colours = {"white": [0.73, 0.73, 0.73, 1], "red": [0.63, 0.065, 0.05, 1], "green": [0.14, 0.45, 0.091, 1]}
    blob = bytearray()
    gltf = {"asset": {"version": "2.0", "generator": "headlight tools/make_cornell_gltf.py"},
            "extensionsUsed": ["KHR_lights_punctual"],
            "extensions": {"KHR_lights_punctual": {"lights": [
                {"type": "point", "color": [1, 0.85, 0.7], "intensity": 4.0}]}},
            "scene": 0, "scenes": [{"nodes": [0, 1]}],
            "nodes": [{"mesh": 0}, {"translation": [0, 1.9, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
            "meshes": [{"primitives": []}], "materials": [], "accessors": [], "bufferViews": []}
    for name, faces in parts.items():
        positions, normals, indices = [], [], []
        for ps, ns, ids in faces:
            base = len(positions)
            positions += ps
            normals += ns
            indices += [base + i for i in ids]
        for data, fmt, target, kind, extra in (
                (positions, "3f", 34962, "VEC3", True), (normals, "3f", 34962, "VEC3", False),
                (indices, "I", 34963, "SCALAR", False)):
            offset = len(blob)
            for item in data:
                blob += struct.pack("<" + fmt, *(item if isinstance(item, (list, tuple)) else [item]))
            gltf["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob) - offset,
                                        "target": target})
            accessor = {"bufferView": len(gltf["bufferViews"]) - 1, "componentType": 5126 if fmt == "3f" else 5125,
                        "count": len(data), "type": kind}
            if extra:
                accessor["min"] = [min(p[i] for p in data) for i in range(3)]
                accessor["max"] = [max(p[i] for p in data) for i in range(3)]
            gltf["accessors"].append(accessor)
            while len(blob) % 4:
                blob += b"\0"
        a = len(gltf["accessors"])
        gltf["materials"].append({"name": "cornell " + name, "pbrMetallicRoughness": {
            "baseColorFactor": colours[name], "metallicFactor": 0.0, "roughnessFactor": 0.9}})
        gltf["meshes"][0]["primitives"].append({"attributes": {"POSITION": a - 3, "NORMAL": a - 2}, "indices": a - 1,
                                                "material": len(gltf["materials"]) - 1})
    gltf["buffers"] = [{"byteLength": len(blob),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}]
    with open(out, "w") as f:
        json.dump(gltf, f)


if __name__ == "__main__":
    main(sys.argv[1])
