#!/usr/bin/env python3
"""Generates the KHR_lights_punctual scenes of the light tests (tests/unit/test_scene.c,
tests/gpu/test_gpu_file_lights.c). Deterministic; the output is committed. Run:
`python3 tests/corpus/gltf/lights/gen_lights.py`.

Every scene is a grey floor, 10 x 10 in the XZ plane at y = 0 facing +Y, plus:
  rgb_points.gltf   three point lights, red / green / blue, under a parent node moved by (0, 1, 0):
                    at world (-3, 2, 0) (range 4), (0, 2, 0) and (3, 2, 0) (no range), 5 cd each
  spot.gltf         a spot light at (0, 3, 0) pointing straight down (inner 0.3, outer 0.5 rad),
                    20 cd, white
  sun.gltf          a unit box standing on the floor and a directional light of 2 lux pointing down
                    and towards -Z (the node turned -60 degrees about X)
  mixed.gltf        one light of each kind (point at (2, 1, 2), spot as in spot.gltf, the sun)
  spots.gltf        a unit box and 96 spot lights with seeded random positions (over and beside
                    the floor, some under it), orientations (any, some straight up or sideways),
                    outer cones from 0.02 rad to exactly pi/2, inner cones below them, ranges 0.5
                    to 6 (three unranged): the hostile set of the clusters' cone test
"""
import json
import math
import os
import random
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltfgen import b64, box, merge  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def floor():
    pos = [(-5, 0, -5), (-5, 0, 5), (5, 0, 5), (5, 0, -5)]
    return pos, [(0, 1, 0)] * 4, [0, 1, 2, 0, 2, 3]


def quat_x(angle):
    return [math.sin(angle / 2), 0.0, 0.0, math.cos(angle / 2)]


def doc(mesh, lights, light_nodes):
    pos, nrm, idx = mesh
    pb = b"".join(struct.pack("<3f", *p) for p in pos)
    nb = b"".join(struct.pack("<3f", *n) for n in nrm)
    ib = struct.pack("<%dI" % len(idx), *idx)
    data = pb + nb + ib
    nodes = [{"name": "floor", "mesh": 0}] + light_nodes
    roots = [0] + [i + 1 for i, n in enumerate(light_nodes) if not n.get("_child")]
    for n in nodes:
        n.pop("_child", None)
    return {
        "asset": {"version": "2.0", "generator": "passgraph gen_lights.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": lights}},
        "scene": 0,
        "scenes": [{"nodes": roots}],
        "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"name": "grey", "pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.9}}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(pos), "type": "VEC3",
             "min": [min(p[k] for p in pos) for k in range(3)], "max": [max(p[k] for p in pos) for k in range(3)]},
            {"bufferView": 1, "componentType": 5126, "count": len(nrm), "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": len(idx), "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pb)},
            {"buffer": 0, "byteOffset": len(pb), "byteLength": len(nb)},
            {"buffer": 0, "byteOffset": len(pb) + len(nb), "byteLength": len(ib)},
        ],
        "buffers": [{"byteLength": len(data), "uri": b64(data)}],
    }


def write(name, d):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(d, f, indent=1)
        f.write("\n")


RGB = [{"name": "red", "type": "point", "color": [1, 0, 0], "intensity": 5, "range": 4},
       {"name": "green", "type": "point", "color": [0, 1, 0], "intensity": 5},
       {"name": "blue", "type": "point", "color": [0, 0, 1], "intensity": 5}]
write("rgb_points.gltf", doc(floor(), RGB, [
    {"name": "lamps", "translation": [0, 1, 0], "children": [2, 3, 4]},
    {"name": "red_lamp", "translation": [-3, 1, 0], "extensions": {"KHR_lights_punctual": {"light": 0}},
     "_child": True},
    {"name": "green_lamp", "translation": [0, 1, 0], "extensions": {"KHR_lights_punctual": {"light": 1}},
     "_child": True},
    {"name": "blue_lamp", "translation": [3, 1, 0], "extensions": {"KHR_lights_punctual": {"light": 2}},
     "_child": True}]))
SPOT = {"name": "spot", "type": "spot", "intensity": 20, "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.5}}
SPOT_NODE = {"name": "spot_node", "translation": [0, 3, 0], "rotation": quat_x(-math.pi / 2),
             "extensions": {"KHR_lights_punctual": {"light": 0}}}
write("spot.gltf", doc(floor(), [SPOT], [SPOT_NODE]))
SUN = {"name": "sun", "type": "directional", "intensity": 2}
write("sun.gltf", doc(merge(floor(), box((-0.5, 0, -0.5), (0.5, 1, 0.5))), [SUN], [
    {"name": "sun_node", "rotation": quat_x(-math.pi / 3), "extensions": {"KHR_lights_punctual": {"light": 0}}}]))
write("mixed.gltf", doc(merge(floor(), box((-0.5, 0, -0.5), (0.5, 1, 0.5))),
                        [{"name": "lamp", "type": "point", "color": [1, 0.8, 0.6], "intensity": 3}, SPOT, SUN], [
    {"name": "lamp_node", "translation": [2, 1, 2], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    dict(SPOT_NODE, extensions={"KHR_lights_punctual": {"light": 1}}),
    {"name": "sun_node", "rotation": quat_x(-math.pi / 3), "extensions": {"KHR_lights_punctual": {"light": 2}}}]))


def quat_towards(d):
    """The rotation that turns the light's forward axis -Z towards the unit vector d."""
    ax = (d[1], -d[0], 0.0)  # (-Z) x d
    c = -d[2]                # cos of the angle between -Z and d
    s = math.sqrt(ax[0] ** 2 + ax[1] ** 2)
    if s < 1e-9:
        return [0.0, 0.0, 0.0, 1.0] if c > 0 else [1.0, 0.0, 0.0, 0.0]
    ang = math.atan2(s, c)
    k = math.sin(ang / 2) / s
    return [ax[0] * k, ax[1] * k, 0.0, math.cos(ang / 2)]


def hostile_spots(n=96, seed=7):
    rng = random.Random(seed)
    outers = [0.02, 0.1, 0.3, 0.5, 0.9, 1.2, 1.5, math.pi / 2]
    fixed = [(0, -1, 0), (0, 1, 0), (1, 0, 0), (0, 0, 1), (0, 0, -1)]  # down, up, sideways
    lights, nodes = [], []
    for i in range(n):
        outer = outers[i % len(outers)]
        inner = outer * rng.choice([0.0, 0.5, 0.9, 0.999])
        if i < len(fixed) * 3:
            d = fixed[i % len(fixed)]
        else:
            while True:
                d = [rng.uniform(-1, 1) for _ in range(3)]
                ln = math.sqrt(sum(c * c for c in d))
                if 0.1 < ln <= 1:
                    d = [c / ln for c in d]
                    break
        light = {"name": "spot%d" % i, "type": "spot", "intensity": round(rng.uniform(0.5, 4), 3),
                 "color": [round(rng.uniform(0.3, 1), 3) for _ in range(3)],
                 "spot": {"innerConeAngle": inner, "outerConeAngle": outer}}
        if i % 32 != 5:  # three unranged lights
            light["range"] = round(rng.uniform(0.5, 6), 3)
        lights.append(light)
        y = rng.uniform(-0.5, 3.0) if i % 11 else -0.2  # a few under the floor
        nodes.append({"name": "spot%d_node" % i,
                      "translation": [round(rng.uniform(-6, 6), 4), round(y, 4), round(rng.uniform(-6, 6), 4)],
                      "rotation": quat_towards(d), "extensions": {"KHR_lights_punctual": {"light": i}}})
    return lights, nodes


SPOTS, SPOT_NODES = hostile_spots()
write("spots.gltf", doc(merge(floor(), box((-0.5, 0, -0.5), (0.5, 1, 0.5))), SPOTS, SPOT_NODES))
