#!/usr/bin/env python3
"""A glTF of one cube mesh (12 triangles) placed by N nodes in a grid: the
many-instances case of docs/BENCHMARKS.md ("Instanced drawing").

    tools/make_instanced_grid.py 100000 > cubes.gltf
"""
import base64
import json
import struct
import sys

count = int(sys.argv[1]) if len(sys.argv) > 1 else 100000
corners = [(x, y, z) for z in (-.5, .5) for y in (-.5, .5) for x in (-.5, .5)]
faces = [0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 1, 3, 7, 1, 7, 5, 0, 4, 6, 0, 6, 2]
data = b"".join(struct.pack("<3f", *c) for c in corners) + b"".join(struct.pack("<H", i) for i in faces)
side = round(count ** (1 / 3)) + 1
nodes = [{"mesh": 0, "translation": [2.0 * (i % side), 2.0 * (i // side % side), 2.0 * (i // side // side)]}
         for i in range(count)]
json.dump({
    "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(count))}], "nodes": nodes,
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96}, {"buffer": 0, "byteOffset": 96, "byteLength": 72}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [-.5] * 3, "max": [.5] * 3},
                  {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}],
}, sys.stdout)
