#!/usr/bin/env python3
"""Generates the KHR_materials_variants scene of the tests. Deterministic; the output is committed.
Run: `python3 tests/corpus/gltf/variants/gen_variants.py`.

  shoe.gltf  one mesh of two primitives over a grey floor (nodes[1]): primitive 0 "body" (a 2 x 1 x 1
             box, default material 0 "white") and primitive 1 "lace" (a 1.2 x 0.2 x 0.6 box on top,
             default material 3 "black"). Materials: 0 white, 1 red, 2 blue, 3 black, 4 yellow,
             5 grey (the floor). Variants: 0 "red", 1 "blue", 2 "midnight". Mappings: body
             {material 1: [0]}, {material 2: [1, 2]}; lace {material 4: [2]}. So the body draws
             0 / 1 / 2 / 2 and the lace 3 / 3 / 3 / 4 for the defaults / red / blue / midnight.
             A camera looks at it from the front and above; one white point light.
"""
import json
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltfgen import Buffer, box, look_rotation  # noqa: E402  (tests/corpus/gltf/gltfgen.py)

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    buf = Buffer()

    def add(blob, count, ctype, typ, minmax=None):
        return buf.add(blob, count, ctype, typ, minmax=minmax)

    def prim(mesh, material, ext=None):
        pos, nrm, idx = mesh
        mn = [min(p[k] for p in pos) for k in range(3)]
        mx = [max(p[k] for p in pos) for k in range(3)]
        p = {"attributes": {"POSITION": add(b"".join(struct.pack("<3f", *q) for q in pos), len(pos), 5126, "VEC3",
                                            (mn, mx)),
                            "NORMAL": add(b"".join(struct.pack("<3f", *q) for q in nrm), len(nrm), 5126, "VEC3")},
             "indices": add(struct.pack("<%dI" % len(idx), *idx), len(idx), 5125, "SCALAR"), "material": material}
        if ext:
            p["extensions"] = {"KHR_materials_variants": {"mappings": ext}}
        return p

    floor = ([(-4, 0, -4), (-4, 0, 4), (4, 0, 4), (4, 0, -4)], [(0, 1, 0)] * 4, [0, 1, 2, 0, 2, 3])
    body = prim(box((-1.0, 0.0, -0.5), (1.0, 1.0, 0.5)), 0,
                [{"material": 1, "variants": [0]}, {"material": 2, "variants": [1, 2], "name": "blue body"}])
    lace = prim(box((-0.6, 1.0, -0.3), (0.6, 1.2, 0.3)), 3, [{"material": 4, "variants": [2]}])
    eye = (1.5, 2.5, 4.0)

    def mat(name, rgb):
        return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(rgb) + [1.0], "metallicFactor": 0.0,
                                                       "roughnessFactor": 0.7}}

    doc = {
        "asset": {"version": "2.0", "generator": "passgraph gen_variants.py"},
        "extensionsUsed": ["KHR_materials_variants", "KHR_lights_punctual"],
        "extensions": {"KHR_materials_variants": {"variants": [{"name": "red"}, {"name": "blue"},
                                                               {"name": "midnight"}]},
                       "KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 40.0, "range": 20.0}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [{"name": "floor", "mesh": 0}, {"name": "shoe", "mesh": 1},
                  {"name": "camera", "camera": 0, "translation": list(eye),
                   "rotation": list(look_rotation(eye, (0.0, 0.6, 0.0)))},
                  {"name": "light", "translation": [1.0, 4.0, 3.0], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1, "zfar": 100.0}}],
        "materials": [mat("white", (0.9, 0.9, 0.9)), mat("red", (0.8, 0.05, 0.05)), mat("blue", (0.05, 0.1, 0.8)),
                      mat("black", (0.02, 0.02, 0.02)), mat("yellow", (0.9, 0.8, 0.05)), mat("grey", (0.5, 0.5, 0.5))],
        "meshes": [{"name": "floor", "primitives": [prim(floor, 5)]}, {"name": "shoe", "primitives": [body, lace]}],
    }
    buf.finish(doc)
    with open(os.path.join(HERE, "shoe.gltf"), "w") as f:
        f.write(json.dumps(doc, indent=1) + "\n")
    print("wrote shoe.gltf")


if __name__ == "__main__":
    main()
