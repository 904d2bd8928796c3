#!/usr/bin/env python3
"""Writes head_animated.gltf + head_animated.bin next to this script: the bundled head (head.gltf,
same geometry, material, textures, light, camera and environment) with three morph targets, a
three-joint neck skin and a 4 s animation using all of them, for preskin's animation path.

Landmarks are found on the mesh itself (the face looks toward +Z, +Y up; see find_landmarks):
the nose tip is the front-most vertex; along the midline profile below it the mouth line is the
deepest point between the lips and above it the nasion is the deepest point between the nose
and the brow.

Morph targets (POSITION and NORMAL deltas, stored as sparse accessors over the vertices they move):
  jawOpen    the lower face turns JAW_ANGLE_RAD about a left-right axis through the jaw hinge
             (in front of the ear, level with the base of the nose), weighted 1 below the mouth
             line and fading smoothly towards the hinge, the throat and the back of the head;
  cheekPuff  both cheeks move out along the surface normal, CHEEK_PUFF_M at the centre of a
             Gaussian bump of CHEEK_SIGMA_M beside each mouth corner;
  browRaise  the brows and the lower forehead slide BROW_RAISE_M upwards along the surface
             (the displacement is projected into the tangent plane), fading above and at the sides.
  NORMAL deltas are the change of the area-weighted vertex normals (vertices welded by position,
  so UV seams stay closed) between the displaced and the undisplaced mesh.
Skin: joints chest -> neck -> head (nodes with translations only, inverse bind matrices their
inverses). Weights blend along the neck with smoothsteps over a height tilted forward so that the
chin and jaw belong to the head; the shoulders follow the chest.
Animation "talk" (0..4 s): the head turns right, nods, turns left and comes back (neck 40 % and head
60 % of the rotation, LINEAR quaternions every 0.1 s); the jaw talks between 1 and 3 s, the brows
rise twice and the cheeks puff near the end (weights, CUBICSPLINE with Catmull-Rom tangents).

Usage: make_head_animated.py   (Python 3 with numpy, Debian package python3-numpy)
"""
import json
import math
import os
import struct

import numpy as np

JAW_ANGLE_RAD = math.radians(14.0)
CHEEK_PUFF_M = 0.006
CHEEK_SIGMA_M = 0.013
BROW_RAISE_M = 0.007
DURATION_S = 4.0
ROTATION_STEP_S = 0.1
WEIGHT_STEP_S = 0.05
TARGET_NAMES = ["jawOpen", "cheekPuff", "browRaise"]

HERE = os.path.dirname(os.path.abspath(__file__))


def smoothstep(e0, e1, x):
    t = np.clip((np.asarray(x, dtype=np.float64) - e0) / (e1 - e0), 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def read_head():
    doc = json.load(open(os.path.join(HERE, "head.gltf")))
    blob = open(os.path.join(HERE, doc["buffers"][0]["uri"]), "rb").read()
    attributes = doc["meshes"][0]["primitives"][0]["attributes"]

    def accessor(index):
        a = doc["accessors"][index]
        view = doc["bufferViews"][a["bufferView"]]
        n = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}[a["type"]]
        dtype = {5126: np.float32, 5123: np.uint16, 5125: np.uint32}[a["componentType"]]
        offset = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        data = np.frombuffer(blob, dtype=dtype, count=a["count"] * n, offset=offset)
        return data.reshape(-1, n) if n > 1 else data.copy()

    return (doc, accessor(attributes["POSITION"]).astype(np.float64), accessor(attributes["NORMAL"]),
            accessor(attributes["TEXCOORD_0"]), accessor(doc["meshes"][0]["primitives"][0]["indices"]))


def welded_normals(positions, triangles, weld):
    """Area-weighted vertex normals, summed over all vertices at one position."""
    a, b, c = (positions[triangles[:, k]] for k in range(3))
    face = np.cross(b - a, c - a)
    sums = np.zeros((weld.max() + 1, 3))
    for k in range(3):
        np.add.at(sums, weld[triangles[:, k]], face)
    n = sums[weld]
    return n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)


def front_profile(positions, x0, y_from, y_to, step=0.0025):
    """(y, front-most z) along the midline |x - x0| < 4 mm, in bins of `step`."""
    mid = positions[np.abs(positions[:, 0] - x0) < 0.004]
    ys, zs = [], []
    for y in np.arange(y_from, y_to, step):
        band = mid[(mid[:, 1] >= y) & (mid[:, 1] < y + step)]
        if len(band):
            ys.append(y + step / 2)
            zs.append(band[:, 2].max())
    return np.array(ys), np.array(zs)


def find_landmarks(positions):
    nose = positions[np.argmax(positions[:, 2])]
    x0 = nose[0]
    ys, zs = front_profile(positions, x0, nose[1] - 0.065, nose[1] - 0.03)
    mouth_y = ys[np.argmin(zs)]
    mouth_z = positions[(np.abs(positions[:, 0] - x0) < 0.004) & (np.abs(positions[:, 1] - mouth_y) < 0.003)][:, 2].max()
    ys, zs = front_profile(positions, x0, nose[1] + 0.02, nose[1] + 0.06)
    nasion_y = ys[np.argmin(zs)]
    level = positions[np.abs(positions[:, 1] - (nose[1] - 0.015)) < 0.004]
    hinge = np.array([x0, nose[1] - 0.015, level[:, 2].min() + 0.45 * (level[:, 2].max() - level[:, 2].min())])
    cheeks = []
    for side in (-1.0, 1.0):
        near = positions[(np.abs(positions[:, 0] - (x0 + side * 0.042)) < 0.005) &
                         (np.abs(positions[:, 1] - (mouth_y + 0.015)) < 0.005)]
        cheeks.append(near[np.argmax(near[:, 2])])
    return {"x0": x0, "nose": nose, "mouth_y": mouth_y, "mouth_z": mouth_z, "chin_y": mouth_y - 0.04,
            "nasion_y": nasion_y, "hinge": hinge, "cheeks": cheeks}


def jaw_open(p, lm):
    hinge = lm["hinge"]
    # The jaw's upper boundary runs from the mouth line at the front up to the hinge at its depth.
    depth = np.clip((lm["mouth_z"] - p[:, 2]) / (lm["mouth_z"] - hinge[2]), 0.0, 1.0)
    boundary = lm["mouth_y"] + (hinge[1] - lm["mouth_y"]) * depth
    w = (smoothstep(boundary + 0.004, boundary - 0.006, p[:, 1]) *
         smoothstep(lm["chin_y"] - 0.035, lm["chin_y"] + 0.005, p[:, 1]) *
         smoothstep(hinge[2] - 0.01, hinge[2] + 0.02, p[:, 2]))
    c, s = math.cos(JAW_ANGLE_RAD), math.sin(JAW_ANGLE_RAD)
    r = p - hinge
    turned = np.stack([r[:, 0], c * r[:, 1] - s * r[:, 2], s * r[:, 1] + c * r[:, 2]], axis=1)
    return w[:, None] * (turned - r)


def cheek_puff(p, n, lm):
    bump = sum(np.exp(-np.sum((p - centre) ** 2, axis=1) / (2.0 * CHEEK_SIGMA_M ** 2)) for centre in lm["cheeks"])
    return CHEEK_PUFF_M * bump[:, None] * n


def brow_raise(p, n, lm):
    y = lm["nasion_y"]
    w = (smoothstep(y - 0.004, y + 0.01, p[:, 1]) * (1.0 - smoothstep(y + 0.025, y + 0.07, p[:, 1])) *
         (1.0 - smoothstep(0.045, 0.075, np.abs(p[:, 0] - lm["x0"]))) * smoothstep(0.1, 0.5, n[:, 2]))
    up = np.zeros_like(p)
    up[:, 1] = BROW_RAISE_M * w
    return up - n * np.sum(n * up, axis=1, keepdims=True)


def skin_weights(p, lm, joints):
    neck_z = joints["neck"][2]
    tilted = p[:, 1] + 0.35 * (p[:, 2] - neck_z)  # the chin and jaw count as higher than the throat
    head = smoothstep(joints["neck"][1] + 0.025, joints["head"][1] - 0.005, tilted)
    chest = 1.0 - smoothstep(joints["chest"][1] - 0.005, joints["neck"][1] - 0.005, p[:, 1])
    neck = np.clip(1.0 - head - chest, 0.0, None)
    w = np.stack([chest, neck, head], axis=1)
    return w / w.sum(axis=1, keepdims=True)


def quat(axis, angle):
    axis = np.asarray(axis, dtype=np.float64)
    return np.concatenate([axis * math.sin(angle / 2), [math.cos(angle / 2)]])


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return np.array([aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz])


def bump(t, start, peak_from, peak_to, end):
    return smoothstep(start, peak_from, t) * (1.0 - smoothstep(peak_to, end, t))


def head_angles(t):
    yaw = 0.35 * math.sin(2.0 * math.pi * t / DURATION_S)              # right, back, left, back
    pitch = 0.16 * math.sin(2.0 * math.pi * (t - 1.0) / 0.6) * float(bump(t, 1.0, 1.15, 1.95, 2.2))
    return yaw, pitch


def morph_weights(t):
    talk = bump(t, 1.0, 1.2, 2.7, 3.0) * (0.3 + 0.3 * math.sin(2.0 * math.pi * 3.5 * (t - 1.0) - math.pi / 2))
    cheeks = bump(t, 3.0, 3.3, 3.6, 3.9)
    brows = bump(t, 0.2, 0.45, 0.8, 1.1) + 0.7 * bump(t, 2.1, 2.3, 2.5, 2.8)
    return [max(float(talk), 0.0), float(cheeks), float(brows)]


def main():
    doc, positions, normals, uvs, indices = read_head()
    triangles = indices.reshape(-1, 3).astype(np.int64)
    _, weld = np.unique(positions, axis=0, return_inverse=True)
    weld = weld.reshape(-1)
    lm = find_landmarks(positions)
    base_normals = welded_normals(positions, triangles, weld)

    displacements = {"jawOpen": jaw_open(positions, lm),
                     "cheekPuff": cheek_puff(positions, base_normals, lm),
                     "browRaise": brow_raise(positions, base_normals, lm)}
    targets = []
    for name in TARGET_NAMES:
        d = displacements[name]
        dn = welded_normals(positions + d, triangles, weld) - base_normals
        moved = np.nonzero((np.abs(d).max(axis=1) > 1e-7) | (np.abs(dn).max(axis=1) > 1e-6))[0]
        targets.append((name, d.astype(np.float32), dn.astype(np.float32), moved))
        print(f"{name}: {len(moved)} vertices, largest displacement {np.linalg.norm(d, axis=1).max() * 1000:.1f} mm")

    joints = {"chest": np.array([lm["x0"], lm["chin_y"] - 0.08, -0.01]),
              "neck": np.array([lm["x0"], lm["chin_y"] - 0.045, -0.02]),
              "head": np.array([lm["x0"], lm["mouth_y"], -0.02])}
    weights = skin_weights(positions, lm, joints)

    blob = bytearray()
    views, accessors = [], []

    def add_view(data, target=None):
        while len(blob) % 4:
            blob.append(0)
        view = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
        if target:
            view["target"] = target
        views.append(view)
        blob.extend(data)
        return len(views) - 1

    def add_accessor(array, component_type, type_name, target=None, bounds=False, normalized=False):
        array = np.ascontiguousarray(array)
        accessor = {"bufferView": add_view(array.tobytes(), target), "componentType": component_type,
                    "count": int(array.shape[0]), "type": type_name}
        if normalized:
            accessor["normalized"] = True
        if bounds:
            flat = array.reshape(array.shape[0], -1)
            accessor["min"] = [float(v) for v in flat.min(axis=0)]
            accessor["max"] = [float(v) for v in flat.max(axis=0)]
        accessors.append(accessor)
        return len(accessors) - 1

    def add_sparse(values, moved, bounds):
        """A VEC3 accessor of zeros except at `moved`, whose values are stored sparsely."""
        accessor = {"componentType": 5126, "count": int(values.shape[0]), "type": "VEC3",
                    "sparse": {"count": int(len(moved)),
                               "indices": {"bufferView": add_view(moved.astype(np.uint16).tobytes()),
                                           "componentType": 5123},
                               "values": {"bufferView": add_view(values[moved].astype(np.float32).tobytes())}}}
        if bounds:
            accessor["min"] = [float(v) for v in np.minimum(values.min(axis=0), 0.0)]
            accessor["max"] = [float(v) for v in np.maximum(values.max(axis=0), 0.0)]
        accessors.append(accessor)
        return len(accessors) - 1

    count = positions.shape[0]
    # Influence slots by decreasing weight; unused slots name joint 0 with weight 0.
    order = np.argsort(-weights, axis=1, kind="stable")
    weight_slots = np.concatenate([np.take_along_axis(weights, order, axis=1), np.zeros((count, 1))], axis=1)
    joint_slots = np.concatenate([order, np.zeros((count, 1), dtype=order.dtype)], axis=1)
    joint_slots[weight_slots == 0.0] = 0
    attributes = {
        "POSITION": add_accessor(positions.astype(np.float32), 5126, "VEC3", 34962, bounds=True),
        "NORMAL": add_accessor(normals.astype(np.float32), 5126, "VEC3", 34962),
        "TEXCOORD_0": add_accessor(uvs.astype(np.float32), 5126, "VEC2", 34962),
        "JOINTS_0": add_accessor(joint_slots.astype(np.uint8), 5121, "VEC4", 34962),
        "WEIGHTS_0": add_accessor(weight_slots.astype(np.float32), 5126, "VEC4", 34962),
    }
    index_accessor = add_accessor(indices.astype(np.uint16), 5123, "SCALAR", 34963)
    target_accessors = [{"POSITION": add_sparse(d, moved, True), "NORMAL": add_sparse(dn, moved, False)}
                        for _, d, dn, moved in targets]

    # Nodes: 0 mesh, 1 light, 2 camera (as in head.gltf), 3 chest -> 4 neck -> 5 head.
    order = ["chest", "neck", "head"]
    inverse_binds = np.zeros((3, 4, 4), dtype=np.float32)
    for k, name in enumerate(order):
        m = np.eye(4)
        m[3, :3] = -joints[name]  # column-major: the last column holds the translation
        inverse_binds[k] = m
    ibm_accessor = add_accessor(inverse_binds.reshape(3, 16), 5126, "MAT4")

    rotation_times = np.round(np.arange(0.0, DURATION_S + 1e-9, ROTATION_STEP_S), 6).astype(np.float32)
    neck_rotations, head_rotations = [], []
    for t in rotation_times:
        yaw, pitch = head_angles(float(t))
        for share, out in ((0.4, neck_rotations), (0.6, head_rotations)):
            out.append(quat_mul(quat([0, 1, 0], share * yaw), quat([1, 0, 0], share * pitch)))
    weight_times = np.round(np.arange(0.0, DURATION_S + 1e-9, WEIGHT_STEP_S), 6).astype(np.float32)
    values = np.array([morph_weights(float(t)) for t in weight_times])
    # Catmull-Rom tangents (per second), zero at the ends; CUBICSPLINE keys: in, value, out.
    tangents = np.zeros_like(values)
    tangents[1:-1] = (values[2:] - values[:-2]) / (2.0 * WEIGHT_STEP_S)
    cubic = np.stack([tangents, values, tangents], axis=1).reshape(-1)

    def time_accessor(times):
        return add_accessor(times, 5126, "SCALAR", bounds=True)

    rotation_input = time_accessor(rotation_times)
    weight_input = time_accessor(weight_times)
    samplers = [
        {"input": rotation_input, "output": add_accessor(np.array(neck_rotations, dtype=np.float32), 5126, "VEC4")},
        {"input": rotation_input, "output": add_accessor(np.array(head_rotations, dtype=np.float32), 5126, "VEC4")},
        {"input": weight_input, "output": add_accessor(cubic.astype(np.float32), 5126, "SCALAR"),
         "interpolation": "CUBICSPLINE"},
    ]
    while len(blob) % 4:
        blob.append(0)

    gltf = {key: doc[key] for key in ("asset", "extensionsUsed", "extensions", "cameras", "materials", "textures",
                                      "samplers", "images")}
    gltf["asset"] = dict(doc["asset"], generator="preskin make_head_animated.py")
    nodes = [dict(node) for node in doc["nodes"]]
    nodes[0]["skin"] = 0
    nodes.append({"name": "chest", "translation": [float(v) for v in joints["chest"]], "children": [4]})
    nodes.append({"name": "neck", "translation": [float(v) for v in joints["neck"] - joints["chest"]], "children": [5]})
    nodes.append({"name": "head", "translation": [float(v) for v in joints["head"] - joints["neck"]]})
    mesh = dict(doc["meshes"][0])
    mesh["primitives"] = [dict(mesh["primitives"][0], attributes=attributes, indices=index_accessor,
                               targets=target_accessors)]
    mesh["weights"] = [0.0] * len(TARGET_NAMES)
    mesh["extras"] = {"targetNames": TARGET_NAMES}
    gltf.update({
        "scene": 0,
        "scenes": [dict(doc["scenes"][0], nodes=doc["scenes"][0]["nodes"] + [3])],
        "nodes": nodes,
        "meshes": [mesh],
        "skins": [{"name": "neck", "joints": [3, 4, 5], "inverseBindMatrices": ibm_accessor, "skeleton": 3}],
        "animations": [{"name": "talk", "samplers": samplers, "channels": [
            {"sampler": 0, "target": {"node": 4, "path": "rotation"}},
            {"sampler": 1, "target": {"node": 5, "path": "rotation"}},
            {"sampler": 2, "target": {"node": 0, "path": "weights"}}]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"uri": "head_animated.bin", "byteLength": len(blob)}],
    })
    with open(os.path.join(HERE, "head_animated.bin"), "wb") as f:
        f.write(blob)
    with open(os.path.join(HERE, "head_animated.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    print("landmarks: nose tip y %.4f, mouth y %.4f, nasion y %.4f, hinge %s" %
          (lm["nose"][1], lm["mouth_y"], lm["nasion_y"], np.round(lm["hinge"], 4)))
    print(f"{count} vertices, {len(blob)} bytes of buffer")


if __name__ == "__main__":
    main()
