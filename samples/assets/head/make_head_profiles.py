#!/usr/bin/env python3
"""Writes head_profiles.gltf next to this script: four copies of the bundled head (head.gltf: the
same buffer head.bin, textures, light and environment) side by side along +X, each with its own
copy of the skin material naming one diffusion profile of the root PRESKIN_materials_skin
extension, to show several profiles in one scene (docs/profiles.md):
  0 d'Eon & Luebke's skin (the bundled default),
  1 Christensen & Burley, wide and translucent (long red mean free path),
  2 Christensen & Burley, short mean free paths (narrow scattering),
  3 a sum of two Gaussians, broad in every channel.
The camera "front" frames all four heads.

Usage: make_head_profiles.py   (Python 3, no other packages)
"""
import copy
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
SPACING_M = 0.34

PROFILES = [
    {"name": "d'Eon & Luebke", "type": "deonLuebke"},
    {"name": "Burley, translucent", "type": "normalizedDiffusion",
     "albedo": [0.9, 0.7, 0.6], "meanFreePathMm": [4.0, 1.6, 0.8]},
    {"name": "Burley, dense", "type": "normalizedDiffusion",
     "albedo": [0.6, 0.4, 0.3], "meanFreePathMm": [0.6, 0.25, 0.12]},
    {"name": "two Gaussians, broad", "type": "sumOfGaussians",
     "gaussians": [{"varianceMm2": 0.5, "weights": [0.3, 0.5, 0.7]},
                   {"varianceMm2": 6.0, "weights": [0.7, 0.5, 0.3]}]},
]


def main():
    with open(os.path.join(HERE, "head.gltf")) as f:
        head = json.load(f)
    out = copy.deepcopy(head)
    mesh = head["meshes"][0]
    material = head["materials"][0]
    out["meshes"], out["materials"] = [], []
    head_node = next(n for n in head["nodes"] if n.get("mesh") == 0)
    others = [n for n in head["nodes"] if n.get("mesh") is None]
    out["nodes"] = []
    for i in range(len(PROFILES)):
        m = copy.deepcopy(material)
        m["name"] = "skin, " + PROFILES[i]["name"]
        m["extensions"]["PRESKIN_materials_skin"]["profile"] = i
        out["materials"].append(m)
        me = copy.deepcopy(mesh)
        me["name"] = "%s %d" % (mesh["name"], i)
        me["primitives"][0]["material"] = i
        out["meshes"].append(me)
        node = copy.deepcopy(head_node)
        node["name"] = "%s %d" % (head_node.get("name", "head"), i)
        node["mesh"] = i
        node["translation"] = [(i - (len(PROFILES) - 1) / 2.0) * SPACING_M, 0.0, 0.0]
        out["nodes"].append(node)
    for n in others:
        n = copy.deepcopy(n)
        if "camera" in n:
            n["translation"] = [0.0, 0.02, 1.05]
        out["nodes"].append(n)
    out["scenes"] = [{"nodes": list(range(len(out["nodes"])))}]
    out["extensions"]["PRESKIN_materials_skin"] = {"profiles": PROFILES}
    with open(os.path.join(HERE, "head_profiles.gltf"), "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
