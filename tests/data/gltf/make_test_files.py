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
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
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


if __name__ == "__main__":
    main()
