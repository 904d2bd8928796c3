#!/usr/bin/env python3
"""Writes the small hostile inputs of tests/data/hostile: one file (or folder) per class of input
that must be refused with one line naming the file, the field and the problem, within bounded
memory and time (tests/e2e/test_hostile_input.cpp lists the expected messages). Files that
cannot live in a repository (FIFOs, links, devices) are made by the tests themselves.
Python 3 standard library only.

Usage: make_hostile_files.py   (writes next to this script)
"""
import json
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(HERE, "..", "gltf"))
import make_test_files as gltf_files  # noqa: E402  (the triangle shared with tests/data/gltf)

data_uri = gltf_files.data_uri
dump = gltf_files.dump


def write(name, data):
    path = os.path.join(HERE, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb" if isinstance(data, bytes) else "w") as f:
        f.write(data)


def triangle_doc():
    """A valid one-triangle scene with its buffer embedded (Khronos glTF-Validator: no errors)."""
    doc = gltf_files.triangle_doc(gltf_files.data_uri(gltf_files.triangle_buffer()))
    doc["accessors"][0].update({"min": [0, 0, 0], "max": [1, 1, 0]})
    return doc


def png_chunk(kind, payload):
    return struct.pack(">I", len(payload)) + kind + payload + struct.pack(">I", zlib.crc32(kind + payload))


def png(width, height, rows=None, bad_idat_crc=False):
    """An RGB PNG; `rows` of raw pixel bytes (filter byte added), or a single row when None."""
    raw = b"".join(b"\0" + r for r in (rows or [b"\x80" * 3 * min(width, 4)]))
    ihdr = png_chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    idat = png_chunk(b"IDAT", zlib.compress(raw))
    if bad_idat_crc:
        idat = idat[:-4] + bytes(b ^ 0xFF for b in idat[-4:])
    return b"\x89PNG\r\n\x1a\n" + ihdr + idat + png_chunk(b"IEND", b"")


def with_texture(doc, image_uri, extra_texture_info=None):
    doc["images"] = [{"uri": image_uri}]
    doc["textures"] = [{"source": 0}]
    info = {"index": 0}
    info.update(extra_texture_info or {})
    doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": info}}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    return doc


def with_light(light):
    doc = triangle_doc()
    doc["extensionsUsed"] = ["KHR_lights_punctual"]
    doc["extensions"] = {"KHR_lights_punctual": {"lights": [light]}}
    doc["nodes"].append({"extensions": {"KHR_lights_punctual": {"light": 0}}})
    doc["scenes"][0]["nodes"].append(1)
    return doc


def radiance(width, height, pixels=b""):
    header = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + f"-Y {height} +X {width}\n".encode()
    return header + pixels


def nested(depth, leaf):
    return "[" * depth + leaf + "]" * depth


def main():
    # Deep nesting: a profile's "type" and a LUT manifest's "format" nested 100 levels deep.
    write("deep_profile.json", '{"type": ' + nested(100, '"sumOfGaussians"') + ', "gaussians": []}\n')
    write("deep_manifest/manifest.json", '{"format": ' + nested(100, '"preskin-lut-set"') + ', "version": 1}\n')

    # Amplification.
    doc = triangle_doc()
    doc["accessors"][0] = {"componentType": 5126, "count": 1 << 25, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]}
    doc["accessors"] = doc["accessors"][:1]
    doc["meshes"][0]["primitives"][0] = {"attributes": {"POSITION": 0}}
    write("accessor_without_view_huge.gltf", dump(doc))
    write("huge_header_no_pixels.hdr", radiance(8192, 4096))
    write("oversized_header.hdr", radiance(65534, 32767))
    write("huge.png", png(16384, 16384))
    write("huge_png.gltf", dump(with_texture(triangle_doc(), "huge.png")))

    # Non-finite pixels: finite JSON numbers beyond float range, and radiance near FLT_MAX.
    write("light_intensity_1e300.gltf", dump(with_light({"type": "directional", "intensity": 1e300})))
    write("light_color_1e300.gltf", dump(with_light({"type": "point", "color": [1e300, 1, 1]})))
    doc = triangle_doc()
    doc["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    doc["materials"] = [{"emissiveFactor": [1, 1, 1],
                         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 1e300}}}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    write("emissive_strength_1e300.gltf", dump(doc))
    doc = triangle_doc()
    doc["extensionsUsed"] = ["PRESKIN_materials_skin"]
    doc["materials"] = [{"extensions": {"PRESKIN_materials_skin": {"specularIntensity": 1e300}}}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    write("skin_specular_1e300.gltf", dump(doc))
    doc = with_texture(triangle_doc(), data_uri(png(2, 2, [b"\x80" * 6, b"\x40" * 6]), "image/png"),
                       {"extensions": {"KHR_texture_transform": {"scale": [1e300, 1]}}})
    doc["extensionsUsed"] = ["KHR_texture_transform"]
    write("texture_transform_1e300.gltf", dump(doc))
    # RGBE (255, 255, 255, 255): (255 + 0.5) * 2^(255 - 136), about 1.7e38 per channel.
    write("radiance_near_flt_max.hdr", radiance(2, 1, bytes([255, 255, 255, 255, 10, 10, 10, 128])))

    # The promise's form: a PNG whose IDAT checksum is wrong (libpng reports it).
    doc = with_texture(triangle_doc(), data_uri(png(2, 2, [b"\x80" * 6, b"\x40" * 6], bad_idat_crc=True), "image/png"))
    write("png_bad_crc.gltf", dump(doc))

    # Invalid glTF that tinygltf accepts (Khronos glTF-Validator: an error each).
    doc = triangle_doc()
    doc["accessors"][1]["byteOffset"] = -4
    write("accessor_negative_byteoffset.gltf", dump(doc))
    doc = triangle_doc()
    doc["accessors"][1]["byteOffset"] = 1.5
    write("accessor_fractional_byteoffset.gltf", dump(doc))
    sparse_doc = triangle_doc()
    sparse_doc["bufferViews"].append({"buffer": 0, "byteOffset": 96, "byteLength": 6})  # 4: sparse indices
    sparse_doc["bufferViews"].append({"buffer": 0, "byteOffset": 72, "byteLength": 8})  # 5: sparse values
    sparse_doc["accessors"][2]["sparse"] = {
        "count": 1,
        "indices": {"bufferView": 4, "componentType": 5123},
        "values": {"bufferView": 5},
    }
    doc = json.loads(json.dumps(sparse_doc))
    doc["accessors"][2]["sparse"]["count"] = (1 << 32) + 1
    write("sparse_count_64bit.gltf", dump(doc))
    doc = json.loads(json.dumps(sparse_doc))
    doc["accessors"][2]["sparse"]["indices"]["byteOffset"] = 1 << 32
    write("sparse_offset_64bit.gltf", dump(doc))
    doc = triangle_doc()
    del doc["scenes"], doc["scene"]
    doc["nodes"] = [{"mesh": 0}, {"children": [2]}, {"children": [1]}]
    write("node_cycle_no_scenes.gltf", dump(doc))
    doc = triangle_doc()
    doc["meshes"].append({"primitives": []})
    write("mesh_without_primitives.gltf", dump(doc))
    doc = with_texture(triangle_doc(), data_uri(png(2, 2, [b"\x80" * 6, b"\x40" * 6]), "image/png"))
    doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = -1
    write("texture_index_negative.gltf", dump(doc))
    write("light_range_zero.gltf", dump(with_light({"type": "point", "range": 0})))
    doc = triangle_doc()
    doc["extensionsUsed"] = ["PRESKIN_materials_skin"]
    doc["materials"] = [{"extensions": {"PRESKIN_materials_skin": [1, 2]}}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    write("skin_extension_not_object.gltf", dump(doc))
    doc = triangle_doc()
    doc["buffers"][0]["uri"] += "===="
    write("base64_overpadded.gltf", dump(doc))


if __name__ == "__main__":
    main()
