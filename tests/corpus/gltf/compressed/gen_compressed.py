#!/usr/bin/env python3
"""Generates the quantized (KHR_mesh_quantization) twins of twin.gltf and the hostile
EXT_meshopt_compression / quantization cases in this folder. Deterministic. Run it alone
(`python3 tests/corpus/gltf/compressed/gen_compressed.py`) or through ../gen_corpus.py, which
calls generate() and adds the returned lines to ../MANIFEST.

twin.gltf      the uncompressed mesh: a 9x9 height-field grid (81 vertices, 128 triangles) with
               FLOAT POSITION, NORMAL, TANGENT, TEXCOORD_0 and UNSIGNED_SHORT indices.
q_u16.gltf     POSITION UNSIGNED_SHORT (integer values), NORMAL/TANGENT normalized BYTE,
               TEXCOORD_0 normalized UNSIGNED_SHORT; the node matrix dequantizes the positions.
q_s16n.gltf    POSITION/NORMAL/TANGENT/TEXCOORD_0 normalized SHORT (node matrix: scale + offset).
q_i8.gltf      POSITION BYTE (integer values), NORMAL/TANGENT/TEXCOORD_0 normalized BYTE.
q_u8n.gltf     POSITION normalized UNSIGNED_BYTE, NORMAL/TANGENT normalized BYTE, TEXCOORD_0
               normalized UNSIGNED_BYTE.
q_s16.gltf     POSITION SHORT (integer values), NORMAL/TANGENT normalized SHORT, TEXCOORD_0 SHORT
               (integer values: 8 * the twin's, which are multiples of 1/8, so exact).
The position scale is uniform (one number for x, y, z) so the node matrix does not bend the
normals. test_scene compares each to twin.gltf within the quantization step (QUANT_STEPS below,
repeated in tests/test_scene.c).

meshopt.gltf/.bin/.glb and draco.gltf/.bin, draco_q.gltf/.bin are written by the C/C++ tools
tests/gen_meshopt.c and tests/gen_draco.cpp (they need the encoders), from twin.gltf; this script
leaves them alone (the hostile draco_*.gltf cases below are made from draco.gltf).
"""
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
N = 9  # grid side

# position / normal(+tangent) / texcoord steps per file: half of each is the tolerance
QUANT_STEPS = {
    "q_u16.gltf": (2.0 / 65535, 1 / 127, 1 / 65535),
    "q_s16n.gltf": (1.0 / 32767, 1 / 32767, 1 / 32767),
    "q_i8.gltf": (1.0 / 127, 1 / 127, 1 / 127),
    "q_u8n.gltf": (2.0 / 255, 1 / 127, 1 / 255),
    "q_s16.gltf": (2.0 / 65534, 1 / 32767, 0),  # texcoords x8 (exact integers)
}


def grid():
    pos, nrm, tan, uv, idx = [], [], [], [], []
    for j in range(N):
        for i in range(N):
            x = -1 + 2 * i / (N - 1)
            y = -1 + 2 * j / (N - 1)
            z = 0.3 * math.sin(2 * x) * math.cos(1.5 * y)
            dzdx = 0.6 * math.cos(2 * x) * math.cos(1.5 * y)
            dzdy = -0.45 * math.sin(2 * x) * math.sin(1.5 * y)
            n = (-dzdx, -dzdy, 1.0)
            ln = math.sqrt(sum(c * c for c in n))
            t = (1.0, 0.0, dzdx)
            lt = math.sqrt(sum(c * c for c in t))
            pos.append((x, y, z))
            nrm.append(tuple(c / ln for c in n))
            tan.append(tuple(c / lt for c in t) + (1.0,))
            uv.append((i / (N - 1), 1 - j / (N - 1)))
    for j in range(N - 1):
        for i in range(N - 1):
            a = j * N + i
            idx += [a, a + 1, a + N + 1, a, a + N + 1, a + N]
    return pos, nrm, tan, uv, idx


def pack(fmt, rows, pad_to=None):
    out = b""
    for r in rows:
        b = struct.pack("<" + fmt, *r)
        if pad_to:
            b += b"\0" * (pad_to - len(b))
        out += b
    return out


FMT = {5126: "f", 5123: "H", 5122: "h", 5121: "B", 5120: "b"}


def rnd(x):
    return int(math.floor(x + 0.5))


def doc(streams, idx, matrix=None, quant=True):
    """streams: list of (semantic, bytes, componentType, type, normalized, stride)."""
    data = b""
    views, accessors, attrs = [], [], {}
    count = len(streams[0][1]) // streams[0][5]
    for sem, b, ct, ty, norm, stride in streams:
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(b), "byteStride": stride,
                      "target": 34962})
        a = {"bufferView": len(views) - 1, "componentType": ct, "count": count, "type": ty}
        if norm:
            a["normalized"] = True
        if sem == "POSITION":
            rows = [struct.unpack_from("<3" + FMT[ct], b, k * stride) for k in range(count)]
            a["min"] = [min(r[c] for r in rows) for c in range(3)]
            a["max"] = [max(r[c] for r in rows) for c in range(3)]
        accessors.append(a)
        attrs[sem] = len(accessors) - 1
        data += b
    ib = struct.pack("<%dH" % len(idx), *idx)
    views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(ib), "target": 34963})
    accessors.append({"bufferView": len(views) - 1, "componentType": 5123, "count": len(idx),
                      "type": "SCALAR"})
    data += ib
    data += b"\0" * ((4 - len(data) % 4) % 4)
    node = {"mesh": 0, "name": "grid"}
    if matrix:
        node["matrix"] = matrix
    d = {"asset": {"version": "2.0", "generator": "passgraph gen_compressed.py"},
         "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [node],
         "meshes": [{"primitives": [{"attributes": attrs, "indices": len(accessors) - 1,
                                     "material": 0}]}],
         "materials": [{"name": "clay", "pbrMetallicRoughness": {
             "baseColorFactor": [0.8, 0.5, 0.3, 1], "metallicFactor": 0, "roughnessFactor": 0.5}}],
         "accessors": accessors, "bufferViews": views,
         "buffers": [{"byteLength": len(data)}]}
    if quant:
        d["extensionsUsed"] = ["KHR_mesh_quantization"]
        d["extensionsRequired"] = ["KHR_mesh_quantization"]
    return d, data


def save(name, d, data):
    """Writes NAME with its buffer in NAME.bin (external, so the files stay readable)."""
    stem = os.path.splitext(name)[0]
    d["buffers"][0]["uri"] = stem + ".bin"
    open(os.path.join(HERE, stem + ".bin"), "wb").write(data)
    open(os.path.join(HERE, name), "w").write(json.dumps(d, indent=1) + "\n")


def uniform_matrix(s, t):
    return [s, 0, 0, 0, 0, s, 0, 0, 0, 0, s, 0, t[0], t[1], t[2], 1]


def quantized_files(pos, nrm, tan, uv, idx):
    lo = [min(p[c] for p in pos) for c in range(3)]
    hi = [max(p[c] for p in pos) for c in range(3)]
    ext = max(hi[c] - lo[c] for c in range(3))  # 2.0
    center = [(lo[c] + hi[c]) / 2 for c in range(3)]
    out = {}
    # q_u16: integer positions 0..65535 (scale ext/65535, offset lo), byte normals/tangents
    s = ext / 65535
    qp = [tuple(rnd((p[c] - lo[c]) / s) for c in range(3)) for p in pos]
    out["q_u16.gltf"] = doc([
        ("POSITION", pack("3H", qp, 8), 5123, "VEC3", False, 8),
        ("NORMAL", pack("3b", [tuple(rnd(c * 127) for c in n) for n in nrm], 4), 5120, "VEC3", True, 4),
        ("TANGENT", pack("4b", [tuple(rnd(c * 127) for c in t) for t in tan]), 5120, "VEC4", True, 4),
        ("TEXCOORD_0", pack("2H", [tuple(rnd(c * 65535) for c in u) for u in uv]), 5123, "VEC2", True, 4),
    ], idx, uniform_matrix(s, lo))
    # q_s16n: normalized shorts in -1..1 (scale ext/2, offset centre)
    h = ext / 2
    qp = [tuple(rnd((p[c] - center[c]) / h * 32767) for c in range(3)) for p in pos]
    out["q_s16n.gltf"] = doc([
        ("POSITION", pack("3h", qp, 8), 5122, "VEC3", True, 8),
        ("NORMAL", pack("3h", [tuple(rnd(c * 32767) for c in n) for n in nrm], 8), 5122, "VEC3", True, 8),
        ("TANGENT", pack("4h", [tuple(rnd(c * 32767) for c in t) for t in tan]), 5122, "VEC4", True, 8),
        ("TEXCOORD_0", pack("2h", [tuple(rnd(c * 32767) for c in u) for u in uv]), 5122, "VEC2", True, 4),
    ], idx, uniform_matrix(h, center))
    # q_i8: integer bytes -127..127 (scale ext/254, offset centre)
    s8 = ext / 254
    qp = [tuple(rnd((p[c] - center[c]) / s8) for c in range(3)) for p in pos]
    out["q_i8.gltf"] = doc([
        ("POSITION", pack("3b", qp, 4), 5120, "VEC3", False, 4),
        ("NORMAL", pack("3b", [tuple(rnd(c * 127) for c in n) for n in nrm], 4), 5120, "VEC3", True, 4),
        ("TANGENT", pack("4b", [tuple(rnd(c * 127) for c in t) for t in tan]), 5120, "VEC4", True, 4),
        ("TEXCOORD_0", pack("2b", [tuple(rnd(c * 127) for c in u) for u in uv], 4), 5120, "VEC2", True, 4),
    ], idx, uniform_matrix(s8, center))
    # q_u8n: normalized unsigned bytes 0..1 (scale ext, offset lo)
    qp = [tuple(rnd((p[c] - lo[c]) / ext * 255) for c in range(3)) for p in pos]
    out["q_u8n.gltf"] = doc([
        ("POSITION", pack("3B", qp, 4), 5121, "VEC3", True, 4),
        ("NORMAL", pack("3b", [tuple(rnd(c * 127) for c in n) for n in nrm], 4), 5120, "VEC3", True, 4),
        ("TANGENT", pack("4b", [tuple(rnd(c * 127) for c in t) for t in tan]), 5120, "VEC4", True, 4),
        ("TEXCOORD_0", pack("2B", [tuple(rnd(c * 255) for c in u) for u in uv], 4), 5121, "VEC2", True, 4),
    ], idx, uniform_matrix(ext, lo))
    # q_s16: integer shorts -32767..32767 (scale ext/65534, offset centre); texcoords x8
    s16 = ext / 65534
    qp = [tuple(rnd((p[c] - center[c]) / s16) for c in range(3)) for p in pos]
    out["q_s16.gltf"] = doc([
        ("POSITION", pack("3h", qp, 8), 5122, "VEC3", False, 8),
        ("NORMAL", pack("3h", [tuple(rnd(c * 32767) for c in n) for n in nrm], 8), 5122, "VEC3", True, 8),
        ("TANGENT", pack("4h", [tuple(rnd(c * 32767) for c in t) for t in tan]), 5122, "VEC4", True, 8),
        ("TEXCOORD_0", pack("2h", [tuple(rnd(c * 8) for c in u) for u in uv]), 5122, "VEC2", False, 4),
    ], idx, uniform_matrix(s16, center))
    return out


def meshopt_case(name, mo, view_len=36, buf_len=64, count=3, fallback_uri=None, ctype=5126,
                 plain_fallback_view=False, fb_len=1024):
    """One triangle whose POSITION bufferView (12-byte stride) is EXT_meshopt_compression data
    described by `mo` (merged into the defaults) in buffers[0]; buffers[1] is the fallback."""
    ext = {"buffer": 0, "byteOffset": 0, "byteLength": 8, "byteStride": 12, "count": count,
           "mode": "ATTRIBUTES"}
    ext.update(mo)
    comp = bytes([0xA0]) + bytes(buf_len - 1)  # vertex codec version 0 header, then zeros
    d = {"asset": {"version": "2.0", "generator": "passgraph gen_compressed.py"},
         "extensionsUsed": ["EXT_meshopt_compression"],
         "extensionsRequired": ["EXT_meshopt_compression"],
         "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
         "accessors": [{"bufferView": 0, "componentType": ctype, "count": count, "type": "VEC3"}],
         "bufferViews": [{"buffer": 1, "byteOffset": 0, "byteLength": view_len, "byteStride": 12,
                          "extensions": {"EXT_meshopt_compression": ext}}],
         "buffers": [{"byteLength": len(comp),
                      "uri": "data:application/octet-stream;base64,"
                             + __import__("base64").b64encode(comp).decode()},
                     {"byteLength": fb_len, "extensions": {"EXT_meshopt_compression": {"fallback": True}}}]}
    if plain_fallback_view:
        del d["bufferViews"][0]["extensions"]
    if fallback_uri:  # never opened: the decoder's error comes first
        d["buffers"][1]["uri"] = fallback_uri
    open(os.path.join(HERE, name), "w").write(json.dumps(d, indent=1) + "\n")


def generate():
    """Writes the files; returns the MANIFEST lines (name relative to ../, code, substring)."""
    for f in os.listdir(HERE):
        if f.endswith((".gltf", ".bin")) and f.split(".")[0] not in ("meshopt", "draco", "draco_q"):
            os.remove(os.path.join(HERE, f))
    pos, nrm, tan, uv, idx = grid()
    twin = doc([("POSITION", pack("3f", pos), 5126, "VEC3", False, 12),
                ("NORMAL", pack("3f", nrm), 5126, "VEC3", False, 12),
                ("TANGENT", pack("4f", tan), 5126, "VEC4", False, 16),
                ("TEXCOORD_0", pack("2f", uv), 5126, "VEC2", False, 8)], idx, quant=False)
    save("twin.gltf", *twin)
    lines = [("compressed/twin.gltf", "PG_OK", "-")]
    for name, (d, data) in quantized_files(pos, nrm, tan, uv, idx).items():
        save(name, d, data)
        lines.append(("compressed/" + name, "PG_OK", "-"))
    # written by tests/gen_meshopt.c (checked by the ctest gen_meshopt_check)
    lines += [("compressed/meshopt.gltf", "PG_OK", "-"), ("compressed/meshopt.glb", "PG_OK", "-")]
    # written by tests/gen_draco.cpp (checked by the ctest gen_draco_check)
    lines += [("compressed/draco.gltf", "PG_OK", "-"), ("compressed/draco_q.gltf", "PG_OK", "-")]

    # quantized types without KHR_mesh_quantization in extensionsUsed stay errors
    d, data = quantized_files(pos, nrm, tan, uv, idx)["q_u16.gltf"]
    del d["extensionsUsed"], d["extensionsRequired"]
    save("q_no_extension.gltf", d, data)
    lines.append(("compressed/q_no_extension.gltf", "PG_ERR_GLTF",
                  "accessors[0]: POSITION must be VEC3 FLOAT (got VEC3 UNSIGNED_SHORT); that type "
                  "needs KHR_mesh_quantization in extensionsUsed"))
    # ... and the extension does not allow everything: NORMAL must be normalized
    d, data = quantized_files(pos, nrm, tan, uv, idx)["q_i8.gltf"]
    del d["accessors"][1]["normalized"]
    save("q_normal_not_normalized.gltf", d, data)
    lines.append(("compressed/q_normal_not_normalized.gltf", "PG_ERR_GLTF",
                  "accessors[1]: NORMAL must be VEC3 FLOAT or normalized BYTE/SHORT (got VEC3 BYTE)"))

    # hostile EXT_meshopt_compression bufferViews
    mw = "bufferViews[0].extensions.EXT_meshopt_compression"
    cases = [
        ("meshopt_bad_mode.gltf", {"mode": "QUADS"}, {},
         mw + ".mode: 'QUADS' is not ATTRIBUTES, TRIANGLES or INDICES"),
        ("meshopt_bad_filter.gltf", {"filter": "WAVELET"}, {},
         mw + ".filter: 'WAVELET' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL"),
        ("meshopt_truncated.gltf", {"byteLength": 8}, {},
         mw + ": meshopt_decodeVertexBuffer returned -2 (malformed or truncated data)"),
        ("meshopt_bad_version.gltf", {"byteOffset": 1, "byteLength": 40}, {},
         mw + ": meshopt_decodeVertexBuffer returned -1 (unsupported encoding version)"),
        ("meshopt_truncated_indices.gltf", {"mode": "TRIANGLES", "byteStride": 2, "count": 3,
                                             "byteLength": 3}, {"view_len": 6},
         mw + ": meshopt_decodeIndexBuffer returned -2 (malformed or truncated data)"),
        ("meshopt_count_overflow.gltf", {"count": 2 ** 63}, {},
         mw + ": count 9223372036854775808 * byteStride 12 is not the bufferView's byteLength 36"),
        ("meshopt_count_mismatch.gltf", {"count": 4}, {},
         mw + ": count 4 * byteStride 12 is not the bufferView's byteLength 36"),
        ("meshopt_source_outside.gltf", {"byteOffset": 60, "byteLength": 8}, {},
         mw + ": byteOffset 60 + byteLength 8 exceeds buffers[0] (64 bytes)"),
        ("meshopt_bad_stride.gltf", {"byteStride": 6}, {},
         mw + ".byteStride: 6 is not a multiple of 4 in 4..256 (ATTRIBUTES)"),
        ("meshopt_filter_stride.gltf", {"filter": "OCTAHEDRAL"}, {},
         mw + ".filter: OCTAHEDRAL needs byteStride 4 or 8 (got 12)"),
        ("meshopt_triangles_count.gltf", {"mode": "TRIANGLES", "byteStride": 4, "count": 8},
         {"view_len": 32}, mw + ".count: 8 is not a multiple of 3 (TRIANGLES)"),
        ("meshopt_fallback_source.gltf", {"buffer": 1}, {},
         mw + ".buffer: buffers[1] is a fallback buffer (never loaded)"),
        ("meshopt_plain_view_on_fallback.gltf", {}, {"plain_fallback_view": True},
         "bufferViews[0]: uses buffers[1], an EXT_meshopt_compression fallback buffer (never "
         "loaded), but is not compressed"),
        ("meshopt_fallback_missing_file.gltf", {"byteOffset": 1, "byteLength": 40},
         {"fallback_uri": "no_such_fallback.bin"},
         mw + ": meshopt_decodeVertexBuffer returned -1 (unsupported encoding version)"),
    ]
    for name, mo, kw, sub in cases:
        meshopt_case(name, mo, **kw)
        lines.append(("compressed/" + name, "PG_ERR_GLTF", sub))
    # a fallback buffer is never loaded, so it can claim any size: the decoded size is bounded
    meshopt_case("meshopt_too_large.gltf", {"count": 2 ** 28, "byteStride": 8},
                 **{"view_len": 2 ** 31, "fb_len": 2 ** 31})
    lines.append(("compressed/meshopt_too_large.gltf", "PG_ERR_LIMIT",
                  mw + ": decoded bufferViews exceed 1 GiB"))
    # hostile KHR_draco_mesh_compression primitives (from draco.gltf, data embedded)
    dw = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression"
    base = json.load(open(os.path.join(HERE, "draco.gltf")))
    real = open(os.path.join(HERE, "draco.bin"), "rb").read()[:base["bufferViews"][0]["byteLength"]]

    def draco_case(name, data, edit, sub):
        d = json.loads(json.dumps(base))
        d["buffers"][0] = {"byteLength": len(data), "uri": "data:application/octet-stream;base64,"
                           + __import__("base64").b64encode(data).decode()}
        d["bufferViews"][0]["byteLength"] = len(data)
        edit(d)
        open(os.path.join(HERE, name), "w").write(json.dumps(d, indent=1) + "\n")
        lines.append(("compressed/" + name, "PG_ERR_GLTF", sub))

    def attrs(d):
        return d["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]

    # Draco used but not required: the accessors have an uncompressed fallback (zeros here),
    # which must not be read (test_scene: equals twin.gltf)
    d = json.loads(json.dumps(base))
    del d["extensionsRequired"]
    zeros_at = len(real) + (4 - len(real) % 4) % 4
    data = real + bytes(zeros_at - len(real))
    sizes = {"VEC3": 12, "VEC4": 16, "VEC2": 8, "SCALAR": 2}
    for a in d["accessors"]:
        n = a["count"] * sizes[a["type"]]
        d["bufferViews"].append({"buffer": 0, "byteOffset": len(data), "byteLength": n})
        a["bufferView"] = len(d["bufferViews"]) - 1
        data += bytes(n + (4 - n % 4) % 4)
    d["buffers"][0] = {"byteLength": len(data), "uri": "draco_fallback.bin"}
    open(os.path.join(HERE, "draco_fallback.bin"), "wb").write(data)
    open(os.path.join(HERE, "draco_fallback.gltf"), "w").write(json.dumps(d, indent=1) + "\n")
    lines.append(("compressed/draco_fallback.gltf", "PG_OK", "-"))

    draco_case("draco_not_draco.gltf", b"NOTDRACO" * 8, lambda d: None,
               dw + ": bufferViews[0] is not Draco data")
    draco_case("draco_truncated.gltf", real[:len(real) // 2], lambda d: None,
               dw + ": Draco decoding of bufferViews[0] failed")
    draco_case("draco_bad_id.gltf", real, lambda d: attrs(d).update(NORMAL=9),
               dw + ".attributes.NORMAL: the Draco data has no attribute with unique id 9")
    draco_case("draco_count_mismatch.gltf", real, lambda d: d["accessors"][0].update(count=80),
               "accessors[0]: count 80, but the Draco data of POSITION has 81 points")
    draco_case("draco_index_count.gltf", real, lambda d: d["accessors"][4].update(count=381),
               "accessors[4]: count 381, but the Draco data has 128 triangles (384 indices)")
    draco_case("draco_unknown_attribute.gltf", real, lambda d: attrs(d).update(COLOR_0=0),
               dw + ".attributes.COLOR_0: the primitive has no COLOR_0 attribute")
    draco_case("draco_bad_view.gltf", real,
               lambda d: d["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]
               .update(bufferView=3),
               dw + ".bufferView: bufferViews index 3 out of range (1 bufferViews)")
    return lines


if __name__ == "__main__":
    print("%d files" % len(generate()))
