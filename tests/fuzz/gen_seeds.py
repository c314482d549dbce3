#!/usr/bin/env python3
"""Generates the extra glTF seeds of the fuzz corpus (tests/fuzz/seeds/gltf/): small binary .glb
files that reach the code the text corpus (tests/corpus/gltf/) reaches less: a BIN chunk, an image
in a bufferView, TANGENT, TEXCOORD_0 as normalized UNSIGNED_SHORT, a TRS hierarchy with a matrix
node, a TRIANGLE_FAN, two materials (MASK + BLEND), and a JPEG texture. Deterministic; the output
is committed. Run: python3 tests/fuzz/gen_seeds.py"""
import json
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "corpus", "gltf"))
from gltfgen import png_rgba  # noqa: E402  (tests/corpus/gltf/gltfgen.py)

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "seeds", "gltf")


def pad4(b, fill=b"\0"):
    return b + fill * ((4 - len(b) % 4) % 4)


def glb(doc, binchunk):
    j = pad4(json.dumps(doc, separators=(",", ":")).encode(), b" ")
    body = struct.pack("<II", len(j), 0x4E4F534A) + j
    binchunk = pad4(binchunk)
    body += struct.pack("<II", len(binchunk), 0x004E4942) + binchunk
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


class Bin:
    def __init__(self):
        self.data = b""
        self.views = []

    def view(self, blob, stride=None):
        self.data = pad4(self.data)
        v = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(blob)}
        if stride:
            v["byteStride"] = stride
        self.views.append(v)
        self.data += blob
        return len(self.views) - 1


def textured_quad_glb():
    b = Bin()
    pos = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0)
    nrm = struct.pack("<12f", *([0, 0, 1] * 4))
    tan = struct.pack("<16f", *([1, 0, 0, 1] * 4))
    uv16 = struct.pack("<8H", 0, 65535, 65535, 65535, 65535, 0, 0, 0)
    idx = struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    png = png_rgba(4, 4, [(i * 37) % 256 for i in range(64)])
    vp, vn, vt, vu, vi, vimg = (b.view(pos), b.view(nrm), b.view(tan), b.view(uv16), b.view(idx),
                                b.view(png))
    s = 0.7071067811865476
    doc = {
        "asset": {"version": "2.0", "generator": "passgraph tests/fuzz/gen_seeds.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 3]}],
        "nodes": [{"translation": [1, 2, 3], "rotation": [0, s, 0, s], "scale": [2, 2, 2], "children": [1, 2]},
                  {"mesh": 0},
                  {"matrix": [-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1], "mesh": 1},
                  {"mesh": 1}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TANGENT": 2, "TEXCOORD_0": 3},
                                    "indices": 4, "material": 0}]},
                   {"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 3}, "mode": 6,
                                    "material": 1},
                                   {"attributes": {"POSITION": 0}, "mode": 1}]}],
        "accessors": [{"bufferView": vp, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": vn, "componentType": 5126, "count": 4, "type": "VEC3"},
                      {"bufferView": vt, "componentType": 5126, "count": 4, "type": "VEC4"},
                      {"bufferView": vu, "componentType": 5123, "normalized": True, "count": 4, "type": "VEC2"},
                      {"bufferView": vi, "componentType": 5123, "count": 6, "type": "SCALAR"}],
        "bufferViews": b.views,
        "images": [{"bufferView": vimg, "mimeType": "image/png", "name": "checker"}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 33648}],
        "textures": [{"source": 0, "sampler": 0}],
        "materials": [{"name": "masked", "alphaMode": "MASK", "alphaCutoff": 0.25, "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, 1],
                                                "baseColorTexture": {"index": 0},
                                                "metallicFactor": 0.2, "roughnessFactor": 0.7},
                       "normalTexture": {"index": 0, "scale": 0.8}},
                      {"name": "blend", "alphaMode": "BLEND",
                       "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "buffers": [{"byteLength": 0}],
    }
    data = pad4(b.data)
    doc["buffers"][0]["byteLength"] = len(data)
    return glb(doc, data)


def interleaved_u32_glb():
    """Interleaved POSITION+NORMAL (stride 24), 32-bit indices, a TRIANGLE_STRIP, no scene."""
    b = Bin()
    verts = b"".join(struct.pack("<6f", x, y, 0, 0, 0, 1) for x, y in ((0, 0), (1, 0), (0, 1), (1, 1)))
    iv = b.view(verts, stride=24)
    ii = b.view(struct.pack("<4I", 0, 1, 2, 3))
    doc = {"asset": {"version": "2.0"},
           "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "mode": 5}]}],
           "accessors": [{"bufferView": iv, "componentType": 5126, "count": 4, "type": "VEC3"},
                         {"bufferView": iv, "byteOffset": 12, "componentType": 5126, "count": 4, "type": "VEC3"},
                         {"bufferView": ii, "componentType": 5125, "count": 4, "type": "SCALAR"}],
           "bufferViews": b.views,
           "buffers": [{"byteLength": 0}]}
    data = pad4(b.data)
    doc["buffers"][0]["byteLength"] = len(data)
    return glb(doc, data)


def tiny_jpeg(w, h):
    """A baseline grayscale JPEG whose 1-bit Huffman codes make every block flat grey (the scan
    data is empty: EOI follows SOS, and decoders read the missing bits as zeros)."""
    def seg(marker, payload):
        return bytes([0xFF, marker]) + struct.pack(">H", len(payload) + 2) + payload
    return (b"\xFF\xD8" + seg(0xDB, bytes([0]) + bytes([1] * 64))
            + seg(0xC0, bytes([8]) + struct.pack(">HH", h, w) + bytes([1, 1, 0x11, 0]))
            + seg(0xC4, bytes([0x00, 1] + [0] * 15 + [0])) + seg(0xC4, bytes([0x10, 1] + [0] * 15 + [0]))
            + seg(0xDA, bytes([1, 1, 0x00, 0, 63, 0])) + b"\xFF\xD9")


def jpeg_triangle_glb():
    """One textured triangle whose base colour is a 16x16 JPEG in a bufferView."""
    b = Bin()
    vp = b.view(struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0))
    vu = b.view(struct.pack("<6f", 0, 0, 1, 0, 0, 1))
    vimg = b.view(tiny_jpeg(16, 16))
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
           "accessors": [{"bufferView": vp, "componentType": 5126, "count": 3, "type": "VEC3"},
                         {"bufferView": vu, "componentType": 5126, "count": 3, "type": "VEC2"}],
           "bufferViews": b.views,
           "images": [{"bufferView": vimg, "mimeType": "image/jpeg"}],
           "textures": [{"source": 0}],
           "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
           "buffers": [{"byteLength": 0}]}
    data = pad4(b.data)
    doc["buffers"][0]["byteLength"] = len(data)
    return glb(doc, data)


def main():
    os.makedirs(HERE, exist_ok=True)
    for name, blob in (("textured_quad.glb", textured_quad_glb()),
                       ("interleaved_u32_strip.glb", interleaved_u32_glb()),
                       ("jpeg_triangle.glb", jpeg_triangle_glb())):
        with open(os.path.join(HERE, name), "wb") as f:
            f.write(blob)
        print("%s: %d bytes" % (name, len(blob)))


if __name__ == "__main__":
    main()
