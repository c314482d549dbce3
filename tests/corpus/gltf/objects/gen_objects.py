#!/usr/bin/env python3
"""Generates the valid single-object glTF files used by the framing / default-lighting / camera
tests (tests/test_scene.c, tests/test_gpu_framing.c, tests/cli_test.sh). Deterministic; the output
is committed. Run: `python3 tests/corpus/gltf/objects/gen_objects.py`.

  cube.gltf          unit cube (side 1) at the origin, flat normals
  sphere.gltf        UV sphere, radius 1, centred at (3, 1, -2)
  quad.gltf          flat 2x2 quad in the XZ plane facing +Y (a floor tile)
  rod.gltf           long thin box 10 x 0.2 x 0.2 along X
  panels.gltf        three 1 x 1 quads side by side in the XY plane facing +Z, 0.2 apart (test
                     panels, as texture sample files show them)
  panel_back.gltf    one 2 x 1 quad in the XY plane facing -Z
  wall_x.gltf        one 1 x 2 quad in the YZ plane facing -X
  panel_tilted.gltf  panel_back's quad turned 30 degrees about X: it faces (0, 0.5, -0.866), away
                     from the default 3/4 view (a flat object that no axis is thin along)
  tall.gltf          a standing box 0.5 x 1.8 x 0.3 on the ground (a character's proportions)
  two_scenes.gltf    the unit cube in two glTF scenes: 'small' (the default, `scene` 0) and 'big'
                     (node scaled 3x, moved to x = 10); --gltf-scene picks one
  tiny.gltf          cube of side 1e-3
  huge.gltf          cube of side 1e4 centred at (5e3, 0, 0)
  camera.gltf        the unit cube + one perspective camera 'front' (node 'front_node') at
                     (0.5, 0.8, 3) looking at the origin, yfov 0.6, znear 0.1, zfar 100
  ortho_first.gltf   the unit cube + an orthographic camera "plan" only (the default view)
  camera_near_1e-8.gltf  camera.gltf with znear 1e-8: the near plane is raised to 1e-6 x
                     the farthest point's distance
                     (a float depth buffer rounded every depth to 1: nothing was drawn)
  ties.gltf          a 4x4 grid of 0.25-unit quads (z = 0, facing +Z) and an orthographic camera
                     'front' (ymag 1, at z = 5): at 128x72 a quad is 9x9 pixels with its corners
                     on pixel corners, so each quad's diagonal passes through 9 pixel centres,
                     which exactly one of its two triangles must cover (the rasterizers' tie rule)
  two_cameras.gltf   the unit cube + camera 'side' (perspective, infinite zfar, node 'side_node'
                     at (4, 0, 0) looking along -X) and camera 'top' (orthographic, node 'top_node')
"""
import base64
import json
import math
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltfgen import b64, box, look_rotation, merge, sphere  # noqa: E402  (shared geometry, tests/corpus/gltf/gltfgen.py)

HERE = os.path.dirname(os.path.abspath(__file__))


def quad():
    pos = [(-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1)]
    return pos, [(0, 1, 0)] * 4, [0, 1, 2, 0, 2, 3]


def panel(x0, x1, y0, y1, plane, face):
    """A quad: plane 'xy' (z = 0) or 'yz' (x = 0); face +1 / -1 along the plane's normal."""
    if plane == "xy":
        pos = [(x0, y0, 0), (x1, y0, 0), (x1, y1, 0), (x0, y1, 0)]
        n = (0, 0, face)
    else:
        pos = [(0, y0, x0), (0, y0, x1), (0, y1, x1), (0, y1, x0)]
        n = (face, 0, 0)
    # counter-clockwise seen from the side the normal points to
    e1 = [pos[1][k] - pos[0][k] for k in range(3)]
    e2 = [pos[2][k] - pos[0][k] for k in range(3)]
    c = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
    idx = [0, 1, 2, 0, 2, 3] if sum(c[k] * n[k] for k in range(3)) > 0 else [0, 2, 1, 0, 3, 2]
    return pos, [n] * 4, idx


def doc(mesh, cameras=None, camera_nodes=None):
    pos, nrm, idx = mesh
    pb = b"".join(struct.pack("<3f", *p) for p in pos)
    nb = b"".join(struct.pack("<3f", *n) for n in nrm)
    ib = struct.pack("<%dI" % len(idx), *idx)
    data = pb + nb + ib
    mn = [min(p[k] for p in pos) for k in range(3)]
    mx = [max(p[k] for p in pos) for k in range(3)]
    nodes = [{"name": "object", "mesh": 0}]
    for cn in camera_nodes or []:
        nodes.append(cn)
    d = {
        "asset": {"version": "2.0", "generator": "passgraph gen_objects.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2,
                                    "material": 0}]}],
        "materials": [{"name": "grey", "pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6}}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(pos), "type": "VEC3",
             "min": mn, "max": mx},
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
    if cameras:
        d["cameras"] = cameras
    return d


def write(name, d):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(d, f, indent=1)
        f.write("\n")


cube = box((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5))
write("cube.gltf", doc(cube))
write("sphere.gltf", doc(sphere((3, 1, -2), 1.0)))
write("quad.gltf", doc(quad()))
write("rod.gltf", doc(box((-5, -0.1, -0.1), (5, 0.1, 0.1))))
write("panels.gltf", doc(merge(*[panel(x, x + 1, 0, 1, "xy", 1) for x in (-1.7, -0.5, 0.7)])))
write("panel_back.gltf", doc(panel(-1, 1, -0.5, 0.5, "xy", -1)))
write("wall_x.gltf", doc(panel(-0.5, 0.5, 0, 2, "yz", -1)))


def tilted(mesh, deg):
    """mesh turned deg degrees about the X axis (y' = y cos - z sin, z' = y sin + z cos)"""
    c, s_ = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    def rot(v):
        return (v[0], round(v[1] * c - v[2] * s_, 7), round(v[1] * s_ + v[2] * c, 7))
    pos, nrm, idx = mesh
    return [rot(p) for p in pos], [rot(n) for n in nrm], idx


write("panel_tilted.gltf", doc(tilted(panel(-1, 1, -0.5, 0.5, "xy", -1), 30)))
write("tall.gltf", doc(box((-0.25, 0, -0.15), (0.25, 1.8, 0.15))))
two = doc(cube)
two["nodes"] = [{"name": "small_cube", "mesh": 0},
                {"name": "big_cube", "mesh": 0, "scale": [3, 3, 3], "translation": [10, 0, 0]}]
two["scenes"] = [{"name": "small", "nodes": [0]}, {"name": "big", "nodes": [1]}]
write("two_scenes.gltf", two)
write("tiny.gltf", doc(box((-5e-4, -5e-4, -5e-4), (5e-4, 5e-4, 5e-4))))
write("huge.gltf", doc(box((0, -5e3, -5e3), (1e4, 5e3, 5e3))))
eye = (0.5, 0.8, 3.0)
write("camera.gltf", doc(cube,
      cameras=[{"name": "front", "type": "perspective",
                "perspective": {"yfov": 0.6, "znear": 0.1, "zfar": 100.0, "aspectRatio": 1.5}}],
      camera_nodes=[{"name": "front_node", "camera": 0, "translation": list(eye),
                     "rotation": look_rotation(eye, (0, 0, 0))}]))
write("camera_near_1e-8.gltf", doc(cube,
      cameras=[{"name": "front", "type": "perspective",
                "perspective": {"yfov": 0.6, "znear": 1e-8, "zfar": 100.0, "aspectRatio": 1.5}}],
      camera_nodes=[{"name": "front_node", "camera": 0, "translation": list(eye),
                     "rotation": look_rotation(eye, (0, 0, 0))}]))
write("two_cameras.gltf", doc(cube,
      cameras=[{"name": "side", "type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05}},
               {"name": "top", "type": "orthographic",
                "orthographic": {"xmag": 1.0, "ymag": 1.0, "znear": 0.1, "zfar": 10.0}}],
      camera_nodes=[{"name": "side_node", "camera": 0, "translation": [4, 0, 0],
                     "rotation": look_rotation((4, 0, 0), (0, 0, 0))},
                    {"name": "top_node", "camera": 1, "translation": [0, 5, 0],
                     "rotation": [-math.sqrt(0.5), 0, 0, math.sqrt(0.5)]}]))
# an orthographic camera first: it is the default view
write("ortho_first.gltf", doc(cube,
      cameras=[{"name": "plan", "type": "orthographic",
                "orthographic": {"xmag": 2.0, "ymag": 1.0, "znear": 0.1, "zfar": 20.0}}],
      camera_nodes=[{"name": "plan_node", "camera": 0, "translation": [0, 5, 0],
                     "rotation": [-math.sqrt(0.5), 0, 0, math.sqrt(0.5)]}]))
# pixel centres on shared edges (the compute rasterizer's tie rule; test_gpu_visibility)
write("ties.gltf", doc(merge(*[panel(-0.5 + 0.25 * i, -0.25 + 0.25 * i, -0.5 + 0.25 * j, -0.25 + 0.25 * j, "xy", 1)
                               for i in range(4) for j in range(4)]),
      cameras=[{"name": "front", "type": "orthographic",
                "orthographic": {"xmag": 16.0 / 9.0, "ymag": 1.0, "znear": 0.1, "zfar": 20.0}}],
      camera_nodes=[{"name": "front_node", "camera": 0, "translation": [0, 0, 5]}]))
