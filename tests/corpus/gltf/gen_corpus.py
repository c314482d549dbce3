#!/usr/bin/env python3
"""Generates the glTF robustness corpus (tiny hostile/malformed files + a few valid ones) and its
MANIFEST. Run from anywhere: `python3 tests/corpus/gltf/gen_corpus.py`. The output is committed;
the script is kept so the corpus can be regenerated or extended. Deterministic.

MANIFEST lines: `FILE  CODE  SUBSTRING` - loading FILE with pg_scene_load_gltf must return CODE
(a pg_result name) and, for errors, a message containing SUBSTRING (the rest of the line).
PG_OK lines expect a successful load ('-' as substring). '#' starts a comment line.
WARNINGS lines: `FILE<TAB>LINE` - the exact scene->warnings of a PG_OK file, in order, each
prefixed there with "PATH: " (the path it was loaded by); a PG_OK file without WARNINGS lines must
load with no warnings.
"""
import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
manifest = []
warnings = []


def b64(data):
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode()


def f32(*v):
    return struct.pack("<%df" % len(v), *v)


def u16(*v):
    return struct.pack("<%dH" % len(v), *v)


def u32(*v):
    return struct.pack("<%dI" % len(v), *v)


def pad4(b):
    return b + b"\0" * ((4 - len(b) % 4) % 4)


TRI_POS = f32(0, 0, 0, 1, 0, 0, 0, 1, 0)          # 36 bytes
TRI_NRM = f32(0, 0, 1, 0, 0, 1, 0, 0, 1)          # 36 bytes
TRI_UV = f32(0, 0, 1, 0, 0, 1)                    # 24 bytes
TRI_IDX16 = pad4(u16(0, 1, 2))                    # 8 bytes


def base_doc(pos=TRI_POS, idx=TRI_IDX16, idx_ct=5123, idx_count=3, extra_bin=b"",
             uri=None, with_normals=False):
    """One triangle: bufferView 0 = positions, 1 = indices (+2 = normals)."""
    data = pos + idx
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
             {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}]
    attrs = {"POSITION": 0}
    accessors = [{"bufferView": 0, "componentType": 5126, "count": len(pos) // 12,
                  "type": "VEC3"},
                 {"bufferView": 1, "componentType": idx_ct, "count": idx_count,
                  "type": "SCALAR"}]
    if with_normals:
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(TRI_NRM)})
        data += TRI_NRM
        accessors.append({"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3"})
        attrs["NORMAL"] = 2
    data += extra_bin
    return {
        "asset": {"version": "2.0", "generator": "passgraph gen_corpus.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": attrs, "indices": 1}]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(data), "uri": uri if uri else b64(data)}],
    }, data


def write(name, doc_or_text, code, substring="-", warn=()):
    path = os.path.join(HERE, name)
    if isinstance(doc_or_text, (bytes, bytearray)):
        open(path, "wb").write(doc_or_text)
    elif isinstance(doc_or_text, str):
        open(path, "w").write(doc_or_text)
    else:
        open(path, "w").write(json.dumps(doc_or_text, indent=1) + "\n")
    manifest.append((name, code, substring))
    warnings.extend((name, w) for w in warn)


def png_chunk(tag, data):
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)


def png_rgba(w, h, pixels):
    raw = b"".join(b"\0" + bytes(pixels[y * w * 4:(y + 1) * w * 4]) for y in range(h))
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
            + png_chunk(b"IDAT", zlib.compress(raw)) + png_chunk(b"IEND", b""))


def png_data_uri(png):
    return "data:image/png;base64," + base64.b64encode(png).decode()


def glb(doc, binchunk):
    j = json.dumps(doc).encode()
    j += b" " * ((4 - len(j) % 4) % 4)
    body = struct.pack("<I", len(j)) + struct.pack("<I", 0x4E4F534A) + j
    if binchunk is not None:
        binchunk = pad4(binchunk)
        body += struct.pack("<I", len(binchunk)) + struct.pack("<I", 0x004E4942) + binchunk
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


for f in os.listdir(HERE):
    if f.endswith((".gltf", ".glb", ".bin", ".png", ".obj")) or f in ("MANIFEST", "WARNINGS"):
        os.remove(os.path.join(HERE, f))

# ------------------------------------------------------------------------------------------------
# syntax / top level
write("not_json.gltf", "this is not JSON {\n", "PG_ERR_PARSE",
      "not_json.gltf: not a glTF 2.0 file (passgraph reads .gltf and .glb only)")
# new-user mistakes: another mesh format, a directory
write("cube.obj", "# an OBJ file\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "PG_ERR_PARSE",
      "cube.obj: not a glTF 2.0 file (passgraph reads .gltf and .glb only)")
manifest.append(("fuzz", "PG_ERR_IO", "fuzz': is a directory, not a regular file"))
write("empty.gltf", "", "PG_ERR_PARSE", "empty file")
write("truncated_json.gltf", '{"asset": {"version": "2.0"}, "nodes": [', "PG_ERR_PARSE",
      "JSON syntax error")
write("array_root.gltf", "[1, 2, 3]\n", "PG_ERR_GLTF", "root: expected a JSON object")
d, _ = base_doc()
del d["asset"]
write("no_asset.gltf", d, "PG_ERR_GLTF", "asset: missing")
d, _ = base_doc()
d["asset"] = {"generator": "x"}
write("no_version.gltf", d, "PG_ERR_GLTF", "asset.version: missing")
d, _ = base_doc()
d["asset"]["version"] = "1.0"
write("version_1.gltf", d, "PG_ERR_GLTF", "asset.version: '1.0': glTF 1.0 is not supported, only 2.0")
d, _ = base_doc()
d["extensionsRequired"] = ["EXT_not_implemented"]
d["extensionsUsed"] = ["EXT_not_implemented"]
write("required_extension.gltf", d, "PG_ERR_GLTF",
      "extensionsRequired: 'EXT_not_implemented' is not supported")
manifest.append(("does_not_exist.gltf", "PG_ERR_IO", "cannot open"))
write("deep_nesting.gltf", '{"asset": {"version": "2.0"}, "extras": ' + "[" * 1000 + "]" * 1000 + "}\n",
      "PG_ERR_LIMIT", "JSON nesting deeper than 200 levels")

# ------------------------------------------------------------------------------------------------
# buffers and views
d, data = base_doc()
d["buffers"][0]["uri"] = b64(data[:30])
write("truncated_buffer.gltf", d, "PG_ERR_GLTF",
      "buffers[0]: data URI holds 30 bytes but byteLength is 44")
d, data = base_doc(uri="short.bin")
d["buffers"][0]["byteLength"] = 100
open(os.path.join(HERE, "short.bin"), "wb").write(data)
write("bytelength_larger_than_file.gltf", d, "PG_ERR_GLTF",
      "buffers[0]: 'short.bin' has 44 bytes but byteLength is 100")
d, _ = base_doc(uri="missing.bin")
write("missing_bin.gltf", d, "PG_ERR_GLTF", "buffers[0]: cannot open 'missing.bin'")
d, data = base_doc()
d["buffers"][0]["uri"] = "data:foo/bar;base64,AAAA"
write("bad_data_uri.gltf", d, "PG_ERR_GLTF", "buffers[0].uri: unsupported data URI")
d, _ = base_doc()
d["bufferViews"][0]["byteOffset"] = 40
write("view_past_buffer.gltf", d, "PG_ERR_GLTF",
      "bufferViews[0]: byteOffset 40 + byteLength 36 exceeds buffers[0] (44 bytes)")
d, _ = base_doc()
d["bufferViews"][0]["buffer"] = 3
write("view_bad_buffer.gltf", d, "PG_ERR_GLTF", "bufferViews[0].buffer: buffers index 3 out of range")
d, _ = base_doc()
d["accessors"][0]["count"] = 10
write("accessor_past_view.gltf", d, "PG_ERR_GLTF", "accessors[0]: count 10")
d, _ = base_doc()
d["accessors"][0]["byteOffset"] = 4
write("accessor_offset_past_view.gltf", d, "PG_ERR_GLTF", "exceeds bufferView 0 (36 bytes)")
d, _ = base_doc()
d["accessors"][0]["count"] = 2147483648
write("huge_accessor_count.gltf", d, "PG_ERR_GLTF", "accessors[0]: count 2147483648")
d, _ = base_doc()
d["accessors"][1]["count"] = 4294967296 * 4
write("huge_index_count.gltf", d, "PG_ERR_GLTF", "accessors[1]: count 17179869184")
d, _ = base_doc()
d["bufferViews"][0]["byteStride"] = 6
write("bad_byte_stride.gltf", d, "PG_ERR_GLTF", "bufferViews[0].byteStride: 6 is not a multiple of 4")
d, _ = base_doc()
d["bufferViews"][0]["byteStride"] = 8
write("stride_smaller_than_element.gltf", d, "PG_ERR_GLTF",
      "byteStride 8 is smaller than the element (12 bytes)")
d, _ = base_doc()
d["accessors"][0]["sparse"] = {"count": 1,
                               "indices": {"bufferView": 1, "componentType": 5123},
                               "values": {"bufferView": 0}}
# index 0 (the first index of the triangle) <- the first position (0,0,0): a valid no-op
write("ok_sparse_noop.gltf", d, "PG_OK")


def sparse_doc(sp_idx, sp_vals, base_view=True, count=None, idx_ct=5123):
    """accessors[0] (POSITION, 3 elements) sparse: indices in bufferView 2, values in 3."""
    d, data = base_doc()
    ib = pad4(u16(*sp_idx) if idx_ct == 5123 else u32(*sp_idx))
    vb = f32(*sp_vals)
    d["bufferViews"].append({"buffer": 0, "byteOffset": len(data), "byteLength": len(ib)})
    data += ib
    d["bufferViews"].append({"buffer": 0, "byteOffset": len(data), "byteLength": len(vb)})
    data += vb
    d["buffers"][0] = {"byteLength": len(data), "uri": b64(data)}
    d["accessors"][0]["sparse"] = {"count": len(sp_idx) if count is None else count,
                                   "indices": {"bufferView": 2, "componentType": idx_ct},
                                   "values": {"bufferView": 3}}
    if not base_view:
        del d["accessors"][0]["bufferView"]
    return d


# vertex 2 moves from (0,1,0) to (0,2,0)
write("ok_sparse.gltf", sparse_doc([2], [0, 2, 0]), "PG_OK")
# no bufferView: zeros, then all three positions substituted (32-bit sparse indices)
write("ok_sparse_no_view.gltf", sparse_doc([0, 1, 2], [0, 0, 0, 1, 0, 0, 0, 3, 0], base_view=False,
                                           idx_ct=5125), "PG_OK")
write("sparse_index_out_of_range.gltf", sparse_doc([5], [0, 2, 0]), "PG_ERR_GLTF",
      "accessors[0].sparse.indices: index 5 at position 0 is out of range (count 3)")
write("sparse_not_increasing.gltf", sparse_doc([1, 1], [0, 2, 0, 0, 3, 0]), "PG_ERR_GLTF",
      "accessors[0].sparse.indices: index 1 at position 1 is not greater than the one before (1)")
write("sparse_values_past_view.gltf", sparse_doc([0, 1], [0, 2, 0], count=2), "PG_ERR_GLTF",
      "accessors[0].sparse.values: 2 elements of 12 bytes (byteOffset 0) exceed bufferView 3 (12 bytes)")
write("sparse_count_too_big.gltf", sparse_doc([0, 1, 2, 0], [0] * 12, count=4), "PG_ERR_GLTF",
      "accessors[0].sparse.count: 4 is outside 1..3 (the accessor's count)")
d, _ = base_doc()
del d["accessors"][0]["bufferView"]
write("accessor_without_view.gltf", d, "PG_ERR_GLTF", "accessors[0]: has no bufferView")
d, _ = base_doc()
d["accessors"][0]["componentType"] = 5130
write("double_component_type.gltf", d, "PG_ERR_GLTF",
      "accessors[0].componentType: 5130 is not a glTF component type")
d, _ = base_doc()
d["accessors"][0]["type"] = "VEC5"
write("bad_accessor_type.gltf", d, "PG_ERR_GLTF", "accessors[0].type: missing or not SCALAR")

# ------------------------------------------------------------------------------------------------
# attributes, indices, values
d, _ = base_doc()
d["accessors"][0]["type"] = "VEC2"
write("position_vec2.gltf", d, "PG_ERR_GLTF", "accessors[0]: POSITION must be VEC3 FLOAT")
d, _ = base_doc()
d["accessors"][0]["componentType"] = 5123
d["accessors"][0]["count"] = 3
write("position_ushort.gltf", d, "PG_ERR_GLTF", "accessors[0]: POSITION must be VEC3 FLOAT")
d, _ = base_doc()
d["meshes"][0]["primitives"][0]["attributes"] = {"NORMAL": 0}
write("no_position.gltf", d, "PG_ERR_GLTF", "meshes[0].primitives[0].attributes: POSITION missing")
d, _ = base_doc(with_normals=True)
d["accessors"][2]["count"] = 2
write("normal_count_mismatch.gltf", d, "PG_ERR_GLTF",
      "NORMAL (accessors[2]) has 2 elements but POSITION has 3")
d, _ = base_doc()
d["accessors"].append({"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"})
d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2
write("texcoord_vec3.gltf", d, "PG_ERR_GLTF", "accessors[2]: TEXCOORD_0 must be VEC2 FLOAT")
d, _ = base_doc(idx=TRI_IDX16)
d["accessors"][1]["componentType"] = 5126
d["accessors"][1]["count"] = 2
write("float_indices.gltf", d, "PG_ERR_GLTF", "accessors[1]: indices must be SCALAR UNSIGNED_BYTE")
d, _ = base_doc(idx=pad4(u16(0, 1, 7)))
write("index_out_of_range_16.gltf", d, "PG_ERR_GLTF",
      "meshes[0].primitives[0]: index 7 at position 2 is out of range (vertex count 3)")
d, _ = base_doc(idx=u32(0, 70000, 2), idx_ct=5125)
write("index_out_of_range_32.gltf", d, "PG_ERR_GLTF",
      "meshes[0].primitives[0]: index 70000 at position 1 is out of range (vertex count 3)")
d, _ = base_doc(idx=pad4(bytes([0, 200, 1])), idx_ct=5121)
write("index_out_of_range_8.gltf", d, "PG_ERR_GLTF",
      "index 200 at position 1 is out of range (vertex count 3)")
d, _ = base_doc(idx=u16(0, 1, 2, 0), idx_count=4)
write("index_count_not_triangles.gltf", d, "PG_ERR_GLTF", "4 indices is not a multiple of 3")
nan = struct.unpack("<f", struct.pack("<I", 0x7FC00000))[0]
d, _ = base_doc(pos=f32(0, 0, 0, nan, 0, 0, 0, 1, 0))
write("nan_position.gltf", d, "PG_ERR_GLTF", "accessors[0]: POSITION element 1 is not finite")
d, _ = base_doc(pos=f32(0, 0, 0, 1, 0, 0, 0, float("inf"), 0))
write("inf_position.gltf", d, "PG_ERR_GLTF", "accessors[0]: POSITION element 2 is not finite (inf)")
d, _ = base_doc()
d["meshes"][0]["primitives"][0]["mode"] = 7
write("bad_primitive_mode.gltf", d, "PG_ERR_GLTF", "meshes[0].primitives[0].mode: 7 is not a glTF primitive mode")
d, _ = base_doc()
d["meshes"][0]["primitives"][0]["mode"] = 0
write("points_only.gltf", d, "PG_ERR_GLTF", "scenes[0] has no triangles")

# ------------------------------------------------------------------------------------------------
# references and node graph
d, _ = base_doc()
d["nodes"] = [{"mesh": 0, "children": [1]}, {"children": [0]}]
write("cyclic_nodes.gltf", d, "PG_ERR_GLTF", "cyclic node graph")
d, _ = base_doc()
d["nodes"] = [{"mesh": 0, "children": [0]}]
write("self_child_node.gltf", d, "PG_ERR_GLTF", "nodes[0]: cyclic node graph")
d, _ = base_doc()
d["nodes"] = [{"children": [1]}, {"children": [2]}, {"mesh": 0, "children": [1]}]
del d["scene"]
del d["scenes"]
write("cyclic_no_scene.gltf", d, "PG_ERR_GLTF", "cyclic node graph")
d, _ = base_doc()
d["nodes"][0]["mesh"] = 5
write("node_missing_mesh.gltf", d, "PG_ERR_GLTF", "nodes[0].mesh: meshes index 5 out of range (1 meshes)")
d, _ = base_doc()
d["nodes"][0]["mesh"] = -1
write("node_negative_mesh.gltf", d, "PG_ERR_GLTF", "nodes[0].mesh: meshes index -1 is negative")
d, _ = base_doc()
d["nodes"][0]["mesh"] = 0.5
write("node_float_mesh.gltf", d, "PG_ERR_GLTF", "nodes[0].mesh: expected an index")
d, _ = base_doc()
d["nodes"][0]["children"] = [9]
write("node_missing_child.gltf", d, "PG_ERR_GLTF", "nodes[0].children[0]: not a valid node index")
d, _ = base_doc()
d["nodes"][0]["matrix"] = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0]
write("node_bad_matrix.gltf", d, "PG_ERR_GLTF", "nodes[0].matrix: expected 16 finite numbers")
d, _ = base_doc()
d["nodes"][0]["rotation"] = [0, 0, 0, 0]
write("node_zero_quaternion.gltf", d, "PG_ERR_GLTF", "nodes[0].rotation: zero-length quaternion")
d, _ = base_doc()
d["scene"] = 3
write("scene_out_of_range.gltf", d, "PG_ERR_GLTF", "scene: 3 is not a valid index")
d, _ = base_doc()
d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9
write("mesh_missing_accessor.gltf", d, "PG_ERR_GLTF",
      "meshes[0].primitives[0].attributes.POSITION: accessors index 9 out of range")
d, _ = base_doc()
d["meshes"][0]["primitives"][0]["indices"] = 4
write("mesh_missing_index_accessor.gltf", d, "PG_ERR_GLTF",
      "meshes[0].primitives[0].indices: accessors index 4 out of range")
d, _ = base_doc()
d["meshes"][0]["primitives"][0]["material"] = 3
write("material_out_of_range.gltf", d, "PG_ERR_GLTF",
      "meshes[0].primitives[0].material: materials index 3 out of range (0 materials)")
d, _ = base_doc()
d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 4}}}]
d["meshes"][0]["primitives"][0]["material"] = 0
write("texture_out_of_range.gltf", d, "PG_ERR_GLTF",
      "materials[0].pbrMetallicRoughness.baseColorTexture.index: textures index 4 out of range")
d, _ = base_doc()
d["materials"] = [{"alphaMode": "CUTOUT"}]
write("bad_alpha_mode.gltf", d, "PG_ERR_GLTF", "materials[0].alphaMode: expected")

# ------------------------------------------------------------------------------------------------
# images
pix = [255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255]
PNG2 = png_rgba(2, 2, pix)


def textured_doc(image):
    d, data = base_doc()
    uvs = TRI_UV
    d["bufferViews"].append({"buffer": 0, "byteOffset": len(data), "byteLength": len(uvs)})
    data += uvs
    d["buffers"][0] = {"byteLength": len(data), "uri": b64(data)}
    d["accessors"].append({"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"})
    d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2
    d["meshes"][0]["primitives"][0]["material"] = 0
    d["images"] = [image]
    d["textures"] = [{"source": 0}]
    d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    return d


# a material's values of the wrong type were read as their defaults ("doubleSided": "yes" as false,
# "alphaCutoff": "half" as 0.5): refused naming the field; the occlusion strength in [0, 1] (clamped)
for name, edit, msg in (
        ("material_cutoff_string.gltf", lambda m: m.update(alphaCutoff="half"),
         'materials[0].alphaCutoff: expected a number, got "half"'),
        ("material_double_sided_string.gltf", lambda m: m.update(doubleSided="yes"),
         'materials[0].doubleSided: expected true or false, got "yes"'),
        ("material_unlit_not_object.gltf", lambda m: m.update(extensions={"KHR_materials_unlit": 5}),
         "materials[0].extensions.KHR_materials_unlit: expected an object (empty: {})"),
        ("material_texcoord_string.gltf",
         lambda m: m["pbrMetallicRoughness"]["baseColorTexture"].update(texCoord="1"),
         "materials[0].pbrMetallicRoughness.baseColorTexture.texCoord: expected a non-negative integer"),
        ("material_texcoord_negative.gltf",
         lambda m: m["pbrMetallicRoughness"]["baseColorTexture"].update(texCoord=-1),
         "materials[0].pbrMetallicRoughness.baseColorTexture.texCoord: expected a non-negative integer"),
        ("material_normal_scale_string.gltf", lambda m: m.update(normalTexture={"index": 0, "scale": "x"}),
         'materials[0].normalTexture.scale: expected a number, got "x"'),
        ("material_occlusion_strength_string.gltf", lambda m: m.update(occlusionTexture={"index": 0, "strength": "x"}),
         'materials[0].occlusionTexture.strength: expected a number in [0, 1], got "x"'),
        ("material_occlusion_strength_2.gltf", lambda m: m.update(occlusionTexture={"index": 0, "strength": 2}),
         "materials[0].occlusionTexture.strength: expected a number in [0, 1], got 2")):
    d = textured_doc({"uri": png_data_uri(PNG2)})
    edit(d["materials"][0])
    write(name, d, "PG_ERR_GLTF", msg)
d = textured_doc({"uri": png_data_uri(PNG2)})
d["meshes"][0]["weights"] = ["x"]
write("mesh_weights_string.gltf", d, "PG_ERR_GLTF", 'meshes[0].weights[0]: expected a number, got "x"')
# the texCoord a texture is read with is its KHR_texture_transform's when it gives one: the warning
# of a texCoord past 1 read the textureInfo's (a transform's 5 unwarned, a textureInfo's 5 that the
# transform sets to 0 warned)
for name, tc, xf_tc, warned in (("ok_texcoord_5.gltf", 5, None, True),
                                ("ok_texcoord_transform_5.gltf", 0, 5, True),
                                ("ok_texcoord_transform_0.gltf", 5, 0, False)):
    d = textured_doc({"uri": png_data_uri(PNG2)})
    d["extensionsUsed"] = ["KHR_texture_transform"]
    ti = d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]
    ti["texCoord"] = tc
    if xf_tc is not None:
        ti["extensions"] = {"KHR_texture_transform": {"texCoord": xf_tc}}
    write(name, d, "PG_OK", warn=["textures of 1 material (materials[0]) ask for a texCoord other than 0 or 1: read "
                                  "with TEXCOORD_0"] if warned else [])
write("missing_image.gltf", textured_doc({"uri": "nope.png"}), "PG_ERR_GLTF",
      "images[0]: cannot open 'nope.png'")
open(os.path.join(HERE, "corrupt.png"), "wb").write(b"\x89PNG\r\n\x1a\n" + bytes(range(64)))
write("corrupt_image_file.gltf", textured_doc({"uri": "corrupt.png"}), "PG_ERR_GLTF",
      "images[0] ('corrupt.png'): cannot decode")
write("corrupt_image_datauri.gltf",
      textured_doc({"uri": "data:image/png;base64," + base64.b64encode(b"garbage!" * 8).decode()}),
      "PG_ERR_GLTF", "images[0] (data URI): cannot decode")
open(os.path.join(HERE, "empty.png"), "wb").write(b"")
write("empty_image_file.gltf", textured_doc({"uri": "empty.png"}), "PG_ERR_GLTF",
      "images[0]: 'empty.png' is empty")
huge = (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", struct.pack(">IIBBBBB", 100000, 100000, 8, 6, 0, 0, 0))
        + png_chunk(b"IDAT", zlib.compress(b"\0" * 64)) + png_chunk(b"IEND", b""))
write("huge_image.gltf", textured_doc({"uri": png_data_uri(huge)}), "PG_ERR_GLTF",
      "images[0] (data URI): size 100000x100000 is outside 1..16384")
wide = (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", struct.pack(">IIBBBBB", 16385, 1, 8, 6, 0, 0, 0))
        + png_chunk(b"IDAT", zlib.compress(b"\0" * 64)) + png_chunk(b"IEND", b""))
open(os.path.join(HERE, "too_wide.png"), "wb").write(wide)
write("too_wide_image.gltf", textured_doc({"uri": "too_wide.png"}), "PG_ERR_GLTF",
      "size 16385x1 is outside 1..16384")
write("image_no_source.gltf", textured_doc({"name": "nothing"}), "PG_ERR_GLTF",
      "images[0]: has neither uri nor bufferView")

# ------------------------------------------------------------------------------------------------
# GLB containers
d, data = base_doc()
del d["buffers"][0]["uri"]
good_glb = glb(d, data)
write("ok_minimal.glb", good_glb, "PG_OK")
write("glb_truncated.glb", good_glb[:60], "PG_ERR_PARSE", "GLB: header length")
bad = bytearray(good_glb)
bad[20:24] = b"{{{{"
write("glb_bad_json.glb", bytes(bad), "PG_ERR_PARSE", "JSON syntax error")
d2 = json.loads(json.dumps(d))
d2["buffers"][0]["byteLength"] = 1000
write("glb_bytelength_exceeds_bin.glb", glb(d2, data), "PG_ERR_GLTF",
      "buffers[0]: byteLength 1000 exceeds the GLB BIN chunk (44 bytes)")
write("glb_no_bin.glb", glb(d, None), "PG_ERR_GLTF", "there is none")
# only buffers[0] may be the BIN chunk: a second buffer without a uri is an error, not read from it
d3 = json.loads(json.dumps(d))
d3["buffers"].append({"byteLength": 4})
write("glb_second_buffer_no_uri.glb", glb(d3, data), "PG_ERR_GLTF",
      "buffers[1].uri: missing (only buffers[0] may refer to the GLB BIN chunk)")
write("glb_version_1.glb", b"glTF" + struct.pack("<II", 1, 20) + b"\0" * 8, "PG_ERR_PARSE",
      "GLB: container version 1")
write("glb_header_only.glb", b"glTF" + struct.pack("<II", 2, 12), "PG_ERR_PARSE",
      "GLB: no JSON chunk after the header (12 bytes in all)")
write("glb_json_empty.glb", b"glTF" + struct.pack("<II", 2, 20) + struct.pack("<II", 0, 0x4E4F534A), "PG_ERR_PARSE",
      "GLB: the JSON chunk is empty (length 0)")

# ------------------------------------------------------------------------------------------------
# valid files (checked in more detail by test_scene.c)
d, _ = base_doc()
write("ok_minimal.gltf", d, "PG_OK")
d, data = base_doc(uri="ok_external.bin")
open(os.path.join(HERE, "ok_external.bin"), "wb").write(data)
write("ok_external_bin.gltf", d, "PG_OK")
# triangle strip of 4 vertices -> 2 triangles; no indices
pos = f32(0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0)
d, data = base_doc(pos=pos)
del d["meshes"][0]["primitives"][0]["indices"]
d["meshes"][0]["primitives"][0]["mode"] = 5
write("ok_strip.gltf", d, "PG_OK")
# mirrored node (negative determinant) with normals: the loader must flip the winding
d, _ = base_doc(with_normals=True)
d["nodes"][0]["scale"] = [-1, 1, 1]
write("ok_mirrored.gltf", d, "PG_OK")
# mirrored node with UVs and TANGENT (1,0,0,-1): the tangent becomes (-1,0,0) and, as the frame is
# mirrored, its handedness flips to +1 (what recomputing from the mirrored UVs gives)
d, data = base_doc(with_normals=True)
tan = f32(1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1)
d["bufferViews"].append({"buffer": 0, "byteOffset": len(data), "byteLength": len(TRI_UV)})
d["bufferViews"].append({"buffer": 0, "byteOffset": len(data) + len(TRI_UV), "byteLength": len(tan)})
data += TRI_UV + tan
d["buffers"][0] = {"byteLength": len(data), "uri": b64(data)}
d["accessors"].append({"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC2"})
d["accessors"].append({"bufferView": 4, "componentType": 5126, "count": 3, "type": "VEC4"})
d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 3
d["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = 4
d["nodes"][0]["scale"] = [-1, 1, 1]
write("ok_mirrored_tangent.gltf", d, "PG_OK")
# hierarchy with TRS: parent translation (10, 0, 0), child rotation 90 deg about +Z
d, _ = base_doc()
s = 0.7071067811865476
d["nodes"] = [{"translation": [10, 0, 0], "children": [1]}, {"rotation": [0, 0, s, s], "mesh": 0}]
write("ok_trs_hierarchy.gltf", d, "PG_OK")
# interleaved positions + normals (byteStride 24), 8-bit indices, no scene (root nodes)
inter = b"".join(TRI_POS[i * 12:(i + 1) * 12] + TRI_NRM[i * 12:(i + 1) * 12] for i in range(3))
idx8 = pad4(bytes([0, 1, 2]))
data = inter + idx8
d = {"asset": {"version": "2.0"},
     "nodes": [{"mesh": 0}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                   {"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 3, "type": "VEC3"},
                   {"bufferView": 1, "componentType": 5121, "count": 3, "type": "SCALAR"}],
     "bufferViews": [{"buffer": 0, "byteLength": len(inter), "byteStride": 24},
                     {"buffer": 0, "byteOffset": len(inter), "byteLength": len(idx8)}],
     "buffers": [{"byteLength": len(data), "uri": b64(data)}]}
write("ok_interleaved_u8.gltf", d, "PG_OK", warn=[
    "no scenes: every root node is drawn (the specification leaves such a file's display to the application: "
    "a library of nodes)"])
# one image used as base colour AND normal map (-> 2 textures), MASK, no TANGENT (-> computed)
d = textured_doc({"uri": "ok_2x2.png"})
open(os.path.join(HERE, "ok_2x2.png"), "wb").write(PNG2)
d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}},
                   "normalTexture": {"index": 0, "scale": 0.5},
                   "alphaMode": "MASK", "alphaCutoff": 0.3, "doubleSided": True}]
write("ok_textured.gltf", d, "PG_OK")
# points + triangles in one mesh: the points primitive is skipped with a warning
d, _ = base_doc()
p = dict(d["meshes"][0]["primitives"][0])
p["mode"] = 0
d["meshes"][0]["primitives"].insert(0, p)
write("ok_points_skipped.gltf", d, "PG_OK",
      warn=["skipped 1 point/line primitive(s) (only triangles are drawn)"])

# decompression bombs: 140 bytes of baseline JPEG header (1-bit Huffman codes, then EOI) that
# claim 16384x16384, which stb_image would decode as zero bits into a 1 GiB image; and a TGA RLE
# header (stb invents the pixels past the end of the data; glTF allows only PNG and JPEG)
def jpeg_segment(marker, payload):
    return bytes([0xFF, marker]) + struct.pack(">H", len(payload) + 2) + payload


bomb_jpeg = (b"\xFF\xD8" + jpeg_segment(0xDB, bytes([0]) + bytes([1] * 64))
             + jpeg_segment(0xC0, bytes([8]) + struct.pack(">HH", 16384, 16384) + bytes([1, 1, 0x11, 0]))
             + jpeg_segment(0xC4, bytes([0x00, 1] + [0] * 15 + [0]))
             + jpeg_segment(0xC4, bytes([0x10, 1] + [0] * 15 + [0]))
             + jpeg_segment(0xDA, bytes([1, 1, 0x00, 0, 63, 0])) + b"\xFF\xD9")
write("jpeg_bomb.gltf",
      textured_doc({"uri": "data:image/jpeg;base64," + base64.b64encode(bomb_jpeg).decode()}),
      "PG_ERR_GLTF", "images[0] (data URI): cannot decode (a 16384x16384 JPEG cannot fit in 140 bytes")
tga = struct.pack("<BBBHHBHHHHBB", 0, 0, 10, 0, 0, 0, 0, 0, 16384, 16384, 32, 8)
write("tga_image.gltf",
      textured_doc({"uri": "data:image/png;base64," + base64.b64encode(tga).decode()}),
      "PG_ERR_GLTF", "images[0] (data URI): cannot decode (not a PNG, JPEG or WebP image")

# a finite position that leaves the float range under its node transform (found by fuzz_gltf)
d, _ = base_doc()
d["nodes"] = [{"scale": [1e39, 1, 1], "mesh": 0}]
write("position_float_overflow.gltf", d, "PG_ERR_GLTF",
      "POSITION element 1 (accessors[0]) is outside the float range after the node transform")

# without NORMAL the normals are flat (glTF 2.0 3.7.2.1): a cube of 8 shared corners, 12 triangles
# wound counter-clockwise seen from outside; the loader gives each triangle its own vertices
CUBE8 = f32(*[c for i in range(8) for c in ((i & 1) - 0.5, ((i >> 1) & 1) - 0.5, ((i >> 2) & 1) - 0.5)])
CUBE8_IDX = u16(0, 2, 3, 0, 3, 1,  4, 5, 7, 4, 7, 6,  0, 1, 5, 0, 5, 4,
                2, 6, 7, 2, 7, 3,  0, 4, 6, 0, 6, 2,  1, 3, 7, 1, 7, 5)
d, data = base_doc(pos=CUBE8, idx=CUBE8_IDX, idx_count=36)
write("ok_flat_normals.gltf", d, "PG_OK")
# the same cube on a mirrored node that an animation moves: its normals are computed in mesh space,
# where the winding is not yet flipped (they came out pointing inward)
times = f32(0, 1)
moves = f32(0.5, 0, 0, 1.5, 0, 0)
d["nodes"][0]["scale"] = [-1, 1, 1]
d["bufferViews"] += [{"buffer": 0, "byteOffset": len(data), "byteLength": 8},
                     {"buffer": 0, "byteOffset": len(data) + 8, "byteLength": 24}]
data += times + moves
d["buffers"][0] = {"byteLength": len(data), "uri": b64(data)}
d["accessors"] += [{"bufferView": 2, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
                   {"bufferView": 3, "componentType": 5126, "count": 2, "type": "VEC3"}]
d["animations"] = [{"channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
                    "samplers": [{"input": 2, "output": 3}]}]
write("ok_flat_normals_mirrored_animated.gltf", d, "PG_OK")
# a normal map that reads TEXCOORD_1 = (1 - u, v): tangents computed from set 1 point along -X
# (TEXCOORD_0 would give +X); and TANGENT given without NORMAL, which must be ignored
QUAD_POS = f32(0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0)
QUAD_NRM = f32(*([0, 0, 1] * 4))
QUAD_UV0 = f32(0, 1, 1, 1, 1, 0, 0, 0)
QUAD_UV1 = f32(1, 1, 0, 1, 0, 0, 1, 0)
QUAD_TAN = f32(*([-1, 0, 0, 1] * 4))
QUAD_IDX = u16(0, 1, 2, 0, 2, 3)


def quad_doc(attrs):
    """A unit quad facing +Z with the named attributes (NORMAL, TEXCOORD_0/1, TANGENT) and a
    normal-mapped material whose texture is a 2x2 PNG (data URI)."""
    data, views, accessors, at = b"", [], [], {}
    for name, blob, typ in [("POSITION", QUAD_POS, "VEC3"), ("NORMAL", QUAD_NRM, "VEC3"),
                            ("TEXCOORD_0", QUAD_UV0, "VEC2"), ("TEXCOORD_1", QUAD_UV1, "VEC2"),
                            ("TANGENT", QUAD_TAN, "VEC4")]:
        if name != "POSITION" and name not in attrs:
            continue
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(blob)})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": 4, "type": typ})
        if name == "POSITION":
            accessors[-1].update({"min": [0, 0, 0], "max": [1, 1, 0]})
        at[name] = len(accessors) - 1
        data += blob
    views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(QUAD_IDX)})
    accessors.append({"bufferView": len(views) - 1, "componentType": 5123, "count": 6, "type": "SCALAR"})
    data += QUAD_IDX
    return {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": at, "indices": len(accessors) - 1, "material": 0}]}],
            "materials": [{"normalTexture": {"index": 0, "texCoord": attrs.get("set", 0)}}],
            "textures": [{"source": 0}], "images": [{"uri": png_data_uri(png_rgba(2, 2, [128, 128, 255, 255] * 4))}],
            "accessors": accessors, "bufferViews": views, "buffers": [{"byteLength": len(data), "uri": b64(data)}]}


write("ok_normal_map_texcoord1.gltf", quad_doc({"NORMAL": 1, "TEXCOORD_0": 1, "TEXCOORD_1": 1, "set": 1}), "PG_OK")
write("ok_tangent_without_normals.gltf", quad_doc({"TEXCOORD_0": 1, "TANGENT": 1}), "PG_OK")
# a normal map sampled through KHR_texture_transform (a quarter turn, u scaled 2x): its tangents
# follow the transformed coordinates (they came from the file's: +X where the map's u runs along Y)
d = quad_doc({"NORMAL": 1, "TEXCOORD_0": 1})
d["materials"][0]["normalTexture"]["extensions"] = {"KHR_texture_transform": {"rotation": 1.5707963, "scale": [2, 1]}}
d["extensionsUsed"] = ["KHR_texture_transform"]
write("ok_normal_map_transform.gltf", d, "PG_OK")

# ------------------------------------------------------------------------------------------------
# features the loader does not draw: each loads, with one exact warning line per feature
d, _ = base_doc()
d["nodes"] = [{"mesh": 0, "skin": 0}, {"children": [0]}]
d["scenes"] = [{"nodes": [1]}]
d["skins"] = [{"joints": [0]}, {"joints": [0, 1]}]
write("ok_skins.gltf", d, "PG_OK",
      warn=["1 primitive(s) of skinned nodes without JOINTS_0/WEIGHTS_0: drawn by their node's transform, unskinned"])
d, _ = base_doc()
times = f32(0, 1)
rots = f32(0, 0, 0, 1, 0, 0.7071068, 0, 0.7071068)
data = _ + times + rots
d["bufferViews"] += [{"buffer": 0, "byteOffset": len(_), "byteLength": 8},
                     {"buffer": 0, "byteOffset": len(_) + 8, "byteLength": 32}]
d["buffers"][0] = {"byteLength": len(data), "uri": b64(data)}
d["accessors"] += [{"bufferView": 2, "componentType": 5126, "count": 2, "type": "SCALAR",
                    "min": [0], "max": [1]},
                   {"bufferView": 3, "componentType": 5126, "count": 2, "type": "VEC4"}]
d["animations"] = [{"channels": [{"sampler": 0, "target": {"node": 0, "path": "rotation"}}],
                    "samplers": [{"input": 2, "output": 3}]}]
write("ok_animation.gltf", d, "PG_OK", warn=[])
# a channel on a node given by a matrix (glTF forbids it) is ignored and named with its reason; two
# channels on one target (forbidden too) are named, the later one applied
# a channel of a path passgraph does not know, and one without target.node (left to an extension by
# the specification): ignored and named with their cause (the line named neither)
d_anim = json.loads(json.dumps(d))
d_anim["animations"][0]["channels"] = [{"sampler": 0, "target": {"node": 0, "path": "colour"}},
                                       {"sampler": 0, "target": {"path": "rotation"}}]
write("ok_animation_unknown_targets.gltf", d_anim, "PG_OK", warn=[
    "2 animation channel(s) ignored: animations[0].channels[0] (unknown target.path 'colour'), "
    "animations[0].channels[1] (no target.node: the specification leaves its target to an extension)"])
# a channel without a target, its path or its sampler (required): tinygltf dropped one without a
# path or a sampler, and the later channels were named by the wrong index
for name, ch, msg in (("animation_channel_no_target.gltf", {"sampler": 0},
                       "animations[0].channels[0].target: missing (required)"),
                      ("animation_channel_no_path.gltf", {"sampler": 0, "target": {"node": 0}},
                       "animations[0].channels[0].target.path: missing or not a string (required)"),
                      ("animation_channel_no_sampler.gltf", {"target": {"node": 0, "path": "rotation"}},
                       "animations[0].channels[0].sampler: missing (required)")):
    d_anim = json.loads(json.dumps(d))
    d_anim["animations"][0]["channels"] = [ch, {"sampler": 0, "target": {"node": 0, "path": "rotation"}}]
    write(name, d_anim, "PG_ERR_GLTF", msg)
d = json.loads(json.dumps(d))
d["nodes"][0]["matrix"] = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
write("ok_animation_matrix_node.gltf", d, "PG_OK", warn=[
    "1 animation channel(s) ignored: animations[0].channels[0] (nodes[0] is given by a matrix)"])
del d["nodes"][0]["matrix"]
d["animations"][0]["channels"].append({"sampler": 0, "target": {"node": 0, "path": "rotation"}})
write("ok_animation_duplicate_target.gltf", d, "PG_OK", warn=[
    "1 animation channel targets what an earlier channel of its animation does (the specification forbids it; the "
    "later one is applied): animations[0].channels[1] (the target of an earlier channel)"])
d, _ = base_doc()
d["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": 0}, {"POSITION": 0}]
d["meshes"][0]["weights"] = [0.5, 0.25]
write("ok_morph_targets.gltf", d, "PG_OK", warn=[])
# extension objects the file does not list in extensionsUsed (invalid): named, with what is done
d, _ = base_doc()
d["meshes"][0]["primitives"][0]["material"] = 0
d["materials"] = [{"extensions": {"KHR_materials_unlit": {}, "KHR_materials_clearcoat": {"clearcoatFactor": 1}}}]
write("ok_extensions_undeclared.gltf", d, "PG_OK", warn=[
    "extensions not listed in extensionsUsed (the specification requires it): KHR_materials_unlit applied; "
    "KHR_materials_clearcoat ignored"])
# morph targets of TEXCOORD_0 are not applied, and a texture read through a TEXCOORD_0 the primitive
# does not have samples one spot: both were silent
d = textured_doc({"uri": png_data_uri(PNG2)})
d["meshes"][0]["primitives"][0]["targets"] = [{"TEXCOORD_0": 2}]
d["meshes"][0]["weights"] = [0.5]
write("ok_morph_texcoord.gltf", d, "PG_OK", warn=[
    "morph targets of TEXCOORD_n or COLOR_n in 1 primitive ignored: POSITION, NORMAL and TANGENT targets are applied"])
d = textured_doc({"uri": png_data_uri(PNG2)})
del d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"]
write("ok_texture_without_texcoord.gltf", d, "PG_OK", warn=[
    "1 primitive without TEXCOORD_0 under a material that reads a texture with it: every pixel samples the texture "
    "at (0, 0)"])
# a scene far below what float shading resolves (a unit cube scaled by 1e-20 drew nothing): said
d, _ = base_doc()
d["nodes"][0]["scale"] = [1e-20, 1e-20, 1e-20]
write("ok_tiny_scene.gltf", d, "PG_OK", warn=[
    "the scene is 1.41e-20 units across: 32-bit float shading loses lights and geometry below about 1e-14 units "
    "(a unit cube scaled by 1e-20 drew nothing); scale it up, e.g. by a root node's scale"])
# a scene past what float shading holds (a unit cube scaled by 1e20 drew nothing), and one far from the
# origin for its size (a unit cube at 1e7 drew nothing): both were silent
d, _ = base_doc()
d["nodes"][0]["scale"] = [1e20, 1e20, 1e20]
write("ok_huge_scene.gltf", d, "PG_OK", warn=[
    "the scene reaches 1.41e+20 units: 32-bit float shading overflows past about 1e18 units (squared distances; a "
    "unit cube scaled by 1e20 drew nothing); scale it down, e.g. by a root node's scale"])
d, _ = base_doc()
d["nodes"][0]["translation"] = [1e7, 0, 0]
write("ok_far_scene.gltf", d, "PG_OK", warn=[
    "the scene is 1.41 units across and lies 1e+07 units from the origin: 32-bit positions there are 1.19 units "
    "apart, so its shape collapses (a unit cube at 1e7 drew nothing); move it toward the origin, e.g. by a root "
    "node's translation"])
d, _ = base_doc()
d["extensionsUsed"] = ["KHR_texture_transform", "KHR_mesh_quantization", "EXT_meshopt_compression",
                       "KHR_draco_mesh_compression", "KHR_materials_clearcoat", "EXT_made_up"]
write("ok_extensions_used.gltf", d, "PG_OK", warn=[  # the first four are implemented: no line
    "extensionsUsed: 'KHR_materials_clearcoat' ignored: the core material is drawn without it",
    "extensionsUsed: 'EXT_made_up' ignored: not supported"])
d, _ = base_doc()
d["extensionsUsed"] = ["EXT_x_%02d" % i for i in range(18)]
write("ok_many_extensions.gltf", d, "PG_OK",
      warn=["extensionsUsed: 'EXT_x_%02d' ignored: not supported" % i for i in range(16)]
      + ["extensionsUsed: 2 more extensions ignored (not supported)"])
IMPLEMENTED = ("EXT_mesh_gpu_instancing", "EXT_meshopt_compression", "EXT_texture_webp",  # may be required
               "KHR_draco_mesh_compression", "KHR_lights_punctual", "KHR_materials_emissive_strength",
               "KHR_materials_unlit", "KHR_materials_variants", "KHR_mesh_quantization", "KHR_texture_transform",
               "PASSGRAPH_lights_table")
for name, exts in (("required_texture_transform.gltf", ["KHR_texture_transform", "KHR_mesh_quantization"]),
                   ("required_meshopt.gltf", ["EXT_meshopt_compression"]),
                   ("required_emissive_and_meshopt.gltf", ["KHR_materials_emissive_strength",
                                                           "EXT_meshopt_compression"]),
                   ("required_made_up.gltf", ["EXT_made_up", "EXT_meshopt_compression"])):
    d, _ = base_doc()
    d["extensionsUsed"] = exts
    d["extensionsRequired"] = exts
    bad = [e for e in exts if e not in IMPLEMENTED]  # implemented: accepted
    names = ", ".join("'%s'" % e for e in bad)
    if not bad:
        write(name, d, "PG_OK")
    else:
        write(name, d, "PG_ERR_GLTF", "extensionsRequired: %s %s not supported (passgraph implements only "
              "these glTF extensions: %s)" % (names, "is" if len(bad) == 1 else "are", ", ".join(IMPLEMENTED)))
# an implemented extension is accepted when required, and not warned about when used
d, _ = base_doc()
d["extensionsUsed"] = ["KHR_materials_emissive_strength"]
d["extensionsRequired"] = ["KHR_materials_emissive_strength"]
d["meshes"][0]["primitives"][0]["material"] = 0
d["materials"] = [{"emissiveFactor": [0.5, 0.25, 1],
                   "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2}}}]
write("ok_required_emissive_strength.gltf", d, "PG_OK")
# emissiveFactor / emissiveStrength must be finite and >= 0. JSON has no infinity: a number past the
# double range (1e999) is refused by the JSON parser; a product past the float range by the loader.
# The metallic-roughness factors are in [0, 1] (the specification's ranges).
for name, mat, msg in (
        ("emissive_negative.gltf", {"emissiveFactor": [1, -0.5, 0]},
         "materials[0].emissiveFactor: expected 3 finite numbers >= 0, got [1,-0.5,0]"),
        ("emissive_infinite.gltf", {"emissiveFactor": [1, "INF", 0]}, "number overflow parsing '1e999'"),
        ("emissive_two_numbers.gltf", {"emissiveFactor": [1, 1]},
         "materials[0].emissiveFactor: expected 3 finite numbers >= 0, got [1,1]"),
        ("emissive_strength_negative.gltf",
         {"emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": -2}}},
         "materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength: expected a finite number >= 0, "
         "got -2"),
        ("emissive_strength_infinite.gltf",
         {"emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": "INF"}}},
         "number overflow parsing '1e999'"),
        ("base_color_out_of_range.gltf", {"pbrMetallicRoughness": {"baseColorFactor": [-1, 2, 0.5, 1]}},
         "materials[0].pbrMetallicRoughness.baseColorFactor: expected 4 numbers in [0, 1], got [-1,2,0.5,1]"),
        ("metallic_out_of_range.gltf", {"pbrMetallicRoughness": {"metallicFactor": 7}},
         "materials[0].pbrMetallicRoughness.metallicFactor: expected a number in [0, 1], got 7"),
        ("roughness_negative.gltf", {"pbrMetallicRoughness": {"roughnessFactor": -5}},
         "materials[0].pbrMetallicRoughness.roughnessFactor: expected a number in [0, 1], got -5"),
        ("emissive_factor_overflow.gltf", {"emissiveFactor": [1e39, 0, 0]},
         "materials[0].emissiveFactor: 1e+39 x emissiveStrength 1 is outside the float range"),
        ("emissive_strength_overflow.gltf",
         {"emissiveFactor": [1, 1e30, 1], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 1e30}}},
         "materials[0].emissiveFactor: 1e+30 x emissiveStrength 1e+30 is outside the float range")):
    d, _ = base_doc()
    d["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    d["meshes"][0]["primitives"][0]["material"] = 0
    d["materials"] = [mat]
    write(name, json.dumps(d, indent=1).replace('"INF"', "1e999") + "\n", "PG_ERR_GLTF", msg)
d, _ = base_doc()
d["meshes"][0]["primitives"][0]["material"] = 0
d["materials"] = [{"name": "glass", "alphaMode": "BLEND",
                   "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.3]}}]
write("ok_alpha_blend.gltf", d, "PG_OK")  # BLEND is drawn (forward_transparent): no warning
d = textured_doc({"uri": "ok_2x2.png"})
d["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 0
d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = 2
d["materials"][0]["name"] = "decal"
d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1
d["meshes"][0]["primitives"][0]["attributes"]["COLOR_1"] = 0
d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_2"] = 2
write("ok_color_texcoord1.gltf", d, "PG_OK", warn=[  # COLOR_0, TEXCOORD_1, texCoord 1 are drawn
    "COLOR_1 (and higher) in 1 primitive ignored: COLOR_0 is used",
    "TEXCOORD_2 (and higher) in 1 primitive ignored: textures read TEXCOORD_0 or TEXCOORD_1"])
d = textured_doc({"uri": "ok_2x2.png"})
d["samplers"] = [{"magFilter": 9729, "minFilter": 9987},
                 {"wrapS": 33071, "wrapT": 33648, "magFilter": 9728, "minFilter": 9984},
                 {"wrapS": 1234, "magFilter": 9986, "minFilter": 77}]
d["textures"] = [{"source": 0, "sampler": 1}]
write("ok_sampler_modes.gltf", d, "PG_OK", warn=[  # the glTF modes are drawn; values outside the spec are warned
    "1 sampler with unknown wrap/filter values (samplers[2]: wrapS 1234 magFilter NEAREST_MIPMAP_LINEAR "
    "minFilter 77) ignored: REPEAT / LINEAR (trilinear) used for them"])
d = textured_doc({"uri": "ok_2x2.png"})
d["extensionsUsed"] = ["KHR_materials_emissive_strength"]
d["materials"] = [{"name": "lamp", "emissiveFactor": [1, 0.5, 0],
                   "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 5}}},
                  {"emissiveTexture": {"index": 0},
                   "pbrMetallicRoughness": {"metallicRoughnessTexture": {"index": 0}},
                   "occlusionTexture": {"index": 0}}]
write("ok_emissive.gltf", d, "PG_OK")  # the metallic-roughness and occlusion textures are read (pbr)

# ------------------------------------------------------------------------------------------------
# KHR_lights_punctual: bad light objects and bad node references fail naming the field


def lights_doc(light, node_ext=None):
    d, _ = base_doc(with_normals=True)
    d["extensionsUsed"] = ["KHR_lights_punctual"]
    d["extensions"] = {"KHR_lights_punctual": {"lights": [light]}}
    d["nodes"].append({"extensions": {"KHR_lights_punctual": node_ext if node_ext is not None else {"light": 0}}})
    d["scenes"][0]["nodes"] = [0, 1]
    return d


write("light_bad_type.gltf", lights_doc({"type": "area"}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].type: 'area': expected \"point\", \"spot\" or \"directional\"")
write("light_color_two.gltf", lights_doc({"type": "point", "color": [1, 0.5]}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].color: expected 3 numbers, got [1,0.5]")
# wrongly typed values were read as the defaults ("red" as white, "5" as 1, "0.5" as pi/4)
write("light_color_string.gltf", lights_doc({"type": "point", "color": "red"}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].color: expected 3 numbers, got \"red\"")
write("light_intensity_string.gltf", lights_doc({"type": "point", "intensity": "5"}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].intensity: expected a number, got \"5\"")
write("light_cone_string.gltf", lights_doc({"type": "spot", "spot": {"outerConeAngle": "0.5"}}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].spot.outerConeAngle: expected a number, got \"0.5\"")
write("light_color_negative.gltf", lights_doc({"type": "point", "color": [1, -1, 0]}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].color: expected three finite numbers >= 0")
write("light_intensity_negative.gltf", lights_doc({"type": "point", "intensity": -2}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].intensity: expected a finite number >= 0")
write("light_range_negative.gltf", lights_doc({"type": "point", "range": -1}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].range: -1: expected a number in [1.2e-38, 1e30]")
# a given range of 0, or one that is 0 as a float, was read as absent: infinite reach
write("light_range_zero.gltf", lights_doc({"type": "point", "range": 0}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].range: 0: expected a number in [1.2e-38, 1e30]")
write("light_range_float_zero.gltf", lights_doc({"type": "point", "range": 1e-46}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].range: 1e-46: expected a number in [1.2e-38, 1e30]")
write("light_range_huge.gltf", lights_doc({"type": "point", "range": 1e39}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].range: 1e+39: expected a number in [1.2e-38, 1e30]")
# past what a float holds once stored (a directional light 1e15 units away, colour x 1e30): the
# lightcut dropped such a sun and RIS halved it
write("light_sun_too_bright.gltf", lights_doc({"type": "directional", "intensity": 1e10}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0]: colour x intensity 1e+10 lux: over the 1e+07 lux")
write("light_point_too_bright.gltf", lights_doc({"type": "point", "color": [1e10, 1, 1], "intensity": 1e25}),
      "PG_ERR_GLTF", "KHR_lights_punctual.lights[0]: colour x intensity 1e+35 candela: over the 1e+30")
write("light_cone_inverted.gltf", lights_doc({"type": "spot", "spot": {"innerConeAngle": 0.6,
                                                                        "outerConeAngle": 0.5}}),
      "PG_ERR_GLTF", "KHR_lights_punctual.lights[0].spot.innerConeAngle: expected an angle in [0, outerConeAngle)")
write("light_cone_wide.gltf", lights_doc({"type": "spot", "spot": {"outerConeAngle": 2.0}}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].spot.outerConeAngle: expected an angle in (0, pi/2]")
write("light_index_out_of_range.gltf", lights_doc({"type": "point"}, {"light": 3}), "PG_ERR_GLTF",
      "nodes[1].extensions.KHR_lights_punctual.light: lights index 3 out of range (1 lights)")
# 2^32 was read as light 0
write("light_index_2_32.gltf", lights_doc({"type": "point"}, {"light": 4294967296}), "PG_ERR_GLTF",
      "nodes[1].extensions.KHR_lights_punctual.light: lights index 4294967296 out of range (1 lights)")
write("light_index_missing.gltf", lights_doc({"type": "point"}, {}), "PG_ERR_GLTF",
      "nodes[1].extensions.KHR_lights_punctual.light: missing (required)")
write("light_type_missing.gltf", lights_doc({"color": [1, 1, 1]}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].type: missing: expected \"point\", \"spot\" or \"directional\"")
write("light_spot_missing.gltf", lights_doc({"type": "spot"}), "PG_ERR_GLTF",
      "KHR_lights_punctual.lights[0].spot: missing (required by type \"spot\")")

# cameras: their type, its object and its required numbers are checked before tinygltf reads them
# (its own messages name no camera); aspectRatio, when given, is > 0


def camera_doc(cam):
    d, _ = base_doc()
    d["cameras"] = [cam]
    d["nodes"].append({"camera": 0, "translation": [0, 0, 3]})
    d["scenes"][0]["nodes"] = [0, 1]
    return d


for name, cam, msg in (
        ("camera_type_bad.gltf", {"type": "fisheye"},
         "cameras[0].type: \"fisheye\" is not one of \"perspective\", \"orthographic\""),
        ("camera_type_missing.gltf", {"perspective": {"yfov": 0.8, "znear": 0.1}},
         "cameras[0].type: missing (required: \"perspective\", \"orthographic\")"),
        ("camera_object_missing.gltf", {"type": "perspective"},
         "cameras[0].perspective: missing (required by type \"perspective\")"),
        ("camera_aspect_zero.gltf", {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "aspectRatio": 0}},
         "cameras[0].perspective.aspectRatio: expected a finite number > 0, got 0"),
        ("camera_ortho_no_zfar.gltf", {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0}},
         "cameras[0].orthographic.zfar: missing (required)")):
    write(name, camera_doc(cam), "PG_ERR_GLTF", msg)
# a negative xmag/ymag ("should not" in the specification) drew a 45-degree perspective view while
# --explain said orthographic: drawn with its magnitude, warned
write("ok_camera_ortho_negative.gltf",
      camera_doc({"type": "orthographic", "orthographic": {"xmag": -2, "ymag": -2, "znear": 0.1, "zfar": 10}}),
      "PG_OK", warn=["1 orthographic camera (cameras[0]) with a negative xmag or ymag (the specification says it "
                     "should not be): drawn with its magnitude"])

# PASSGRAPH_lights_table: a good table of two lights, and bad ones refused naming the field


def table_doc(records, count, stride=None, ext=None):
    table = b"".join(struct.pack("<8f", *r) for r in records)
    d, data = base_doc(with_normals=True, extra_bin=table)
    view = {"buffer": 0, "byteOffset": len(data) - len(table), "byteLength": len(table)}
    if stride:
        view["byteStride"] = stride
    d["bufferViews"].append(view)
    d["buffers"][0] = {"byteLength": len(data), "uri": b64(data)}
    d["extensionsUsed"] = ["PASSGRAPH_lights_table"]
    d["extensions"] = {"PASSGRAPH_lights_table": ext if ext is not None else
                       {"bufferView": len(d["bufferViews"]) - 1, "count": count}}
    return d


TWO = [(0, 1, 0, 2, 1, 0.5, 0.25, 3), (1, 2, 3, 0, 0, 1, 0, 1)]
write("ok_lights_table.gltf", table_doc(TWO, 2), "PG_OK")
write("lights_table_short.gltf", table_doc(TWO, 3), "PG_ERR_GLTF",
      "extensions.PASSGRAPH_lights_table.count: 3 lights need 96 bytes, bufferViews[3] has 64")
write("lights_table_negative.gltf", table_doc([(0, 1, 0, 2, 1, -0.5, 0, 3)], 1), "PG_ERR_GLTF",
      "extensions.PASSGRAPH_lights_table: light 0: colour -0.5")
write("lights_table_stride.gltf", table_doc(TWO, 2, stride=16), "PG_ERR_GLTF",
      "extensions.PASSGRAPH_lights_table: bufferViews[3].byteStride 16 (the records are 32 bytes")
write("lights_table_no_count.gltf", table_doc(TWO, 2, ext={"bufferView": 3}), "PG_ERR_GLTF",
      "extensions.PASSGRAPH_lights_table.count: missing (required)")
write("lights_table_bad_view.gltf", table_doc(TWO, 2, ext={"bufferView": 9, "count": 2}), "PG_ERR_GLTF",
      "extensions.PASSGRAPH_lights_table.bufferView: bufferViews index 9 out of range (4 bufferViews)")
# a count or index of 2^32 and past was read modulo 2^32 (2^32 + 3: three lights), a count of 0 or an
# array extension was taken for no table, an unknown key was ignored
write("lights_table_count_2_32.gltf", table_doc(TWO, 2, ext={"bufferView": 3, "count": 4294967298}), "PG_ERR_GLTF",
      "extensions.PASSGRAPH_lights_table.count: 4294967298: expected an integer in 1..16777216")
write("lights_table_view_2_32.gltf", table_doc(TWO, 2, ext={"bufferView": 4294967299, "count": 2}), "PG_ERR_GLTF",
      "extensions.PASSGRAPH_lights_table.bufferView: bufferViews index 4294967299 out of range (4 bufferViews)")
write("lights_table_count_zero.gltf", table_doc(TWO, 0), "PG_ERR_GLTF",
      "extensions.PASSGRAPH_lights_table.count: 0: expected an integer in 1..16777216")
write("lights_table_array.gltf", table_doc(TWO, 2, ext=[3, 2]), "PG_ERR_GLTF",
      "extensions.PASSGRAPH_lights_table: expected an object")
write("lights_table_unknown_key.gltf", table_doc(TWO, 2, ext={"bufferView": 3, "count": 2, "stride": 32}),
      "PG_ERR_GLTF", "extensions.PASSGRAPH_lights_table.stride: unknown key (expected bufferView and count)")

# EXT_mesh_gpu_instancing: the triangle drawn at instances whose TRANSLATION and SCALE are the
# triangle's own positions accessor (3 VEC3 FLOAT: (0,0,0), (1,0,0), (0,1,0)); bad ones refused


def instancing_doc(attrs, mesh=True, extra_accessor=None):
    d, _ = base_doc()
    if extra_accessor:
        d["accessors"].append(extra_accessor)
    d["extensionsUsed"] = ["EXT_mesh_gpu_instancing"]
    node = {"extensions": {"EXT_mesh_gpu_instancing": {"attributes": attrs}}}
    if mesh:
        node["mesh"] = 0
    else:
        d["nodes"].append(node)
        d["scenes"] = [{"nodes": [0, 1]}]
        return d
    d["nodes"] = [node]
    return d


write("ok_instancing.gltf", instancing_doc({"TRANSLATION": 0, "_ID": 1}), "PG_OK")
write("instancing_no_mesh.gltf", instancing_doc({"TRANSLATION": 0}, mesh=False), "PG_ERR_GLTF",
      "nodes[1].extensions.EXT_mesh_gpu_instancing: the node has no mesh to instance")
write("instancing_count_mismatch.gltf",
      instancing_doc({"TRANSLATION": 0, "SCALE": 2},
                     extra_accessor={"bufferView": 0, "componentType": 5126, "count": 2, "type": "VEC3"}),
      "PG_ERR_GLTF", "EXT_mesh_gpu_instancing.attributes: accessors of 3 and 2 instances")
write("instancing_bad_type.gltf", instancing_doc({"ROTATION": 0}), "PG_ERR_GLTF",
      "EXT_mesh_gpu_instancing.attributes.ROTATION: accessors[0] must be VEC4 FLOAT or normalized BYTE/SHORT "
      "(got VEC3 FLOAT)")
write("instancing_bad_attribute.gltf", instancing_doc({"COLOR": 0}), "PG_ERR_GLTF",
      "EXT_mesh_gpu_instancing.attributes: 'COLOR' is not TRANSLATION, ROTATION, SCALE")
write("instancing_bad_accessor.gltf", instancing_doc({"SCALE": 7}), "PG_ERR_GLTF",
      "EXT_mesh_gpu_instancing.attributes.SCALE: expected an accessor index (2 accessors)")
write("instancing_only_custom.gltf", instancing_doc({"_ID": 0}), "PG_ERR_GLTF",
      "EXT_mesh_gpu_instancing.attributes: none of TRANSLATION, ROTATION, SCALE")

# a small file that draws a 400-vertex mesh (1,200 indices: 24,000 baked bytes) at 2^19 leaves of a
# DAG of children, or at 2^20 EXT_mesh_gpu_instancing instances (a sparse accessor: 12 bytes of
# data): 12.6 and 25 GB of vertices and indices, refused before anything is baked
BIG_POS = f32(*[c for i in range(400) for c in (i % 20 * 0.05, i // 20 * 0.05, 0.0)])
BIG_IDX = struct.pack("<1200H", *[(i * 7) % 400 for i in range(1200)])


def bake_limit_doc():
    d, data = base_doc(pos=BIG_POS, idx=BIG_IDX, idx_count=1200)
    d["accessors"][0]["count"] = 400
    return d, data


d, _ = bake_limit_doc()
d["nodes"] = [{"children": [i + 1, i + 1]} for i in range(19)] + [{"mesh": 0}]
write("bake_limit_dag.gltf", d, "PG_ERR_LIMIT",
      "nodes[19]: the meshes drawn at every node and instance would bake more than 8 GiB of vertices and indices")
d, data = bake_limit_doc()
d["bufferViews"].append({"buffer": 0, "byteOffset": len(data), "byteLength": 16})
data += struct.pack("<I3f", 5, 1.0, 2.0, 3.0)
d["buffers"][0] = {"byteLength": len(data), "uri": b64(data)}
d["accessors"].append({"componentType": 5126, "count": 1 << 20, "type": "VEC3",
                       "sparse": {"count": 1, "indices": {"bufferView": 2, "componentType": 5125},
                                  "values": {"bufferView": 2, "byteOffset": 4}}})
d["nodes"] = [{"mesh": 0, "extensions": {"EXT_mesh_gpu_instancing": {"attributes": {"TRANSLATION": 2}}}}]
d["extensionsUsed"] = ["EXT_mesh_gpu_instancing"]
write("bake_limit_instances.gltf", d, "PG_ERR_LIMIT",
      "nodes[0]: the meshes drawn at every node and instance would bake more than 8 GiB of vertices and indices")

# without NORMAL every index bakes its own vertex (flat normals): 3 positions and 1,200 indices drawn
# at the 2^18 leaves of a DAG bake 16.4 GB; counted by positions the plan was 1.3 GB and let it through
d, _ = base_doc(idx=struct.pack("<1200H", *[i % 3 for i in range(1200)]), idx_count=1200)
d["nodes"] = [{"children": [i + 1, i + 1]} for i in range(18)] + [{"mesh": 0}]
write("bake_limit_flat_normals.gltf", d, "PG_ERR_LIMIT",
      "nodes[18]: the meshes drawn at every node and instance would bake more than 8 GiB of vertices and indices")

# KHR_materials_variants (variants/gen_variants.py has the file that loads): bad variants and mappings


def variants_doc(variants, mappings):
    d, _ = base_doc()
    d["extensionsUsed"] = ["KHR_materials_variants"]
    d["extensions"] = {"KHR_materials_variants": {"variants": variants}}
    d["materials"] = [{"name": "a"}, {"name": "b"}]
    d["meshes"][0]["primitives"][0]["extensions"] = {"KHR_materials_variants": {"mappings": mappings}}
    return d


write("variants_no_name.gltf", variants_doc([{"name": "x"}, {}], []), "PG_ERR_GLTF",
      "extensions.KHR_materials_variants.variants[1].name: expected a string")
write("variants_material_out_of_range.gltf", variants_doc([{"name": "x"}], [{"material": 2, "variants": [0]}]),
      "PG_ERR_GLTF", "meshes[0].primitives[0].extensions.KHR_materials_variants.mappings[0].material: 2 out of range "
      "(2 materials)")
write("variants_index_out_of_range.gltf", variants_doc([{"name": "x"}], [{"material": 1, "variants": [1]}]),
      "PG_ERR_GLTF", "mappings[0].variants: expected variant indices below 1")
write("variants_mapped_twice.gltf", variants_doc([{"name": "x"}], [{"material": 1, "variants": [0]},
                                                                   {"material": 0, "variants": [0]}]),
      "PG_ERR_GLTF", "mappings[1].variants: variant 0 is mapped twice in this primitive")

# texture-source extensions (webp/gen_webp.py has the files that load): a truncated WebP image, a
# KHR_texture_basisu texture without a fallback source, an EXT_texture_webp source out of range


def texture_ext_doc(images, texture, used):
    d, _ = base_doc()
    d["extensionsUsed"] = used
    d["images"] = images
    d["textures"] = [texture]
    d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    d["meshes"][0]["primitives"][0]["material"] = 0
    return d


TRUNCATED_WEBP = b"RIFF" + struct.pack("<I", 40) + b"WEBPVP8L" + struct.pack("<I", 28) + b"\x2f\x0f\xc0\x03"
write("webp_truncated.gltf",
      texture_ext_doc([{"uri": "data:image/webp;base64," + base64.b64encode(TRUNCATED_WEBP).decode()}],
                      {"extensions": {"EXT_texture_webp": {"source": 0}}}, ["EXT_texture_webp"]),
      "PG_ERR_GLTF", "images[0] (data URI): cannot decode (not a valid WebP image)")
write("basisu_no_fallback.gltf",
      texture_ext_doc([{"uri": "data:image/ktx2;base64," + base64.b64encode(bytes(16)).decode()}],
                      {"extensions": {"KHR_texture_basisu": {"source": 0}}}, ["KHR_texture_basisu"]),
      "PG_ERR_GLTF", "textures[0]: no usable source image (its image is only in KHR_texture_basisu, which passgraph "
      "does not decode, and it has no fallback source)")
write("webp_source_out_of_range.gltf",
      texture_ext_doc([], {"extensions": {"EXT_texture_webp": {"source": 2}}}, ["EXT_texture_webp"]),
      "PG_ERR_GLTF", "textures[0].extensions.EXT_texture_webp.source: expected an image index (0 images)")

# ------------------------------------------------------------------------------------------------
# fuzz findings (tests/fuzz/README.md): the inputs are kept verbatim in fuzz/, which this script
# neither deletes nor regenerates; only their MANIFEST lines are listed here.
FUZZ_CASES = [
    # fuzz_gltf: finite positions scaled past FLT_MAX by a node transform loaded as +-inf
    ("fuzz/position_float_overflow.glb", "PG_ERR_GLTF",
     "meshes[0].primitives[0]: POSITION element 0 (accessors[0]) is outside the float range"),
]
manifest.extend(FUZZ_CASES)

# quantized twins and hostile EXT_meshopt_compression cases (compressed/gen_compressed.py)
import sys  # noqa: E402
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(HERE, "compressed"))
import gen_compressed  # noqa: E402
manifest.extend(gen_compressed.generate())

with open(os.path.join(HERE, "MANIFEST"), "w") as m:
    m.write("# glTF robustness corpus, generated by gen_corpus.py.\n"
            "# FILE  CODE  SUBSTRING-of-the-message ('-' for PG_OK)\n")
    for name, code, sub in manifest:
        m.write("%-36s %-14s %s\n" % (name, code, sub))
with open(os.path.join(HERE, "WARNINGS"), "w") as m:
    for name, line in warnings:
        m.write("%s\t%s\n" % (name, line))
print("%d manifest entries, %d warning lines" % (len(manifest), len(warnings)))
