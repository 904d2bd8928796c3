#!/usr/bin/env python3
"""Writes the small glTF files of tests/data/gltf: one valid triangle (triangle.gltf + .bin) and
one malformed file per bad-input case the loader must reject with a message naming the file and
the field (tests/unit/test_gltf_errors.cpp lists the expected fields). Python 3 standard library.

Usage: make_test_files.py   (writes next to this script)
"""
import base64
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, data):
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(os.path.join(HERE, name), mode) as f:
        f.write(data)


def triangle_buffer(position_values=None, index_values=(0, 1, 2)):
    positions = position_values or [0, 0, 0, 1, 0, 0, 0, 1, 0]
    blob = struct.pack("<9f", *positions)                       # 0..36   POSITION
    blob += struct.pack("<9f", 0, 0, 1, 0, 0, 1, 0, 0, 1)       # 36..72  NORMAL
    blob += struct.pack("<6f", 0, 1, 1, 1, 0, 0)                # 72..96  TEXCOORD_0
    blob += struct.pack("<3H", *index_values) + b"\0\0"         # 96..104 indices (+ padding)
    return blob


def triangle_doc(buffer_uri, byte_length=104):
    return {
        "asset": {"version": "2.0"},
        "buffers": [{"uri": buffer_uri, "byteLength": byte_length}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 36},
            {"buffer": 0, "byteOffset": 72, "byteLength": 24},
            {"buffer": 0, "byteOffset": 96, "byteLength": 6},
        ],
        "accessors": [
            # POSITION carries its bounds (glTF requires them; the default triangle's)
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 3, "type": "SCALAR"},
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }


def data_uri(blob, mime="application/octet-stream"):
    return f"data:{mime};base64," + base64.b64encode(blob).decode()


def dump(doc):
    return json.dumps(doc, indent=1) + "\n"


def glb(doc, blob):
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(blob), 0x004E4942) + blob
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def skinned_triangle(joints=((0, 0, 0, 0), (1, 0, 0, 0), (1, 0, 0, 0)), times=(0.0, 1.0),
                     translations=(0, 1, 0, 0, 1.5, 0), ibm_count=2):
    """A triangle skinned to two joints (root, tip), with one morph target, animated by a LINEAR
    translation of the tip and a weights channel. Returns (doc, buffer) with the buffer embedded."""
    identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    tip_bind = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1]
    parts = [
        ("VEC3", 5126, "<9f", [0, 0, 0, 1, 0, 0, 0, 1, 0]),                # 0 POSITION
        ("VEC3", 5126, "<9f", [0, 0, 1] * 3),                             # 1 NORMAL
        ("SCALAR", 5123, "<3H", [0, 1, 2]),                               # 2 indices
        ("VEC4", 5121, "<12B", [c for j in joints for c in j]),           # 3 JOINTS_0
        ("VEC4", 5126, "<12f", [1, 0, 0, 0] * 3),                         # 4 WEIGHTS_0
        ("VEC3", 5126, "<9f", [0, 0, 0.1] * 3),                           # 5 target POSITION
        ("MAT4", 5126, "<%df" % (16 * ibm_count), (identity + tip_bind)[:16 * ibm_count]),  # 6 IBM
        ("SCALAR", 5126, "<%df" % len(times), list(times)),              # 7 times
        ("VEC3", 5126, "<%df" % len(translations), list(translations)),  # 8 translations
        ("SCALAR", 5126, "<2f", [0.0, 1.0]),                              # 9 weights
    ]
    blob = b""
    views, accessors = [], []
    sizes = {"SCALAR": 1, "VEC3": 3, "VEC4": 4, "MAT4": 16}
    for index, (type_name, component_type, fmt, values) in enumerate(parts):
        data = struct.pack(fmt, *values)
        view = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
        if index <= 5:
            view["target"] = 34963 if index == 2 else 34962
        views.append(view)
        n = sizes[type_name]
        accessor = {"bufferView": len(views) - 1, "componentType": component_type,
                    "count": len(values) // n, "type": type_name}
        if index in (0, 5, 7):  # POSITION, its target and the times carry bounds, as glTF requires
            accessor["min"] = [min(values[k::n]) for k in range(n)]
            accessor["max"] = [max(values[k::n]) for k in range(n)]
        accessors.append(accessor)
        blob += data + b"\0" * (-len(data) % 4)
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [{"uri": data_uri(blob), "byteLength": len(blob)}],
        "bufferViews": views,
        "accessors": accessors,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "JOINTS_0": 3, "WEIGHTS_0": 4},
                                    "indices": 2, "targets": [{"POSITION": 5}]}],
                    "weights": [0.0]}],
        "nodes": [{"name": "triangle", "mesh": 0, "skin": 0},
                  {"name": "root", "children": [2]},
                  {"name": "tip", "translation": [0, 1, 0]}],
        "skins": [{"joints": [1, 2], "inverseBindMatrices": 6}],
        "animations": [{"name": "move",
                        "samplers": [{"input": 7, "output": 8}, {"input": 7, "output": 9}],
                        "channels": [{"sampler": 0, "target": {"node": 2, "path": "translation"}},
                                     {"sampler": 1, "target": {"node": 0, "path": "weights"}}]}],
        "scenes": [{"nodes": [0, 1]}],
        "scene": 0,
    }
    return doc


def animation_files():
    """The valid skinned triangle and one file per bad skin, morph target or animation case."""
    nan, inf = float("nan"), float("inf")
    write("skinned_triangle.gltf", dump(skinned_triangle()))
    write("skin_joint_out_of_range.gltf", dump(skinned_triangle(joints=((0, 0, 0, 0), (2, 0, 0, 0), (1, 0, 0, 0)))))
    write("skin_no_joints.gltf", dump(dict(skinned_triangle(), skins=[{"joints": []}])))
    write("skin_joints_missing.gltf", dump(dict(skinned_triangle(), skins=[{"inverseBindMatrices": 6}])))
    write("skin_inverse_bind_count.gltf", dump(skinned_triangle(ibm_count=1)))
    write("anim_count_mismatch.gltf", dump(skinned_triangle(translations=(0, 1, 0, 0, 1.5, 0, 0, 2, 0))))
    doc = skinned_triangle()
    doc["animations"][0]["samplers"][0]["interpolation"] = "CUBICSPLINE"
    write("anim_cubic_count.gltf", dump(doc))
    write("anim_nan_time.gltf", dump(skinned_triangle(times=(0.0, nan))))
    write("anim_infinite_value.gltf", dump(skinned_triangle(translations=(0, 1, 0, 0, inf, 0))))
    write("anim_times_not_increasing.gltf", dump(skinned_triangle(times=(1.0, 1.0))))
    doc = skinned_triangle()
    doc["nodes"][2] = {"name": "tip", "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1]}
    write("anim_matrix_node.gltf", dump(doc))
    doc = skinned_triangle()
    second = dict(doc["meshes"][0]["primitives"][0])
    second["targets"] = [{"POSITION": 5}, {"POSITION": 5}]
    doc["meshes"][0]["primitives"].append(second)
    write("morph_target_count_mismatch.gltf", dump(doc))
    doc = skinned_triangle()
    doc["meshes"][0]["weights"] = [0.0, 0.5]
    write("morph_weights_length.gltf", dump(doc))


def main():
    blob = triangle_buffer()
    write("triangle.bin", blob)
    write("triangle.gltf", dump(triangle_doc("triangle.bin")))

    glb_doc = triangle_doc(None)
    del glb_doc["buffers"][0]["uri"]
    good_glb = glb(glb_doc, blob)
    write("truncated.glb", good_glb[:60])
    write("bad_magic.glb", b"glTX" + good_glb[4:])
    json_length = struct.unpack_from("<I", good_glb, 12)[0]
    write("bad_chunk_length.glb", good_glb[:12] + struct.pack("<I", json_length + 4096) + good_glb[16:])

    write("bad_json.gltf", dump(triangle_doc("triangle.bin"))[:200])

    write("missing_buffer.gltf", dump(triangle_doc("absent.bin")))

    doc = triangle_doc("triangle.bin")
    doc["images"] = [{"uri": "absent.png"}]
    write("missing_image.gltf", dump(doc))

    doc = triangle_doc("triangle.bin")
    doc["extensionsUsed"] = doc["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    write("required_extension.gltf", dump(doc))

    doc = triangle_doc("triangle.bin")
    doc["accessors"][0]["count"] = 100
    write("accessor_out_of_range.gltf", dump(doc))

    doc = triangle_doc("triangle.bin")
    doc["bufferViews"][2]["byteLength"] = 64
    write("bufferview_out_of_range.gltf", dump(doc))

    doc = triangle_doc("triangle.bin")
    doc["accessors"][0]["count"] = 4294967295
    write("huge_count.gltf", dump(doc))

    write("index_out_of_range.gltf", dump(triangle_doc(data_uri(triangle_buffer(index_values=(0, 1, 7))))))

    nan = float("nan")
    write("nan_position.gltf", dump(triangle_doc(data_uri(triangle_buffer([0, 0, 0, 1, nan, 0, 0, 1, 0])))))

    write("uri_parent.gltf", dump(triangle_doc("../gltf/triangle.bin")))
    write("uri_absolute.gltf", dump(triangle_doc("/etc/hostname")))
    write("uri_file_scheme.gltf", dump(triangle_doc("file:///etc/hostname")))

    doc = triangle_doc("triangle.bin")
    doc["images"] = [{"uri": data_uri(b"\x89PNG\r\n\x1a\n" + b"\0" * 40, "image/png")}]
    write("bad_image.gltf", dump(doc))

    doc = triangle_doc("triangle.bin")
    doc["images"] = [{"uri": data_uri(b"GIF89a\x01\x00\x01\x00\x00\x00\x00;", "image/gif")}]
    doc["textures"] = [{"source": 0}]
    doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    write("unsupported_image.gltf", dump(doc))

    doc = triangle_doc("triangle.bin")
    doc["nodes"] = [{"mesh": 0, "children": [1]}, {"children": [0]}]
    write("node_cycle.gltf", dump(doc))

    animation_files()


if __name__ == "__main__":
    main()
