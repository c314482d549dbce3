#!/usr/bin/env python3
"""Generates the metallic-roughness scenes of the pbr tests (tests/gpu/test_gpu_pbr.c,
tests/unit/test_scene.c). Deterministic; the output is committed. Run:
`python3 tests/corpus/gltf/pbr/gen_pbr.py`.

  patches.gltf   a 10 x 10 floor at y = 0 facing +Y in four 5 x 5 patches, one material each:
                 (x < 0, z < 0) grey dielectric, roughness 0.9; (x > 0, z < 0) blue dielectric, 0.2;
                 (x < 0, z > 0) gold metal, 0.5; (x > 0, z > 0) copper metal, 0.15. Two point lights
                 without a range: white 10 cd at (-2, 1.5, -1), warm 8 cd at (2, 2, 1.5).
  spheres.gltf   5 x 5 UV spheres (radius 0.4, 1 apart, in the z = 0 plane) of base colour
                 (0.9, 0.55, 0.25): row r (from the bottom, y = r - 2) metallic r / 4, column c (x =
                 c - 2) roughness 0.1 + 0.2 c; two point lights in front (30 cd at (-3, 3, 5), 20 cd
                 at (3, 1, 6)); a camera at (0, 0, 9) looking down -Z (yfov 0.6).
  textured.gltf  a 4 x 4 floor (y = 0, facing +Y, UV (x + 2) / 4, (z + 2) / 4) of base colour 0.8 with
                 a 2 x 2 metallicRoughnessTexture (nearest; u < 0.5: G 1.0 B 0 = rough dielectric,
                 u > 0.5: G 0.2 B 1.0 = metal) and a 2 x 2 occlusionTexture (nearest; v < 0.5: R 1.0,
                 v > 0.5: R 0.25), strength 1; an unlit box (KHR_materials_unlit, base colour
                 (0.2, 0.9, 0.3)) 0.5 high at the centre; a point light of 6 cd at (0, 2, 0).
"""
import base64
import json
import math
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltfgen import box, pad4, png_rgba, sphere  # noqa: E402  (tests/corpus/gltf/gltfgen.py)

HERE = os.path.dirname(os.path.abspath(__file__))


class Doc:
    def __init__(self, name):
        self.name = name
        self.bin = b""
        self.d = {"asset": {"version": "2.0", "generator": "passgraph gen_pbr.py"}, "scene": 0,
                  "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "materials": [], "accessors": [],
                  "bufferViews": []}

    def accessor(self, data, ctype, count, typ, mn=None, mx=None):
        self.d["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += pad4(data)
        a = {"bufferView": len(self.d["bufferViews"]) - 1, "componentType": ctype, "count": count, "type": typ}
        if mn is not None:
            a["min"], a["max"] = mn, mx
        self.d["accessors"].append(a)
        return len(self.d["accessors"]) - 1

    def mesh(self, pos, nrm, idx, material, uv=None, translation=None):
        attrs, ind = self.streams(pos, nrm, idx, uv)
        self.mesh_of(attrs, ind, material, translation)

    def mesh_of(self, attrs, ind, material, translation=None):
        self.d["meshes"].append({"primitives": [{"attributes": attrs, "indices": ind, "material": material}]})
        n = {"mesh": len(self.d["meshes"]) - 1}
        if translation:
            n["translation"] = translation
        self.node(n)

    def streams(self, pos, nrm, idx, uv=None):
        attrs = {"POSITION": self.accessor(b"".join(struct.pack("<3f", *p) for p in pos), 5126, len(pos), "VEC3",
                                           [min(p[k] for p in pos) for k in range(3)],
                                           [max(p[k] for p in pos) for k in range(3)]),
                 "NORMAL": self.accessor(b"".join(struct.pack("<3f", *n) for n in nrm), 5126, len(nrm), "VEC3")}
        if uv is not None:
            attrs["TEXCOORD_0"] = self.accessor(b"".join(struct.pack("<2f", *t) for t in uv), 5126, len(uv), "VEC2")
        ind = self.accessor(struct.pack("<%dI" % len(idx), *idx), 5125, len(idx), "SCALAR")
        return attrs, ind

    def node(self, n):
        self.d["nodes"].append(n)
        self.d["scenes"][0]["nodes"].append(len(self.d["nodes"]) - 1)

    def material(self, m):
        self.d["materials"].append(m)
        return len(self.d["materials"]) - 1

    def lights(self, lights):
        """lights: (colour, intensity, position) point lights without a range"""
        self.d.setdefault("extensionsUsed", []).append("KHR_lights_punctual")
        self.d.setdefault("extensions", {})["KHR_lights_punctual"] = {
            "lights": [{"type": "point", "color": c, "intensity": i} for c, i, _ in lights]}
        for k, (_, _, p) in enumerate(lights):
            self.node({"name": "light%d" % k, "translation": p, "extensions": {"KHR_lights_punctual": {"light": k}}})

    def image(self, w, h, pixels):
        uri = "data:image/png;base64," + base64.b64encode(png_rgba(w, h, pixels)).decode()
        self.d.setdefault("images", []).append({"uri": uri})
        self.d.setdefault("samplers", [{"magFilter": 9728, "minFilter": 9728}])  # nearest, no mips
        self.d.setdefault("textures", []).append({"source": len(self.d["images"]) - 1, "sampler": 0})
        return len(self.d["textures"]) - 1

    def write(self):
        self.d["buffers"] = [{"byteLength": len(self.bin),
                              "uri": "data:application/octet-stream;base64," + base64.b64encode(self.bin).decode()}]
        with open(os.path.join(HERE, self.name), "w") as f:
            f.write(json.dumps(self.d, indent=1) + "\n")


def quad_y(x0, z0, x1, z1, uv=False):
    """a floor quad at y = 0 facing +Y (counter-clockwise seen from above)"""
    pos = [(x0, 0, z0), (x0, 0, z1), (x1, 0, z1), (x1, 0, z0)]
    uvs = [((x + 2) / 4, (z + 2) / 4) for x, _, z in pos] if uv else None
    return pos, [(0, 1, 0)] * 4, [0, 1, 2, 0, 2, 3], uvs


def pbr(name, base, metallic, roughness, **extra):
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(base) + [1.0], "metallicFactor": metallic,
                                                "roughnessFactor": roughness}}
    m.update(extra)
    return m


def patches():
    doc = Doc("patches.gltf")
    mats = [pbr("grey_rough", (0.8, 0.8, 0.8), 0.0, 0.9), pbr("blue_glossy", (0.2, 0.4, 0.8), 0.0, 0.2),
            pbr("gold", (1.0, 0.77, 0.34), 1.0, 0.5), pbr("copper", (0.95, 0.64, 0.54), 1.0, 0.15)]
    for k, m in enumerate(mats):
        x0, z0 = (-5 if k % 2 == 0 else 0), (-5 if k < 2 else 0)
        pos, nrm, idx, _ = quad_y(x0, z0, x0 + 5, z0 + 5)
        doc.mesh(pos, nrm, idx, doc.material(m))
    doc.lights([([1, 1, 1], 10.0, [-2, 1.5, -1]), ([1, 0.8, 0.6], 8.0, [2, 2, 1.5])])
    doc.write()


def spheres():
    doc = Doc("spheres.gltf")
    attrs, ind = doc.streams(*sphere((0.0, 0.0, 0.0), 0.4, 32, 16))  # one sphere, placed 25 times
    for row in range(5):
        for col in range(5):
            m = doc.material(pbr("m%.2f_r%.1f" % (row / 4, 0.1 + 0.2 * col), (0.9, 0.55, 0.25), row / 4,
                                 0.1 + 0.2 * col))
            doc.mesh_of(attrs, ind, m, [col - 2.0, row - 2.0, 0.0])
    doc.d["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.6, "znear": 0.1, "zfar": 100}}]
    doc.node({"name": "camera", "camera": 0, "translation": [0, 0, 9]})
    doc.lights([([1, 1, 1], 30.0, [-3, 3, 5]), ([1, 1, 1], 20.0, [3, 1, 6])])
    doc.write()


def textured():
    doc = Doc("textured.gltf")
    # 2 x 2 texels, row 0 first (v < 0.5)
    mr = doc.image(2, 2, [0, 255, 0, 255, 0, 51, 255, 255] * 2)
    ao = doc.image(2, 2, [255, 255, 255, 255] * 2 + [64, 255, 255, 255] * 2)
    floor = doc.material({"name": "floor", "pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 1.0, "roughnessFactor": 1.0,
        "metallicRoughnessTexture": {"index": mr}}, "occlusionTexture": {"index": ao, "strength": 1.0}})
    pos, nrm, idx, uv = quad_y(-2, -2, 2, 2, uv=True)
    doc.mesh(pos, nrm, idx, floor, uv)
    unlit = doc.material(pbr("unlit", (0.2, 0.9, 0.3), 0.0, 1.0, extensions={"KHR_materials_unlit": {}}))
    pos, nrm, idx = box((-0.25, 0, -0.25), (0.25, 0.5, 0.25))
    doc.mesh(pos, nrm, idx, unlit)
    doc.lights([([1, 1, 1], 6.0, [0, 2, 0])])
    doc.d["extensionsUsed"].append("KHR_materials_unlit")
    doc.write()


patches()
spheres()
textured()
