#!/usr/bin/env python3
"""Generates the node-animation, skinning and morph-target scenes of the animation tests.
Deterministic; the output is committed. Run: `python3 tests/corpus/gltf/animation/gen_animation.py`.
Metres, +Y up; every mesh has POSITION + NORMAL (+ UNSIGNED_INT indices); the materials are
metallic-roughness with metallic 0, roughness 1; one scene, no cameras, no lights. Every file has a
grey 20 x 20 floor quad at y = 0 facing +Y (nodes[0] "floor", meshes[0], not animated).

  rigid.gltf     nodes[1] "spinner" (translation (0, 0.5, 0), mesh 1 = unit box centred at the
                 origin, red) with child nodes[2] "satellite" (translation (1.5, 0, 0), scale 0.5,
                 the same mesh 1).
                 animations[0] "spin": spinner rotation LINEAR about +Y, t = 0 1 2 3 4 s ->
                 0 90 180 270 360 deg; spinner translation STEP t = 0 -> (0, 0.5, 0), t = 2 ->
                 (2, 0.5, 0); satellite scale CUBICSPLINE t = 0 2 4 -> 0.5 1 0.5 (uniform), all
                 tangents 0 but the middle key's in/out tangents (0.25, 0.25, 0.25).
                 animations[1] "bounce": spinner translation LINEAR t = 0 -> (0, 0.5, 0), t = 1 ->
                 (0, 2, 0).
  skinned.gltf   a 0.4 x 2 x 0.4 tube (x, z in [-0.2, 0.2], y in [0, 2]; 9 rings of 4 corners, 8
                 segments, flat side normals, a top cap, no bottom cap; orange) skinned to skins[0]:
                 joints [nodes[1] "root" (origin), nodes[2] "elbow" (child of root, translation
                 (0, 1, 0))], skeleton = root, inverseBindMatrices identity and translate(0, -1, 0).
                 JOINTS_0 UNSIGNED_BYTE VEC4, WEIGHTS_0 FLOAT VEC4: w_elbow = clamp((y - 0.75) / 0.5,
                 0, 1), w_root = 1 - w_elbow (rings at y <= 0.75 follow root, y = 1 half/half,
                 y >= 1.25 elbow). nodes[3] "arm_mesh" (skin 0, mesh 1) has translation (5, 0, 0),
                 which glTF says is IGNORED for a skinned mesh.
                 animations[0] "bend": elbow rotation LINEAR about +Z, t = 0 1 2 -> 0 90 0 deg.
  morph.gltf     nodes[1] "morpher" (translation (0, 0.5, 0), mesh 1 = unit box centred at the
                 origin, green) with 2 morph targets: target 0 POSITION (a sparse accessor, no
                 bufferView: zeros but for the 12 vertices at y = +0.5) moves y = +0.5 up by 1;
                 target 1 POSITION moves the 12 vertices at x = +0.5 by +0.5 in x, and has a NORMAL
                 accessor of zero deltas (a stretch keeps the face normals). mesh.weights = [0.25, 0].
                 animations[0] "breathe": morpher weights LINEAR, t = 0 1 2 -> [0, 0] [1, 0.5] [0, 0].

Vertex numbering: the unit boxes are gltfgen.box((-0.5,)*3, (0.5,)*3): faces +X -X +Y -Y +Z -Z, 4
vertices each, so vertex 10 is (0.5, 0.5, 0.5) on the +Y face, vertex 2 the same corner on the +X
face, vertex 12 is (-0.5, -0.5, -0.5). The tube's vertex side * 18 + ring * 2 + c (side 0..3 = +Z +X
-Z -X, ring 0..8 at y = ring / 4, c 0/1 = the side's two corners counter-clockwise seen from outside)
then the cap's 72..75; vertex 17 is (0.2, 2, 0.2), vertex 9 is (0.2, 1, 0.2), vertex 1 is
(0.2, 0, 0.2).

README (hand-written) lists the easy poses. After writing, the script reads every file back (JSON +
base64), checks its structure (counts, bufferView lengths, exact min/max, POSITION min/max present,
increasing sampler inputs with min/max, output counts, skins, targets, winding) and evaluates the poses
of POSES below with its own sampler/skinning/morph code, asserting them.
"""
import base64
import json
import math
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltfgen import box, pad4, png_rgba  # noqa: E402  (tests/corpus/gltf/gltfgen.py)

HERE = os.path.dirname(os.path.abspath(__file__))
FLOAT, UBYTE, USHORT, UINT = 5126, 5121, 5123, 5125


def f32(v):
    """v rounded to float32 (what the buffer holds), as a Python float"""
    return struct.unpack("<f", struct.pack("<f", v))[0]


def quat_axis(axis, deg):
    s, c = math.sin(math.radians(deg) / 2), math.cos(math.radians(deg) / 2)
    return [0.0 if abs(x) < 1e-12 else x for x in (axis[0] * s, axis[1] * s, axis[2] * s, c)]  # exact 0 at 180 deg


def floats(rows):
    return b"".join(struct.pack("<%df" % len(r), *r) for r in rows)


class Doc:
    def __init__(self, name):
        self.name = name
        self.bin = b""
        self.d = {"asset": {"version": "2.0", "generator": "passgraph gen_animation.py"}, "scene": 0,
                  "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "materials": [], "accessors": [],
                  "bufferViews": []}

    def view(self, data):
        self.d["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += pad4(data)
        return len(self.d["bufferViews"]) - 1

    def accessor(self, data, ctype, count, typ, mn=None, mx=None):
        a = {"bufferView": self.view(data), "componentType": ctype, "count": count, "type": typ}
        if mn is not None:
            a["min"], a["max"] = mn, mx
        self.d["accessors"].append(a)
        return len(self.d["accessors"]) - 1

    def vec3(self, rows, bounds=False):
        if bounds:
            return self.accessor(floats(rows), FLOAT, len(rows), "VEC3", *minmax(rows))
        return self.accessor(floats(rows), FLOAT, len(rows), "VEC3")

    def times(self, t):
        return self.accessor(floats([[x] for x in t]), FLOAT, len(t), "SCALAR", [f32(min(t))], [f32(max(t))])

    def sparse_vec3(self, count, values):
        """a VEC3 FLOAT accessor of `count` zeros (no bufferView) but for values {index: xyz}"""
        idx = sorted(values)
        rows = [values[i] for i in idx]
        dense = [values.get(i, (0, 0, 0)) for i in range(count)]
        a = {"componentType": FLOAT, "count": count, "type": "VEC3"}
        a["min"], a["max"] = minmax(dense)
        a["sparse"] = {"count": len(idx),
                       "indices": {"bufferView": self.view(struct.pack("<%dH" % len(idx), *idx)),
                                   "componentType": USHORT},
                       "values": {"bufferView": self.view(floats(rows))}}
        self.d["accessors"].append(a)
        return len(self.d["accessors"]) - 1

    def mesh(self, name, pos, nrm, idx, material, extra_attrs=None, targets=None, weights=None):
        attrs = {"POSITION": self.vec3(pos, bounds=True), "NORMAL": self.vec3(nrm)}
        attrs.update(extra_attrs or {})
        prim = {"attributes": attrs, "indices": self.accessor(struct.pack("<%dI" % len(idx), *idx), UINT,
                                                              len(idx), "SCALAR"), "material": material}
        if targets:
            prim["targets"] = targets
        m = {"name": name, "primitives": [prim]}
        if weights is not None:
            m["weights"] = weights
        self.d["meshes"].append(m)
        return len(self.d["meshes"]) - 1

    def node(self, n, root=True):
        self.d["nodes"].append(n)
        if root:
            self.d["scenes"][0]["nodes"].append(len(self.d["nodes"]) - 1)
        return len(self.d["nodes"]) - 1

    def material(self, name, base, alpha=None):
        """alpha: None opaque, else alphaMode BLEND with that base colour alpha"""
        m = {"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": list(base) + [1.0 if alpha is None else alpha], "metallicFactor": 0.0,
            "roughnessFactor": 1.0}}
        if alpha is not None:
            m["alphaMode"] = "BLEND"
        self.d["materials"].append(m)
        return len(self.d["materials"]) - 1

    def animation(self, name, channels, pointer=False):
        """channels: (node, path, interpolation, times, output rows); pointer: targets given as
        KHR_animation_pointer JSON pointers (/nodes/N/path), and a node of None takes `path` as the
        pointer itself, its type from the rows' width (e.g. a material's baseColorFactor, VEC4)"""
        anim = {"name": name, "channels": [], "samplers": []}
        for node, path, interp, t, rows in channels:
            typ = {"translation": "VEC3", "scale": "VEC3", "rotation": "VEC4", "weights": "SCALAR"}.get(path) \
                or {1: "SCALAR", 2: "VEC2", 3: "VEC3", 4: "VEC4"}[len(rows[0])]
            out = self.accessor(floats(rows), FLOAT, len(rows), typ)
            anim["samplers"].append({"input": self.times(t), "interpolation": interp, "output": out})
            if pointer:
                ptr = path if node is None else "/nodes/%d/%s" % (node, path)
                target = {"path": "pointer", "extensions": {"KHR_animation_pointer": {"pointer": ptr}}}
            else:
                target = {"node": node, "path": path}
            anim["channels"].append({"sampler": len(anim["samplers"]) - 1, "target": target})
        self.d.setdefault("animations", []).append(anim)

    def floor(self):
        pos = [(-10, 0, -10), (-10, 0, 10), (10, 0, 10), (10, 0, -10)]
        mesh = self.mesh("floor", pos, [(0, 1, 0)] * 4, [0, 1, 2, 0, 2, 3],
                         self.material("floor_grey", (0.5, 0.5, 0.5)))
        self.node({"name": "floor", "mesh": mesh})

    def write(self):
        self.d["buffers"] = [{"byteLength": len(self.bin),
                              "uri": "data:application/octet-stream;base64," + base64.b64encode(self.bin).decode()}]
        with open(os.path.join(HERE, self.name), "w") as f:
            f.write(json.dumps(self.d, indent=1) + "\n")


def minmax(rows):
    return ([f32(min(r[k] for r in rows)) for k in range(len(rows[0]))],
            [f32(max(r[k] for r in rows)) for k in range(len(rows[0]))])


UNIT_BOX = box((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5))


def rigid():
    doc = Doc("rigid.gltf")
    doc.floor()
    cube = doc.mesh("box", *UNIT_BOX, doc.material("box_red", (0.8, 0.15, 0.1)))
    spinner = doc.node({"name": "spinner", "mesh": cube, "translation": [0, 0.5, 0], "children": [2]})
    satellite = doc.node({"name": "satellite", "mesh": cube, "translation": [1.5, 0, 0],
                          "scale": [0.5, 0.5, 0.5]}, root=False)
    assert (spinner, satellite) == (1, 2)
    half, one, tan = (0.5, 0.5, 0.5), (1, 1, 1), (0.25, 0.25, 0.25)
    doc.animation("spin", [
        (spinner, "rotation", "LINEAR", [0, 1, 2, 3, 4], [quat_axis((0, 1, 0), a) for a in (0, 90, 180, 270, 360)]),
        (spinner, "translation", "STEP", [0, 2], [(0, 0.5, 0), (2, 0.5, 0)]),
        (satellite, "scale", "CUBICSPLINE", [0, 2, 4],
         [(0, 0, 0), half, (0, 0, 0), tan, one, tan, (0, 0, 0), half, (0, 0, 0)])])
    doc.animation("bounce", [(spinner, "translation", "LINEAR", [0, 1], [(0, 0.5, 0), (0, 2, 0)])])
    doc.write()


def nonunit():
    """rigid.gltf's spinner alone, its rotation keys halved: 0.5 q(0) and 0.5 q(120 deg) about +Y over
    1 s (not unit quaternions, as the specification requires; slerp between them turned by the wrong
    angle: 32.2 deg at t = 0.25 instead of 30)"""
    doc = Doc("nonunit.gltf")
    doc.floor()
    cube = doc.mesh("box", *UNIT_BOX, doc.material("box_red", (0.8, 0.15, 0.1)))
    spinner = doc.node({"name": "spinner", "mesh": cube, "translation": [0, 0.5, 0]})
    assert spinner == 1
    doc.animation("spin", [(spinner, "rotation", "LINEAR", [0, 1],
                            [tuple(0.5 * c for c in quat_axis((0, 1, 0), a)) for a in (0, 120)])])
    doc.write()


def pointer():
    """rigid.gltf's two animations with every target a KHR_animation_pointer (/nodes/N/path), and a
    channel animating a material's KHR_materials_ior ior that passgraph ignores (and warns about)"""
    doc = Doc("pointer.gltf")
    doc.d["extensionsUsed"] = ["KHR_animation_pointer"]
    doc.floor()
    red = doc.material("box_red", (0.8, 0.15, 0.1))
    cube = doc.mesh("box", *UNIT_BOX, red)
    spinner = doc.node({"name": "spinner", "mesh": cube, "translation": [0, 0.5, 0], "children": [2]})
    satellite = doc.node({"name": "satellite", "mesh": cube, "translation": [1.5, 0, 0],
                          "scale": [0.5, 0.5, 0.5]}, root=False)
    assert (spinner, satellite, red) == (1, 2, 1)
    half, one, tan = (0.5, 0.5, 0.5), (1, 1, 1), (0.25, 0.25, 0.25)
    doc.animation("spin", [
        (spinner, "rotation", "LINEAR", [0, 1, 2, 3, 4], [quat_axis((0, 1, 0), a) for a in (0, 90, 180, 270, 360)]),
        (spinner, "translation", "STEP", [0, 2], [(0, 0.5, 0), (2, 0.5, 0)]),
        (satellite, "scale", "CUBICSPLINE", [0, 2, 4],
         [(0, 0, 0), half, (0, 0, 0), tan, one, tan, (0, 0, 0), half, (0, 0, 0)]),
        (None, "/materials/1/extensions/KHR_materials_ior/ior", "LINEAR", [0, 4], [(1.5,), (1.2,)])], pointer=True)
    doc.animation("bounce", [(spinner, "translation", "LINEAR", [0, 1], [(0, 0.5, 0), (0, 2, 0)])], pointer=True)
    doc.write()


def beacon():
    """a spot light on a still node, pointing down, whose colour, intensity, range and cones are
    animated by KHR_animation_pointer (/extensions/KHR_lights_punctual/lights/0/...), and a still
    camera whose yfov and zfar are (/cameras/0/perspective/...)"""
    doc = Doc("beacon.gltf")
    doc.d["extensionsUsed"] = ["KHR_lights_punctual", "KHR_animation_pointer"]
    doc.floor()
    cube = doc.mesh("post", *UNIT_BOX, doc.material("post_blue", (0.1, 0.2, 0.8)))
    doc.node({"name": "post", "mesh": cube, "translation": [1.5, 0.5, 0]})
    lamp_node = doc.node({"name": "beacon", "translation": [0, 3, 0], "rotation": quat_axis((1, 0, 0), -90),
                          "extensions": {"KHR_lights_punctual": {"light": 0}}})
    # a still camera at (0, 4, 6) looking at the origin, zooming in: yfov 0.8 -> 0.4, zfar 50 -> 30
    eye = doc.node({"name": "eye", "camera": 0, "translation": [0, 4, 6],
                    "rotation": quat_axis((1, 0, 0), -math.degrees(math.atan2(4, 6)))})
    doc.d["cameras"] = [{"name": "eye", "type": "perspective",
                         "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 50.0}}]
    assert (lamp_node, eye) == (2, 3)
    doc.d["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "beacon", "type": "spot", "color": [1.0, 1.0, 1.0], "intensity": 20.0, "range": 8.0,
         "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.6}}]}}
    L = "/extensions/KHR_lights_punctual/lights/0/"
    doc.animation("pulse", [
        (None, L + "color", "LINEAR", [0, 2, 4], [(1, 1, 1), (1, 0.3, 0.2), (0.2, 0.4, 1)]),
        (None, L + "intensity", "LINEAR", [0, 4], [(20,), (60,)]),
        (None, L + "range", "STEP", [0, 2], [(8,), (4,)]),
        (None, L + "spot/innerConeAngle", "LINEAR", [0, 4], [(0.3,), (0.1,)]),
        (None, L + "spot/outerConeAngle", "LINEAR", [0, 4], [(0.6,), (0.9,)]),
        (None, "/cameras/0/perspective/yfov", "LINEAR", [0, 4], [(0.8,), (0.4,)]),
        (None, "/cameras/0/perspective/zfar", "LINEAR", [0, 4], [(50,), (30,)])], pointer=True)
    doc.write()


def shimmer():
    """KHR_animation_pointer on materials: four boxes under a directional light whose base colour,
    metallic and roughness ("tint"), emissive factor and KHR_materials_emissive_strength ("glow"),
    base-colour texture's KHR_texture_transform offset, rotation and scale ("scroll", a 2x2 texture
    red green / blue white, NEAREST, REPEAT), alpha cutoff ("fade", MASK with alpha 0.6: seen
    while the cutoff is below 0.6) and a fifth box's normal scale and occlusion strength ("bump",
    behind the row) are animated; and one channel on a property passgraph does not
    animate (KHR_materials_ior's ior: ignored, warned)"""
    doc = Doc("shimmer.gltf")
    doc.d["extensionsUsed"] = ["KHR_lights_punctual", "KHR_animation_pointer", "KHR_materials_emissive_strength",
                               "KHR_texture_transform"]
    doc.floor()
    tint = doc.material("tint", (0.8, 0.15, 0.1))
    glow = doc.material("glow", (0.2, 0.2, 0.2))
    doc.d["materials"][glow]["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": 1.0}}
    scroll = doc.material("scroll", (1, 1, 1))
    doc.d["materials"][scroll]["pbrMetallicRoughness"]["baseColorTexture"] = {
        "index": 0, "extensions": {"KHR_texture_transform": {"offset": [0, 0]}}}
    fade = doc.material("fade", (0.3, 0.8, 0.3), alpha=0.6)
    doc.d["materials"][fade]["alphaMode"] = "MASK"
    # "bump": a 2x2 normal map (flat, tilted +x, tilted +y, tilted -x -y), also its occlusion (R)
    bump = doc.material("bump", (0.7, 0.7, 0.7))
    doc.d["materials"][bump]["normalTexture"] = {"index": 1}
    doc.d["materials"][bump]["occlusionTexture"] = {"index": 1}
    doc.d["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png_rgba(2, 2, [
        255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255])).decode()},
        {"uri": "data:image/png;base64," + base64.b64encode(png_rgba(2, 2, [
            128, 128, 255, 255, 200, 128, 200, 255, 128, 200, 200, 255, 90, 90, 230, 255])).decode()}]
    doc.d["samplers"] = [{"magFilter": 9728, "minFilter": 9728, "wrapS": 10497, "wrapT": 10497}]
    doc.d["textures"] = [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}]
    pos, nrm, idx = UNIT_BOX
    uv = [c for _ in range(6) for c in ((0, 0), (1, 0), (1, 1), (0, 1))]  # each face's corners
    uvs = doc.accessor(floats(uv), FLOAT, len(uv), "VEC2")
    for x, z, mat in ((-1.6, -0.5, tint), (-0.5, -0.5, glow), (0.6, -0.5, scroll), (1.7, -0.5, fade),
                      (0.05, -2.3, bump)):  # bump floats at y 1.6: seen above the row
        extra = {"TEXCOORD_0": uvs} if mat in (scroll, bump) else None
        mesh = doc.mesh(doc.d["materials"][mat]["name"], pos, nrm, idx, mat, extra_attrs=extra)
        doc.node({"name": doc.d["materials"][mat]["name"], "mesh": mesh,
                  "translation": [x, 1.6 if mat == bump else 0.5, z]})
    doc.node({"name": "sun", "rotation": quat_axis((1, 0, 0), -60),
              "extensions": {"KHR_lights_punctual": {"light": 0}}})
    doc.d["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "sun", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 3.0}]}}
    # a still camera at (0, 2.2, 4) looking at (0, 0.5, -0.5)
    doc.node({"name": "eye", "camera": 0, "translation": [0, 2.2, 4],
              "rotation": quat_axis((1, 0, 0), -math.degrees(math.atan2(1.7, 4.5)))})
    doc.d["cameras"] = [{"name": "eye", "type": "perspective",
                         "perspective": {"yfov": 0.7, "znear": 0.1, "zfar": 50.0}}]
    M = "/materials/%d/"
    X = M % scroll + "pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/"
    doc.animation("shimmer", [
        (None, M % tint + "pbrMetallicRoughness/baseColorFactor", "LINEAR", [0, 4],
         [(0.8, 0.15, 0.1, 1), (0.1, 0.15, 0.8, 1)]),
        (None, M % tint + "pbrMetallicRoughness/metallicFactor", "STEP", [0, 2], [(0,), (1,)]),
        (None, M % tint + "pbrMetallicRoughness/roughnessFactor", "LINEAR", [0, 4], [(1,), (0.3,)]),
        (None, M % glow + "emissiveFactor", "LINEAR", [0, 4], [(0, 0, 0), (1, 0.5, 0.1)]),
        (None, M % glow + "extensions/KHR_materials_emissive_strength/emissiveStrength", "LINEAR", [0, 4],
         [(1,), (3,)]),
        (None, X + "offset", "LINEAR", [0, 4], [(0, 0), (1.5, 0.5)]),
        (None, X + "rotation", "STEP", [0, 2], [(0,), (0.5,)]),
        (None, X + "scale", "LINEAR", [0, 4], [(1, 1), (2, 1)]),
        (None, M % fade + "alphaCutoff", "LINEAR", [0, 4], [(0.2,), (0.9,)]),
        (None, M % bump + "normalTexture/scale", "LINEAR", [0, 4], [(1,), (0.2,)]),
        (None, M % bump + "occlusionTexture/strength", "LINEAR", [0, 4], [(1,), (0,)]),
        (None, M % 0 + "extensions/KHR_materials_ior/ior", "LINEAR", [0, 4], [(1.5,), (1.2,)])], pointer=True)
    doc.write()


def target_of(c):
    """(node, path) of an animation channel, KHR_animation_pointer's /nodes/N/path included; (None,
    pointer) for another pointer"""
    t = c["target"]
    if t["path"] != "pointer":
        return t["node"], t["path"]
    ptr = t["extensions"]["KHR_animation_pointer"]["pointer"]
    parts = ptr.split("/")
    if len(parts) == 4 and parts[1] == "nodes":
        return int(parts[2]), parts[3]
    return None, ptr


def tube(h, rings, dy):
    """the sides (flat normals) of a square tube x, z in [-h, h], y in [0, (rings - 1) dy], and its top cap"""
    corners = [(-h, h), (h, h), (h, -h), (-h, -h)]  # (x, z): sides +Z, +X, -Z, -X
    pos, nrm, idx = [], [], []
    for s in range(4):
        (ax, az), (bx, bz) = corners[s], corners[(s + 1) % 4]
        n = (-(bz - az) / (2 * h), 0, (bx - ax) / (2 * h))  # (b - a) x (+Y), outwards
        base = len(pos)
        for r in range(rings):
            pos += [(ax, r * dy, az), (bx, r * dy, bz)]
            nrm += [n, n]
        for r in range(rings - 1):
            a, b, c, d = base + 2 * r, base + 2 * r + 1, base + 2 * r + 3, base + 2 * r + 2
            idx += [a, b, c, a, c, d]
    base, top = len(pos), (rings - 1) * dy
    pos += [(x, top, z) for x, z in corners]  # wound to face +Y
    nrm += [(0, 1, 0)] * 4
    idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, idx


def skinned():
    doc = Doc("skinned.gltf")
    doc.floor()
    pos, nrm, idx = tube(0.2, 9, 0.25)
    joints, weights = [], []
    for p in pos:
        we = min(max((p[1] - 0.75) / 0.5, 0.0), 1.0)
        if we == 0:
            joints.append((0, 0, 0, 0))
            weights.append((1, 0, 0, 0))
        elif we == 1:
            joints.append((1, 0, 0, 0))
            weights.append((1, 0, 0, 0))
        else:
            joints.append((0, 1, 0, 0))
            weights.append((1 - we, we, 0, 0))
    j = doc.accessor(b"".join(struct.pack("<4B", *x) for x in joints), UBYTE, len(joints), "VEC4")
    w = doc.accessor(floats(weights), FLOAT, len(weights), "VEC4")
    arm = doc.mesh("arm", pos, nrm, idx, doc.material("arm_orange", (0.9, 0.5, 0.1)),
                   extra_attrs={"JOINTS_0": j, "WEIGHTS_0": w})
    root = doc.node({"name": "root", "children": [2]})
    elbow = doc.node({"name": "elbow", "translation": [0, 1, 0]}, root=False)
    mesh_node = doc.node({"name": "arm_mesh", "mesh": arm, "skin": 0, "translation": [5, 0, 0]})
    assert (root, elbow, mesh_node) == (1, 2, 3)
    ident = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    elbow_inv = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1]  # column-major translate(0, -1, 0)
    ibm = doc.accessor(floats([ident, elbow_inv]), FLOAT, 2, "MAT4")
    doc.d["skins"] = [{"name": "arm_skin", "inverseBindMatrices": ibm, "joints": [root, elbow], "skeleton": root}]
    doc.animation("bend", [(elbow, "rotation", "LINEAR", [0, 1, 2],
                            [quat_axis((0, 0, 1), a) for a in (0, 90, 0)])])
    doc.write()


def skinned8():
    """8 joints a vertex (JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1): a tube 1 high, whose top two
    rings (y >= 0.75) weigh the 8 joints 1/8 each; joints 0-3 stay, joints 4-7 rise by 2 at t = 1 ("lift"),
    so the top rings rise by 4/8 x 2 = 1 (by 0 if JOINTS_1 were dropped); the rest follows joint 0"""
    doc = Doc("skinned8.gltf")
    doc.floor()
    pos, nrm, idx = tube(0.2, 5, 0.25)
    j0, w0, j1, w1 = [], [], [], []
    for p in pos:
        if p[1] >= 0.75:
            j0.append((0, 1, 2, 3)), w0.append((0.125,) * 4), j1.append((4, 5, 6, 7)), w1.append((0.125,) * 4)
        else:
            j0.append((0, 0, 0, 0)), w0.append((1, 0, 0, 0)), j1.append((0, 0, 0, 0)), w1.append((0, 0, 0, 0))
    acc = {"JOINTS_0": doc.accessor(b"".join(struct.pack("<4B", *x) for x in j0), UBYTE, len(j0), "VEC4"),
           "WEIGHTS_0": doc.accessor(floats(w0), FLOAT, len(w0), "VEC4"),
           "JOINTS_1": doc.accessor(b"".join(struct.pack("<4H", *x) for x in j1), USHORT, len(j1), "VEC4"),
           "WEIGHTS_1": doc.accessor(floats(w1), FLOAT, len(w1), "VEC4")}
    post = doc.mesh("post8", pos, nrm, idx, doc.material("post_violet", (0.6, 0.2, 0.8)), extra_attrs=acc)
    root = doc.node({"name": "root", "children": list(range(2, 10))})
    bones = [doc.node({"name": "bone%d" % k}, root=False) for k in range(8)]
    mesh_node = doc.node({"name": "post8_mesh", "mesh": post, "skin": 0})
    assert (root, bones, mesh_node) == (1, list(range(2, 10)), 10)
    doc.d["skins"] = [{"name": "post8_skin", "joints": bones, "skeleton": root}]  # no inverseBindMatrices: identity
    doc.animation("lift", [(b, "translation", "LINEAR", [0, 1, 2], [(0, 0, 0), (0, 2, 0), (0, 0, 0)])
                           for b in bones[4:]])
    doc.write()


def morph():
    doc = Doc("morph.gltf")
    doc.floor()
    pos, nrm, idx = UNIT_BOX
    up = doc.sparse_vec3(len(pos), {i: (0, 1.0, 0) for i, p in enumerate(pos) if p[1] == 0.5})
    wide = [(0.5, 0, 0) if p[0] == 0.5 else (0, 0, 0) for p in pos]
    targets = [{"POSITION": up}, {"POSITION": doc.vec3(wide, bounds=True), "NORMAL": doc.vec3([(0, 0, 0)] * len(pos))}]
    cube = doc.mesh("morph_box", pos, nrm, idx, doc.material("box_green", (0.1, 0.7, 0.2)), targets=targets,
                    weights=[0.25, 0])
    morpher = doc.node({"name": "morpher", "mesh": cube, "translation": [0, 0.5, 0]})
    assert morpher == 1
    doc.animation("breathe", [(morpher, "weights", "LINEAR", [0, 1, 2], [(0,), (0,), (1,), (0.5,), (0,), (0,)])])
    doc.write()


# ---- read-back checks ------------------------------------------------------------------------------

NCOMP = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
CSIZE = {UBYTE: 1, USHORT: 2, UINT: 4, FLOAT: 4}
CFMT = {UBYTE: "B", USHORT: "H", UINT: "I", FLOAT: "f"}


class Gltf:
    def __init__(self, name):
        self.path = os.path.join(HERE, name)
        with open(self.path) as f:
            self.d = json.load(f)
        buf = self.d["buffers"][0]
        self.bin = base64.b64decode(buf["uri"].split(",", 1)[1])
        assert len(self.d["buffers"]) == 1 and buf["byteLength"] == len(self.bin), name

    def raw(self, view, offset, ctype, n):
        v = self.d["bufferViews"][view]
        o = v["byteOffset"] + offset
        assert o % CSIZE[ctype] == 0
        return struct.unpack_from("<%d%s" % (n, CFMT[ctype]), self.bin, o)

    def read(self, i):
        """accessors[i] as a list of tuples, sparse substitution applied"""
        a = self.d["accessors"][i]
        nc, cs = NCOMP[a["type"]], CSIZE[a["componentType"]]
        if "bufferView" in a:
            v = self.d["bufferViews"][a["bufferView"]]
            assert "byteStride" not in v and v["byteLength"] == a["count"] * nc * cs, (self.path, i)
            flat = self.raw(a["bufferView"], a.get("byteOffset", 0), a["componentType"], a["count"] * nc)
        else:
            flat = (0,) * (a["count"] * nc)
        rows = [tuple(flat[k * nc:(k + 1) * nc]) for k in range(a["count"])]
        sp = a.get("sparse")
        if sp:
            n = sp["count"]
            ii, vv = sp["indices"], sp["values"]
            assert self.d["bufferViews"][ii["bufferView"]]["byteLength"] == n * CSIZE[ii["componentType"]]
            assert self.d["bufferViews"][vv["bufferView"]]["byteLength"] == n * nc * cs
            idx = self.raw(ii["bufferView"], 0, ii["componentType"], n)
            vals = self.raw(vv["bufferView"], 0, a["componentType"], n * nc)
            assert all(idx[k] < idx[k + 1] for k in range(n - 1)) and idx[-1] < a["count"]
            for k, j in enumerate(idx):
                rows[j] = tuple(vals[k * nc:(k + 1) * nc])
        return rows

    def check(self):
        d = self.d
        assert os.path.getsize(self.path) < 30 * 1024, self.path
        for v in d["bufferViews"]:
            assert v["buffer"] == 0 and v["byteOffset"] % 4 == 0 and v["byteOffset"] + v["byteLength"] <= len(self.bin)
        for i, a in enumerate(d["accessors"]):  # every accessor is readable; min/max, where given, are exact
            rows = self.read(i)
            if "min" in a:
                assert a["min"] == [min(r[k] for r in rows) for k in range(len(rows[0]))], (self.path, i)
                assert a["max"] == [max(r[k] for r in rows) for k in range(len(rows[0]))], (self.path, i)
        for m in d["meshes"]:
            for p in m["primitives"]:
                attrs = p["attributes"]
                n = d["accessors"][attrs["POSITION"]]["count"]
                assert "NORMAL" in attrs and all(d["accessors"][a]["count"] == n for a in attrs.values())
                for t in p.get("targets", []):
                    assert "min" in d["accessors"][t["POSITION"]]
                    assert all(d["accessors"][a]["count"] == n for a in t.values())
                assert len(m.get("weights", p.get("targets", []))) == len(p.get("targets", []))
                assert "min" in d["accessors"][attrs["POSITION"]]
                idx = [r[0] for r in self.read(p["indices"])]
                assert len(idx) % 3 == 0 and max(idx) < n
                pos, nrm = self.read(attrs["POSITION"]), self.read(attrs["NORMAL"])
                for k in range(0, len(idx), 3):  # counter-clockwise seen from the side the normals face
                    a, b, c = (pos[i] for i in idx[k:k + 3])
                    e1, e2 = [b[i] - a[i] for i in range(3)], [c[i] - a[i] for i in range(3)]
                    g = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
                    assert all(sum(g[i] * nrm[j][i] for i in range(3)) > 0 for j in idx[k:k + 3]), (self.path, k)
                if "JOINTS_0" in attrs:  # the weights of all the joint sets sum to 1
                    sets = [self.read(attrs[k]) for k in ("WEIGHTS_0", "WEIGHTS_1") if k in attrs]
                    for ws in zip(*sets):
                        assert abs(sum(sum(w) for w in ws) - 1) < 1e-6
        seen = []
        stack = list(d["scenes"][0]["nodes"])
        while stack:
            k = stack.pop()
            assert k not in seen
            seen.append(k)
            stack += d["nodes"][k].get("children", [])
        assert sorted(seen) == list(range(len(d["nodes"])))
        for s in d.get("skins", []):
            assert "inverseBindMatrices" not in s or len(self.read(s["inverseBindMatrices"])) == len(s["joints"])
            for n in d["nodes"]:
                if n.get("skin") is not None and d["skins"][n["skin"]] is s:
                    attrs = d["meshes"][n["mesh"]]["primitives"][0]["attributes"]
                    assert max(max(j) for j in self.read(attrs["JOINTS_0"])) < len(s["joints"])
        for anim in d.get("animations", []):
            for c in anim["channels"]:
                smp = anim["samplers"][c["sampler"]]
                node_i, path = target_of(c)
                t = [r[0] for r in self.read(smp["input"])]
                assert "min" in d["accessors"][smp["input"]] and all(t[k] < t[k + 1] for k in range(len(t) - 1))
                per = 3 if smp.get("interpolation") == "CUBICSPLINE" else 1
                if node_i is None:
                    continue
                node = d["nodes"][node_i]
                if path == "weights":
                    per *= len(d["meshes"][node["mesh"]]["primitives"][0]["targets"])
                assert d["accessors"][smp["output"]]["count"] == len(t) * per


def lerp(a, b, s):
    return tuple(a[k] + (b[k] - a[k]) * s for k in range(len(a)))


def slerp(a, b, s):
    dot = sum(a[k] * b[k] for k in range(4))
    if dot < 0:
        b, dot = tuple(-x for x in b), -dot
    if dot > 0.9995:
        q = lerp(a, b, s)
    else:
        th = math.acos(dot)
        q = tuple((math.sin((1 - s) * th) * a[k] + math.sin(s * th) * b[k]) / math.sin(th) for k in range(4))
    n = math.sqrt(sum(x * x for x in q))
    return tuple(x / n for x in q)


def sample(g, smp, path, t, width):
    """the value of sampler smp at time t (rows of `width` floats per key)"""
    times = [r[0] for r in g.read(smp["input"])]
    flat = [x for r in g.read(smp["output"]) for x in r]
    interp = smp.get("interpolation", "LINEAR")
    per = 3 if interp == "CUBICSPLINE" else 1
    key = [tuple(flat[(k * per + (1 if per == 3 else 0)) * width:][:width]) for k in range(len(times))]
    if t <= times[0]:
        return key[0]
    if t >= times[-1]:
        return key[-1]
    k = max(i for i in range(len(times)) if times[i] <= t)
    if interp == "STEP":
        return key[k]
    td = times[k + 1] - times[k]
    s = (t - times[k]) / td
    if interp == "LINEAR":
        return slerp(key[k], key[k + 1], s) if path == "rotation" else lerp(key[k], key[k + 1], s)
    out_k = flat[(k * 3 + 2) * width:][:width]
    in_k1 = flat[((k + 1) * 3) * width:][:width]
    h = (2 * s ** 3 - 3 * s ** 2 + 1, s ** 3 - 2 * s ** 2 + s, -2 * s ** 3 + 3 * s ** 2, s ** 3 - s ** 2)
    return tuple(h[0] * key[k][i] + h[1] * td * out_k[i] + h[2] * key[k + 1][i] + h[3] * td * in_k1[i]
                 for i in range(width))


def mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def trs(t, q, s):
    x, y, z, w = q
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    return [[r[i][0] * s[0], r[i][1] * s[1], r[i][2] * s[2], t[i]] for i in range(3)] + [[0, 0, 0, 1]]


def xform(m, p):
    return tuple(sum(m[i][k] * p[k] for k in range(3)) + m[i][3] for i in range(3))


def pose(g, anim, t):
    """(world matrices, morph weights per node) at time t of animations[anim]"""
    d = g.d
    local = [{"translation": tuple(n.get("translation", (0, 0, 0))), "rotation": tuple(n.get("rotation", (0, 0, 0, 1))),
              "scale": tuple(n.get("scale", (1, 1, 1))),
              "weights": tuple(n.get("weights", d["meshes"][n["mesh"]].get("weights", ())) if "mesh" in n else ())}
             for n in d["nodes"]]
    if anim is not None:
        a = d["animations"][anim]
        for c in a["channels"]:
            node, path = target_of(c)
            if node is None:
                continue
            width = {"translation": 3, "scale": 3, "rotation": 4, "weights": len(local[node]["weights"])}[path]
            local[node][path] = sample(g, a["samplers"][c["sampler"]], path, t, width)
    world = [None] * len(d["nodes"])

    def walk(k, parent):
        world[k] = mat_mul(parent, trs(local[k]["translation"], local[k]["rotation"], local[k]["scale"]))
        for c in d["nodes"][k].get("children", []):
            walk(c, world[k])
    for k in d["scenes"][0]["nodes"]:
        walk(k, [[float(i == j) for j in range(4)] for i in range(4)])
    return world, [lw["weights"] for lw in local]


def vertex(g, node, v, anim, t):
    """the world position of vertex v of node's mesh (morphed, skinned) at time t of animations[anim]"""
    d = g.d
    world, weights = pose(g, anim, t)
    n = d["nodes"][node]
    prim = d["meshes"][n["mesh"]]["primitives"][0]
    p = g.read(prim["attributes"]["POSITION"])[v]
    for w, tg in zip(weights[node], prim.get("targets", [])):
        p = lerp(p, tuple(p[k] + g.read(tg["POSITION"])[v][k] for k in range(3)), w)
    if "skin" not in n:
        return xform(world[node], p)
    skin = d["skins"][n["skin"]]
    ident = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    ibm = g.read(skin["inverseBindMatrices"]) if "inverseBindMatrices" in skin else [ident] * len(skin["joints"])
    js, ws = g.read(prim["attributes"]["JOINTS_0"])[v], g.read(prim["attributes"]["WEIGHTS_0"])[v]
    if "JOINTS_1" in prim["attributes"]:
        js = tuple(js) + tuple(g.read(prim["attributes"]["JOINTS_1"])[v])
        ws = tuple(ws) + tuple(g.read(prim["attributes"]["WEIGHTS_1"])[v])
    out = [0.0, 0.0, 0.0]
    for j, w in zip(js, ws):
        inv = [[ibm[j][c * 4 + r] for c in range(4)] for r in range(4)]  # column-major
        q = xform(mat_mul(world[skin["joints"][j]], inv), p)
        out = [out[k] + w * q[k] for k in range(3)]
    return tuple(out)


R2 = math.sqrt(0.5)
# (file, node, vertex, animation (None: the rest pose), time, expected world position)
POSES = [
    ("rigid.gltf", 1, 10, 0, 0.0, (0.5, 1.0, 0.5)),
    ("rigid.gltf", 1, 10, 0, 0.5, (R2, 1.0, 0.0)),                  # 45 deg about +Y
    ("rigid.gltf", 1, 10, 0, 1.0, (0.5, 1.0, -0.5)),                # 90 deg
    ("rigid.gltf", 1, 10, 0, 2.0, (1.5, 1.0, -0.5)),                # 180 deg, STEP to x = 2
    ("rigid.gltf", 2, 10, 0, 0.0, (1.75, 0.75, 0.25)),              # satellite scale 0.5
    ("rigid.gltf", 2, 10, 0, 0.5, ((1.5 + 0.5546875 * 1.0) * R2, 0.5 + 0.27734375, -1.5 * R2)),
    ("rigid.gltf", 2, 10, 0, 1.0, (0.34375, 0.84375, -1.84375)),    # scale 0.6875, 90 deg
    ("rigid.gltf", 2, 10, 0, 2.0, (0.0, 1.0, -0.5)),                # scale 1, 180 deg, spinner at x 2
    ("rigid.gltf", 1, 10, 1, 0.5, (0.5, 1.75, 0.5)),                # bounce: spinner at y 1.25
    ("rigid.gltf", 1, 10, 1, 1.0, (0.5, 2.5, 0.5)),
    ("rigid.gltf", 1, 10, None, 0.0, (0.5, 1.0, 0.5)),
    ("pointer.gltf", 1, 10, 0, 1.0, (0.5, 1.0, -0.5)),              # rigid.gltf's, by pointers
    ("pointer.gltf", 1, 10, 0, 2.0, (1.5, 1.0, -0.5)),
    ("pointer.gltf", 2, 10, 0, 1.0, (0.34375, 0.84375, -1.84375)),
    ("pointer.gltf", 1, 10, 1, 0.5, (0.5, 1.75, 0.5)),
    ("skinned.gltf", 3, 17, 0, 0.0, (0.2, 2.0, 0.2)),               # the mesh node's (5, 0, 0) ignored
    ("skinned.gltf", 3, 17, 0, 0.5, (-0.8 * R2, 1 + 1.2 * R2, 0.2)),
    ("skinned.gltf", 3, 17, 0, 1.0, (-1.0, 1.2, 0.2)),
    ("skinned.gltf", 3, 9, 0, 1.0, (0.1, 1.1, 0.2)),                # the y = 1 ring, half/half
    ("skinned.gltf", 3, 9, 0, 0.5, ((0.2 + 0.2 * R2) / 2, (1 + 1 + 0.2 * R2) / 2, 0.2)),
    ("skinned.gltf", 3, 1, 0, 1.0, (0.2, 0.0, 0.2)),                # the y = 0 ring: root only
    ("skinned.gltf", 3, 17, 0, 2.0, (0.2, 2.0, 0.2)),
    ("skinned8.gltf", 10, 9, 0, 0.0, (0.2, 1.0, 0.2)),              # the top ring: 8 joints, 1/8 each
    ("skinned8.gltf", 10, 9, 0, 1.0, (0.2, 2.0, 0.2)),              # joints 4-7 up by 2: + 1
    ("skinned8.gltf", 10, 9, 0, 0.5, (0.2, 1.5, 0.2)),
    ("skinned8.gltf", 10, 7, 0, 1.0, (0.2, 1.75, 0.2)),             # the y = 0.75 ring likewise
    ("skinned8.gltf", 10, 5, 0, 1.0, (0.2, 0.5, 0.2)),              # below: joint 0 alone, still
    ("morph.gltf", 1, 10, None, 0.0, (0.5, 1.25, 0.5)),             # mesh.weights [0.25, 0]
    ("morph.gltf", 1, 10, 0, 0.0, (0.5, 1.0, 0.5)),
    ("morph.gltf", 1, 10, 0, 0.5, (0.625, 1.5, 0.5)),               # weights [0.5, 0.25]
    ("morph.gltf", 1, 10, 0, 1.0, (0.75, 2.0, 0.5)),                # weights [1, 0.5]
    ("morph.gltf", 1, 2, 0, 1.0, (0.75, 2.0, 0.5)),
    ("morph.gltf", 1, 12, 0, 1.0, (-0.5, 0.0, -0.5)),
]


def warm_light_orbiting(doc, orbit):
    """the file's one light (warm, range 6) and the animation "orbit": node `orbit` turns about +Y
    once in 4 s"""
    doc.d["extensionsUsed"] = ["KHR_lights_punctual"]
    doc.d["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "warm", "type": "point", "color": [1.0, 0.8, 0.5], "intensity": 30.0, "range": 6.0}]}}
    doc.animation("orbit", [(orbit, "rotation", "LINEAR", [0, 1, 2, 3, 4],
                             [quat_axis((0, 1, 0), a) for a in (0, 90, 180, 270, 360)])])


def lamp():
    """a point light on a node that orbits the origin: KHR_lights_punctual lights move with their nodes"""
    doc = Doc("lamp.gltf")
    doc.floor()
    cube = doc.mesh("post", *UNIT_BOX, doc.material("post_blue", (0.1, 0.2, 0.8)))
    doc.node({"name": "post", "mesh": cube, "translation": [0, 0.5, 0]})
    orbit = doc.node({"name": "orbit", "children": [3]})
    lamp_node = doc.node({"name": "lamp", "translation": [2.5, 1, 0],
                          "extensions": {"KHR_lights_punctual": {"light": 0}}}, root=False)
    assert (orbit, lamp_node) == (2, 3)
    warm_light_orbiting(doc, orbit)
    doc.write()


def lantern():
    """a point light and a box on one orbiting node: geometry and a light moving together, so the
    geometry_animate and light_animate passes of a frame share one pose"""
    doc = Doc("lantern.gltf")
    doc.floor()
    cube = doc.mesh("post", *UNIT_BOX, doc.material("post_blue", (0.1, 0.2, 0.8)))
    doc.node({"name": "post", "mesh": cube, "translation": [0, 0.5, 0]})
    cart = doc.mesh("cart", *UNIT_BOX, doc.material("cart_red", (0.8, 0.2, 0.1)))
    orbit = doc.node({"name": "orbit", "children": [3, 4, 5]})
    lamp_node = doc.node({"name": "lamp", "translation": [2.5, 1.5, 0],
                          "extensions": {"KHR_lights_punctual": {"light": 0}}}, root=False)
    cart_node = doc.node({"name": "cart", "mesh": cart, "translation": [1.5, 0.25, 0], "scale": [0.5, 0.5, 0.5]},
                         root=False)
    # a camera riding the orbit at (0, 3, 6), looking at the origin (pitched down atan(1/2))
    eye = doc.node({"name": "eye", "camera": 0, "translation": [0, 3, 6],
                    "rotation": quat_axis((1, 0, 0), -math.degrees(math.atan2(3, 6)))}, root=False)
    doc.d["cameras"] = [{"name": "eye", "type": "perspective",
                         "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100.0}}]
    assert (orbit, lamp_node, cart_node, eye) == (2, 3, 4, 5)
    warm_light_orbiting(doc, orbit)
    doc.write()


def glass():
    """two alphaMode BLEND boxes: a red one still, a blue one moving from behind it (t = 0, 2) to in
    front of it (t = 1) as seen from tests/gpu/test_gpu_animation.c's camera (0.3, 2.2, 4): the
    transparent pass must sort them by their posed bounds"""
    doc = Doc("glass.gltf")
    doc.floor()
    red = doc.mesh("red_glass", *UNIT_BOX, doc.material("red_glass", (0.9, 0.1, 0.1), alpha=0.5))
    blue = doc.mesh("blue_glass", *UNIT_BOX, doc.material("blue_glass", (0.1, 0.2, 0.9), alpha=0.5))
    still = doc.node({"name": "still", "mesh": red, "translation": [0, 1, -0.5]})
    mover = doc.node({"name": "mover", "mesh": blue, "translation": [0, 1, -2.5]})
    sun = doc.node({"name": "sun", "rotation": quat_axis((1, 0, 0), -45),  # shines along (0, -1, -1)
                    "extensions": {"KHR_lights_punctual": {"light": 0}}})
    assert (still, mover, sun) == (1, 2, 3)
    doc.d["extensionsUsed"] = ["KHR_lights_punctual"]
    doc.d["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "sun", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 3.0}]}}
    doc.animation("pass", [(mover, "translation", "LINEAR", [0, 1, 2], [(0, 1, -2.5), (0, 1.2, 2.0), (0, 1, -2.5)])])
    doc.write()


def glass_morph():
    """glass.gltf's passing blue box moved by a morph target instead of its node: its bounds move
    with the target's weight, so the transparent pass must sort by the morphed bounds"""
    doc = Doc("glass_morph.gltf")
    doc.floor()
    red = doc.mesh("red_glass", *UNIT_BOX, doc.material("red_glass", (0.9, 0.1, 0.1), alpha=0.5))
    pos, nrm, idx = UNIT_BOX
    ahead = [(0, 0.2, 4.5)] * len(pos)  # the whole box to (0, 1.2, 2) from (0, 1, -2.5)
    blue = doc.mesh("blue_glass", pos, nrm, idx, doc.material("blue_glass", (0.1, 0.2, 0.9), alpha=0.5),
                    targets=[{"POSITION": doc.vec3(ahead, bounds=True)}], weights=[0])
    still = doc.node({"name": "still", "mesh": red, "translation": [0, 1, -0.5]})
    mover = doc.node({"name": "mover", "mesh": blue, "translation": [0, 1, -2.5]})
    sun = doc.node({"name": "sun", "rotation": quat_axis((1, 0, 0), -45),
                    "extensions": {"KHR_lights_punctual": {"light": 0}}})
    assert (still, mover, sun) == (1, 2, 3)
    doc.d["extensionsUsed"] = ["KHR_lights_punctual"]
    doc.d["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "sun", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 3.0}]}}
    doc.animation("pass", [(mover, "weights", "LINEAR", [0, 1, 2], [(0,), (1,), (0,)])])
    doc.write()


def mirror():
    """two unit boxes whose animated scale mirrors them, each with a double-sided panel child facing
    +Z: "turn" (x = -1) has scale 1 at rest and STEPs to (-1, 1, 1) at t = 1 (and slides from z = -0.1
    to -0.9 over 2 s, so that no pose is its rest pose); "back" (x = 1) is
    mirrored at rest (scale (-1, 1, 1), so its indices are wound for a mirror) and STEPs to 1 at
    t = 1. From t = 1 on both face the other way than their indices were wound at load: drawn with
    the winding of the rest pose they would show their insides, and the panels their back sides"""
    doc = Doc("mirror.gltf")
    doc.floor()
    cube = doc.mesh("box", *UNIT_BOX, doc.material("box_red", (0.8, 0.15, 0.1)))
    quad = [(-0.5, -0.5, 0), (0.5, -0.5, 0), (0.5, 0.5, 0), (-0.5, 0.5, 0)]  # counter-clockwise from +Z
    panel_mat = doc.material("panel_green", (0.1, 0.7, 0.2))
    doc.d["materials"][panel_mat]["doubleSided"] = True
    panel = doc.mesh("panel", quad, [(0, 0, 1)] * 4, [0, 1, 2, 0, 2, 3], panel_mat)
    turn = doc.node({"name": "turn", "mesh": cube, "translation": [-1, 0.5, -0.5], "children": [2]})
    turn_panel = doc.node({"name": "turn_panel", "mesh": panel, "translation": [0.3, 0.9, 0.6],
                           "scale": [0.6, 0.6, 0.6]}, root=False)
    back = doc.node({"name": "back", "mesh": cube, "translation": [1, 0.5, -0.5], "scale": [-1, 1, 1],
                     "children": [4]})
    back_panel = doc.node({"name": "back_panel", "mesh": panel, "translation": [0.3, 0.9, 0.6],
                           "scale": [0.6, 0.6, 0.6]}, root=False)
    assert (turn, turn_panel, back, back_panel) == (1, 2, 3, 4)
    doc.animation("flip", [(turn, "scale", "STEP", [0, 1, 2], [(1, 1, 1), (-1, 1, 1), (-1, 1, 1)]),
                           (turn, "translation", "LINEAR", [0, 2], [(-1, 0.5, -0.1), (-1, 0.5, -0.9)]),
                           (back, "scale", "STEP", [0, 1, 2], [(-1, 1, 1), (1, 1, 1), (1, 1, 1)])])
    doc.write()


def check_poses():
    cache = {}
    for name, node, v, anim, t, want in POSES:
        g = cache.setdefault(name, Gltf(name))
        got = vertex(g, node, v, anim, t)
        assert all(abs(got[k] - want[k]) < 1e-5 for k in range(3)), (name, node, v, anim, t, got, want)
    # the skinned tube's centre line tip (the mean of the 4 top cap corners) at t = 1: (-1, 1, 0)
    g = cache["skinned.gltf"]
    tip = [sum(vertex(g, 3, v, 0, 1.0)[k] for v in range(72, 76)) / 4 for k in range(3)]
    assert all(abs(tip[k] - (-1, 1, 0)[k]) < 1e-5 for k in range(3)), tip
    return cache


rigid()
nonunit()
pointer()
beacon()
shimmer()
skinned()
skinned8()
morph()
lamp()
lantern()
glass()
glass_morph()
mirror()
for f in ("rigid.gltf", "pointer.gltf", "beacon.gltf", "shimmer.gltf", "skinned.gltf", "skinned8.gltf", "morph.gltf", "lamp.gltf", "lantern.gltf", "glass.gltf", "glass_morph.gltf", "mirror.gltf"):
    Gltf(f).check()
check_poses()
print("rigid.gltf pointer.gltf beacon.gltf shimmer.gltf skinned.gltf skinned8.gltf morph.gltf lamp.gltf lantern.gltf glass.gltf glass_morph.gltf mirror.gltf: written and checked (%d poses)" % len(POSES))
