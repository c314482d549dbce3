#!/usr/bin/env python3
"""Generates the emissive test scenes (tests/test_gpu_emissive.c, tests/test_scene.c). Deterministic;
the output is committed. Run: `python3 tests/corpus/gltf/emissive/gen_emissive.py`.

Three unit cubes in a row along X (centres x = -2, 0, 2; y 0..1, z -0.5..0.5) on a 7 x 3 floor
quad (y = 0), seen by the camera 'front' at (0, 1.6, 4.2) looking at (0, 0.45, 0), yfov 0.75, so each
cube lies in its own third of a 16:9 image:
  emissive.gltf           'glow'  (left)  emissiveFactor (1, 0.5, 0.25), no strength extension;
                          'lamp'  (middle) emissiveFactor (0.25, 0.5, 1) x
                                  KHR_materials_emissive_strength 4 = (1, 2, 4);
                          'matte' (right) and the floor: no emission.
                          Every emissive value is exact in rgba16f, so every pipeline must store it
                          unchanged.
  emissive_required.gltf  the same with KHR_materials_emissive_strength in extensionsRequired.
  plain.gltf              the same geometry and base colours, no emissive material at all.
  hot.gltf                'glow' emits (1e30, 1, 0) (strength 1): past the rgba16f range, which the
                          pipelines must clamp to PG_HDR_MAX (pg_hdr_sanitize) like any other sum.
Base colours: glow (0.8, 0.3, 0.2), lamp (0.2, 0.3, 0.8), matte (0.7, 0.7, 0.7), floor (0.5, 0.5, 0.5).
"""
import base64
import json
import math
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltfgen import box, look_rotation  # noqa: E402  (shared geometry, tests/corpus/gltf/gltfgen.py)

HERE = os.path.dirname(os.path.abspath(__file__))


def floor():
    pos = [(-3.5, 0, -1.5), (-3.5, 0, 1.5), (3.5, 0, 1.5), (3.5, 0, -1.5)]
    return pos, [(0, 1, 0)] * 4, [0, 1, 2, 0, 2, 3]


def scene(emissive, required=False, hot=False):
    meshes = [("glow", box((-2.5, 0, -0.5), (-1.5, 1, 0.5))), ("lamp", box((-0.5, 0, -0.5), (0.5, 1, 0.5))),
              ("matte", box((1.5, 0, -0.5), (2.5, 1, 0.5))), ("floor", floor())]
    data = b""
    views, accessors, gmeshes, nodes = [], [], [], []
    for i, (name, (pos, nrm, idx)) in enumerate(meshes):
        acc = len(accessors)
        for arr, typ in ((pos, "VEC3"), (nrm, "VEC3")):
            b = struct.pack("<%df" % (3 * len(arr)), *[c for v in arr for c in v])
            views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(b)})
            a = {"bufferView": len(views) - 1, "componentType": 5126, "count": len(arr), "type": typ}
            if arr is pos:
                a["min"] = [min(v[k] for v in arr) for k in range(3)]
                a["max"] = [max(v[k] for v in arr) for k in range(3)]
            accessors.append(a)
            data += b
        b = struct.pack("<%dH" % len(idx), *idx)
        b += b"\0" * ((4 - len(b) % 4) % 4)
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": 2 * len(idx)})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5123, "count": len(idx), "type": "SCALAR"})
        data += b
        gmeshes.append({"name": name, "primitives": [{"attributes": {"POSITION": acc, "NORMAL": acc + 1},
                                                      "indices": acc + 2, "material": i}]})
        nodes.append({"name": name, "mesh": i})
    mats = [{"name": "glow", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.3, 0.2, 1], "metallicFactor": 0}},
            {"name": "lamp", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.3, 0.8, 1], "metallicFactor": 0}},
            {"name": "matte", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1], "metallicFactor": 0}},
            {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0}}]
    doc = {"asset": {"version": "2.0", "generator": "passgraph gen_emissive.py"}}
    if emissive:
        mats[0]["emissiveFactor"] = [1, 0.5, 0.25]
        mats[1]["emissiveFactor"] = [0.25, 0.5, 1]
        mats[1]["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}
        doc["extensionsUsed"] = ["KHR_materials_emissive_strength"]
        if required:
            doc["extensionsRequired"] = ["KHR_materials_emissive_strength"]
        if hot:
            mats[0]["emissiveFactor"] = [1e30, 1, 0]
    eye = (0, 1.6, 4.2)
    nodes.append({"name": "front_node", "camera": 0, "translation": list(eye),
                  "rotation": look_rotation(eye, (0, 0.45, 0))})
    doc.update({
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{"name": "front", "type": "perspective",
                     "perspective": {"yfov": 0.75, "znear": 0.1, "zfar": 50}}],
        "meshes": gmeshes,
        "materials": mats,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    })
    return doc


for name, doc in (("emissive.gltf", scene(True)), ("emissive_required.gltf", scene(True, True)),
                  ("plain.gltf", scene(False)), ("hot.gltf", scene(True, hot=True))):
    with open(os.path.join(HERE, name), "w") as f:
        f.write(json.dumps(doc, indent=1) + "\n")
print("wrote emissive.gltf, emissive_required.gltf, plain.gltf, hot.gltf")
