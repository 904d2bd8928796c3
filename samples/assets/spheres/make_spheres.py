#!/usr/bin/env python3
"""Writes the sphere scenes of samples/assets/spheres: a skin sphere of 10 mm and one of 40 mm
diameter (UV spheres, 64 segments x 32 rings, exact normals, metres), constant albedo, lit by one
shadow-casting directional light from the upper left front, no environment (so the renderer's
default dim grey ambient unless --env-intensity 0). `preskin compare` measures the skin path on
them (README, "Fidelity"). Python 3 standard library only.

Usage: make_spheres.py   (writes next to this script)
"""
import base64
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
SEGMENTS, RINGS = 64, 32


def grid_indices(rows, columns, first=0, flip=False):
    """Two triangles per cell of a (rows + 1) x (columns + 1) vertex grid, row-major from vertex
    `first`: counter-clockwise when a row's next vertex and the next row's span the outside
    (`flip` reverses the winding)."""
    indices = []
    for r in range(rows):
        for s in range(columns):
            a = first + r * (columns + 1) + s
            b = a + columns + 1
            indices += [a, a + 1, b, b, a + 1, b + 1] if flip else [a, b, a + 1, a + 1, b, b + 1]
    return indices


def sphere(radius):
    positions, normals, uvs, indices = [], [], [], []
    for r in range(RINGS + 1):
        theta = math.pi * r / RINGS
        for s in range(SEGMENTS + 1):
            phi = 2.0 * math.pi * s / SEGMENTS
            n = (math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi))
            normals += n
            positions += [c * radius for c in n]
            uvs += [s / SEGMENTS, r / RINGS]
    indices = grid_indices(RINGS, SEGMENTS)  # counter-clockwise seen from outside
    return positions, normals, uvs, indices


def quaternion_from_minus_z_to(d):
    """Rotation taking the light's local -Z onto direction d (unit)."""
    a = (0.0, 0.0, -1.0)
    axis = (a[1] * d[2] - a[2] * d[1], a[2] * d[0] - a[0] * d[2], a[0] * d[1] - a[1] * d[0])
    dot = sum(x * y for x, y in zip(a, d))
    w = 1.0 + dot
    q = (axis[0], axis[1], axis[2], w)
    norm = math.sqrt(sum(x * x for x in q))
    return [x / norm for x in q]


def scene_document(name, positions, normals, uvs, indices, light_direction, albedo=(0.8, 0.6, 0.5)):
    """A glTF document (dict) of one skin mesh (metres) lit by one shadow-casting directional
    light travelling along light_direction."""
    count = len(positions) // 3
    blob = struct.pack(f"<{len(positions)}f", *positions)
    blob += struct.pack(f"<{len(normals)}f", *normals)
    blob += struct.pack(f"<{len(uvs)}f", *uvs)
    blob += struct.pack(f"<{len(indices)}I", *indices)
    offsets = [0, 12 * count, 24 * count, 32 * count]
    lo = [min(positions[i::3]) for i in range(3)]
    hi = [max(positions[i::3]) for i in range(3)]
    length = math.sqrt(sum(x * x for x in light_direction))
    d = tuple(x / length for x in light_direction)
    return {
        "asset": {"version": "2.0", "generator": "preskin make_spheres.py"},
        "extensionsUsed": ["KHR_lights_punctual", "PRESKIN_materials_skin"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "key", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 3.0,
             "extras": {"castsShadow": True}}]}},
        "buffers": [{"uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode(),
                     "byteLength": len(blob)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": offsets[0], "byteLength": 12 * count},
            {"buffer": 0, "byteOffset": offsets[1], "byteLength": 12 * count},
            {"buffer": 0, "byteOffset": offsets[2], "byteLength": 8 * count},
            {"buffer": 0, "byteOffset": offsets[3], "byteLength": 4 * len(indices)},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": count, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": count, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
        ],
        "materials": [{
            "name": "skin",
            "pbrMetallicRoughness": {"baseColorFactor": [albedo[0], albedo[1], albedo[2], 1.0], "metallicFactor": 0.0,
                                     "roughnessFactor": 0.5},
            "extensions": {"PRESKIN_materials_skin": {}},
        }],
        "meshes": [{"name": name, "primitives": [
            {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
        "nodes": [{"name": name, "mesh": 0},
                  {"name": "key", "rotation": quaternion_from_minus_z_to(d),
                   "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "scenes": [{"name": name, "nodes": [0, 1]}],
        "scene": 0,
    }


def write_document(path, doc):
    with open(path, "w") as f:
        f.write(json.dumps(doc, indent=1) + "\n")


def write_scene(name, diameter_m):
    positions, normals, uvs, indices = sphere(0.5 * diameter_m)
    doc = scene_document("sphere", positions, normals, uvs, indices, (0.8, -0.35, -0.5))
    doc["scenes"][0]["name"] = name
    write_document(os.path.join(HERE, name + ".gltf"), doc)


if __name__ == "__main__":
    write_scene("sphere_10mm", 0.010)
    write_scene("sphere_40mm", 0.040)
