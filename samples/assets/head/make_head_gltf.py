#!/usr/bin/env python3
"""Converts the Lee Perry-Smith head scan (three.js's LeePerrySmith.glb) into preskin's bundled
sample scene: head.gltf + head.bin next to this script.

What it changes (see CREDITS.md):
  * positions scaled to metres: one source unit = METRES_PER_UNIT metres. Measured on the scan:
    chin (menton) to crown 4.7 units, head breadth above the ears 3.16 units, glabella to back of
    the head 4.19 units; adult male means of about 0.232 m, 0.155 m and 0.197 m give 0.049, 0.049
    and 0.047 m per unit, so 0.048.
  * V flipped to glTF's convention (v = 0 at the top row of the image): v' = 1 - v.
  * normals kept (a uniform scale leaves them unchanged); no tangents (preskin builds them at load).
  * the textures that ship with the scan are referenced (the source .glb references none):
    Map-COL.jpg as base colour, Infinite-Level_02_Tangent_SmoothUV.jpg as the normal map and
    Map-SPEC.jpg as the skin specular map (PRESKIN_materials_skin, docs/gltf-extensions.md).
  * a directional key light (KHR_lights_punctual, 3 lux, shadow-casting via extras.castsShadow)
    from the upper front-left, a camera 0.7 m in front of the face, close-up cameras of the nose
    and cheek, the lips and the ear, and the studio environment (PRESKIN_environment) are added.
The source's empty Camera/Lamp nodes (its scene 1) are dropped.

Usage: make_head_gltf.py SOURCE.glb [--hdr studio_small_05_1k.hdr]
The source folder must also hold the three JPEGs and the license files; they are copied next to
the output, as is the environment (and the LICENSE.txt beside it) when --hdr is given.
Python 3 standard library only.
"""
import json
import math
import os
import shutil
import struct
import sys

METRES_PER_UNIT = 0.048
TEXTURES = ["Map-COL.jpg", "Infinite-Level_02_Tangent_SmoothUV.jpg", "Map-SPEC.jpg"]
LICENSE_FILES = ["LICENSE.txt", "LeePerrySmith_License.txt"]
ENVIRONMENT = "studio_small_05_1k.hdr"
ENVIRONMENT_LICENSE = "studio_small_05_1k.LICENSE.txt"

COMPONENT_FORMATS = {5121: "B", 5123: "H", 5125: "I", 5126: "f"}
TYPE_SIZES = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


def read_glb(path):
    data = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    if magic != b"glTF" or version != 2 or length != len(data):
        sys.exit(f"{path}: not a glTF 2.0 binary")
    offset = 12
    doc, binary = None, b""
    while offset + 8 <= length:
        chunk_length, chunk_type = struct.unpack_from("<II", data, offset)
        chunk = data[offset + 8: offset + 8 + chunk_length]
        if chunk_type == 0x4E4F534A:
            doc = json.loads(chunk)
        elif chunk_type == 0x004E4942:
            binary = chunk
        offset += 8 + chunk_length
    if doc is None:
        sys.exit(f"{path}: no JSON chunk")
    return doc, binary


def read_accessor(doc, binary, index):
    accessor = doc["accessors"][index]
    view = doc["bufferViews"][accessor["bufferView"]]
    components = TYPE_SIZES[accessor["type"]]
    fmt = COMPONENT_FORMATS[accessor["componentType"]]
    size = struct.calcsize("<" + fmt)
    stride = view.get("byteStride", size * components)
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    values = []
    for i in range(accessor["count"]):
        element = struct.unpack_from(f"<{components}{fmt}", binary, start + i * stride)
        values.append(element if components > 1 else element[0])
    return values


def normalize(v):
    length = math.sqrt(sum(c * c for c in v))
    return [c / length for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def quaternion_looking_along(forward, up=(0.0, 1.0, 0.0)):
    """Unit quaternion (x, y, z, w) rotating the node's -Z axis onto `forward` (+Y towards `up`)."""
    z_axis = normalize([-c for c in forward])
    x_axis = normalize(cross(up, z_axis))
    y_axis = cross(z_axis, x_axis)
    m = [[x_axis[r], y_axis[r], z_axis[r]] for r in range(3)]  # columns are the axes
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0.0:
        s = 0.5 / math.sqrt(trace + 1.0)
        q = [(m[2][1] - m[1][2]) * s, (m[0][2] - m[2][0]) * s, (m[1][0] - m[0][1]) * s, 0.25 / s]
    else:
        i = max(range(3), key=lambda k: m[k][k])
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * math.sqrt(1.0 + m[i][i] - m[j][j] - m[k][k])
        q = [0.0, 0.0, 0.0, (m[k][j] - m[j][k]) / s]
        q[i] = 0.25 * s
        q[j] = (m[j][i] + m[i][j]) / s
        q[k] = (m[k][i] + m[i][k]) / s
    return normalize(q)


def main(argv):
    if len(argv) not in (2, 4) or (len(argv) == 4 and argv[2] != "--hdr"):
        sys.exit(__doc__)
    source = argv[1]
    source_dir = os.path.dirname(os.path.abspath(source))
    out_dir = os.path.dirname(os.path.abspath(__file__))
    doc, binary = read_glb(source)

    primitive = doc["meshes"][0]["primitives"][0]
    positions = read_accessor(doc, binary, primitive["attributes"]["POSITION"])
    normals = read_accessor(doc, binary, primitive["attributes"]["NORMAL"])
    uvs = read_accessor(doc, binary, primitive["attributes"]["TEXCOORD_0"])
    indices = read_accessor(doc, binary, primitive["indices"])

    positions = [[c * METRES_PER_UNIT for c in p] for p in positions]
    uvs = [[u, 1.0 - v] for (u, v) in uvs]
    vertex_count = len(positions)

    blob = bytearray()
    views = []

    def add_view(payload, target):
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(payload),
                      "target": target})
        blob.extend(payload)
        return len(views) - 1

    flat = lambda rows: [c for row in rows for c in row]
    position_view = add_view(struct.pack(f"<{3 * vertex_count}f", *flat(positions)), 34962)
    normal_view = add_view(struct.pack(f"<{3 * vertex_count}f", *flat(normals)), 34962)
    uv_view = add_view(struct.pack(f"<{2 * vertex_count}f", *flat(uvs)), 34962)
    index_view = add_view(struct.pack(f"<{len(indices)}H", *indices), 34963)
    while len(blob) % 4:
        blob.append(0)

    # float32 bounds, as the GPU will see them
    stored = struct.unpack(f"<{3 * vertex_count}f", blob[0:12 * vertex_count])
    pmin = [min(stored[k::3]) for k in range(3)]
    pmax = [max(stored[k::3]) for k in range(3)]

    # Camera 0.7 m in front of the face (the face looks toward +Z), aimed level at the head.
    head_centre_y = 0.075
    camera_position = [0.0, head_centre_y, 0.7]
    # Key light from the upper front-left (seen from the camera) so the face has a terminator and
    # the nose shadows the cheek.
    light_travel = normalize([0.6, -0.55, -0.58])

    # Close-up cameras for measuring skin where people look (docs/fidelity.md), each framing about
    # 60 to 90 mm, so 768 pixels give 8 to 13 pixels per mm: the nose and the cheek its shadow
    # falls on (from the front right, the shadowed side), the lips, and the lit ear from the side.
    def close_up(name, target, from_direction, distance, frame_height):
        offset = [c * distance for c in normalize(from_direction)]
        position = [t + o for t, o in zip(target, offset)]
        return ({"name": name, "translation": position,
                 "rotation": quaternion_looking_along([-o for o in offset]), "camera": len(cameras)},
                {"name": name, "type": "perspective",
                 "perspective": {"yfov": 2.0 * math.atan(0.5 * frame_height / distance), "znear": 0.02,
                                 "zfar": 10.0}})
    cameras = [{"name": "front", "type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.05, "zfar": 10.0}}]
    camera_nodes = [{"name": "front", "translation": camera_position, "camera": 0}]
    for name, target, from_direction, distance, frame_height in [
            ("cheek_nose", [0.03, 0.05, 0.08], [0.45, 0.1, 1.0], 0.25, 0.09),
            ("lips", [0.0, 0.03, 0.1], [0.15, -0.05, 1.0], 0.2, 0.06),
            ("ear", [-0.082, 0.07, 0.0], [-1.0, 0.05, 0.3], 0.25, 0.09)]:
        node, camera = close_up(name, target, from_direction, distance, frame_height)
        camera_nodes.append(node)
        cameras.append(camera)

    gltf = {
        "asset": {"version": "2.0", "generator": "preskin make_head_gltf.py",
                  "copyright": "\"Infinite, 3D Head Scan\" by Lee Perry-Smith (Infinite-Realities), "
                               "CC BY 3.0; converted for preskin (see CREDITS.md)"},
        "extensionsUsed": ["KHR_lights_punctual", "PRESKIN_materials_skin", "PRESKIN_environment"],
        "extensions": {
            "KHR_lights_punctual": {"lights": [{
                "name": "key", "type": "directional", "color": [1.0, 0.96, 0.92], "intensity": 3.0,
                "extras": {"castsShadow": True}}]},
            "PRESKIN_environment": {"uri": ENVIRONMENT, "intensity": 0.5, "rotation": 4.712389},
        },
        "scene": 0,
        "scenes": [{"name": "head", "nodes": list(range(2 + len(camera_nodes)))}],
        "nodes": [
            {"name": "LeePerrySmith", "mesh": 0},
            {"name": "key", "rotation": quaternion_looking_along(light_travel),
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
        ] + camera_nodes,
        "cameras": cameras,
        "meshes": [{"name": "LeePerrySmith", "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
            "indices": 3, "material": 0, "mode": 4}]}],
        "materials": [{
            "name": "skin",
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0,
                                     "roughnessFactor": 0.45},
            "normalTexture": {"index": 1, "scale": 1.0},
            "extensions": {"PRESKIN_materials_skin": {"specularTexture": {"index": 2}}},
        }],
        "textures": [{"sampler": 0, "source": i} for i in range(len(TEXTURES))],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
        "images": [{"uri": name} for name in TEXTURES],
        "accessors": [
            {"bufferView": position_view, "componentType": 5126, "count": vertex_count,
             "type": "VEC3", "min": pmin, "max": pmax},
            {"bufferView": normal_view, "componentType": 5126, "count": vertex_count, "type": "VEC3"},
            {"bufferView": uv_view, "componentType": 5126, "count": vertex_count, "type": "VEC2"},
            {"bufferView": index_view, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        ],
        "bufferViews": views,
        "buffers": [{"uri": "head.bin", "byteLength": len(blob)}],
    }

    with open(os.path.join(out_dir, "head.bin"), "wb") as f:
        f.write(blob)
    with open(os.path.join(out_dir, "head.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    for name in TEXTURES + LICENSE_FILES:
        shutil.copyfile(os.path.join(source_dir, name), os.path.join(out_dir, name))
    if len(argv) == 4:
        shutil.copyfile(argv[3], os.path.join(out_dir, ENVIRONMENT))
        hdr_license = os.path.join(os.path.dirname(os.path.abspath(argv[3])), "LICENSE.txt")
        if os.path.exists(hdr_license):
            shutil.copyfile(hdr_license, os.path.join(out_dir, ENVIRONMENT_LICENSE))
    print(f"{vertex_count} vertices, {len(indices) // 3} triangles, "
          f"bounds {['%.4f' % c for c in pmin]} .. {['%.4f' % c for c in pmax]} m")


if __name__ == "__main__":
    main(sys.argv)
