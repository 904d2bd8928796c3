#!/usr/bin/env python3
"""Writes tube.gltf + tube.bin next to this script: a small open tube skinned to two joints that
bends from 0 to 90 degrees over its one animation, for tests of skinning and of curvature after
deformation.

Geometry: a cylinder of radius RADIUS_M along +Y from y = 0 to LENGTH_M, RINGS rings of SEGMENTS
vertices (one extra seam column so u runs 0..1), outward normals, tangents along +u, no caps.
Skin: joint 0 "root" at the origin, joint 1 "bend" at y = LENGTH_M / 2 (a child of root). Weights
blend along the length: w_bend = smoothstep(BLEND_START, BLEND_END, y / LENGTH_M), w_root = 1 - w_bend;
inverse bind matrices are the inverses of the joints' rest world transforms.
Animation "bend": the bend joint turns about +Z from 0 to 90 degrees between 0 and 1 s (LINEAR,
keys every 0.25 s, so slerp is exercised between unequal neighbours), so at 1 s the upper half
points along -X.
Usage: make_tube_gltf.py   (Python 3 standard library only)
"""
import json
import math
import os
import struct

RADIUS_M = 0.05
LENGTH_M = 1.0
RINGS = 17
SEGMENTS = 12
BLEND_START, BLEND_END = 0.35, 0.65
BEND_KEYS_S = [0.0, 0.25, 0.5, 0.75, 1.0]
BEND_ANGLE = math.pi / 2


def smoothstep(e0, e1, x):
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


def main():
    out_dir = os.path.dirname(os.path.abspath(__file__))
    positions, normals, tangents, uvs, joints, weights = [], [], [], [], [], []
    for r in range(RINGS):
        v = r / (RINGS - 1)
        y = v * LENGTH_M
        w_bend = smoothstep(BLEND_START, BLEND_END, v)
        for s in range(SEGMENTS + 1):
            u = s / SEGMENTS
            a = 2.0 * math.pi * u
            n = (math.sin(a), 0.0, math.cos(a))
            positions.append((RADIUS_M * n[0], y, RADIUS_M * n[2]))
            normals.append(n)
            tangents.append((math.cos(a), 0.0, -math.sin(a), 1.0))
            uvs.append((u, 1.0 - v))
            used = [(j, w) for j, w in ((0, 1.0 - w_bend), (1, w_bend)) if w > 0.0]  # unused slots: joint 0, weight 0
            used += [(0, 0.0)] * (4 - len(used))
            joints.append(tuple(j for j, _ in used))
            weights.append(tuple(w for _, w in used))
    columns = SEGMENTS + 1
    indices = []
    for r in range(RINGS - 1):
        for s in range(SEGMENTS):
            a, b = r * columns + s, r * columns + s + 1
            c, d = a + columns, b + columns
            indices += [a, b, d, a, d, c]  # counter-clockwise seen from outside

    # Animation: rotation of the bend joint about +Z, x y z w.
    rotations = []
    for t in BEND_KEYS_S:
        half = 0.5 * BEND_ANGLE * t / BEND_KEYS_S[-1]
        rotations.append((0.0, 0.0, math.sin(half), math.cos(half)))
    bend_y = 0.5 * LENGTH_M
    inverse_binds = [
        [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1],
        [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -bend_y, 0, 1],
    ]

    blob = bytearray()
    views = []

    def add(fmt, rows, target=None):
        while len(blob) % 4:
            blob.append(0)
        flat = [c for row in rows for c in (row if isinstance(row, (list, tuple)) else [row])]
        data = struct.pack("<%d%s" % (len(flat), fmt), *flat)
        view = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
        if target:
            view["target"] = target
        views.append(view)
        blob.extend(data)
        return len(views) - 1

    n = len(positions)
    pmin = [min(p[k] for p in positions) for k in range(3)]
    pmax = [max(p[k] for p in positions) for k in range(3)]
    accessors = [
        {"bufferView": add("f", positions, 34962), "componentType": 5126, "count": n, "type": "VEC3",
         "min": pmin, "max": pmax},
        {"bufferView": add("f", normals, 34962), "componentType": 5126, "count": n, "type": "VEC3"},
        {"bufferView": add("f", tangents, 34962), "componentType": 5126, "count": n, "type": "VEC4"},
        {"bufferView": add("f", uvs, 34962), "componentType": 5126, "count": n, "type": "VEC2"},
        {"bufferView": add("B", joints, 34962), "componentType": 5121, "count": n, "type": "VEC4"},
        {"bufferView": add("f", weights, 34962), "componentType": 5126, "count": n, "type": "VEC4"},
        {"bufferView": add("H", indices, 34963), "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        {"bufferView": add("f", inverse_binds), "componentType": 5126, "count": 2, "type": "MAT4"},
        {"bufferView": add("f", BEND_KEYS_S), "componentType": 5126, "count": len(BEND_KEYS_S), "type": "SCALAR",
         "min": [BEND_KEYS_S[0]], "max": [BEND_KEYS_S[-1]]},
        {"bufferView": add("f", rotations), "componentType": 5126, "count": len(rotations), "type": "VEC4"},
    ]
    while len(blob) % 4:
        blob.append(0)

    gltf = {
        "asset": {"version": "2.0", "generator": "preskin make_tube_gltf.py"},
        "scene": 0,
        "scenes": [{"name": "tube", "nodes": [0, 1]}],
        "nodes": [
            {"name": "tube", "mesh": 0, "skin": 0},
            {"name": "root", "children": [2]},
            {"name": "bend", "translation": [0.0, bend_y, 0.0]},
        ],
        "meshes": [{"name": "tube", "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1, "TANGENT": 2, "TEXCOORD_0": 3, "JOINTS_0": 4, "WEIGHTS_0": 5},
            "indices": 6, "material": 0}]}],
        "materials": [{"name": "tube", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.55, 0.45, 1.0],
                                                                "metallicFactor": 0.0, "roughnessFactor": 0.5}}],
        "skins": [{"name": "tube", "joints": [1, 2], "inverseBindMatrices": 7, "skeleton": 1}],
        "animations": [{"name": "bend",
                        "samplers": [{"input": 8, "output": 9, "interpolation": "LINEAR"}],
                        "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}}]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"uri": "tube.bin", "byteLength": len(blob)}],
    }
    with open(os.path.join(out_dir, "tube.bin"), "wb") as f:
        f.write(blob)
    with open(os.path.join(out_dir, "tube.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    print(f"{n} vertices, {len(indices) // 3} triangles, {len(blob)} bytes of buffer")


if __name__ == "__main__":
    main()
