#!/usr/bin/env python3
"""Generates the glTF feature files of tests/corpus/gltf/features/ (vertex colours, TEXCOORD_1,
sampler wrap/filter modes, KHR_texture_transform, the emissive texture's parsing) checked by
tests/test_scene.c (the loader fills exactly these values) and tests/test_gpu_surface.c (the
pixels). Run from anywhere: `python3 tests/corpus/gltf/features/gen_features.py`. Deterministic;
the outputs are committed next to this script.

Every file is a unit quad [-1,1]^2 in the plane z = 0 facing +Z (corners TL (-1,1), TR (1,1),
BL (-1,-1), BR (1,-1)), except where said. UV corners are given as (u, v) for TL, TR, BL, BR.
Textures are tiny PNG data URIs whose channels are 0 or 255 (exact in sRGB and linear).
"""
import base64
import json
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltfgen import pad4, png_rgba  # noqa: E402  (tests/corpus/gltf/gltfgen.py)

HERE = os.path.dirname(os.path.abspath(__file__))


def f32(*v):
    return struct.pack("<%df" % len(v), *v)


def png_uri(w, h, pixels):
    return "data:image/png;base64," + base64.b64encode(png_rgba(w, h, pixels)).decode()


class Doc:
    """A glTF document with one buffer built up accessor by accessor."""

    def __init__(self):
        self.bin = b""
        self.d = {"asset": {"version": "2.0", "generator": "passgraph gen_features.py"},
                  "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
                  "meshes": [{"primitives": []}], "accessors": [], "bufferViews": []}

    def accessor(self, data, ctype, count, typ, normalized=False):
        self.d["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += pad4(data)
        a = {"bufferView": len(self.d["bufferViews"]) - 1, "componentType": ctype, "count": count,
             "type": typ}
        if normalized:
            a["normalized"] = True
        self.d["accessors"].append(a)
        return len(self.d["accessors"]) - 1

    def primitive(self, attrs, indices, material=None):
        p = {"attributes": attrs, "indices": self.accessor(struct.pack("<%dH" % len(indices), *indices),
                                                          5123, len(indices), "SCALAR")}
        if material is not None:
            p["material"] = material
        self.d["meshes"][0]["primitives"].append(p)

    def write(self, name):
        self.d["buffers"] = [{"byteLength": len(self.bin),
                              "uri": "data:application/octet-stream;base64," +
                                     base64.b64encode(self.bin).decode()}]
        with open(os.path.join(HERE, name), "w") as f:
            f.write(json.dumps(self.d, indent=1) + "\n")


CORNERS = [(-1, 1), (1, 1), (-1, -1), (1, -1)]          # TL, TR, BL, BR
QUAD_IDX = [2, 3, 1, 2, 1, 0]                           # counter-clockwise seen from +Z


def quad_attrs(doc, uv0=None, uv1=None, x0=-1.0, y0=-1.0, x1=1.0, y1=1.0):
    pos = [(x0, y1), (x1, y1), (x0, y0), (x1, y0)]
    attrs = {"POSITION": doc.accessor(f32(*[c for p in pos for c in (p[0], p[1], 0.0)]), 5126, 4, "VEC3"),
             "NORMAL": doc.accessor(f32(*([0.0, 0.0, 1.0] * 4)), 5126, 4, "VEC3")}
    if uv0:
        attrs["TEXCOORD_0"] = doc.accessor(f32(*[c for uv in uv0 for c in uv]), 5126, 4, "VEC2")
    if uv1:
        attrs["TEXCOORD_1"] = doc.accessor(f32(*[c for uv in uv1 for c in uv]), 5126, 4, "VEC2")
    return attrs


# ---- vertex colours: four sub-quads (TL, TR, BL, BR of the quad), one colour each --------------
# linear RGBA per sub-quad; the unorm files store round(c * 255) / round(c * 65535)
SUB_COLORS = [(1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0), (0.25, 0.5, 1.0, 0.5)]


def vcolor_file(name, ctype, ncomp, factor, extra_plain):
    doc = Doc()
    pos, col, idx = [], [], []
    for k, (cx, cy) in enumerate([(-0.5, 0.5), (0.5, 0.5), (-0.5, -0.5), (0.5, -0.5)]):
        for (sx, sy) in CORNERS:
            pos += [cx + 0.5 * sx, cy + 0.5 * sy, 0.0]
            col.append(SUB_COLORS[k][:ncomp])
        idx += [4 * k + i for i in QUAD_IDX]
    if ctype == 5126:
        data = f32(*[c for cc in col for c in cc])
    elif ctype == 5121:
        data = bytes(round(c * 255) for cc in col for c in cc)
    else:
        data = struct.pack("<%dH" % (len(col) * ncomp), *[round(c * 65535) for cc in col for c in cc])
    attrs = {"POSITION": doc.accessor(f32(*pos), 5126, 16, "VEC3"),
             "NORMAL": doc.accessor(f32(*([0.0, 0.0, 1.0] * 16)), 5126, 16, "VEC3"),
             "COLOR_0": doc.accessor(data, ctype, 16, "VEC%d" % ncomp, normalized=ctype != 5126)}
    doc.d["materials"] = [{"name": "vc", "pbrMetallicRoughness": {"baseColorFactor": factor,
                                                                  "metallicFactor": 0}}]
    doc.primitive(attrs, idx, 0)
    if extra_plain:  # a second primitive without COLOR_0 (its vertices get white), right of the quad
        doc.primitive(quad_attrs(doc, x0=1.2, y0=-0.2, x1=1.6, y1=0.2), QUAD_IDX, 0)
    doc.write(name)


vcolor_file("vcolor_float3.gltf", 5126, 3, [1, 1, 1, 1], False)
vcolor_file("vcolor_unorm8.gltf", 5121, 4, [1, 1, 1, 1], True)
vcolor_file("vcolor_unorm16.gltf", 5123, 4, [1, 0.5, 1, 1], False)

# ---- textured quads ----------------------------------------------------------------------------
R, G, B, Y, M, C, W, K = ([255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 0, 255],
                          [255, 0, 255, 255], [0, 255, 255, 255], [255, 255, 255, 255], [0, 0, 0, 255])


def textured(name, w, h, pixels, uv0, sampler, tex_info=None, uv1=None, extensions=None):
    doc = Doc()
    doc.d["images"] = [{"uri": png_uri(w, h, sum(pixels, []))}]
    doc.d["samplers"] = [sampler]
    doc.d["textures"] = [{"source": 0, "sampler": 0}]
    ti = {"index": 0}
    ti.update(tex_info or {})
    doc.d["materials"] = [{"name": name.split(".")[0],
                           "pbrMetallicRoughness": {"baseColorTexture": ti, "metallicFactor": 0}}]
    if extensions:
        doc.d["extensionsUsed"] = extensions
    doc.primitive(quad_attrs(doc, uv0, uv1), QUAD_IDX, 0)
    return doc


NEAREST = {"magFilter": 9728, "minFilter": 9728}
# wrap modes: UVs -1..2 over an asymmetric 3x2 texture: 3x3 periods on the quad
WRAP_UV = [(-1, -1), (2, -1), (-1, 2), (2, 2)]
WRAP_TEX = (3, 2, [R, G, B, Y, M, W])
for name, ws, wt in (("wrap_repeat.gltf", 10497, 10497), ("wrap_clamp.gltf", 33071, 33071),
                     ("wrap_mirror.gltf", 33648, 33648), ("wrap_clamp_mirror.gltf", 33071, 33648)):
    s = dict(NEAREST, wrapS=ws, wrapT=wt)
    textured(name, *WRAP_TEX, WRAP_UV, s).write(name)

# magnification: a 2x2 checker stretched over the quad, NEAREST vs LINEAR
for name, mag in (("mag_nearest.gltf", 9728), ("mag_linear.gltf", 9729)):
    textured(name, 2, 2, [K, W, W, K], [(0, 0), (1, 0), (0, 1), (1, 1)],
             {"magFilter": mag, "minFilter": 9987, "wrapS": 33071, "wrapT": 33071}).write(name)

# minification: a 2x2 checker repeated 128 times across the quad (2 texels per pixel at 64 px:
# LOD >= 1): minFilter NEAREST samples level 0 only (every pixel black or white), with
# NEAREST_MIPMAP_NEAREST the 1x1 level (grey)
for name, mn in (("min_nearest.gltf", 9728), ("min_nearest_mipmap.gltf", 9984)):
    textured(name, 2, 2, [K, W, W, K], [(0, 0), (128, 0), (0, 128), (128, 128)],
             {"magFilter": 9728, "minFilter": mn}).write(name)

# TEXCOORD_1: TEXCOORD_0 covers the left (red) texel, TEXCOORD_1 the right (blue) one
UV_LEFT = [(0.05, 0.1), (0.45, 0.1), (0.05, 0.9), (0.45, 0.9)]
UV_RIGHT = [(0.55, 0.1), (0.95, 0.1), (0.55, 0.9), (0.95, 0.9)]
textured("texcoord1.gltf", 2, 1, [R, B], UV_LEFT, NEAREST, {"texCoord": 1}, UV_RIGHT).write("texcoord1.gltf")
textured("texcoord0.gltf", 2, 1, [R, B], UV_LEFT, NEAREST, {"texCoord": 0}, UV_RIGHT).write("texcoord0.gltf")

# KHR_texture_transform on a 2x2 texture (red green / blue white), REPEAT, NEAREST
XF_TEX = (2, 2, [R, G, B, W])
UV01 = [(0, 0), (1, 0), (0, 1), (1, 1)]
REPEAT_NEAREST = dict(NEAREST, wrapS=10497, wrapT=10497)
for name, xf in (("xform_offset.gltf", {"offset": [0.5, 0]}),
                 ("xform_scale.gltf", {"scale": [0.5, 0.5]}),
                 ("xform_rotation.gltf", {"rotation": 1.5707963267948966}),
                 ("xform_all.gltf", {"offset": [0, 1], "rotation": 1.5707963267948966, "scale": [0.5, 1]})):
    textured(name, *XF_TEX, UV01, REPEAT_NEAREST, {"extensions": {"KHR_texture_transform": xf}},
             extensions=["KHR_texture_transform"]).write(name)
# the transform's texCoord overrides the textureInfo's; required: accepted (implemented)
d = textured("xform_texcoord.gltf", 2, 1, [R, B], UV_LEFT, NEAREST,
             {"texCoord": 0, "extensions": {"KHR_texture_transform": {"texCoord": 1}}}, UV_RIGHT,
             extensions=["KHR_texture_transform"])
d.d["extensionsRequired"] = ["KHR_texture_transform"]
d.write("xform_texcoord.gltf")

# ---- loader-only files (test_scene) ------------------------------------------------------------
# every slot: base texCoord 0, normal texCoord 1 + transform, emissive texCoord 0 overridden to 1
# by its transform; a second material with a texCoord 2 (warned, read with TEXCOORD_0)
doc = Doc()
doc.d["images"] = [{"uri": png_uri(2, 1, R + B)}]
doc.d["textures"] = [{"source": 0}]
doc.d["extensionsUsed"] = ["KHR_texture_transform"]
doc.d["materials"] = [
    {"name": "slots",
     "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}},
     "normalTexture": {"index": 0, "texCoord": 1,
                       "extensions": {"KHR_texture_transform": {"offset": [0.25, -0.5], "scale": [2, 3]}}},
     "emissiveTexture": {"index": 0,
                         "extensions": {"KHR_texture_transform": {"rotation": 0.5, "texCoord": 1}}}},
    {"name": "far", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 2}}}]
doc.primitive(quad_attrs(doc, UV01, UV_RIGHT), QUAD_IDX, 0)
doc.primitive(quad_attrs(doc, UV01, x0=1.2, x1=1.6), QUAD_IDX, 1)
doc.write("slots.gltf")

# TEXCOORD_1 present but no texture reads it: no uv1 stream
textured("uv1_unused.gltf", 2, 1, [R, B], UV_LEFT, NEAREST, None, UV_RIGHT).write("uv1_unused.gltf")

# TEXCOORD_1 read by a material but missing in primitives 0 and 2 (primitive 1 has it): their
# TEXCOORD_1 is a copy of their TEXCOORD_0 (warned)
doc = Doc()
doc.d["images"] = [{"uri": png_uri(2, 1, R + B)}]
doc.d["textures"] = [{"source": 0}]
doc.d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1}}}]
doc.primitive(quad_attrs(doc, [(0.1, 0.2), (0.3, 0.2), (0.1, 0.4), (0.3, 0.4)], x0=-1, x1=-0.5), QUAD_IDX, 0)
doc.primitive(quad_attrs(doc, UV01, UV_RIGHT, x0=-0.4, x1=0.1), QUAD_IDX, 0)
doc.primitive(quad_attrs(doc, [(0.6, 0.7), (0.8, 0.7), (0.6, 0.9), (0.8, 0.9)], x0=0.2, x1=0.7), QUAD_IDX, 0)
doc.write("uv1_missing.gltf")

# samplers: one image used through every minFilter value and wrap mode; samplers 6 and 7 have
# the same state (one pg_texture); texture 8 has no sampler (the default state, = sampler 5):
# 7 pg_textures
doc = Doc()
doc.d["images"] = [{"uri": png_uri(2, 1, R + B)}]
doc.d["samplers"] = [{"minFilter": 9728, "magFilter": 9728, "wrapS": 33071, "wrapT": 33648},
                     {"minFilter": 9729, "magFilter": 9729, "wrapS": 33648, "wrapT": 33071},
                     {"minFilter": 9984},
                     {"minFilter": 9985},
                     {"minFilter": 9986},
                     {"minFilter": 9987},
                     {"wrapS": 33071},
                     {"wrapS": 33071, "wrapT": 10497, "magFilter": 9729}]
doc.d["textures"] = [{"source": 0, "sampler": i} for i in range(8)] + [{"source": 0}]
doc.d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": i}}} for i in range(9)]
for i in range(9):
    doc.primitive(quad_attrs(doc, UV01, x0=-1 + 0.2 * i, x1=-0.9 + 0.2 * i), QUAD_IDX, i)
doc.write("samplers.gltf")

# ---- textured boxes: one 16x16 checker texture (trilinear, REPEAT) over the six faces of a unit
# box seen at an angle (the default camera frames it), so minification and triangle edges both
# show. box_plain reads TEXCOORD_0; box_xform an identity KHR_texture_transform; box_uv1 reads
# TEXCOORD_1 (= box_plain's UVs; its TEXCOORD_0 is scrambled). All three must render alike.
def box_doc(tex_info, uv_scramble, extensions=None):
    doc = Doc()
    n = 16
    doc.d["images"] = [{"uri": png_uri(n, n, sum([(W if ((x // 2 + y // 2) % 2) else [200, 40, 20, 255])
                                                   for y in range(n) for x in range(n)], []))}]
    doc.d["samplers"] = [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}]
    doc.d["textures"] = [{"source": 0, "sampler": 0}]
    ti = {"index": 0}
    ti.update(tex_info)
    doc.d["materials"] = [{"name": "box", "pbrMetallicRoughness": {"baseColorTexture": ti, "metallicFactor": 0}}]
    if extensions:
        doc.d["extensionsUsed"] = extensions
    pos, nrm, uv, idx = [], [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            u_ax, v_ax = [a for a in range(3) if a != axis]
            base = len(pos)
            for (cu, cv) in ((-1, -1), (1, -1), (-1, 1), (1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis], p[u_ax], p[v_ax] = sign, cu * sign, cv
                q = [0.0, 0.0, 0.0]
                q[axis] = sign
                pos.append(p)
                nrm.append(q)
                uv.append(((cu + 1) * 2.0, (cv + 1) * 2.0))
            idx += [base + i for i in (0, 1, 3, 0, 3, 2)]
    cnt = len(pos)
    attrs = {"POSITION": doc.accessor(f32(*[c for p in pos for c in p]), 5126, cnt, "VEC3"),
             "NORMAL": doc.accessor(f32(*[c for p in nrm for c in p]), 5126, cnt, "VEC3")}
    if uv_scramble:
        attrs["TEXCOORD_0"] = doc.accessor(f32(*[c for k, t in enumerate(uv) for c in (0.37 * k, 0.11 * k * k)]),
                                           5126, cnt, "VEC2")
        attrs["TEXCOORD_1"] = doc.accessor(f32(*[c for t in uv for c in t]), 5126, cnt, "VEC2")
    else:
        attrs["TEXCOORD_0"] = doc.accessor(f32(*[c for t in uv for c in t]), 5126, cnt, "VEC2")
    doc.primitive(attrs, idx, 0)
    doc.d["nodes"][0]["rotation"] = [0.2, 0.35, 0.1, 0.9092]
    return doc


box_doc({}, False).write("box_plain.gltf")
box_doc({"extensions": {"KHR_texture_transform": {"offset": [0, 0], "rotation": 0, "scale": [1, 1]}}}, False,
        ["KHR_texture_transform"]).write("box_xform.gltf")
box_doc({"texCoord": 1}, True).write("box_uv1.gltf")

# ---- KHR_materials_pbrSpecularGlossiness (archived): three quads. Material 0 has only the
# extension (diffuseFactor (0.8, 0.2, 0.1, 1), glossinessFactor 0.75): approximated as base colour
# (0.8, 0.2, 0.1, 1), roughness 0.25, metallic 0. Material 1 has only the extension with a
# diffuseTexture (a 2x2 texture, texCoord 0, a KHR_texture_transform scale 2): the base colour
# texture with that transform. Material 2 has pbrMetallicRoughness (green, metallic 0.5, roughness
# 0.4) and the extension (red): the core material is drawn.
doc = Doc()
doc.d["extensionsUsed"] = ["KHR_materials_pbrSpecularGlossiness", "KHR_texture_transform", "KHR_xmp_json_ld"]
doc.d["images"] = [{"uri": png_uri(2, 2, [255, 255, 255, 255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255, 255])}]
doc.d["textures"] = [{"source": 0}]
SG = "KHR_materials_pbrSpecularGlossiness"
doc.d["materials"] = [
    {"name": "sg_factor", "extensions": {SG: {"diffuseFactor": [0.8, 0.2, 0.1, 1.0], "glossinessFactor": 0.75,
                                              "specularFactor": [0.5, 0.5, 0.5]}}},
    {"name": "sg_texture", "extensions": {SG: {"diffuseTexture": {"index": 0, "extensions": {
        "KHR_texture_transform": {"scale": [2.0, 2.0]}}}}}},
    {"name": "core_and_sg", "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.8, 0.1, 1.0], "metallicFactor": 0.5,
                                                     "roughnessFactor": 0.4},
     "extensions": {SG: {"diffuseFactor": [1.0, 0.0, 0.0, 1.0]}}}]
for i in range(3):
    doc.primitive(quad_attrs(doc, UV01, x0=-1 + 0.7 * i, x1=-0.4 + 0.7 * i), QUAD_IDX, i)
doc.write("spec_gloss.gltf")

# errors
doc = Doc()
attrs = quad_attrs(doc)
attrs["COLOR_0"] = doc.accessor(f32(*([1.0, 0.0] * 4)), 5126, 4, "VEC2")
doc.primitive(attrs, QUAD_IDX)
doc.write("bad_color_vec2.gltf")
doc = Doc()
attrs = quad_attrs(doc)
attrs["COLOR_0"] = doc.accessor(bytes([255, 0, 0, 255] * 4), 5121, 4, "VEC4")  # not normalized
doc.primitive(attrs, QUAD_IDX)
doc.write("bad_color_not_normalized.gltf")
textured("bad_xform_offset.gltf", *XF_TEX, UV01, NEAREST,
         {"extensions": {"KHR_texture_transform": {"offset": [0.5, 0, 1]}}}).write("bad_xform_offset.gltf")
textured("bad_xform_rotation.gltf", *XF_TEX, UV01, NEAREST,
         {"extensions": {"KHR_texture_transform": {"rotation": "90deg"}}}).write("bad_xform_rotation.gltf")
print("wrote", len([f for f in os.listdir(HERE) if f.endswith(".gltf")]), "files")
