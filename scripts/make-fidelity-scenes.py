#!/usr/bin/env python3
"""Writes scenes that `preskin compare` has not been tuned on, to check that the fidelity figures
of the README ("Fidelity") hold beyond the bundled scenes:

  sphere_20mm_side.gltf  a 20 mm skin sphere (a size between the bundled ones) lit from the
                         right and slightly behind, so the terminator crosses the view;
  torus.gltf             a skin torus of tube radius 6 mm around a 10 mm ring radius: convex
                         outside, concave round the 4 mm hole (mean curvature -1/24 per mm on the
                         inner equator), casting shadows on itself, lit from the upper left;
  rod_over_skin.gltf     a skin rod of radius 2 mm lying 1 mm over a skin floor, one mesh (a
                         finger over a palm), lit 30 degrees above the horizon across it: its
                         shadow on the floor begins under its terminator, 1.3 mm up (a curved
                         nearby occluder, for the light its lit side sends into the shadow);
  head_low_left.gltf     the bundled head (its files copied) under a key light from the lower left
                         front instead of the upper right;
  head_below_behind.gltf the head under a key light from below and behind: the ears and nostrils
                         seen from the front lit through (transmission);
  head_grazing.gltf      the head under a key light from above that grazes the forehead (N.L near
                         0.1 there: its terminator band crosses the brow);
  head_studio.gltf       the head under the studio environment alone (no lights: compare takes
                         the environment's strongest light, with its shadow, and the rest as SH);
  sphere_10mm_studio.gltf  the 10 mm sphere under the studio environment alone, no lights (for
                         `compare --trace-environment`).

Usage: make-fidelity-scenes.py OUTDIR   (Python 3 standard library only)
"""
import json
import math
import os
import shutil
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "samples", "assets", "spheres"))
import make_spheres  # noqa: E402


def torus(ring_radius, tube_radius, segments=128, sides=64):
    positions, normals, uvs, indices = [], [], [], []
    for i in range(segments + 1):
        u = 2.0 * math.pi * i / segments
        for j in range(sides + 1):
            v = 2.0 * math.pi * j / sides
            n = (math.cos(v) * math.cos(u), math.sin(v), math.cos(v) * math.sin(u))
            c = (ring_radius * math.cos(u), 0.0, ring_radius * math.sin(u))
            normals += n
            positions += [c[k] + tube_radius * n[k] for k in range(3)]
            uvs += [i / segments, j / sides]
    indices = make_spheres.grid_indices(segments, sides, flip=True)  # counter-clockwise seen from outside
    return positions, normals, uvs, indices


def rod_over_floor(radius, gap, axis_x, half, sides=128, rows=64, cells=64):
    """A rod along Z of `radius` whose underside lies `gap` over a floor (the XZ plane, facing +Y),
    its axis at x = axis_x, both 2 half long and wide: one mesh, metres."""
    positions, normals, uvs, indices = [], [], [], []
    for j in range(cells + 1):  # the floor: counter-clockwise seen from +Y
        for i in range(cells + 1):
            positions += [-half + 2.0 * half * i / cells, 0.0, -half + 2.0 * half * j / cells]
            normals += [0.0, 1.0, 0.0]
            uvs += [i / cells, j / cells]
    indices = make_spheres.grid_indices(cells, cells)
    first = len(positions) // 3
    for i in range(rows + 1):  # the rod: counter-clockwise seen from outside
        z = -half + 2.0 * half * i / rows
        for j in range(sides + 1):
            v = 2.0 * math.pi * j / sides
            n = (math.cos(v), math.sin(v), 0.0)
            positions += [axis_x + radius * n[0], gap + radius + radius * n[1], z]
            normals += n
            uvs += [j / sides, i / rows]
    indices += make_spheres.grid_indices(rows, sides, first, flip=True)
    return positions, normals, uvs, indices


def copy_head(out):
    """Copies the bundled head's files into `out` and returns its glTF document (a dict)."""
    head_dir = os.path.join(ROOT, "samples", "assets", "head")
    with open(os.path.join(head_dir, "head.gltf")) as f:
        head = json.load(f)
    for name in ["head.bin", "Map-COL.jpg", "Map-SPEC.jpg", "Infinite-Level_02_Tangent_SmoothUV.jpg",
                 "studio_small_05_1k.hdr"]:
        shutil.copyfile(os.path.join(head_dir, name), os.path.join(out, name))
    return head


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)

    positions, normals, uvs, indices = make_spheres.sphere(0.010)
    make_spheres.write_document(os.path.join(out, "sphere_20mm_side.gltf"),
                                make_spheres.scene_document("sphere", positions, normals, uvs, indices,
                                                            (-0.9, -0.15, 0.25), albedo=(0.75, 0.55, 0.45)))

    positions, normals, uvs, indices = torus(0.010, 0.006)
    doc = make_spheres.scene_document("torus", positions, normals, uvs, indices, (0.45, -0.8, -0.4),
                                      albedo=(0.85, 0.62, 0.52))
    # Tilted towards the camera (+Z) so the hole and the inner wall are in view.
    doc["nodes"][0]["rotation"] = [math.sin(0.5 * 0.9), 0.0, 0.0, math.cos(0.5 * 0.9)]
    make_spheres.write_document(os.path.join(out, "torus.gltf"), doc)

    positions, normals, uvs, indices = rod_over_floor(0.002, 0.001, -0.004, 0.02)
    make_spheres.write_document(os.path.join(out, "rod_over_skin.gltf"),
                                make_spheres.scene_document("rod_over_skin", positions, normals, uvs, indices,
                                                            (math.cos(math.radians(30.0)), -0.5, 0.0)))

    head = copy_head(out)
    for node in head["nodes"]:
        if node.get("name") == "key":
            node["rotation"] = make_spheres.quaternion_from_minus_z_to(
                tuple(x / math.sqrt(0.7 ** 2 + 0.45 ** 2 + 0.55 ** 2) for x in (0.7, 0.45, -0.55)))
    make_spheres.write_document(os.path.join(out, "head_low_left.gltf"), head)

    # The same head under other single key lights (directions the light travels, world +Y up, the
    # camera at +Z), and under its environment alone.
    for name, travel in [("head_below_behind.gltf", (-0.2, 0.6, 0.75)), ("head_grazing.gltf", (-0.1, -0.97, 0.2))]:
        head = copy_head(out)
        length = math.sqrt(sum(x * x for x in travel))
        for node in head["nodes"]:
            if node.get("name") == "key":
                node["rotation"] = make_spheres.quaternion_from_minus_z_to(tuple(x / length for x in travel))
        make_spheres.write_document(os.path.join(out, name), head)
    head = copy_head(out)
    lit = [i for i, node in enumerate(head["nodes"]) if "KHR_lights_punctual" in node.get("extensions", {})]
    head["nodes"] = [node for i, node in enumerate(head["nodes"]) if i not in lit]
    head["extensions"].pop("KHR_lights_punctual", None)
    head["extensionsUsed"] = [e for e in head["extensionsUsed"] if e != "KHR_lights_punctual"]
    renumber = {old: new for new, old in enumerate(i for i in range(len(head["nodes"]) + len(lit)) if i not in lit)}
    for scene in head["scenes"]:
        scene["nodes"] = [renumber[i] for i in scene["nodes"] if i in renumber]
    for node in head["nodes"]:
        if "children" in node:
            node["children"] = [renumber[i] for i in node["children"] if i in renumber]
    make_spheres.write_document(os.path.join(out, "head_studio.gltf"), head)

    # The bundled 10 mm sphere under the studio environment alone (no lights): what the skin's SH
    # ambient gives against the traced environment (`preskin compare --trace-environment`).
    positions, normals, uvs, indices = make_spheres.sphere(0.005)
    doc = make_spheres.scene_document("sphere", positions, normals, uvs, indices, (0.0, -1.0, 0.0))
    del doc["extensions"]["KHR_lights_punctual"]
    doc["extensionsUsed"] = ["PRESKIN_materials_skin", "PRESKIN_environment"]
    doc["extensions"]["PRESKIN_environment"] = {"uri": "studio_small_05_1k.hdr", "intensity": 1.0}
    doc["nodes"] = doc["nodes"][:1]
    doc["scenes"][0]["nodes"] = [0]
    make_spheres.write_document(os.path.join(out, "sphere_10mm_studio.gltf"), doc)


if __name__ == "__main__":
    main()
