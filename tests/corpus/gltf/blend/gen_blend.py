#!/usr/bin/env python3
"""Generates the alphaMode BLEND scenes of tests/test_gpu_blend.c. Deterministic; the output is
committed. Run: `python3 tests/corpus/gltf/blend/gen_blend.py`. All quads are flat, normals
along their face; colours are linear base colour factors (no textures).

  blend_over.gltf   opaque floor 4x4 at y=0 facing +Y (base 0.8 grey) and one BLEND quad 1x1 at
                    y=0.5 facing +Y (base (1, 0.25, 0), alpha 0.5, single-sided), both centred on
                    the Y axis: seen from above, the quad covers the floor at the image centre
  blend_order.gltf  two double-sided BLEND quads facing +Y, no floor: 'red' (1, 0, 0, alpha 0.5)
                    at y=0.5 over x in [-1, 0.5] and 'green' (0, 1, 0, alpha 0.5) at y=1.0 over
                    x in [-0.5, 1] (both z in [-0.5, 0.5]); they overlap over x in [-0.5, 0.5].
                    Red comes first in the file, so scene order is back to front only from above
  blend_lit.gltf    a lit room corner for the pipeline comparison: floor 4x4 (grey), an opaque
                    box 0.8 on it, a vertical double-sided BLEND pane (0.2, 0.5, 1, alpha 0.4) in
                    front of the box and a horizontal single-sided BLEND quad (1, 0.8, 0.2,
                    alpha 0.6) above the floor's other half
"""
import base64
import json
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltfgen import box  # noqa: E402  (shared geometry, tests/corpus/gltf/gltfgen.py)

HERE = os.path.dirname(os.path.abspath(__file__))


def quad_y(x0, x1, z0, z1, y):
    """Quad in the plane y, facing +Y (counter-clockwise seen from above)."""
    pos = [(x0, y, z0), (x0, y, z1), (x1, y, z1), (x1, y, z0)]
    return pos, [(0, 1, 0)] * 4, [0, 1, 2, 0, 2, 3]


def quad_z(x0, x1, y0, y1, z):
    """Quad in the plane z, facing +Z."""
    pos = [(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)]
    return pos, [(0, 0, 1)] * 4, [0, 1, 2, 0, 2, 3]


def material(name, rgba, blend, double_sided=False):
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(rgba), "metallicFactor": 0.0}}
    if blend:
        m["alphaMode"] = "BLEND"
    if double_sided:
        m["doubleSided"] = True
    return m


def write(name, objects, materials):
    """objects: list of (mesh name, (pos, nrm, idx), material index)."""
    data = bytearray()
    views, accessors, meshes, nodes = [], [], [], []

    def view(blob, target):
        while len(data) % 4:
            data.append(0)
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(blob), "target": target})
        data.extend(blob)
        return len(views) - 1

    for mesh_name, (pos, nrm, idx), mat in objects:
        pv = view(b"".join(struct.pack("<3f", *p) for p in pos), 34962)
        nv = view(b"".join(struct.pack("<3f", *n) for n in nrm), 34962)
        iv = view(b"".join(struct.pack("<H", i) for i in idx), 34963)
        mn = [min(p[k] for p in pos) for k in range(3)]
        mx = [max(p[k] for p in pos) for k in range(3)]
        a0 = len(accessors)
        accessors += [
            {"bufferView": pv, "componentType": 5126, "count": len(pos), "type": "VEC3", "min": mn, "max": mx},
            {"bufferView": nv, "componentType": 5126, "count": len(nrm), "type": "VEC3"},
            {"bufferView": iv, "componentType": 5123, "count": len(idx), "type": "SCALAR"},
        ]
        meshes.append({"name": mesh_name, "primitives": [
            {"attributes": {"POSITION": a0, "NORMAL": a0 + 1}, "indices": a0 + 2, "material": mat}]})
        nodes.append({"name": mesh_name, "mesh": len(meshes) - 1})
    doc = {
        "asset": {"version": "2.0", "generator": "passgraph tests/corpus/gltf/blend/gen_blend.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(data)).decode()}],
    }
    with open(os.path.join(HERE, name), "w", newline="\n") as f:
        json.dump(doc, f, indent=1, sort_keys=True)
        f.write("\n")


def main():
    write("blend_over.gltf",
          [("floor", quad_y(-2, 2, -2, 2, 0.0), 0), ("glass", quad_y(-0.5, 0.5, -0.5, 0.5, 0.5), 1)],
          [material("floor", (0.8, 0.8, 0.8, 1), False), material("glass", (1, 0.25, 0, 0.5), True)])
    write("blend_order.gltf",
          [("red", quad_y(-1, 0.5, -0.5, 0.5, 0.5), 0), ("green", quad_y(-0.5, 1, -0.5, 0.5, 1.0), 1)],
          [material("red", (1, 0, 0, 0.5), True, True), material("green", (0, 1, 0, 0.5), True, True)])
    write("blend_lit.gltf",
          [("floor", quad_y(-2, 2, -2, 2, 0.0), 0), ("box", box((-1.2, 0, -1.2), (-0.4, 0.8, -0.4)), 0),
           ("pane", quad_z(-1.6, 0.0, 0.0, 1.2, 0.2), 1), ("roof", quad_y(0.2, 1.8, -1.0, 1.0, 0.6), 2)],
          [material("grey", (0.8, 0.8, 0.8, 1), False), material("pane", (0.2, 0.5, 1, 0.4), True, True),
           material("roof", (1, 0.8, 0.2, 0.6), True)])


if __name__ == "__main__":
    main()
