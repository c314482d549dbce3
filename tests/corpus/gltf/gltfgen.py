"""gltfgen.py - helpers shared by the glTF corpus generators (objects/, blend/, emissive/, pbr/,
features/): a flat-shaded box, a UV sphere, a look-at node rotation, PNG encoding. Standard library
only; deterministic."""
import base64
import math
import struct
import zlib


def b64(data):
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode()


def box(mn, mx):
    """24 vertices (flat normals), 36 indices."""
    faces = [  # normal, four corners (counter-clockwise seen from outside)
        ((1, 0, 0), [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)]),
        ((-1, 0, 0), [(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)]),
        ((0, 1, 0), [(0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)]),
        ((0, -1, 0), [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)]),
        ((0, 0, 1), [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]),
        ((0, 0, -1), [(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)]),
    ]
    pos, nrm, idx = [], [], []
    for n, corners in faces:
        base = len(pos)
        for c in corners:
            pos.append(tuple(mn[k] + c[k] * (mx[k] - mn[k]) for k in range(3)))
            nrm.append(n)
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, idx


def sphere(center, r, nu=24, nv=12):
    """A UV sphere: (nu + 1) x (nv + 1) vertices with smooth normals, 6 nu nv indices."""
    pos, nrm, idx = [], [], []
    for j in range(nv + 1):
        th = math.pi * j / nv
        for i in range(nu + 1):
            ph = 2 * math.pi * i / nu
            n = (math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph))
            nrm.append(n)
            pos.append(tuple(center[k] + r * n[k] for k in range(3)))
    for j in range(nv):
        for i in range(nu):
            a = j * (nu + 1) + i
            b = a + nu + 1
            idx += [a, b, a + 1, a + 1, b, b + 1]
    return pos, nrm, idx


def pad4(b):
    return b + b"\0" * ((4 - len(b) % 4) % 4)


def png_rgba(w, h, pixels):
    """An 8-bit RGBA PNG of w x h pixels (a flat list of bytes, rows from the top)."""
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)
    raw = b"".join(b"\0" + bytes(pixels[y * w * 4:(y + 1) * w * 4]) for y in range(h))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def look_rotation(eye, target):
    """Unit quaternion (x, y, z, w) turning the node's -Z to (target - eye), +Y kept up."""
    f = [target[k] - eye[k] for k in range(3)]
    l = math.sqrt(sum(x * x for x in f))
    f = [x / l for x in f]
    z = [-x for x in f]                       # node +Z = -forward
    up = (0, 1, 0)
    x = [up[1] * z[2] - up[2] * z[1], up[2] * z[0] - up[0] * z[2], up[0] * z[1] - up[1] * z[0]]
    lx = math.sqrt(sum(v * v for v in x))
    x = [v / lx for v in x]
    y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]]
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


def merge(*meshes):
    """One (positions, normals, indices) mesh from several, the indices rebased."""
    pos, nrm, idx = [], [], []
    for p, n, i in meshes:
        base = len(pos)
        pos += p
        nrm += n
        idx += [base + j for j in i]
    return pos, nrm, idx


class Buffer:
    """One glTF buffer built up view by view: add() appends a blob (4-byte aligned) as a bufferView
    and an accessor of it, and returns the accessor's index; finish(doc) stores the accessors,
    views and the buffer (a base64 data URI) in doc."""

    def __init__(self):
        self.data = b""
        self.views, self.accessors = [], []

    def add(self, blob, count, ctype, typ, normalized=False, minmax=None):
        self.data = pad4(self.data)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(blob)})
        self.data += blob
        acc = {"bufferView": len(self.views) - 1, "componentType": ctype, "count": count, "type": typ}
        if normalized:
            acc["normalized"] = True
        if minmax:
            acc["min"], acc["max"] = minmax
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def finish(self, doc):
        doc["accessors"] = self.accessors
        doc["bufferViews"] = self.views
        doc["buffers"] = [{"byteLength": len(self.data),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(self.data).decode()}]
