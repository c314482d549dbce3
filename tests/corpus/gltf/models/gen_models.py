#!/usr/bin/env python3
"""Generates ten small, recognisable everyday-object glTF 2.0 models (the goal: "for ten
object-type glTF models, `passgraph render --scene MODEL --out x.png` with no other option gives a
framed, lit, recognisable image") and one animated, skinned character (walker.gltf). Python 3
standard library only; deterministic (no random module, no time stamps: the same bytes on every
run); the output is committed next to this file.
Run: `python3 tests/corpus/gltf/models/gen_models.py` (`--out DIR` writes into DIR instead).

Every model faces +Z, stands on y = 0, is in metres, and has several materials and node
transforms (translation / rotation / scale) for some parts. Geometry is built from a few
primitives (box, lathe, sphere, torus, polygon); each triangle is wound counter-clockwise seen
from the side its (outward, unit) vertex normals point to, and every closed part is checked to
have a positive signed volume (outward winding). `validate()` re-reads every written file and
checks accessor min/max, byteLength, bufferView ranges / alignment / targets, index ranges, unit
normals and triangle winding against the normals before the file is written; with skins and
animations (validate_animated) also the inverse bind matrices against the joints' bind pose,
JOINTS_0 / WEIGHTS_0 (1 or 2 joints a vertex, in range, weights summing to 1), sampler key times
(increasing, exact min/max) and output counts; walker_check() poses walker.gltf by CPU skinning.

  mug.gltf           glazed mug: lathe body with a wall thickness (outside / inside materials),
                     half-torus handle (node rotation), coffee disc
  pawn.gltf          white and black chess pawns (lathe; one set of accessors, two meshes with
                     different materials) on a 4 x 4 chess-board corner
  table_chair.gltf   table and chair from boxes, a procedural wood PNG texture (TEXCOORD_0)
                     shared by two materials (oak / walnut via baseColorFactor), chair turned by a
                     node rotation, plate and apple
  donut.gltf         torus dough and an icing shell coloured by COLOR_0 vertex colours (pink with
                     sprinkles; the icing material itself is white)
  rocket.glb         (binary) white body, red nose cone, four fins (one mesh, four rotated nodes),
                     porthole, nozzle, flame cone with emissiveFactor, launch pad
  house.gltf         walls with a door and window holes, a gable roof (two rotated slabs), chimney,
                     door, window panes with alphaMode BLEND glass, a floor inside
  tree.gltf          fir tree: trunk and three foliage cones with a leaf texture repeated by
                     KHR_texture_transform (scale 6 x 3; extensionsUsed only), grass disc
  snowman.gltf       three snow spheres, coal eyes and buttons, carrot cone, top hat, scarf
                     (torus), stick arms (node rotations)
  crate.glb          (binary) wooden crate: planks base-colour texture AND a matching tangent-space
                     normal map (sampler CLAMP_TO_EDGE), metal corners, a second smaller crate
                     on top (node rotation + scale)
  desk_lamp.gltf     desk lamp: metal base and arms, open shade (doubleSided), emissive bulb,
                     and a perspective glTF camera 'product_shot' (the default view)
  walker.gltf        animated stylised person, 1.8 m: one skinned mesh (skin, shirt, trousers,
                     shoes/hair materials) on a 15-joint skeleton (nodes 0-14, root 'hips'; mesh
                     node 'walker_body' with skin 0), JOINTS_0 UNSIGNED_BYTE blended at the elbows,
                     knees, ankles, spine and neck; animations 'walk' (1 s loop in place, hips bob)
                     and 'wave' (2 s, right arm), LINEAR, keys every 1/16 s
"""
import base64
import json
import math
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = HERE

# ----------------------------------------------------------------------------- small vector math


def add(a, b):
    return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def mulv(a, s):
    return [a[0] * s, a[1] * s, a[2] * s]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    l = math.sqrt(dot(a, a))
    return [a[0] / l, a[1] / l, a[2] / l]


# 4x4 matrices, row-major nested lists, acting on column vectors
def mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def chain(*ms):
    r = I4()
    for m in ms:
        r = mat_mul(r, m)
    return r


def I4():
    return [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]


def T(x, y, z):
    m = I4()
    m[0][3], m[1][3], m[2][3] = x, y, z
    return m


def S(x, y=None, z=None):
    m = I4()
    m[0][0], m[1][1], m[2][2] = x, x if y is None else y, x if z is None else z
    return m


def R(axis, deg):
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    m = I4()
    i, j = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[axis]
    m[i][i], m[i][j], m[j][i], m[j][j] = c, -s, s, c
    return m


def xf_point(m, p):
    return [m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] for i in range(3)]


def xf_normal(m, n):
    # inverse-transpose of the upper 3x3 = cofactor matrix / det; the scale does not matter
    a = [[m[i][j] for j in range(3)] for i in range(3)]
    cof = [[a[(i + 1) % 3][(j + 1) % 3] * a[(i + 2) % 3][(j + 2) % 3] -
            a[(i + 1) % 3][(j + 2) % 3] * a[(i + 2) % 3][(j + 1) % 3] for j in range(3)]
           for i in range(3)]
    det = sum(a[0][j] * cof[0][j] for j in range(3))
    r = [sum(cof[i][j] * n[j] for j in range(3)) for i in range(3)]
    return norm(r if det > 0 else mulv(r, -1))


def quat(axis, deg):
    """glTF rotation (x, y, z, w) about a unit axis."""
    a = math.radians(deg) / 2
    ax = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}[axis] if isinstance(axis, str) else norm(axis)
    return [ax[0] * math.sin(a), ax[1] * math.sin(a), ax[2] * math.sin(a), math.cos(a)]


def look_rotation(eye, target):
    """Unit quaternion (x, y, z, w) turning the node's -Z to (target - eye), +Y kept up."""
    z = norm(sub(eye, target))                # node +Z = -forward
    x = norm(cross([0, 1, 0], z))
    y = cross(z, x)
    m00, m01, m02 = x[0], y[0], z[0]
    m10, m11, m12 = x[1], y[1], z[1]
    m20, m21, m22 = x[2], y[2], z[2]
    tr = m00 + m11 + m22
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        return [(m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s]
    if m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        return [0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s]
    if m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        return [(m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s]
    s = math.sqrt(1.0 + m22 - m00 - m11) * 2
    return [(m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s]


# ----------------------------------------------------------------------------- geometry


class Prim:
    """One glTF primitive: POSITION, NORMAL, optional TEXCOORD_0 / COLOR_0, uint16/32 indices."""

    def __init__(self, material, uv=False, color=False):
        self.material = material
        self.has_uv, self.has_color = uv, color
        self.pos, self.nrm, self.uv, self.col, self.idx = [], [], [], [], []

    def vert(self, p, n, uv=(0.0, 0.0), col=(1.0, 1.0, 1.0, 1.0)):
        self.pos.append([float(v) for v in p])
        self.nrm.append(norm(n))
        self.uv.append([float(uv[0]), float(uv[1])])
        self.col.append([float(c) for c in col])
        return len(self.pos) - 1

    def tri(self, a, b, c):
        """Adds a triangle wound counter-clockwise seen from where its vertex normals point;
        degenerate triangles (at a lathe's axis) are dropped."""
        P = self.pos
        g = cross(sub(P[b], P[a]), sub(P[c], P[a]))
        if dot(g, g) < 1e-22:
            return
        n = add(add(self.nrm[a], self.nrm[b]), self.nrm[c])
        if dot(g, n) < 0:
            b, c = c, b
        self.idx += [a, b, c]

    def quad(self, a, b, c, d):
        self.tri(a, b, c)
        self.tri(a, c, d)

    def signed_volume(self, first_index):
        v = 0.0
        for t in range(first_index, len(self.idx), 3):
            a, b, c = (self.pos[i] for i in self.idx[t:t + 3])
            v += dot(a, cross(b, c)) / 6.0
        return v


def closed(fn):
    """Decorator for closed shapes: checks that the added triangles enclose a positive volume."""
    def wrapper(prim, *args, **kw):
        first = len(prim.idx)
        fn(prim, *args, **kw)
        vol = prim.signed_volume(first)
        assert vol > 0, "%s: signed volume %g (inward winding)" % (fn.__name__, vol)
    wrapper.__name__ = fn.__name__
    return wrapper


def emit(prim, m, p, n, uv=(0, 0), col=(1, 1, 1, 1)):
    if m is None:
        return prim.vert(p, n, uv, col)
    return prim.vert(xf_point(m, p), xf_normal(m, n), uv, col)


@closed
def box(prim, mn, mx, m=None, uv_scale=1.0, uv_unit=False):
    """Axis-aligned box (flat normals). UVs: metres x uv_scale along the face, or 0..1 per face
    with uv_unit; v grows downwards (image rows) on the side faces."""
    for k in range(3):
        u_ax, v_ax = [(2, 1), (0, 2), (0, 1)][k]
        for side in (0, 1):
            n = [0, 0, 0]
            n[k] = 1 if side else -1
            corners = []
            for (cu, cv) in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0, 0, 0]
                p[k] = mx[k] if side else mn[k]
                p[u_ax] = mn[u_ax] if cu == 0 else mx[u_ax]
                p[v_ax] = mn[v_ax] if cv == 0 else mx[v_ax]
                if uv_unit:
                    uv = (cu, 1 - cv)
                else:
                    uv = ((p[u_ax] - mn[u_ax]) * uv_scale, (mx[v_ax] - p[v_ax]) * uv_scale)
                corners.append(emit(prim, m, p, n, uv))
            prim.quad(*corners)


def lathe(prim, profile, m=None, seg=32, smooth_deg=40.0, v_scale=1.0, colour=None):
    """Surface of revolution about +Y. profile: [(r, y)] from the axis at the bottom, outwards,
    up, and back (a path with the solid on its left when walked in the (r, y) plane), so
    (dy, -dr) is the outward normal of each step. Neighbouring steps whose normals differ by
    less than smooth_deg share an averaged normal (smooth), others get a crease. UV: u = angle /
    360, v = path length x v_scale."""
    steps = []
    for (r0, y0), (r1, y1) in zip(profile, profile[1:]):
        d = (r1 - r0, y1 - y0)
        l = math.hypot(*d)
        if l < 1e-12:
            continue
        steps.append(((r0, y0), (r1, y1), (d[1] / l, -d[0] / l), l))
    cos_s = math.cos(math.radians(smooth_deg))

    def joint(na, nb):
        if na is None or na[0] * nb[0] + na[1] * nb[1] < cos_s:
            return nb
        s = (na[0] + nb[0], na[1] + nb[1])
        l = math.hypot(*s)
        return (s[0] / l, s[1] / l)

    vpos = 0.0
    for i, (p0, p1, n, l) in enumerate(steps):
        prev = steps[i - 1][2] if i > 0 else None
        nxt = steps[i + 1][2] if i + 1 < len(steps) else None
        n0 = joint(prev, n)
        n1 = joint(nxt, n)
        rows = []
        for (r, y), (nr, ny), v in ((p0, n0, vpos), (p1, n1, vpos + l)):
            row = []
            for s in range(seg + 1):
                a = 2 * math.pi * s / seg
                c, sn = math.cos(a), math.sin(a)
                col = colour(r, y, a) if colour else (1, 1, 1, 1)
                row.append(emit(prim, m, (r * c, y, -r * sn), (nr * c, ny, -nr * sn),
                                (s / seg, v * v_scale), col))
            rows.append(row)
        for s in range(seg):
            prim.quad(rows[0][s], rows[0][s + 1], rows[1][s + 1], rows[1][s])
        vpos += l


closed_lathe = closed(lathe)


@closed
def sphere(prim, c, r, m=None, nu=24, nv=12):
    rows = []
    for j in range(nv + 1):
        th = math.pi * j / nv
        row = []
        for i in range(nu + 1):
            ph = 2 * math.pi * i / nu
            n = (math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph))
            row.append(emit(prim, m, add(c, mulv(n, r)), n, (i / nu, j / nv)))
        rows.append(row)
    for j in range(nv):
        for i in range(nu):
            prim.quad(rows[j][i], rows[j][i + 1], rows[j + 1][i + 1], rows[j + 1][i])


def torus(prim, R_, r, m=None, nu=40, nv=16, u_range=(0.0, 360.0), v_range=(0.0, 360.0),
          colour=None, r_of=None):
    """Torus about +Y: ring radius R_, tube radius r (r_of(u, v) may vary it slightly: the
    normals are then the tube's, fine for small variations). Partial with u_range / v_range
    (degrees; v = 90 is the top of the tube)."""
    rows = []
    for j in range(nv + 1):
        v = math.radians(v_range[0] + (v_range[1] - v_range[0]) * j / nv)
        row = []
        for i in range(nu + 1):
            u = math.radians(u_range[0] + (u_range[1] - u_range[0]) * i / nu)
            rr = r_of(u, v) if r_of else r
            n = (math.cos(v) * math.cos(u), math.sin(v), -math.cos(v) * math.sin(u))
            p = ((R_ + rr * math.cos(v)) * math.cos(u), rr * math.sin(v),
                 -(R_ + rr * math.cos(v)) * math.sin(u))
            col = colour(u, v) if colour else (1, 1, 1, 1)
            row.append(emit(prim, m, p, n, (i / nu, j / nv), col))
        rows.append(row)
    for j in range(nv):
        for i in range(nu):
            prim.quad(rows[j][i], rows[j][i + 1], rows[j + 1][i + 1], rows[j + 1][i])


closed_torus = closed(torus)


def poly(prim, pts, n, m=None, uvs=None):
    """Flat convex polygon (fan), normal n."""
    ids = [emit(prim, m, p, n, uvs[i] if uvs else (0, 0)) for i, p in enumerate(pts)]
    for i in range(1, len(ids) - 1):
        prim.tri(ids[0], ids[i], ids[i + 1])


def cylinder(prim, r, h, y0=0.0, m=None, seg=32):
    closed_lathe(prim, [(0, y0), (r, y0), (r, y0 + h), (0, y0 + h)], m=m, seg=seg)


def cone(prim, r, h, y0=0.0, m=None, seg=32, v_scale=1.0):
    closed_lathe(prim, [(0, y0), (r, y0), (0, y0 + h)], m=m, seg=seg, v_scale=v_scale)


# ----------------------------------------------------------------------------- skinned geometry


class SkinPrim(Prim):
    """A Prim with JOINTS_0 / WEIGHTS_0: every vertex gets `weigh(world position)` -> (4 joint
    indices, 4 weights), set by the caller before each part."""

    def __init__(self, material):
        Prim.__init__(self, material)
        self.jw = []
        self.weigh = None

    def vert(self, p, n, uv=(0.0, 0.0), col=(1.0, 1.0, 1.0, 1.0)):
        i = Prim.vert(self, p, n, uv, col)
        self.jw.append(self.weigh(self.pos[i]))
        return i


def skin_blend(j0, j1, w1):
    """Joint j0 blended into j1 by w1 (0..1), quantised to 1/1024 so that the two float weights
    are exact and sum to exactly 1; one joint where the blend is 0 or 1."""
    q = round(min(1.0, max(0.0, w1)) * 1024) / 1024.0
    if q <= 0.0:
        return ((j0, 0, 0, 0), (1.0, 0.0, 0.0, 0.0))
    if q >= 1.0:
        return ((j1, 0, 0, 0), (1.0, 0.0, 0.0, 0.0))
    return ((j0, j1, 0, 0), (1.0 - q, q, 0.0, 0.0))


def smoothstep(c, h, s):
    """0 below c - h, 1 above c + h, smooth in between."""
    t = min(1.0, max(0.0, (s - (c - h)) / (2 * h)))
    return t * t * (3 - 2 * t)


def smooth_profile(pts):
    """(r, y) points from the bottom pole (r = 0) up to the top pole (r = 0) -> rings (r, y, nr, ny)
    with the averaged (smooth) normals of the neighbouring steps."""
    steps = []
    for (r0, y0), (r1, y1) in zip(pts, pts[1:]):
        l = math.hypot(r1 - r0, y1 - y0)
        steps.append(((y1 - y0) / l, -(r1 - r0) / l))
    rings = [(0.0, pts[0][1], 0.0, -1.0)]
    for k in range(1, len(pts) - 1):
        a, b = steps[k - 1], steps[k]
        l = math.hypot(a[0] + b[0], a[1] + b[1])
        rings.append((pts[k][0], pts[k][1], (a[0] + b[0]) / l, (a[1] + b[1]) / l))
    rings.append((0.0, pts[-1][1], 0.0, 1.0))
    return rings


@closed
def revolve(prim, rings, m=None, seg=16):
    """Closed smooth surface of revolution about +Y (mapped by m): rings [(r, y, nr, ny)] from the
    bottom pole (r = 0) to the top pole (r = 0); each ring's seg vertices are shared by the quads
    above and below it (no seam duplicate: no UVs). A ring repeated with another normal makes a
    crease (the zero-area quads between them are dropped)."""
    ids = []
    for r, y, nr, ny in rings:
        if r == 0:
            ids.append([emit(prim, m, (0.0, y, 0.0), (0.0, ny, 0.0))])
            continue
        row = []
        for s in range(seg):
            a = 2 * math.pi * s / seg
            c, sn = math.cos(a), math.sin(a)
            row.append(emit(prim, m, (r * c, y, -r * sn), (nr * c, ny, -nr * sn)))
        ids.append(row)
    for A, B in zip(ids, ids[1:]):
        for s in range(seg):
            s1 = (s + 1) % seg
            if len(A) == 1:
                prim.tri(A[0], B[s], B[s1])
            elif len(B) == 1:
                prim.tri(A[s], A[s1], B[0])
            else:
                prim.quad(A[s], A[s1], B[s1], B[s])


def ellipsoid_rings(r, nv, phi0=-90.0, phi1=90.0):
    """Rings of a sphere of radius r (scaled into an ellipsoid by the caller's matrix) between the
    latitudes phi0 and phi1 (degrees), nv steps; the poles at +-90 have r = 0."""
    out = []
    for k in range(nv + 1):
        ph = math.radians(phi0 + (phi1 - phi0) * k / nv)
        c, s = math.cos(ph), math.sin(ph)
        out.append((0.0 if abs(abs(ph) - math.pi / 2) < 1e-9 else r * c, r * s, c, s))
    return out


def frame_y(d):
    """Rotation matrix whose +Y column is the unit vector d (and +Z stays world +Z for d in the XY
    plane)."""
    ref = [0.0, 0.0, 1.0] if abs(d[2]) < 0.9 else [1.0, 0.0, 0.0]
    x = norm(cross(d, ref))
    z = cross(x, d)
    m = I4()
    for i in range(3):
        m[i][0], m[i][1], m[i][2] = x[i], d[i], z[i]
    return m


def capsule(prim, a, b, ra, rb, shaft=(), seg=12, cap=3, sx=1.0, sz=1.0):
    """Smooth tapered capsule from point a (radius ra) to point b (radius rb): a hemisphere around
    each end point, rings at the distances `shaft` from a (denser where a joint bends it); the
    cross-section scaled by sx, sz in the capsule's own frame (frame_y)."""
    L = math.sqrt(dot(sub(b, a), sub(b, a)))
    d = mulv(sub(b, a), 1.0 / L)
    ln = math.hypot(L, ra - rb)
    n = (L / ln, (ra - rb) / ln)          # outward normal (r, y) of the tapered shaft
    rings = []
    for k in range(cap + 1):
        ph = -math.pi / 2 + math.pi / 2 * k / cap
        rings.append((0.0 if k == 0 else ra * math.cos(ph), ra * math.sin(ph),
                      math.cos(ph), math.sin(ph)))
    for s in shaft:
        assert 0 < s < L
        rings.append((ra + (rb - ra) * s / L, s, n[0], n[1]))
    for k in range(cap + 1):
        ph = math.pi / 2 * k / cap
        rings.append((0.0 if k == cap else rb * math.cos(ph), L + rb * math.sin(ph),
                      math.cos(ph), math.sin(ph)))
    revolve(prim, rings, m=chain(T(*a), frame_y(d), S(sx, 1.0, sz)), seg=seg)


# ----------------------------------------------------------------------------- textures (PNG)


def png(w, h, pixel):
    """8-bit RGB PNG; pixel(x, y) -> (r, g, b) in 0..1 (already sRGB-encoded for colour)."""
    raw = bytearray()
    for y in range(h):
        raw.append(0)
        for x in range(w):
            for c in pixel(x, y):
                raw.append(max(0, min(255, int(round(c * 255)))))

    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + chunk(b"IEND", b""))


def hash01(*k):
    """Deterministic integer hash to [0, 1)."""
    h = 2166136261
    for v in k:
        h = ((h ^ (v & 0xffffffff)) * 16777619) & 0xffffffff
        h ^= h >> 13
        h = (h * 0x5bd1e995) & 0xffffffff
        h ^= h >> 15
    return h / 4294967296.0


def vnoise(x, y, seed, period):
    """Tileable value noise (period cells)."""
    x0, y0 = int(math.floor(x)), int(math.floor(y))
    fx, fy = x - x0, y - y0
    fx, fy = fx * fx * (3 - 2 * fx), fy * fy * (3 - 2 * fy)

    def g(i, j):
        return hash01(seed, i % period, j % period)
    a = g(x0, y0) + (g(x0 + 1, y0) - g(x0, y0)) * fx
    b = g(x0, y0 + 1) + (g(x0 + 1, y0 + 1) - g(x0, y0 + 1)) * fx
    return a + (b - a) * fy


def mix(a, b, t):
    return tuple(a[i] + (b[i] - a[i]) * t for i in range(3))


def wood_png(n=128):
    """Wood grain running along u (x), tileable."""
    def px(x, y):
        u, v = x / n, y / n
        warp = 0.6 * vnoise(u * 4, v * 4, 7, 4) + 0.25 * vnoise(u * 8, v * 8, 8, 8)
        ring = 0.5 + 0.5 * math.sin(2 * math.pi * (v * 9 + warp * 1.6))
        ring = ring ** 3
        fine = vnoise(u * 64, v * 32, 9, 64) * 0.15
        return mix((0.80, 0.62, 0.40), (0.55, 0.36, 0.20), min(1.0, ring * 0.85 + fine))
    return png(n, n, px)


CRATE_N = 128
CRATE_BORDER = 14     # frame board width (pixels)
CRATE_GAP = 2         # dark gap between boards


def crate_height(x, y):
    """Height field of one crate face (0..1): frame boards at the border, horizontal planks inside,
    grooves between them; drives both the colour and the normal map."""
    n, b, g = CRATE_N, CRATE_BORDER, CRATE_GAP
    inner = b <= x < n - b and b <= y < n - b
    if not inner:
        # frame: distance to the frame board's own edges (bevel)
        e = min(x, y, n - 1 - x, n - 1 - y, abs(x - b + 0.5), abs(y - b + 0.5),
                abs(x - (n - b) + 0.5), abs(y - (n - b) + 0.5))
        return min(1.0, 0.55 + e / 4.0), "frame"
    plank_h = (n - 2 * b) / 4.0
    t = (y - b) / plank_h
    k = int(t)
    f = (t - k) * plank_h
    d = min(f, plank_h - f)
    if d < g:
        return 0.0, "gap"
    return min(0.75, 0.35 + (d - g) / 5.0), "plank%d" % k


def crate_png():
    def px(x, y):
        h, part = crate_height(x, y)
        if part == "gap":
            return (0.18, 0.11, 0.06)
        tint = {"frame": 0.85, "plank0": 1.0, "plank1": 0.92, "plank2": 1.04, "plank3": 0.95}[part]
        grain = vnoise(x / 4.0, y / 24.0, 3 + len(part), 64) if part == "frame" and (
            x < CRATE_BORDER or x >= CRATE_N - CRATE_BORDER) else vnoise(x / 24.0, y / 4.0, 5 + len(part), 64)
        base = mix((0.78, 0.58, 0.34), (0.58, 0.40, 0.22), grain)
        shade = 0.8 + 0.2 * h
        return tuple(c * tint * shade for c in base)
    return png(CRATE_N, CRATE_N, px)


def crate_normal_png():
    """Tangent-space normal map of crate_height (+X right = +u, +Y up = -v, +Z out)."""
    depth = 6.0   # pixels of height per unit of the height field

    def hgt(x, y):
        return crate_height(min(CRATE_N - 1, max(0, x)), min(CRATE_N - 1, max(0, y)))[0] * depth

    def px(x, y):
        dx = (hgt(x + 1, y) - hgt(x - 1, y)) / 2
        dy = (hgt(x, y + 1) - hgt(x, y - 1)) / 2      # towards the image bottom (+v)
        n = norm([-dx, dy, 1.0])                       # +Y up in the image = -v
        return tuple(0.5 + 0.5 * c for c in n)
    return png(CRATE_N, CRATE_N, px)


def leaf_png(n=64):
    """Needles / leaves: dark and light green streaks, tileable."""
    def px(x, y):
        u, v = x / n, y / n
        a = vnoise(u * 16, v * 4, 11, 16)
        b = vnoise(u * 32, v * 16, 12, 32)
        t = min(1.0, max(0.0, a * 0.7 + b * 0.5 - 0.1))
        return mix((0.10, 0.30, 0.08), (0.35, 0.62, 0.20), t)
    return png(n, n, px)


# ----------------------------------------------------------------------------- glTF writer


def mat(name, rgba, metal=0.0, rough=0.6, **extra):
    m = {"name": name, "pbrMetallicRoughness": {
        "baseColorFactor": [round(c, 4) for c in rgba], "metallicFactor": metal, "roughnessFactor": rough}}
    m.update(extra)
    return m


class Model:
    def __init__(self, name):
        self.name = name
        self.materials, self.meshes, self.nodes, self.roots = [], [], [], []
        self.images, self.textures, self.samplers = [], [], []
        self.cameras, self.ext_used = [], []
        self.mat_index = {}
        # skins: (name, joint nodes, inverse bind matrices (16 floats, column-major), skeleton);
        # animations: (name, key times, [(node, path, values)]): LINEAR samplers sharing the times
        self.skins, self.animations = [], []
        self.check = None    # check(d, blob): extra checks of the built file (after validate)

    def material(self, m):
        self.materials.append(m)
        self.mat_index[m["name"]] = len(self.materials) - 1
        return len(self.materials) - 1

    def mesh(self, name, prims):
        self.meshes.append((name, prims))
        return len(self.meshes) - 1

    def node(self, name, mesh=None, t=None, r=None, s=None, children=None, camera=None, root=True):
        n = {"name": name}
        if mesh is not None:
            n["mesh"] = mesh
        if camera is not None:
            n["camera"] = camera
        if t is not None:
            n["translation"] = [round(v, 6) for v in t]
        if r is not None:
            n["rotation"] = [round(v, 7) for v in r]
        if s is not None:
            n["scale"] = [round(v, 6) for v in s]
        if children:
            n["children"] = children
        self.nodes.append(n)
        if root:
            self.roots.append(len(self.nodes) - 1)
        return len(self.nodes) - 1

    def image(self, name, data):
        self.images.append((name, data))
        return len(self.images) - 1

    def texture(self, image, sampler=None):
        t = {"source": image}
        if sampler is not None:
            t["sampler"] = sampler
        self.textures.append(t)
        return len(self.textures) - 1

    # -- serialisation
    def build(self, glb):
        blob = bytearray()
        views, accessors = [], []

        def view(data, target=None):
            while len(blob) % 4:
                blob.append(0)
            v = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
            if target:
                v["target"] = target
            blob.extend(data)
            views.append(v)
            return len(views) - 1

        def acc(values, ctype, typ, with_minmax=False, normalized=False, target=-1):
            comps = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}[typ]
            fmt = {5126: "f", 5121: "B", 5123: "H", 5125: "I"}[ctype]
            flat = values if comps == 1 else [c for v in values for c in v]
            data = struct.pack("<%d%s" % (len(flat), fmt), *flat)
            if target == -1:   # vertex attributes and indices; None: no target (animation, skin data)
                target = 34963 if typ == "SCALAR" else 34962
            a = {"bufferView": view(data, target),
                 "componentType": ctype, "count": len(values), "type": typ}
            if with_minmax:
                # min/max of the values as stored (float32-rounded)
                st = [struct.unpack("<f", struct.pack("<f", c))[0] for c in flat]
                a["min"] = [min(st[i::comps]) for i in range(comps)]
                a["max"] = [max(st[i::comps]) for i in range(comps)]
            accessors.append(a)
            return len(accessors) - 1

        meshes = []
        shared = {}          # id(prim) -> attributes/indices already written (reused accessors)
        for name, prims in self.meshes:
            out = []
            for p, mi in prims:
                if id(p) not in shared:
                    at = {"POSITION": acc(p.pos, 5126, "VEC3", True), "NORMAL": acc(p.nrm, 5126, "VEC3")}
                    if p.has_uv:
                        at["TEXCOORD_0"] = acc(p.uv, 5126, "VEC2")
                    if p.has_color:
                        at["COLOR_0"] = acc(p.col, 5126, "VEC4")
                    if isinstance(p, SkinPrim):
                        at["JOINTS_0"] = acc([j for j, _ in p.jw], 5121, "VEC4")
                        at["WEIGHTS_0"] = acc([w for _, w in p.jw], 5126, "VEC4")
                    big = len(p.pos) > 65535
                    ind = acc(p.idx, 5125 if big else 5123, "SCALAR")
                    shared[id(p)] = (at, ind)
                at, ind = shared[id(p)]
                out.append({"attributes": dict(at), "indices": ind, "material": mi})
            meshes.append({"name": name, "primitives": out})

        skins = []
        for name, joints, ibms, skeleton in self.skins:
            skins.append({"name": name, "inverseBindMatrices": acc(ibms, 5126, "MAT4", target=None),
                          "joints": joints, "skeleton": skeleton})
        animations = []
        for name, times, channels in self.animations:
            inp = acc(times, 5126, "SCALAR", True, target=None)
            an = {"name": name, "channels": [], "samplers": []}
            for node, path, values in channels:
                out = acc(values, 5126, "VEC4" if path == "rotation" else "VEC3", target=None)
                an["channels"].append({"sampler": len(an["samplers"]),
                                       "target": {"node": node, "path": path}})
                an["samplers"].append({"input": inp, "interpolation": "LINEAR", "output": out})
            animations.append(an)

        images = []
        for name, data in self.images:
            if glb:
                images.append({"name": name, "bufferView": view(data), "mimeType": "image/png"})
            else:
                images.append({"name": name, "uri": "data:image/png;base64," +
                               base64.b64encode(data).decode()})
        while len(blob) % 4:
            blob.append(0)

        d = {"asset": {"version": "2.0", "generator": "passgraph gen_models.py"}}
        if self.ext_used:
            d["extensionsUsed"] = list(self.ext_used)
        d["scene"] = 0
        d["scenes"] = [{"name": self.name, "nodes": self.roots}]
        d["nodes"] = self.nodes
        d["meshes"] = meshes
        d["materials"] = self.materials
        if self.textures:
            d["textures"] = self.textures
            d["images"] = images
        if self.samplers:
            d["samplers"] = self.samplers
        if self.cameras:
            d["cameras"] = self.cameras
        if skins:
            d["skins"] = skins
        if animations:
            d["animations"] = animations
        d["accessors"] = accessors
        d["bufferViews"] = views
        buf = {"byteLength": len(blob)}
        if not glb:
            buf["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()
        d["buffers"] = [buf]
        return d, bytes(blob)

    def write(self, filename):
        glb = filename.endswith(".glb")
        d, blob = self.build(glb)
        validate(d, blob, filename)
        if self.check:
            self.check(d, blob)
        path = os.path.join(OUT, filename)
        if glb:
            js = json.dumps(d, separators=(",", ":")).encode()
            js += b" " * ((4 - len(js) % 4) % 4)
            body = (struct.pack("<I", len(js)) + b"JSON" + js +
                    struct.pack("<I", len(blob)) + b"BIN\x00" + blob)
            with open(path, "wb") as f:
                f.write(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)
        else:
            with open(path, "w") as f:
                json.dump(d, f, separators=(",", ":"))
                f.write("\n")
        tris = sum(len(p.idx) // 3 for n in self.nodes if "mesh" in n
                   for p, _ in self.meshes[n["mesh"]][1])
        return os.path.getsize(path), tris


def validate(d, blob, who):
    """Checks what the glTF 2.0 spec requires of what this script writes."""
    def fail(msg):
        raise AssertionError("%s: %s" % (who, msg))
    if d["buffers"][0]["byteLength"] != len(blob):
        fail("buffer byteLength")
    for i, v in enumerate(d["bufferViews"]):
        if v["byteOffset"] % 4 or v["byteOffset"] + v["byteLength"] > len(blob):
            fail("bufferViews[%d] range/alignment" % i)

    def read(ai):
        a = d["accessors"][ai]
        v = d["bufferViews"][a["bufferView"]]
        comps = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[a["type"]]
        fmt, size = {5126: ("f", 4), 5123: ("H", 2), 5125: ("I", 4)}[a["componentType"]]
        if a["count"] * comps * size != v["byteLength"]:
            fail("accessors[%d] does not fill its bufferView" % ai)
        flat = struct.unpack_from("<%d%s" % (a["count"] * comps, fmt), blob, v["byteOffset"])
        return [flat[i:i + comps] for i in range(0, len(flat), comps)], a, v

    for mi, m in enumerate(d["meshes"]):
        for pi, p in enumerate(m["primitives"]):
            w = "meshes[%d].primitives[%d]" % (mi, pi)
            pos, a, v = read(p["attributes"]["POSITION"])
            if v.get("target") != 34962:
                fail(w + ": POSITION target")
            for k in range(3):
                if a["min"][k] != min(q[k] for q in pos) or a["max"][k] != max(q[k] for q in pos):
                    fail(w + ": POSITION min/max")
            nrm = read(p["attributes"]["NORMAL"])[0]
            if len(nrm) != len(pos) or any(abs(math.sqrt(dot(n, n)) - 1) > 1e-5 for n in nrm):
                fail(w + ": NORMAL count or not unit")
            for key in ("TEXCOORD_0", "COLOR_0"):
                if key in p["attributes"]:
                    vals, _, vv = read(p["attributes"][key])
                    if len(vals) != len(pos) or vv.get("target") != 34962:
                        fail(w + ": " + key)
            idx, _, iv = read(p["indices"])
            idx = [i[0] for i in idx]
            if iv.get("target") != 34963 or len(idx) % 3 or max(idx) >= len(pos):
                fail(w + ": indices")
            for t in range(0, len(idx), 3):
                A, B, C = (pos[i] for i in idx[t:t + 3])
                g = cross(sub(B, A), sub(C, A))
                n = add(add(nrm[idx[t]], nrm[idx[t + 1]]), nrm[idx[t + 2]])
                if dot(g, n) <= 0:
                    fail(w + ": triangle %d wound against its normals" % (t // 3))
            if "material" in p and p["material"] >= len(d["materials"]):
                fail(w + ": material")
        for n in d["nodes"]:
            if "rotation" in n and abs(math.sqrt(sum(c * c for c in n["rotation"])) - 1) > 1e-6:
                fail("node %s: rotation not unit" % n["name"])
    if "skins" in d or "animations" in d:
        validate_animated(d, blob, who)


# ----------------------------------------------------------------------------- skins and animations


ACC_COMPS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
ACC_FMT = {5126: ("f", 4), 5121: ("B", 1), 5123: ("H", 2), 5125: ("I", 4)}


def accessor_rows(d, blob, ai):
    """accessors[ai] read back as tuples; it must fill its bufferView, which must lie in the buffer."""
    a = d["accessors"][ai]
    v = d["bufferViews"][a["bufferView"]]
    comps = ACC_COMPS[a["type"]]
    fmt, size = ACC_FMT[a["componentType"]]
    if (a.get("byteOffset", 0) or "byteStride" in v or a["count"] * comps * size != v["byteLength"] or
            v["byteOffset"] % 4 or v["byteOffset"] + v["byteLength"] > len(blob)):
        raise AssertionError("accessors[%d] does not fill its bufferView (or it is out of the buffer)" % ai)
    flat = struct.unpack_from("<%d%s" % (a["count"] * comps, fmt), blob, v["byteOffset"])
    return [tuple(flat[i:i + comps]) for i in range(0, len(flat), comps)]


def trs_matrix(t, q, s=(1.0, 1.0, 1.0)):
    x, y, z, w = q
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    return [[r[i][0] * s[0], r[i][1] * s[1], r[i][2] * s[2], t[i]] for i in range(3)] + [[0.0, 0.0, 0.0, 1.0]]


def col_major(m16):
    """A glTF MAT4 (16 floats, column-major) as row-major nested lists."""
    return [[m16[c * 4 + r] for c in range(4)] for r in range(4)]


def qmul(a, b):
    """Hamilton product a * b of (x, y, z, w) quaternions: rotates by b, then by a."""
    return [a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
            a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
            a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
            a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]]


def slerp(a, b, s):
    d = sum(a[k] * b[k] for k in range(4))
    if d < 0:
        b, d = [-x for x in b], -d
    if d > 0.9995:
        q = [a[k] + (b[k] - a[k]) * s for k in range(4)]
    else:
        th = math.acos(d)
        q = [(math.sin((1 - s) * th) * a[k] + math.sin(s * th) * b[k]) / math.sin(th) for k in range(4)]
    l = math.sqrt(sum(x * x for x in q))
    return [x / l for x in q]


def sample_linear(times, values, path, t):
    """A LINEAR sampler at time t (clamped to its keys); rotations slerp."""
    if t <= times[0]:
        return list(values[0])
    if t >= times[-1]:
        return list(values[-1])
    k = max(i for i in range(len(times)) if times[i] <= t)
    s = (t - times[k]) / (times[k + 1] - times[k])
    if path == "rotation":
        return slerp(values[k], values[k + 1], s)
    return [values[k][i] + (values[k + 1][i] - values[k][i]) * s for i in range(len(values[k]))]


def pose_world(d, rows, anim, t):
    """World matrices of all nodes at time t of animations[anim] (None: the nodes' own TRS)."""
    local = [[n.get("translation", [0.0] * 3), n.get("rotation", [0.0, 0.0, 0.0, 1.0]),
              n.get("scale", [1.0] * 3)] for n in d["nodes"]]
    if anim is not None:
        a = d["animations"][anim]
        for c in a["channels"]:
            smp = a["samplers"][c["sampler"]]
            path = c["target"]["path"]
            v = sample_linear([r[0] for r in rows[smp["input"]]], rows[smp["output"]], path, t)
            local[c["target"]["node"]][("translation", "rotation", "scale").index(path)] = v
    world = [None] * len(d["nodes"])

    def walk(k, parent):
        world[k] = mat_mul(parent, trs_matrix(*local[k]))
        for c in d["nodes"][k].get("children", []):
            walk(c, world[k])
    for k in d["scenes"][d["scene"]]["nodes"]:
        walk(k, I4())
    return world


def skinned_positions(d, rows, node, anim, t):
    """The skinned world positions of node's primitives (one list each) at time t (linear blend
    skinning: sum of weight x world(joint) x inverseBind(joint))."""
    skin = d["skins"][d["nodes"][node]["skin"]]
    world = pose_world(d, rows, anim, t)
    jm = [mat_mul(world[jn], col_major(m))
          for jn, m in zip(skin["joints"], rows[skin["inverseBindMatrices"]])]
    out = []
    for p in d["meshes"][d["nodes"][node]["mesh"]]["primitives"]:
        at = p["attributes"]
        ps = []
        for v, js, ws in zip(rows[at["POSITION"]], rows[at["JOINTS_0"]], rows[at["WEIGHTS_0"]]):
            q = [0.0, 0.0, 0.0]
            for j, w in zip(js, ws):
                if w:
                    q = add(q, mulv(xf_point(jm[j], v), w))
            ps.append(q)
        out.append(ps)
    return out


def validate_animated(d, blob, who):
    """What glTF 2.0 requires of skins, skinned primitives and animations (and what this script
    promises: 1 or 2 joints per vertex, weights summing to 1, LINEAR samplers)."""
    def fail(msg):
        raise AssertionError("%s: %s" % (who, msg))
    rows = {}
    for i, a in enumerate(d["accessors"]):
        rows[i] = r = accessor_rows(d, blob, i)
        if len(r) != a["count"]:
            fail("accessors[%d] count" % i)
        if "min" in a and (a["min"] != [min(x[k] for x in r) for k in range(len(r[0]))] or
                           a["max"] != [max(x[k] for x in r) for k in range(len(r[0]))]):
            fail("accessors[%d] min/max" % i)
    nn = len(d["nodes"])
    seen, stack = [], list(d["scenes"][d["scene"]]["nodes"])
    while stack:                               # a forest: every node reached once from the scene
        k = stack.pop()
        if k in seen or not 0 <= k < nn:
            fail("node %d reached twice or out of range" % k)
        seen.append(k)
        stack += d["nodes"][k].get("children", [])
    if sorted(seen) != list(range(nn)):
        fail("nodes not all in the scene")
    parent = {c: k for k, n in enumerate(d["nodes"]) for c in n.get("children", [])}
    rest = pose_world(d, rows, None, 0.0)

    def no_target(ai, what):
        if "target" in d["bufferViews"][d["accessors"][ai]["bufferView"]]:
            fail(what + ": bufferView has a target")
    for si, sk in enumerate(d.get("skins", [])):
        js = sk["joints"]
        if len(set(js)) != len(js) or any(not 0 <= j < nn for j in js):
            fail("skins[%d].joints" % si)
        a = d["accessors"][sk["inverseBindMatrices"]]
        if (a["type"], a["componentType"], a["count"]) != ("MAT4", 5126, len(js)):
            fail("skins[%d].inverseBindMatrices: MAT4 FLOAT, one per joint" % si)
        no_target(sk["inverseBindMatrices"], "skins[%d].inverseBindMatrices" % si)
        for k, (j, m) in enumerate(zip(js, rows[sk["inverseBindMatrices"]])):
            p = mat_mul(rest[j], col_major(m))          # world(bind) x inverseBind = identity
            if any(abs(p[r][c] - (r == c)) > 1e-6 for r in range(4) for c in range(4)):
                fail("skins[%d]: inverseBindMatrices[%d] is not the inverse of joint %d's bind pose" %
                     (si, k, j))
            a_, up = j, []
            while a_ in parent:
                a_ = parent[a_]
                up.append(a_)
            if "skeleton" in sk and sk["skeleton"] != j and sk["skeleton"] not in up:
                fail("skins[%d].skeleton is not a common root of the joints" % si)
    for ni, n in enumerate(d["nodes"]):
        if "skin" not in n:
            continue
        if "mesh" not in n or any(k in n for k in ("translation", "rotation", "scale", "matrix")):
            fail("skinned node %d: needs a mesh and no transform of its own" % ni)
        nj = len(d["skins"][n["skin"]]["joints"])
        for pi, p in enumerate(d["meshes"][n["mesh"]]["primitives"]):
            w = "node %d primitive %d" % (ni, pi)
            at = p["attributes"]
            cnt = d["accessors"][at["POSITION"]]["count"]
            ja, wa = d["accessors"][at["JOINTS_0"]], d["accessors"][at["WEIGHTS_0"]]
            if ja["type"] != "VEC4" or ja["componentType"] not in (5121, 5123) or ja["count"] != cnt:
                fail(w + ": JOINTS_0 must be VEC4 UNSIGNED_BYTE/SHORT, one per vertex")
            if wa["type"] != "VEC4" or wa["componentType"] != 5126 or wa["count"] != cnt:
                fail(w + ": WEIGHTS_0 must be VEC4 FLOAT, one per vertex")
            for key in ("JOINTS_0", "WEIGHTS_0"):
                if d["bufferViews"][d["accessors"][at[key]]["bufferView"]].get("target") != 34962:
                    fail(w + ": " + key + " target")
            for v, (js, ws) in enumerate(zip(rows[at["JOINTS_0"]], rows[at["WEIGHTS_0"]])):
                used = [j for j, x in zip(js, ws) if x > 0]
                if abs(sum(ws) - 1) > 1e-6 or min(ws) < 0 or not 1 <= len(used) <= 2:
                    fail(w + ": vertex %d weights %r" % (v, ws))
                if max(js) >= nj or len(set(used)) != len(used):
                    fail(w + ": vertex %d joints %r" % (v, js))
    for ai, an in enumerate(d.get("animations", [])):
        targets = set()
        for c in an["channels"]:
            node, path = c["target"]["node"], c["target"]["path"]
            w = "animations[%d] channel node %d %s" % (ai, node, path)
            if ((node, path) in targets or not 0 <= node < nn or
                    path not in ("translation", "rotation", "scale")):
                fail(w + ": duplicate or bad target")
            targets.add((node, path))
            smp = an["samplers"][c["sampler"]]
            ia, oa = d["accessors"][smp["input"]], d["accessors"][smp["output"]]
            t = [r[0] for r in rows[smp["input"]]]
            if (ia["type"], ia["componentType"]) != ("SCALAR", 5126) or "min" not in ia or t[0] < 0:
                fail(w + ": input must be SCALAR FLOAT with min/max, from t >= 0")
            if any(t[k] >= t[k + 1] for k in range(len(t) - 1)):
                fail(w + ": key times not increasing")
            want = "VEC4" if path == "rotation" else "VEC3"
            if (smp.get("interpolation", "LINEAR") != "LINEAR" or
                    (oa["type"], oa["componentType"], oa["count"]) != (want, 5126, len(t))):
                fail(w + ": output must be %s FLOAT, one per key (LINEAR)" % want)
            no_target(smp["input"], w)
            no_target(smp["output"], w)
            if path == "rotation" and any(abs(math.sqrt(sum(x * x for x in q)) - 1) > 1e-6
                                          for q in rows[smp["output"]]):
                fail(w + ": rotation keys not unit")


# ----------------------------------------------------------------------------- the models


def mug():
    M = Model("mug")
    glaze = M.material(mat("blue_glaze", (0.05, 0.16, 0.50, 1), rough=0.25))
    inside = M.material(mat("white_glaze", (0.85, 0.85, 0.80, 1), rough=0.25))
    coffee = M.material(mat("coffee", (0.10, 0.045, 0.015, 1), rough=0.1))
    R_, H, t, tb = 0.042, 0.095, 0.0045, 0.007
    body_out, body_in, handle, liquid = Prim(glaze), Prim(inside), Prim(glaze), Prim(coffee)
    # outside: bottom, rounded foot, wall, rounded rim (the half of the rim outside the wall)
    out = [(0, 0.0015), (R_ - 0.006, 0.0015), (R_ - 0.004, 0)]
    for k in range(7):
        a = math.radians(-90 + 90 * k / 6)
        out.append((R_ - 0.004 + 0.004 * math.cos(a), 0.004 + 0.004 * math.sin(a)))
    for k in range(7):
        a = math.radians(90 * k / 6)
        out.append((R_ - t / 2 + t / 2 * math.cos(a), H + t / 2 * math.sin(a)))
    inn = [(R_ - t / 2 + t / 2 * math.cos(math.radians(90 + 90 * k / 6)),
            H + t / 2 * math.sin(math.radians(90 + 90 * k / 6))) for k in range(7)]
    inn += [(R_ - t, tb + 0.004), (R_ - t - 0.004, tb), (0, tb)]
    first = len(body_out.idx)
    lathe(body_out, out, seg=48)
    lathe(body_in, inn, seg=48)
    # the two halves together are closed: check the winding on both
    v = body_out.signed_volume(first) + body_in.signed_volume(0)
    assert v > 0, "mug body winding"
    # coffee surface 1.5 cm below the rim
    closed_lathe(liquid, [(0, H - 0.03), (R_ - t + 0.0005, H - 0.03), (R_ - t + 0.0005, H - 0.0155),
                          (0, H - 0.0155)], seg=48)
    # handle: half torus in its own XY plane, placed by the node (rotation about X turns the torus
    # axis Y to Z, so the ring lies in the XY plane)
    # (open at both ends: at u = +-90 degrees the end circles lie in the plane x = 0.04 of the
    # node, inside the wall between its inner (0.0375) and outer (0.042) radius)
    torus(handle, 0.026, 0.0055, u_range=(-90, 90), nu=24, nv=12)
    body = M.mesh("mug_body", [(body_out, glaze), (body_in, inside), (liquid, coffee)])
    hmesh = M.mesh("mug_handle", [(handle, glaze)])
    M.node("body", body)
    M.node("handle", hmesh, t=(R_ - 0.002, 0.05, 0), r=quat("x", 90), s=(1, 1.25, 1))
    return M


def pawn_profile():
    """Staunton-style pawn, 5.4 cm tall: base, collar, stem, collar, head."""
    p = [(0, 0), (0.0155, 0), (0.0155, 0.003)]
    for k in range(1, 9):           # rounded base torus
        a = math.radians(-90 + 180 * k / 8)
        p.append((0.0135 + 0.004 * math.cos(a), 0.007 + 0.004 * math.sin(a)))
    p += [(0.0125, 0.011), (0.0120, 0.012)]
    for k in range(1, 9):           # stem: concave curve narrowing upwards
        f = k / 8
        p.append((0.0120 - 0.0062 * math.sin(f * math.pi / 2) ** 0.8, 0.012 + 0.022 * f))
    p += [(0.0100, 0.0345), (0.0100, 0.0365), (0.0062, 0.0375)]   # collar
    cy, cr = 0.0455, 0.0088
    a0 = math.asin((0.0375 + 0.0004 - cy) / cr)
    for k in range(0, 13):          # head sphere, from the collar to the top
        a = a0 + (math.pi / 2 - a0) * k / 12
        p.append((cr * math.cos(a), cy + cr * math.sin(a)))
    p[-1] = (0, cy + cr)
    return p


def pawn():
    M = Model("pawn")
    white = M.material(mat("ivory", (0.85, 0.80, 0.68, 1), rough=0.35))
    black = M.material(mat("ebony", (0.035, 0.03, 0.03, 1), rough=0.3))
    light_sq = M.material(mat("maple_square", (0.75, 0.60, 0.38, 1), rough=0.5))
    dark_sq = M.material(mat("walnut_square", (0.22, 0.11, 0.05, 1), rough=0.5))
    frame = M.material(mat("board_frame", (0.12, 0.06, 0.03, 1), rough=0.45))
    body = Prim(white)
    closed_lathe(body, pawn_profile(), seg=40, smooth_deg=35)
    # one set of accessors, two meshes: the same primitive drawn with two materials
    wm = M.mesh("pawn_white", [(body, white)])
    bm = M.mesh("pawn_black", [(body, black)])
    sq = 0.05
    lp, dp, fp = Prim(light_sq), Prim(dark_sq), Prim(frame)
    for i in range(3):
        for j in range(3):
            x0, z0 = (i - 1.5) * sq, (j - 1.5) * sq
            box(lp if (i + j) % 2 == 0 else dp, (x0, -0.012, z0), (x0 + sq, 0, z0 + sq))
    box(fp, (-1.5 * sq - 0.012, -0.015, -1.5 * sq - 0.012), (1.5 * sq + 0.012, -0.0005, 1.5 * sq + 0.012))
    board = M.mesh("board", [(lp, light_sq), (dp, dark_sq), (fp, frame)])
    M.node("board", board)
    M.node("white_pawn", wm, t=(0, 0, sq))
    M.node("black_pawn", bm, t=(-sq, 0, -sq), r=quat("y", 30))
    return M


def table_chair():
    M = Model("table_chair")
    wood = M.image("wood", wood_png())
    tex = M.texture(wood)
    oak = M.material(mat("oak", (1, 1, 1, 1), rough=0.55,
                         **{}))
    M.materials[oak]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": tex}
    walnut = M.material(mat("walnut", (0.55, 0.42, 0.35, 1), rough=0.5))
    M.materials[walnut]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": tex}
    china = M.material(mat("plate", (0.85, 0.85, 0.85, 1), rough=0.2))
    apple = M.material(mat("apple", (0.55, 0.03, 0.02, 1), rough=0.35))
    # table: 1.2 x 0.75 x 0.8, top 4 cm
    tp = Prim(oak, uv=True)
    box(tp, (-0.6, 0.71, -0.4), (0.6, 0.75, 0.4), uv_scale=1.0)
    for sx in (-1, 1):
        for sz in (-1, 1):
            x, z = sx * 0.53, sz * 0.33
            box(tp, (x - 0.03, 0, z - 0.03), (x + 0.03, 0.71, z + 0.03), uv_scale=1.0)
    box(tp, (-0.5, 0.63, -0.36), (0.5, 0.71, -0.34), uv_scale=1.0)   # aprons
    box(tp, (-0.5, 0.63, 0.34), (0.5, 0.71, 0.36), uv_scale=1.0)
    box(tp, (-0.56, 0.63, -0.3), (-0.54, 0.71, 0.3), uv_scale=1.0)
    box(tp, (0.54, 0.63, -0.3), (0.56, 0.71, 0.3), uv_scale=1.0)
    table = M.mesh("table", [(tp, oak)])
    # chair in its own frame: seat 0.42 x 0.45 high, front towards +Z, back at -Z
    cp = Prim(walnut, uv=True)
    box(cp, (-0.21, 0.42, -0.2), (0.21, 0.45, 0.2), uv_scale=2.0)
    for sx in (-1, 1):
        for sz in (-1, 1):
            x, z = sx * 0.18, sz * 0.17
            top = 0.42 if sz > 0 else 0.92
            box(cp, (x - 0.02, 0, z - 0.02), (x + 0.02, top, z + 0.02), uv_scale=2.0)
    for k in range(3):              # back slats
        y = 0.6 + k * 0.11
        box(cp, (-0.16, y, -0.185), (0.16, y + 0.06, -0.165), uv_scale=2.0)
    chair = M.mesh("chair", [(cp, walnut)])
    pl, ap = Prim(china), Prim(apple)
    closed_lathe(pl, [(0, 0), (0.07, 0), (0.11, 0.012), (0.125, 0.02), (0.12, 0.022), (0.1, 0.015),
                      (0.07, 0.006), (0, 0.006)], seg=40)
    prof = []
    for k in range(17):             # apple: a squashed sphere with a dimple at the top
        a = math.radians(-90 + 180 * k / 16)
        r = 0.04 * math.cos(a) * (1 + 0.08 * math.cos(2 * a))
        y = 0.035 * (1 + math.sin(a)) - (0.006 if k == 16 else 0)
        prof.append((r, y))
    prof[0] = (0, 0.004)
    closed_lathe(ap, prof, seg=24)
    stem = Prim(walnut, uv=True)
    box(stem, (-0.0025, 0.06, -0.0025), (0.0025, 0.085, 0.0025))
    M.node("table", table)
    M.node("chair", chair, t=(0.15, 0, 0.62), r=quat("y", 200))
    plate = M.mesh("plate", [(pl, china)])
    fruit = M.mesh("apple", [(ap, apple), (stem, walnut)])
    M.node("plate", plate, t=(-0.25, 0.75, 0.05))
    M.node("apple", fruit, t=(-0.25, 0.756, 0.05), r=quat("z", 8))
    return M


def donut():
    M = Model("donut")
    dough = M.material(mat("dough", (0.55, 0.28, 0.09, 1), rough=0.8))
    icing = M.material(mat("icing", (1, 1, 1, 1), rough=0.25))   # colour from COLOR_0
    plate = M.material(mat("plate", (0.15, 0.35, 0.6, 1), rough=0.3))
    Rr, r = 0.045, 0.022
    dp, ip, pp = Prim(dough), Prim(icing, color=True), Prim(plate)
    closed_torus(dp, Rr, r, nu=48, nv=24)
    sprinkle_cols = [(0.9, 0.9, 0.1, 1), (0.1, 0.5, 0.9, 1), (0.95, 0.95, 0.95, 1),
                     (0.1, 0.7, 0.2, 1), (0.7, 0.1, 0.6, 1)]
    pink = (0.95, 0.35, 0.55, 1)
    nu, nv = 96, 24

    def colour(u, v):
        i = int(round(math.degrees(u) / 360 * nu))
        j = int(round((math.degrees(v) + 30) / 240 * nv))
        h = hash01(i, j, 77)
        if h < 0.12 and 2 < j < nv - 2:
            return sprinkle_cols[int(hash01(i, j, 78) * len(sprinkle_cols))]
        return pink

    def r_of(u, v):
        return r * 1.06 + 0.0008 * math.sin(5 * u)
    # icing shell: the top of the tube (v from 5 to 175 degrees: from just above the outer
    # equator over the top to just above the inner one), a little thicker than the dough
    torus(ip, Rr, r, nu=nu, nv=nv, v_range=(5, 175), colour=colour, r_of=r_of)
    closed_lathe(pp, [(0, -0.004), (0.07, -0.004), (0.1, 0.008), (0.098, 0.01), (0.068, -0.001),
                      (0, -0.001)], seg=48)
    M.materials[icing]["doubleSided"] = True
    M.node("donut", M.mesh("donut", [(dp, dough), (ip, icing)]), t=(0, r + 0.003, 0),
           r=quat("y", 20))
    M.node("plate", M.mesh("plate", [(pp, plate)]), t=(0, 0.004, 0))
    return M


def rocket():
    M = Model("rocket")
    white = M.material(mat("hull_white", (0.85, 0.85, 0.85, 1), metal=0.1, rough=0.35))
    red = M.material(mat("red_paint", (0.7, 0.04, 0.03, 1), rough=0.4))
    metal = M.material(mat("nozzle_metal", (0.3, 0.3, 0.32, 1), metal=0.9, rough=0.35))
    glass = M.material(mat("porthole", (0.1, 0.35, 0.7, 1), rough=0.1))
    flame = M.material(mat("flame", (1.0, 0.55, 0.1, 1), rough=1.0,
                           emissiveFactor=[1.0, 0.5, 0.08]))
    concrete = M.material(mat("launch_pad", (0.35, 0.35, 0.33, 1), rough=0.9))
    y0 = 0.85                         # bottom of the hull (hovering: lift-off)
    hull, nose, fins, noz, port, fl, pad = (Prim(white), Prim(red), Prim(red), Prim(metal),
                                            Prim(glass), Prim(flame), Prim(concrete))
    rim = Prim(metal)
    closed_lathe(hull, [(0, y0), (0.16, y0), (0.18, y0 + 0.15), (0.18, y0 + 1.3), (0, y0 + 1.3)],
                 seg=40)
    prof = [(0, y0 + 1.3)]
    for k in range(0, 13):            # ogive nose cone
        f = k / 12
        prof.append((0.18 * math.cos(f * math.pi / 2) ** 0.9, y0 + 1.3 + 0.55 * math.sin(f * math.pi / 2)))
    prof[-1] = (0, y0 + 1.85)
    prof.insert(1, (0.18, y0 + 1.3))
    closed_lathe(nose, prof, seg=40)
    closed_lathe(noz, [(0, y0 - 0.12), (0.11, y0 - 0.12), (0.09, y0 - 0.06), (0.07, y0),
                       (0, y0)], seg=32)
    # fin: a swept trapezoid slab in the XY plane (+X outwards), 2 cm thick
    fin = [(0.15, y0 + 0.45), (0.17, y0 + 0.45), (0.42, y0 - 0.05), (0.42, y0 - 0.2), (0.15, y0 + 0.05)]
    th = 0.012
    poly(fins, [(x, y, th) for x, y in fin], (0, 0, 1))
    poly(fins, [(x, y, -th) for x, y in reversed(fin)], (0, 0, -1))
    for (x0, y0_), (x1, y1) in zip(fin, fin[1:] + fin[:1]):
        n = norm([y1 - y0_, -(x1 - x0), 0])
        if dot(n, [x0 - 0.25, y0_ - y0, 0]) < 0:
            n = mulv(n, -1)
        poly(fins, [(x0, y0_, th), (x1, y1, th), (x1, y1, -th), (x0, y0_, -th)], n)
    assert fins.signed_volume(0) > 0
    # porthole: a short cylinder along +Z sticking out of the hull on the front
    cylinder(port, 0.06, 0.03, y0=0.165, m=chain(T(0, y0 + 1.0, 0), R("x", 90)), seg=28)
    closed_lathe(rim, [(0, 0.17), (0.075, 0.17), (0.075, 0.186), (0.058, 0.19), (0, 0.19)],
                 m=chain(T(0, y0 + 1.0, 0), R("x", 90)), seg=28)
    # flame: a long cone pointing down from the nozzle (lift-off)
    closed_lathe(fl, [(0, 0.06), (0.06, 0.1), (0.13, 0.35), (0.1, y0 - 0.12), (0, y0 - 0.12)],
                 seg=32, smooth_deg=60)
    cylinder(pad, 0.75, 0.06, y0=0.0, seg=48)
    box(pad, (-0.5, 0.0, -0.5), (-0.35, 0.06, 0.5))
    body = M.mesh("rocket_body", [(hull, white), (nose, red), (noz, metal), (port, glass),
                                  (rim, metal)])
    fmesh = M.mesh("fin", [(fins, red)])
    M.node("rocket", body)
    for k in range(4):
        M.node("fin_%d" % k, fmesh, r=quat("y", 45 + 90 * k))
    M.node("flame", M.mesh("flame", [(fl, flame)]))
    M.node("launch_pad", M.mesh("launch_pad", [(pad, concrete)]))
    return M


def wall_with_holes(prim, x0, x1, y0, y1, z0, z1, holes, axis="x", uv_scale=1.0):
    """A wall slab [x0,x1] x [y0,y1] x [z0,z1] minus rectangular holes (u0, u1, v0, v1) in the
    (along-axis, y) plane, as boxes on the grid the holes' edges cut."""
    along = (x0, x1) if axis == "x" else (z0, z1)
    us = sorted(set([along[0], along[1]] + [h[0] for h in holes] + [h[1] for h in holes]))
    vs = sorted(set([y0, y1] + [h[2] for h in holes] + [h[3] for h in holes]))
    for ua, ub in zip(us, us[1:]):
        for va, vb in zip(vs, vs[1:]):
            cu, cv = (ua + ub) / 2, (va + vb) / 2
            if any(h[0] < cu < h[1] and h[2] < cv < h[3] for h in holes):
                continue
            if axis == "x":
                box(prim, (ua, va, z0), (ub, vb, z1), uv_scale=uv_scale)
            else:
                box(prim, (x0, va, ua), (x1, vb, ub), uv_scale=uv_scale)


def house():
    M = Model("house")
    plaster = M.material(mat("plaster", (0.80, 0.72, 0.55, 1), rough=0.9))
    tiles = M.material(mat("roof_tiles", (0.45, 0.08, 0.04, 1), rough=0.7))
    wood = M.material(mat("door_wood", (0.25, 0.12, 0.05, 1), rough=0.6))
    frame = M.material(mat("window_frame", (0.9, 0.9, 0.9, 1), rough=0.5))
    glass = M.material(mat("glass", (0.55, 0.75, 0.85, 0.35), rough=0.05, alphaMode="BLEND"))
    brick = M.material(mat("chimney_brick", (0.4, 0.15, 0.1, 1), rough=0.9))
    floor = M.material(mat("floor", (0.3, 0.25, 0.2, 1), rough=0.8))
    W, D, H, t = 4.0, 3.0, 2.5, 0.15        # x width, z depth, wall height, wall thickness
    x0, x1, z0, z1 = -W / 2, W / 2, -D / 2, D / 2
    walls, doors, frames, panes, gables, roofp, chim, fl = (
        Prim(plaster), Prim(wood), Prim(frame), Prim(glass), Prim(plaster), Prim(tiles),
        Prim(brick), Prim(floor))
    door = (-0.45, 0.45, 0.0, 2.0)
    win_f = [(-1.6, -0.8, 1.0, 1.9), (0.8, 1.6, 1.0, 1.9)]
    win_s = [(-0.5, 0.5, 1.0, 1.9)]
    wall_with_holes(walls, x0, x1, 0, H, z1 - t, z1, [door] + win_f)          # front (+Z)
    wall_with_holes(walls, x0, x1, 0, H, z0, z0 + t, win_f)                   # back
    wall_with_holes(walls, x0, x0 + t, 0, H, z0 + t, z1 - t, win_s, axis="z")  # left
    wall_with_holes(walls, x1 - t, x1, 0, H, z0 + t, z1 - t, win_s, axis="z")  # right
    box(fl, (x0 + t, 0, z0 + t), (x1 - t, 0.05, z1 - t))
    # door: slightly ajar-looking, set 4 cm into the opening; knob
    box(doors, (door[0] + 0.02, 0.0, z1 - 0.09), (door[1] - 0.02, door[3] - 0.02, z1 - 0.05))
    sphere(doors, (door[1] - 0.15, 1.0, z1 - 0.03), 0.035, nu=12, nv=6)
    # windows: a frame (sill, cross bars) and a glass pane in the middle of the wall
    def window(u0, u1, v0, v1, face):
        zc = {"front": z1 - t / 2, "back": z0 + t / 2}.get(face)
        if face in ("front", "back"):
            box(panes, (u0, v0, zc - 0.01), (u1, v1, zc + 0.01))
            s = 1 if face == "front" else -1
            zf = zc + s * 0.035
            box(frames, ((u0 + u1) / 2 - 0.03, v0, zf - 0.025), ((u0 + u1) / 2 + 0.03, v1, zf + 0.025))
            box(frames, (u0, (v0 + v1) / 2 - 0.03, zf - 0.025), (u1, (v0 + v1) / 2 + 0.03, zf + 0.025))
            zs = zc + s * t / 2
            box(frames, (u0 - 0.08, v0 - 0.06, min(zs, zs + s * 0.08) - 0.0), (u1 + 0.08, v0, max(zs, zs + s * 0.08)))
        else:
            xc = x0 + t / 2 if face == "left" else x1 - t / 2
            s = -1 if face == "left" else 1
            box(panes, (xc - 0.01, v0, u0), (xc + 0.01, v1, u1))
            xf = xc + s * 0.035
            box(frames, (xf - 0.025, v0, (u0 + u1) / 2 - 0.03), (xf + 0.025, v1, (u0 + u1) / 2 + 0.03))
            box(frames, (xf - 0.025, (v0 + v1) / 2 - 0.03, u0), (xf + 0.025, (v0 + v1) / 2 + 0.03, u1))
            xs = xc + s * t / 2
            box(frames, (min(xs, xs + s * 0.08), v0 - 0.06, u0 - 0.08), (max(xs, xs + s * 0.08), v0, u1 + 0.08))
    for w in win_f:
        window(*w, "front")
        window(*w, "back")
    for w in win_s:
        window(*w, "left")
        window(*w, "right")
    # gables: a triangular prism on the side walls, ridge along X at height H + 1.2
    rh = 1.2
    for xa, xb, nx in ((x0, x0 + t, -1), (x1 - t, x1, 1)):
        for xx, sgn in ((xa, -1), (xb, 1)):
            pts = [(xx, H, z0), (xx, H, z1), (xx, H + rh, 0)]
            poly(gables, pts, (sgn, 0, 0))
        for za, zb in ((z0, 0), (z1, 0)):
            n = [0, D / 2, rh * (1 if za > 0 else -1)]
            poly(gables, [(xa, H, za), (xb, H, za), (xb, H + rh, 0), (xa, H + rh, 0)], n)
        poly(gables, [(xa, H, z0), (xb, H, z0), (xb, H, z1), (xa, H, z1)], (0, -1, 0))
    assert gables.signed_volume(0) > 0
    # roof: one slab mesh (in its own frame: the slab's top face at y = 0, sloping down to +Z),
    # two nodes rotated about X, the back one also turned 180 degrees about Y
    ang = math.degrees(math.atan2(rh, D / 2))
    slope = math.hypot(rh, D / 2)
    box(roofp, (-W / 2 - 0.3, -0.1, 0), (W / 2 + 0.3, 0.0, slope + 0.35))
    slab = M.mesh("roof_slab", [(roofp, tiles)])
    # chimney through the back slope
    box(chim, (0.9, H + 0.3, -0.9), (1.3, H + 1.6, -0.5))
    house_m = M.mesh("house", [(walls, plaster), (gables, plaster), (fl, floor), (doors, wood),
                               (frames, frame), (chim, brick)])
    M.node("house", house_m)
    M.node("roof_front", slab, t=(0, H + rh + 0.06, 0), r=quat("x", ang))
    q = quat("y", 180)
    qx = quat("x", ang)
    # q * qx (Hamilton product): first tilt, then turn around
    qq = [q[3] * qx[0] + q[0] * qx[3] + q[1] * qx[2] - q[2] * qx[1],
          q[3] * qx[1] - q[0] * qx[2] + q[1] * qx[3] + q[2] * qx[0],
          q[3] * qx[2] + q[0] * qx[1] - q[1] * qx[0] + q[2] * qx[3],
          q[3] * qx[3] - q[0] * qx[0] - q[1] * qx[1] - q[2] * qx[2]]
    M.node("roof_back", slab, t=(0, H + rh + 0.06, 0), r=qq)
    # glass last: blended after the opaque parts (a BLEND material in its own mesh)
    M.node("windows", M.mesh("window_glass", [(panes, glass)]))
    return M


def tree():
    M = Model("tree")
    leaf = M.image("needles", leaf_png())
    tex = M.texture(leaf)
    bark = M.material(mat("bark", (0.22, 0.12, 0.06, 1), rough=0.9))
    needles = M.material(mat("needles", (1, 1, 1, 1), rough=0.8))
    M.materials[needles]["pbrMetallicRoughness"]["baseColorTexture"] = {
        "index": tex, "extensions": {"KHR_texture_transform": {"scale": [6.0, 3.0]}}}
    M.ext_used.append("KHR_texture_transform")
    grass = M.material(mat("grass", (0.12, 0.30, 0.06, 1), rough=0.95))
    stone = M.material(mat("stone", (0.4, 0.4, 0.38, 1), rough=0.8))
    trunk, fol, gr, st = Prim(bark), Prim(needles, uv=True), Prim(grass), Prim(stone)
    closed_lathe(trunk, [(0, 0.02), (0.17, 0.02), (0.13, 0.25), (0.11, 1.2), (0, 1.2)], seg=20)
    for k, (y, r, h) in enumerate(((0.75, 0.95, 1.4), (1.4, 0.75, 1.25), (2.0, 0.55, 1.1))):
        prof = [(0, y), (r * 0.85, y), (r, y + 0.08), (0, y + h)]
        closed_lathe(fol, prof, seg=36, smooth_deg=20, v_scale=1.0 / h)
    closed_lathe(gr, [(0, 0), (1.5, 0), (1.55, 0.02), (0, 0.02)], seg=48)
    M.node("trunk", M.mesh("trunk", [(trunk, bark)]))
    M.node("foliage", M.mesh("foliage", [(fol, needles)]))
    M.node("ground", M.mesh("ground", [(gr, grass)]))
    sphere(st, (0, 0, 0), 1.0, nu=12, nv=6)
    rock = M.mesh("rock", [(st, stone)])
    M.node("rock_a", rock, t=(0.9, 0.02, 0.6), s=(0.16, 0.1, 0.12))
    M.node("rock_b", rock, t=(1.05, 0.02, 0.35), s=(0.09, 0.06, 0.08), r=quat("y", 40))
    return M


def snowman():
    M = Model("snowman")
    snow = M.material(mat("snow", (0.9, 0.92, 0.95, 1), rough=0.9))
    coal = M.material(mat("coal", (0.03, 0.03, 0.03, 1), rough=0.6))
    carrot = M.material(mat("carrot", (0.9, 0.3, 0.02, 1), rough=0.6))
    hat = M.material(mat("hat_felt", (0.04, 0.04, 0.05, 1), rough=0.7))
    band = M.material(mat("hat_band", (0.6, 0.03, 0.03, 1), rough=0.5))
    scarf = M.material(mat("scarf_wool", (0.05, 0.25, 0.6, 1), rough=0.95))
    twig = M.material(mat("twig", (0.25, 0.15, 0.07, 1), rough=0.9))
    sn, co, ca, ha, ba, sc, tw = (Prim(snow), Prim(coal), Prim(carrot), Prim(hat), Prim(band),
                                  Prim(scarf), Prim(twig))
    sphere(sn, (0, 0.5, 0), 0.5, nu=40, nv=20)
    sphere(sn, (0, 1.17, 0), 0.36, nu=36, nv=18)
    sphere(sn, (0, 1.68, 0), 0.25, nu=32, nv=16)
    # coal: eyes and buttons on the +Z side
    for x in (-0.085, 0.085):
        sphere(co, (x, 1.74, 0.22), 0.03, nu=10, nv=5)
    for k in range(3):
        a = math.radians(-20 + 25 * k)
        sphere(co, (0, 1.17 + 0.36 * math.sin(a), 0.36 * math.cos(a)), 0.035, nu=10, nv=5)
    # mouth: a smile of small coals
    for k in range(5):
        a = math.radians(-30 + 15 * k)
        x = 0.1 * math.sin(a)
        y = 1.625 - 0.03 * math.cos(a) + 0.03
        sphere(co, (x, y, math.sqrt(max(0.0, 0.25 ** 2 - x * x - (y - 1.68) ** 2)) - 0.005),
               0.016, nu=8, nv=4)
    # carrot: cone along +Z (lathe about Y turned by the baked rotation)
    cone(ca, 0.045, 0.26, m=chain(T(0, 1.68, 0.21), R("x", 90)), seg=20)
    # hat: brim, crown, band
    cylinder(ha, 0.3, 0.025, y0=1.88)
    cylinder(ha, 0.19, 0.32, y0=1.9)
    cylinder(ba, 0.195, 0.06, y0=1.91)
    # scarf: torus around the neck
    closed_torus(sc, 0.21, 0.055, m=T(0, 1.47, 0), nu=32, nv=12)
    box(sc, (0.1, 1.12, 0.25), (0.2, 1.45, 0.29), m=chain(T(0.15, 1.45, 0.27), R("x", -12),
                                                         T(-0.15, -1.45, -0.27)))
    # arms: one stick mesh (along +Y), two nodes rotated to point out and up
    cylinder(tw, 0.018, 0.7, seg=10)
    cylinder(tw, 0.012, 0.2, m=chain(T(0, 0.5, 0), R("z", -35)), seg=8)
    body = M.mesh("snowman", [(sn, snow), (co, coal), (ca, carrot), (ha, hat), (ba, band), (sc, scarf)])
    arm = M.mesh("stick_arm", [(tw, twig)])
    M.node("snowman", body)
    M.node("arm_left", arm, t=(-0.3, 1.25, 0), r=quat("z", 60))
    M.node("arm_right", arm, t=(0.3, 1.25, 0), r=quat("z", -55))
    return M


def crate():
    M = Model("crate")
    samp = len(M.samplers)
    M.samplers.append({"magFilter": 9729, "minFilter": 9987, "wrapS": 33071, "wrapT": 33071})
    base = M.texture(M.image("crate_planks", crate_png()), samp)
    nmap = M.texture(M.image("crate_planks_normal", crate_normal_png()), samp)
    wood = M.material(mat("crate_wood", (1, 1, 1, 1), rough=0.7))
    M.materials[wood]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": base}
    M.materials[wood]["normalTexture"] = {"index": nmap, "scale": 1.0}
    iron = M.material(mat("iron_corners", (0.25, 0.25, 0.27, 1), metal=0.8, rough=0.45))
    floor = M.material(mat("floor_boards", (0.30, 0.28, 0.26, 1), rough=0.9))
    cp, ir, fl = Prim(wood, uv=True), Prim(iron), Prim(floor)
    s = 0.5
    box(cp, (-s, 0, -s), (s, 2 * s, s), uv_unit=True)
    c = 0.09
    for x in (-1, 1):
        for y in (0, 1):
            for z in (-1, 1):
                px_, py, pz = x * s, y * 2 * s, z * s
                box(ir, (px_ - c if x > 0 else px_ - 0.01, py - c if y else py, pz - c if z > 0 else pz - 0.01),
                    (px_ + 0.01 if x > 0 else px_ + c, py + 0.01 if y else py + c, pz + 0.01 if z > 0 else pz + c))
    box(fl, (-1.1, -0.02, -0.9), (1.3, 0.0, 1.1))
    cm = M.mesh("crate", [(cp, wood), (ir, iron)])
    M.node("crate_big", cm)
    M.node("crate_small", cm, t=(0.05, 1.01, -0.02), r=quat("y", 24), s=(0.55, 0.55, 0.55))
    M.node("crate_side", cm, t=(0.95, 0, 0.4), r=quat("y", -15), s=(0.6, 0.6, 0.6))
    M.node("floor", M.mesh("floor", [(fl, floor)]))
    return M


def desk_lamp():
    M = Model("desk_lamp")
    metal = M.material(mat("lamp_metal", (0.05, 0.25, 0.12, 1), metal=0.6, rough=0.35))
    chrome = M.material(mat("chrome", (0.7, 0.7, 0.72, 1), metal=1.0, rough=0.2))
    inner = M.material(mat("shade_inside", (0.45, 0.45, 0.45, 1), rough=0.6))
    bulb = M.material(mat("bulb", (1.0, 0.8, 0.35, 1), rough=0.2, emissiveFactor=[1.0, 0.85, 0.5]))
    desk = M.material(mat("desk", (0.42, 0.30, 0.2, 1), rough=0.5))
    b, ch, sh_o, sh_i, bu, dk = (Prim(metal), Prim(chrome), Prim(metal), Prim(inner), Prim(bulb),
                                 Prim(desk))
    # base: a rounded disc
    closed_lathe(b, [(0, 0), (0.09, 0), (0.1, 0.01), (0.095, 0.022), (0.04, 0.03), (0.02, 0.04),
                     (0, 0.04)], seg=40)
    # arms: lower arm from the base tilted back, elbow, upper arm forward (baked rotations)
    la, ua = 0.32, 0.3
    t1, t2 = -20.0, 70.0          # degrees from +Y, positive = towards +Z
    cylinder(ch, 0.011, la, m=chain(T(0, 0.035, 0), R("x", t1)), seg=14)
    e = [0, 0.035 + la * math.cos(math.radians(t1)), la * math.sin(math.radians(t1))]
    sphere(ch, e, 0.02, nu=14, nv=7)
    cylinder(ch, 0.011, ua, m=chain(T(*e), R("x", t2)), seg=14)
    h = add(e, [0, ua * math.cos(math.radians(t2)), ua * math.sin(math.radians(t2))])
    sphere(ch, h, 0.018, nu=14, nv=7)
    # shade: an open cone (outside metal, inside cream), opening pointing down and forward
    sm = chain(T(*h), R("x", 150), T(0, -0.02, 0))
    out_prof = [(0.025, 0.0), (0.03, 0.03), (0.1, 0.13)]
    lathe(sh_o, out_prof + [(0.102, 0.135)], m=sm, seg=40)
    lathe(sh_i, [(0.0995, 0.135), (0.0975, 0.13), (0.0275, 0.03), (0.0225, 0.0)], m=sm, seg=40)
    closed_lathe(sh_o, [(0, -0.005), (0.026, -0.005), (0.026, 0.002), (0, 0.002)], m=sm, seg=24)
    sphere(bu, [0, 0.11, 0], 0.034, m=sm, nu=20, nv=10)
    box(dk, (-0.35, -0.03, -0.3), (0.45, 0.0, 0.45))
    M.materials[inner]["doubleSided"] = True
    M.materials[metal]["doubleSided"] = True
    lamp = M.mesh("lamp", [(b, metal), (ch, chrome), (sh_o, metal), (sh_i, inner), (bu, bulb)])
    M.node("lamp", lamp, r=quat("y", 35))
    M.node("desk", M.mesh("desk", [(dk, desk)]))
    eye = (-0.2, 0.5, 1.0)
    M.cameras.append({"name": "product_shot", "type": "perspective",
                      "perspective": {"yfov": 0.7, "znear": 0.05, "zfar": 20.0, "aspectRatio": 16 / 9}})
    M.node("camera", camera=0, t=eye, r=look_rotation(eye, (0.05, 0.25, 0.05)))
    return M


# walker.gltf: joints (name, parent index, bind position in metres); the bind pose has no joint
# rotations, so inverseBindMatrices[j] = translate(-position). The character's left is +X.
WALKER_JOINTS = [
    ("hips", -1, (0.0, 0.95, 0.0)),
    ("spine", 0, (0.0, 1.08, 0.0)),
    ("chest", 1, (0.0, 1.26, 0.0)),
    ("neck", 2, (0.0, 1.47, 0.0)),
    ("head", 3, (0.0, 1.57, 0.0)),
    ("upper_arm_L", 2, (0.2, 1.41, 0.0)),
    ("forearm_L", 5, (0.245, 1.13, 0.0)),
    ("upper_arm_R", 2, (-0.2, 1.41, 0.0)),
    ("forearm_R", 7, (-0.245, 1.13, 0.0)),
    ("thigh_L", 0, (0.095, 0.9, 0.0)),
    ("shin_L", 9, (0.095, 0.49, 0.0)),
    ("foot_L", 10, (0.095, 0.085, 0.0)),
    ("thigh_R", 0, (-0.095, 0.9, 0.0)),
    ("shin_R", 12, (-0.095, 0.49, 0.0)),
    ("foot_R", 13, (-0.095, 0.085, 0.0)),
]
WALKER_TORSO = [(0, 0.96), (0.1, 0.965), (0.138, 0.985), (0.142, 1.03), (0.138, 1.1), (0.148, 1.18),
                (0.165, 1.27), (0.178, 1.35), (0.178, 1.4), (0.165, 1.445), (0.13, 1.475), (0.08, 1.495),
                (0, 1.505)]
WALKER_PELVIS = [(0, 0.79), (0.07, 0.795), (0.12, 0.81), (0.155, 0.845), (0.168, 0.9), (0.165, 0.96),
                 (0.155, 1.01), (0.152, 1.03), (0.12, 1.045), (0, 1.05)]
WALK_KEYS = 16          # walk: keys every 1/16 s over 1 s
WAVE_KEYS = 32          # wave: keys every 1/16 s over 2 s


def walk_rotations(t):
    """Joint rotations of the walk cycle at t (s, period 1): legs and arms in opposite phases, the
    left leg forward at t = 0.25 (its knee bent in the swing, t = 0.84 .. 1.25, most at about
    t = 0.05), hips and chest twisting against each other; the feet kept nearly level."""
    ph = 2 * math.pi * t
    q = {"hips": quat("y", -5 * math.sin(ph)), "chest": quat("y", 8 * math.sin(ph))}
    for side, off in (("L", 0.0), ("R", math.pi)):
        f = ph + off
        thigh = -22 * math.sin(f)                      # about +X: negative swings forward (+Z)
        sw = math.atan2(math.sin(f), math.cos(f)) - 0.3  # the swing: |sw| < 1.3 (f in -1 .. 1.6)
        knee = 5 + (55 * math.cos(sw * math.pi / 2.6) if abs(sw) < 1.3 else 0.0)  # folds the shin back
        q["thigh_" + side] = quat("x", thigh)
        q["shin_" + side] = quat("x", knee)
        q["foot_" + side] = quat("x", -0.85 * (thigh + knee))
        q["upper_arm_" + side] = quat("x", 18 * math.sin(f))
        q["forearm_" + side] = quat("x", -(15 + 15 * max(0.0, -math.sin(f))))
    return q


def wave_rotations(t):
    """The right arm raised (0 - 0.5 s) out to the side and up, the forearm vertical and waving
    +-25 degrees in the frontal plane twice a second (0.5 - 1.5 s), lowered again (1.5 - 2 s)."""
    up = smoothstep(0.25, 0.25, t) * (1 - smoothstep(1.75, 0.25, t))
    wv = math.sin(4 * math.pi * (t - 0.5)) if 0.5 <= t <= 1.5 else 0.0
    return {"upper_arm_R": qmul(quat("z", -130 * up), quat("x", -15 * up)),
            "forearm_R": quat("z", -50 * up + 25 * wv)}


def walker_fk(rot, hips_t):
    """World matrices of the joints for local rotations rot {name: quat} and the hips translation."""
    world = []
    for name, parent, pos in WALKER_JOINTS:
        t = hips_t if parent < 0 else sub(pos, WALKER_JOINTS[parent][2])
        m = trs_matrix(t, rot.get(name, [0.0, 0.0, 0.0, 1.0]))
        world.append(m if parent < 0 else mat_mul(world[parent], m))
    return world


def walker():
    M = Model("walker")
    skin = M.material(mat("skin", (0.80, 0.57, 0.44, 1), rough=0.7))
    shirt = M.material(mat("shirt", (0.12, 0.32, 0.62, 1), rough=0.85))
    trousers = M.material(mat("trousers", (0.2, 0.21, 0.25, 1), rough=0.8))
    dark = M.material(mat("shoes_hair", (0.1, 0.06, 0.035, 1), rough=0.6))
    J = {name: k for k, (name, _, _) in enumerate(WALKER_JOINTS)}
    P = {name: list(pos) for name, _, pos in WALKER_JOINTS}
    sk, sh, tr, dk = SkinPrim(skin), SkinPrim(shirt), SkinPrim(trousers), SkinPrim(dark)

    def rigid(name):
        w = ((J[name], 0, 0, 0), (1.0, 0.0, 0.0, 0.0))
        return lambda p: w

    def torso_w(p):                            # hips -> spine -> chest along y
        if p[1] < 1.14:
            return skin_blend(J["hips"], J["spine"], smoothstep(1.06, 0.05, p[1]))
        return skin_blend(J["spine"], J["chest"], smoothstep(1.22, 0.06, p[1]))

    def neck_w(p):
        if p[1] < 1.515:
            return skin_blend(J["chest"], J["neck"], smoothstep(1.47, 0.03, p[1]))
        return skin_blend(J["neck"], J["head"], smoothstep(1.565, 0.03, p[1]))
    # torso (shirt) and pelvis (trousers): elliptical cross-sections
    sh.weigh = tr.weigh = torso_w
    revolve(sh, smooth_profile(WALKER_TORSO), m=S(1, 1, 0.62), seg=16)
    revolve(tr, smooth_profile(WALKER_PELVIS), m=S(1, 1, 0.72), seg=14)
    # neck, head (an ellipsoid), nose; hair (a tilted cap, lower at the back) and eyes
    sk.weigh = neck_w
    capsule(sk, (0, 1.43, 0), (0, 1.59, 0), 0.05, 0.045, shaft=(0.05, 0.1), seg=10, cap=2)
    hc = (0.0, 1.675, 0.005)
    sk.weigh = dk.weigh = rigid("head")
    revolve(sk, ellipsoid_rings(0.11, 10), m=chain(T(*hc), S(0.88, 1.1, 1.0)), seg=16)
    revolve(sk, ellipsoid_rings(0.02, 4), m=chain(T(0, 1.665, 0.11), S(0.8, 1.2, 1.0)), seg=8)
    hr, h0 = 0.118, 12.0
    y0 = hr * math.sin(math.radians(h0))
    revolve(dk, [(0.0, y0, 0.0, -1.0), (hr * math.cos(math.radians(h0)), y0, 0.0, -1.0)] +
            ellipsoid_rings(hr, 6, h0, 90.0), m=chain(T(*hc), R("x", -20), S(0.88, 1.1, 1.0)), seg=16)
    for x in (-0.036, 0.036):
        revolve(dk, ellipsoid_rings(0.016, 4), m=T(x, 1.692, 0.1), seg=8)
    # arms: one sleeve tube shoulder -> wrist (rings dense at the elbow), hands
    for side in ("L", "R"):
        ua, fa = "upper_arm_" + side, "forearm_" + side
        a, e = P[ua], P[fa]
        lu = math.sqrt(dot(sub(e, a), sub(e, a)))
        d = norm(sub(e, a))
        wrist = add(e, mulv(d, 0.25))

        def arm_w(p, a=a, d=d, lu=lu, j=(J[ua], J[fa])):     # upper arm -> forearm at the elbow
            return skin_blend(j[0], j[1], smoothstep(lu, 0.05, dot(sub(p, a), d)))
        sh.weigh = arm_w
        capsule(sh, a, wrist, 0.05, 0.04, seg=10,
                shaft=(0.1, 0.2, lu - 0.035, lu - 0.017, lu, lu + 0.017, lu + 0.035, 0.42))
        sk.weigh = rigid(fa)
        capsule(sk, add(wrist, mulv(d, 0.01)), add(wrist, mulv(d, 0.08)), 0.034, 0.03, seg=8, cap=2, sx=0.6)
    # legs: one trouser tube hip -> ankle (dense at the knee), shoes (flattened capsules along +Z)
    for side in ("L", "R"):
        th, sn, ft = "thigh_" + side, "shin_" + side, "foot_" + side
        a, k, f = P[th], P[sn], P[ft]
        lk, lf = a[1] - k[1], a[1] - f[1]

        def leg_w(p, a=a, lk=lk, lf=lf, j=(J[th], J[sn], J[ft])):
            s = a[1] - p[1]
            if s < (lk + lf) / 2:
                return skin_blend(j[0], j[1], smoothstep(lk, 0.06, s))
            return skin_blend(j[1], j[2], smoothstep(lf, 0.03, s))
        tr.weigh = leg_w
        capsule(tr, a, f, 0.075, 0.048, seg=12,
                shaft=(0.17, 0.26, 0.33, 0.37, 0.41, 0.45, 0.49, 0.6, 0.72))
        dk.weigh = rigid(ft)
        capsule(dk, (f[0], 0.045, -0.07), (f[0], 0.045, 0.13), 0.05, 0.05, shaft=(0.1,), seg=10, sx=0.9)
    # skeleton: joint nodes 0..14 (hips the root), then the skinned mesh node (no transform)
    world = []
    for k, (name, parent, pos) in enumerate(WALKER_JOINTS):
        M.node(name, t=pos if parent < 0 else sub(pos, WALKER_JOINTS[parent][2]), root=parent < 0)
        kids = [c for c, (_, p, _) in enumerate(WALKER_JOINTS) if p == k]
        if kids:
            M.nodes[k]["children"] = kids
        tk = M.nodes[k]["translation"]
        world.append(tk if parent < 0 else add(world[parent], tk))
    body = M.mesh("walker", [(sk, skin), (sh, shirt), (tr, trousers), (dk, dark)])
    M.node("walker_body", body)
    M.nodes[-1]["skin"] = 0
    ibms = [[1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -w[0], -w[1], -w[2], 1.0]
            for w in world]             # column-major translate(-bind position)
    M.skins.append(("walker_skin", list(range(len(WALKER_JOINTS))), ibms, 0))
    # walk: the hips bob so that the lowest shoe vertex touches y = 0 at every key
    bind = {J[n]: P[n] for n in J}
    times = [k / WALK_KEYS for k in range(WALK_KEYS + 1)]
    keys = []
    for t in times[:-1]:
        rot = walk_rotations(t)
        hips = P["hips"]
        wm = walker_fk(rot, hips)
        low = min(xf_point(mat_mul(wm[js[0]], T(*mulv(bind[js[0]], -1))), v)[1]
                  for v, (js, _) in zip(dk.pos, dk.jw) if js[0] in (J["foot_L"], J["foot_R"]))
        keys.append((rot, [hips[0], hips[1] - low, hips[2]]))
    keys.append(keys[0])                       # the last key is the first: a seamless loop
    order = ["hips", "chest", "thigh_L", "shin_L", "foot_L", "thigh_R", "shin_R", "foot_R", "upper_arm_L",
             "forearm_L", "upper_arm_R", "forearm_R"]
    ch = [(J["hips"], "translation", [h for _, h in keys])]
    ch += [(J[n], "rotation", [r[n] for r, _ in keys]) for n in order]
    M.animations.append(("walk", times, ch))
    wt = [k / 16.0 for k in range(WAVE_KEYS + 1)]
    wr = [wave_rotations(t) for t in wt]
    wr[-1] = wr[0]
    M.animations.append(("wave", wt, [(J[n], "rotation", [r[n] for r in wr])
                                      for n in ("upper_arm_R", "forearm_R")]))
    M.check = walker_check
    return M


def walker_check(d, blob):
    """Poses by CPU skinning of the written data: the rest pose is the bind pose; no vertex moves
    more than 1.5 m from it; in the walk the shoes stay on y = 0 at every key (>= -0.2 m between),
    the left foot ahead at 0.25 s and behind at 0.75 s; in the wave the right hand is above the
    head at 1 s and the left arm does not move; every animation loops (first key = last key)."""
    rows = {i: accessor_rows(d, blob, i) for i in range(len(d["accessors"]))}
    body = len(d["nodes"]) - 1
    prims = d["meshes"][d["nodes"][body]["mesh"]]["primitives"]
    bind = [rows[p["attributes"]["POSITION"]] for p in prims]
    joints = [rows[p["attributes"]["JOINTS_0"]] for p in prims]
    weights = [rows[p["attributes"]["WEIGHTS_0"]] for p in prims]
    names = [n["name"] for n in d["nodes"]]
    shoes = [m["name"] for m in d["materials"]].index("shoes_hair")

    def only(pi, jname):                       # vertices of primitive pi weighted to one joint
        j = names.index(jname)
        return [v for v, (js, ws) in enumerate(zip(joints[pi], weights[pi])) if js[0] == j and ws[0] == 1.0]
    rest = skinned_positions(d, rows, body, None, 0.0)
    assert all(abs(a[k] - b[k]) < 1e-5 for pa, pb in zip(rest, bind) for a, b in zip(pa, pb)
               for k in range(3))
    for an in d["animations"]:
        for smp in an["samplers"]:
            out = rows[smp["output"]]
            assert out[0] == out[-1], an["name"]
            t = [r[0] for r in rows[smp["input"]]]
            assert t[0] == 0.0 and max(b - a for a, b in zip(t, t[1:])) <= 0.125, an["name"]
    assert [an["name"] for an in d["animations"]] == ["walk", "wave"]
    stats = {}
    for ai, (dur, steps) in enumerate(((1.0, 32), (2.0, 40))):
        moved, low = 0.0, 1e9
        for k in range(steps + 1):
            t = dur * k / steps
            pos = skinned_positions(d, rows, body, ai, t)
            for pa, pb in zip(pos, bind):
                for a, b in zip(pa, pb):
                    moved = max(moved, math.sqrt(dot(sub(a, b), sub(a, b))))
            low = min(low, min(p[1] for pa in pos for p in pa))
            if ai == 0:
                shoe_low = min(p[1] for p in pos[shoes])
                assert shoe_low >= -0.2, (t, shoe_low)
                if k % 2 == 0:                 # a key (1/16 s): the planted shoe touches y = 0
                    assert abs(shoe_low) < 1e-4, (t, shoe_low)
        assert moved <= 1.5, (ai, moved)
        stats[d["animations"][ai]["name"]] = (moved, low)
    pos = skinned_positions(d, rows, body, 0, 0.25)
    fl = [pos[shoes][v][2] for v in only(shoes, "foot_L")]
    fr = [pos[shoes][v][2] for v in only(shoes, "foot_R")]
    assert sum(fl) / len(fl) > sum(fr) / len(fr) + 0.2, "walk t = 0.25: left foot not ahead"
    stats["walk t=0.25 feet z"] = (sum(fl) / len(fl), sum(fr) / len(fr))
    stats["walk t=0.25 min y"] = min(p[1] for pa in pos for p in pa)
    pos = skinned_positions(d, rows, body, 0, 0.75)
    fl = [pos[shoes][v][2] for v in only(shoes, "foot_L")]
    fr = [pos[shoes][v][2] for v in only(shoes, "foot_R")]
    assert sum(fl) / len(fl) + 0.2 < sum(fr) / len(fr), "walk t = 0.75: left foot not behind"
    pos = skinned_positions(d, rows, body, 1, 1.0)
    skin = [m["name"] for m in d["materials"]].index("skin")
    hand = max(pos[skin][v][1] for v in only(skin, "forearm_R"))
    assert hand > 1.85, hand
    assert all(abs(pos[skin][v][k] - bind[skin][v][k]) < 1e-5 for v in only(skin, "forearm_L")
               for k in range(3))
    stats["wave t=1 right hand top"] = hand
    hips = [r[1] for r in rows[d["animations"][0]["samplers"][0]["output"]]]
    stats["walk hips y"] = (min(hips), max(hips))
    print("walker.gltf: " + "; ".join(
        "%s %s" % (k, " ".join("%.3f" % x for x in (v if isinstance(v, tuple) else (v,))))
        for k, v in stats.items()))


MODELS = [("mug.gltf", mug), ("pawn.gltf", pawn), ("table_chair.gltf", table_chair),
          ("donut.gltf", donut), ("rocket.glb", rocket), ("house.gltf", house),
          ("tree.gltf", tree), ("snowman.gltf", snowman), ("crate.glb", crate),
          ("desk_lamp.gltf", desk_lamp), ("walker.gltf", walker)]

if __name__ == "__main__":
    # --out DIR writes elsewhere (cli_test.sh checks that the committed files are what this
    # script writes)
    if len(sys.argv) == 3 and sys.argv[1] == "--out":
        OUT = sys.argv[2]
        os.makedirs(OUT, exist_ok=True)
    elif len(sys.argv) != 1:
        sys.exit("usage: gen_models.py [--out DIR]")
    for fname, fn in MODELS:
        size, tris = fn().write(fname)
        assert size < (150 if fname == "walker.gltf" else 300) * 1024, (fname, size)
        print("%-18s %7d bytes %6d triangles" % (fname, size, tris))
