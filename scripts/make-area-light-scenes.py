#!/usr/bin/env python3
"""Writes scenes lit by area lights (PRESKIN_lights_area, docs/area-lights.md), for
`preskin compare` and the README's pictures:

  sphere_10mm_sphere_light.gltf, sphere_40mm_sphere_light.gltf
      a 10 mm and a 40 mm skin sphere under a sphere light of 20 cm diameter at 1 m, from the
      bundled spheres' key-light direction (3 cd: 3 lux at the sphere, like their key light);
  sphere_10mm_rectangle_light.gltf, sphere_40mm_rectangle_light.gltf
      the same spheres under a 1 m x 0.5 m rectangle at 1 m, facing them (3 cd along its normal);
  sphere_10mm_tube_light.gltf, sphere_10mm_disc_light.gltf
      the 10 mm sphere under a tube (radius 2 cm, length 60 cm) and a disc (radius 25 cm) at 1 m;
  head_softbox.gltf
      the bundled head (its files copied) under a 1 m x 0.5 m soft box 0.8 m to its upper right
      front, the environment at a tenth of its bundled intensity, no directional light (shipped
      as samples/assets/head/head_softbox.gltf);
  head_softbox_point.gltf
      the same with the point light the soft box stands for (the extension removed).

None of these casts shadows: only a directional light casts them in preskin.

Usage: make-area-light-scenes.py OUTDIR   (Python 3 standard library only)
"""
import importlib.util
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "samples", "assets", "spheres"))
import make_spheres  # noqa: E402

# The bundled head's files, copied as make-fidelity-scenes.py copies them.
_spec = importlib.util.spec_from_file_location("fidelity_scenes", os.path.join(ROOT, "scripts", "make-fidelity-scenes.py"))
FIDELITY_SCENES = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(FIDELITY_SCENES)

KEY_TOWARDS_LIGHT = (-0.5, 0.6, 0.65)  # the bundled spheres' key light, reversed


def unit(v):
    length = math.sqrt(sum(x * x for x in v))
    return tuple(x / length for x in v)


def area_light_node(name, towards, distance, centre=(0.0, 0.0, 0.0)):
    """A node `distance` metres from `centre` in direction `towards`, its -Z facing the centre."""
    d = unit(towards)
    return {"name": name, "translation": [centre[k] + distance * d[k] for k in range(3)],
            "rotation": make_spheres.quaternion_from_minus_z_to(tuple(-x for x in d)),
            "extensions": {"KHR_lights_punctual": {"light": 0}}}


def with_area_light(doc, shape, intensity, towards, distance, centre=(0.0, 0.0, 0.0)):
    """Replaces the document's lights with one area light of `shape` (PRESKIN_lights_area fields)."""
    doc["extensions"]["KHR_lights_punctual"] = {"lights": [{
        "name": "area", "type": "point", "color": [1.0, 1.0, 1.0], "intensity": intensity,
        "extensions": {"PRESKIN_lights_area": shape}}]}
    used = doc.setdefault("extensionsUsed", [])
    for name in ("KHR_lights_punctual", "PRESKIN_lights_area"):
        if name not in used:
            used.append(name)
    nodes = [n for n in doc["nodes"] if "KHR_lights_punctual" not in n.get("extensions", {})]
    nodes.append(area_light_node("area", towards, distance, centre))
    doc["nodes"] = nodes
    doc["scenes"][0]["nodes"] = list(range(len(nodes)))
    return doc


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)

    shapes = {
        "sphere_light": {"shape": "sphere", "radius": 0.1},
        "rectangle_light": {"shape": "rectangle", "width": 1.0, "height": 0.5},
        "tube_light": {"shape": "tube", "radius": 0.02, "length": 0.6},
        "disc_light": {"shape": "disc", "radius": 0.25},
    }
    for size, radius in (("10mm", 0.005), ("40mm", 0.020)):
        for kind, shape in shapes.items():
            if size == "40mm" and kind in ("tube_light", "disc_light"):
                continue
            positions, normals, uvs, indices = make_spheres.sphere(radius)
            doc = make_spheres.scene_document("sphere", positions, normals, uvs, indices, (0.0, -1.0, 0.0))
            with_area_light(doc, shape, 3.0, KEY_TOWARDS_LIGHT, 1.0)
            make_spheres.write_document(os.path.join(out, f"sphere_{size}_{kind}.gltf"), doc)

    head = FIDELITY_SCENES.copy_head(out)
    head["extensions"]["PRESKIN_environment"]["intensity"] *= 0.1
    # 1.9 cd over 0.8 m: about 3 lux facing it, like the bundled key light.
    with_area_light(head, {"shape": "rectangle", "width": 1.0, "height": 0.5}, 1.9, (0.6, 0.35, 0.7), 0.8,
                    centre=(0.0, 0.075, 0.0))
    make_spheres.write_document(os.path.join(out, "head_softbox.gltf"), head)
    # The point light the soft box stands for in a viewer without the extension.
    del head["extensions"]["KHR_lights_punctual"]["lights"][0]["extensions"]
    head["extensionsUsed"].remove("PRESKIN_lights_area")
    make_spheres.write_document(os.path.join(out, "head_softbox_point.gltf"), head)


if __name__ == "__main__":
    main()
