#!/usr/bin/env python3
"""Generates the EXT_mesh_gpu_instancing scenes of the tests and their twins written with plain
nodes. Deterministic; the output is committed. Run:
`python3 tests/corpus/gltf/instancing/gen_instancing.py`.

Metres, +Y up. Every file has a grey 12 x 12 floor quad at y = 0 facing +Y (nodes[0], meshes[0]),
a camera (nodes[2], looking at the boxes from (0, 4, 9)) and one white point light (nodes[3],
(0, 5, 2), intensity 60, range 20). meshes[1] is a unit box centred at y = 0.5 over the origin,
one primitive, material 1 (orange, metallic 0, roughness 0.6).

  grove.gltf         nodes[1] "grove" (translation (0, 0, -1), mesh 1) with EXT_mesh_gpu_instancing
                     (in extensionsRequired): 7 instances, TRANSLATION FLOAT, ROTATION normalized
                     SHORT, SCALE FLOAT; one instance is mirrored (scale x -1: its winding flips).
  grove_twin.gltf    the same, but nodes[1] "grove" has no mesh and 7 child nodes (nodes[4..10]),
                     each with mesh 1 and the instance's translation, rotation (the SHORT values
                     decoded as passgraph and the glTF spec decode them: max(c / 32767, -1), to
                     float32) and scale: the loader must give exactly the same vertices.
  grove_moving.gltf  grove.gltf with animations[0] "turn": grove's rotation LINEAR about +Y,
                     t = 0 2 4 s -> 0 90 180 deg (the instances turn with their node).
  grove_moving_twin.gltf  grove_twin.gltf with the same animation.
"""
import json
import math
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltfgen import Buffer, box, look_rotation, pad4  # noqa: E402  (tests/corpus/gltf/gltfgen.py)

HERE = os.path.dirname(os.path.abspath(__file__))
FLOAT, SHORT, UINT = 5126, 5122, 5125


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def quat_y(deg):
    h = math.radians(deg) / 2
    return (0.0, math.sin(h), 0.0, math.cos(h))


def quat_axis(axis, deg):
    n = math.sqrt(sum(a * a for a in axis))
    h = math.radians(deg) / 2
    return tuple(a / n * math.sin(h) for a in axis) + (math.cos(h),)


# the instances: translation, rotation (a unit quaternion, stored as normalized SHORT), scale
INSTANCES = [
    ((-3.0, 0.0, 0.0), quat_y(0), (1.0, 1.0, 1.0)),
    ((-1.5, 0.0, 0.5), quat_y(30), (0.75, 1.5, 0.75)),
    ((0.0, 0.0, 0.0), quat_axis((1, 1, 0), 20), (1.0, 0.5, 1.0)),
    ((1.5, 0.0, 0.5), quat_y(-45), (0.5, 2.0, 0.5)),
    ((3.0, 0.0, 0.0), quat_y(60), (-1.0, 1.0, 1.0)),        # mirrored
    ((-2.25, 0.0, -2.0), quat_y(10), (1.25, 0.25, 1.25)),
    ((2.25, 0.25, -2.0), quat_axis((0, 1, 1), 35), (0.5, 0.5, 0.5)),
]


def short_of(x):
    return max(-32767, min(32767, int(round(x * 32767))))


def short_decoded(c):
    """what a normalized SHORT c decodes to (glTF: max(c / 32767, -1)), as float32"""
    return f32(max(c / 32767.0, -1.0))


def build(instanced, moving):
    buf = Buffer()

    def add(blob, fmt, count, ctype, typ, normalized=False, minmax=None):
        return buf.add(blob, count, ctype, typ, normalized, minmax)

    def mesh_acc(pos, nrm, idx):
        mn = [min(p[k] for p in pos) for k in range(3)]
        mx = [max(p[k] for p in pos) for k in range(3)]
        a_p = add(b"".join(struct.pack("<3f", *p) for p in pos), None, len(pos), FLOAT, "VEC3",
                  minmax=([f32(x) for x in mn], [f32(x) for x in mx]))
        a_n = add(b"".join(struct.pack("<3f", *n) for n in nrm), None, len(nrm), FLOAT, "VEC3")
        a_i = add(struct.pack("<%dI" % len(idx), *idx), None, len(idx), UINT, "SCALAR")
        return a_p, a_n, a_i

    floor = ([(-6, 0, -6), (-6, 0, 6), (6, 0, 6), (6, 0, -6)], [(0, 1, 0)] * 4, [0, 1, 2, 0, 2, 3])
    fp, fn, fi = mesh_acc(*floor)
    bp, bn, bi = mesh_acc(*box((-0.5, 0.0, -0.5), (0.5, 1.0, 0.5)))
    shorts = [[short_of(q) for q in r] for _, r, _ in INSTANCES]
    nodes = [{"name": "floor", "mesh": 0}]
    grove = {"name": "grove", "translation": [0.0, 0.0, -1.0]}
    children = []
    if instanced:
        a_t = add(b"".join(struct.pack("<3f", *t) for t, _, _ in INSTANCES), None, len(INSTANCES), FLOAT, "VEC3")
        a_r = add(pad4(b"".join(struct.pack("<4h", *s) for s in shorts)), None, len(INSTANCES), SHORT, "VEC4",
                  normalized=True)
        buf.views[-1]["byteLength"] = 8 * len(INSTANCES)
        a_s = add(b"".join(struct.pack("<3f", *s) for _, _, s in INSTANCES), None, len(INSTANCES), FLOAT, "VEC3")
        grove["mesh"] = 1
        grove["extensions"] = {"EXT_mesh_gpu_instancing": {"attributes": {
            "TRANSLATION": a_t, "ROTATION": a_r, "SCALE": a_s, "_ID": a_t}}}
    else:
        for i, (t, _, s) in enumerate(INSTANCES):
            children.append({"name": "instance%d" % i, "mesh": 1, "translation": [f32(x) for x in t],
                             "rotation": [short_decoded(c) for c in shorts[i]], "scale": [f32(x) for x in s]})
        grove["children"] = list(range(4, 4 + len(INSTANCES)))
    nodes.append(grove)
    eye = (0.0, 4.0, 9.0)
    nodes.append({"name": "camera", "camera": 0, "translation": list(eye),
                  "rotation": list(look_rotation(eye, (0.0, 0.5, -1.0)))})
    nodes.append({"name": "light", "translation": [0.0, 5.0, 2.0],
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})
    nodes += children
    doc = {
        "asset": {"version": "2.0", "generator": "passgraph gen_instancing.py"},
        "extensionsUsed": ["KHR_lights_punctual"] + (["EXT_mesh_gpu_instancing"] if instanced else []),
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100.0}}],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1.0, 1.0, 1.0], "intensity": 60.0, "range": 20.0}]}},
        "materials": [
            {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1.0],
                                                       "metallicFactor": 0.0, "roughnessFactor": 1.0}},
            {"name": "orange", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.45, 0.1, 1.0],
                                                        "metallicFactor": 0.0, "roughnessFactor": 0.6}}],
        "meshes": [
            {"name": "floor", "primitives": [{"attributes": {"POSITION": fp, "NORMAL": fn}, "indices": fi,
                                              "material": 0}]},
            {"name": "box", "primitives": [{"attributes": {"POSITION": bp, "NORMAL": bn}, "indices": bi,
                                            "material": 1}]}],
    }
    if instanced:
        doc["extensionsRequired"] = ["EXT_mesh_gpu_instancing"]
    if moving:
        times = [0.0, 2.0, 4.0]
        a_in = add(struct.pack("<3f", *times), None, 3, FLOAT, "SCALAR", minmax=([0.0], [4.0]))
        a_out = add(b"".join(struct.pack("<4f", *quat_y(d)) for d in (0, 90, 180)), None, 3, FLOAT, "VEC4")
        doc["animations"] = [{"name": "turn", "samplers": [{"input": a_in, "output": a_out,
                                                            "interpolation": "LINEAR"}],
                              "channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}}]}]
    buf.finish(doc)
    return doc


def main():
    for name, instanced, moving in (("grove.gltf", True, False), ("grove_twin.gltf", False, False),
                                    ("grove_moving.gltf", True, True), ("grove_moving_twin.gltf", False, True)):
        doc = build(instanced, moving)
        with open(os.path.join(HERE, name), "w") as f:
            f.write(json.dumps(doc, indent=1) + "\n")
        # read back: every accessor inside its view, every view inside the buffer
        back = json.load(open(os.path.join(HERE, name)))
        blen = back["buffers"][0]["byteLength"]
        for v in back["bufferViews"]:
            assert v["byteOffset"] + v["byteLength"] <= blen
        for a in back["accessors"]:
            size = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[a["type"]] * (2 if a["componentType"] == SHORT else 4)
            assert a["count"] * size <= back["bufferViews"][a["bufferView"]]["byteLength"], name
    print("wrote grove.gltf, grove_twin.gltf, grove_moving.gltf, grove_moving_twin.gltf")


if __name__ == "__main__":
    main()
