/* scene_gltf_mesh.cpp - step 4 of the glTF load (scene_gltf.cpp): accessors (range-checked views,
 * sparse, KHR_mesh_quantization types) and primitives baked into vertices and indices under their
 * node transform.
 */
#include "scene_gltf_internal.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <memory>

namespace pg_gltf {

/* ------------------------------------------------------------------------------------------ */
/* step 4: accessors, nodes, primitives                                                         */

const char *type_name(int t)
{
    switch (t) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "?";
    }
}


struct View {
    int index = -1;
    const unsigned char *base = nullptr;
    size_t stride = 0, count = 0;
    int type = 0, ctype = 0, ncomp = 0;
    bool normalized = false;
};

inline uint32_t read_index(const View &v, size_t i)
{
    const unsigned char *p = v.base + i * v.stride;
    switch (v.ctype) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t x;
        memcpy(&x, p, 2);
        return x;
    }
    default: {
        uint32_t x;
        memcpy(&x, p, 4);
        return x;
    }
    }
}


/* Sparse accessors (core glTF 2.0): a dense copy of the base data (zeros without a bufferView)
 * with sparse.count elements substituted at sparse.indices (strictly increasing, < count). */
void apply_sparse(Ctx &c, int ai, const tinygltf::Accessor &a, View &v, size_t elem)
{
    auto done = c.sparse_data.find(ai);
    if (done != c.sparse_data.end()) {
        v.base = done->second.data();
        v.stride = elem;
        return;
    }
    const std::string sw = strf("accessors[%d].sparse", ai);
    constexpr uint64_t kMaxSparseBytes = uint64_t(1) << 30;
    if (uint64_t(a.count) > kMaxSparseBytes / elem)
        fail(PG_ERR_LIMIT, strf("accessors[%d]: sparse accessor of %zu elements (%zu bytes each) "
                                "exceeds 1 GiB",
                                ai, a.count, elem));
    std::vector<unsigned char> d(a.count * elem, 0);
    if (v.base)
        for (size_t i = 0; i < a.count; i++) memcpy(&d[i * elem], v.base + i * v.stride, elem);
    const size_t sc = a.sparse.count < 0 ? 0 : size_t(a.sparse.count);
    if (sc < 1 || sc > a.count)
        gfail(strf("%s.count: %d is outside 1..%zu (the accessor's count)", sw.c_str(),
                   a.sparse.count, a.count));
    const int ict = a.sparse.indices.componentType;
    const size_t isz = ctype_size(ict);
    if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        gfail(strf("%s.indices.componentType: %d is not an unsigned integer type", sw.c_str(), ict));
    auto ib = view_bytes(c, a.sparse.indices.bufferView, sw + ".indices");
    auto vb = view_bytes(c, a.sparse.values.bufferView, sw + ".values");
    const uint64_t ioff = uint64_t(a.sparse.indices.byteOffset < 0 ? 0 : a.sparse.indices.byteOffset);
    const uint64_t voff = uint64_t(a.sparse.values.byteOffset < 0 ? 0 : a.sparse.values.byteOffset);
    if (ioff > ib.second || sc > (ib.second - ioff) / isz)
        gfail(strf("%s.indices: %zu indices (byteOffset %llu) exceed bufferView %d (%zu bytes)",
                   sw.c_str(), sc, (unsigned long long)ioff, a.sparse.indices.bufferView,
                   ib.second));
    if (voff > vb.second || sc > (vb.second - voff) / elem)
        gfail(strf("%s.values: %zu elements of %zu bytes (byteOffset %llu) exceed bufferView %d "
                   "(%zu bytes)",
                   sw.c_str(), sc, elem, (unsigned long long)voff, a.sparse.values.bufferView,
                   vb.second));
    View iv;
    iv.base = ib.first + ioff;
    iv.stride = isz;
    iv.ctype = ict;
    uint64_t prev = 0;
    for (size_t k = 0; k < sc; k++) {
        uint32_t idx = read_index(iv, k);
        if (idx >= a.count)
            gfail(strf("%s.indices: index %u at position %zu is out of range (count %zu)",
                       sw.c_str(), idx, k, a.count));
        if (k > 0 && idx <= prev)
            gfail(strf("%s.indices: index %u at position %zu is not greater than the one before "
                       "(%llu)",
                       sw.c_str(), idx, k, (unsigned long long)prev));
        prev = idx;
        memcpy(&d[size_t(idx) * elem], vb.first + voff + k * elem, elem);
    }
    auto &stored = c.sparse_data[ai];
    stored.swap(d);
    v.base = stored.data();
    v.stride = elem;
}

View get_view(Ctx &c, int ai)
{
    const tinygltf::Model &m = c.model;
    if (ai < 0 || size_t(ai) >= m.accessors.size())
        gfail(strf("accessors[%d]: out of range (%zu accessors)", ai, m.accessors.size()));
    const tinygltf::Accessor &a = m.accessors[size_t(ai)];
    View v;
    v.index = ai;
    v.type = a.type;
    v.ctype = a.componentType;
    v.ncomp = type_comps(a.type);
    v.count = a.count;
    v.normalized = a.normalized;
    const bool sparse = a.sparse.isSparse;
    size_t csize = ctype_size(a.componentType);
    if (!csize || !v.ncomp)
        gfail(strf("accessors[%d]: invalid componentType %d or type", ai, a.componentType));
    size_t elem = csize * size_t(v.ncomp);
    auto dd = c.draco_data.find(ai);
    if (dd != c.draco_data.end()) {
        v.base = dd->second.data();
        v.stride = elem;
        return v;
    }
    if (a.bufferView < 0 || c.draco_index_fix.count(ai)) {
        if (!sparse)
            gfail(strf("accessors[%d]: has no bufferView (zero-filled accessors are not supported "
                       "without sparse)",
                       ai));
        apply_sparse(c, ai, a, v, elem);
        return v;
    }
    if (size_t(a.bufferView) >= m.bufferViews.size())
        gfail(strf("accessors[%d]: bufferView %d out of range", ai, a.bufferView));
    const tinygltf::BufferView &bv = m.bufferViews[size_t(a.bufferView)];
    auto bytes = view_bytes(c, a.bufferView, strf("accessors[%d]", ai));
    size_t stride = bv.byteStride ? bv.byteStride : elem;
    if (stride < elem)
        gfail(strf("accessors[%d]: bufferViews[%d].byteStride %zu is smaller than the element "
                   "(%zu bytes)",
                   ai, a.bufferView, stride, elem));
    if (a.count > 0) {
        uint64_t len = bv.byteLength;
        bool ok = a.byteOffset <= len && elem <= len - a.byteOffset &&
                  uint64_t(a.count - 1) <= (len - a.byteOffset - elem) / stride;
        if (!ok)
            gfail(strf("accessors[%d]: count %zu (byteOffset %zu, stride %zu, element %zu bytes) "
                       "exceeds bufferView %d (%zu bytes)",
                       ai, a.count, a.byteOffset, stride, elem, a.bufferView, bv.byteLength));
    }
    v.base = bytes.first + a.byteOffset;
    v.stride = stride;
    if (sparse) apply_sparse(c, ai, a, v, elem);
    return v;
}

/* KHR_mesh_quantization: the component types a vertex attribute may have. Core glTF 2.0 allows
 * FLOAT for POSITION/NORMAL/TANGENT and FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT for
 * TEXCOORD_n; with KHR_mesh_quantization in extensionsUsed also POSITION: (normalized or not)
 * BYTE/UNSIGNED_BYTE/SHORT/UNSIGNED_SHORT; NORMAL and TANGENT: normalized BYTE/SHORT; TEXCOORD_n:
 * (normalized or not) BYTE/UNSIGNED_BYTE/SHORT/UNSIGNED_SHORT. */
enum AttrKind { ATTR_POSITION, ATTR_NORMAL, ATTR_TANGENT, ATTR_TEXCOORD };

bool attr_type_ok(AttrKind k, int ct, bool normalized, bool quantization)
{
    const bool i8_16 = ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                       ct == TINYGLTF_COMPONENT_TYPE_SHORT || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    if (ct == TINYGLTF_COMPONENT_TYPE_FLOAT) return !normalized;
    switch (k) {
    case ATTR_POSITION: return quantization && i8_16;
    case ATTR_NORMAL:
    case ATTR_TANGENT:
        return quantization && normalized &&
               (ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT);
    case ATTR_TEXCOORD:
        if (normalized && (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                           ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))
            return true; /* core glTF 2.0 */
        return quantization && i8_16;
    }
    return false;
}

void expect_attr(const View &v, const char *semantic, int type, AttrKind k, bool quantization)
{
    if (v.type == type && attr_type_ok(k, v.ctype, v.normalized, quantization)) return;
    static const char *const allowed_core[] = {"FLOAT", "FLOAT", "FLOAT",
                                               "FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT"};
    static const char *const allowed_q[] = {
        "FLOAT or (normalized) BYTE/UNSIGNED_BYTE/SHORT/UNSIGNED_SHORT",
        "FLOAT or normalized BYTE/SHORT", "FLOAT or normalized BYTE/SHORT",
        "FLOAT or (normalized) BYTE/UNSIGNED_BYTE/SHORT/UNSIGNED_SHORT"};
    const bool would_be_ok = !quantization && v.type == type && attr_type_ok(k, v.ctype, v.normalized, true);
    gfail(strf("accessors[%d]: %s must be %s %s (got %s %s%s)%s", v.index, semantic,
               type_name(type), quantization ? allowed_q[k] : allowed_core[k], type_name(v.type),
               v.normalized ? "normalized " : "",
               ctype_name(v.ctype),
               would_be_ok ? "; that type needs KHR_mesh_quantization in extensionsUsed" : ""));
}

/* Reads element i as floats, converted as glTF 2.0 and KHR_mesh_quantization say: FLOAT as is;
 * normalized UNSIGNED_BYTE c / 255, UNSIGNED_SHORT c / 65535, BYTE max(c / 127, -1), SHORT
 * max(c / 32767, -1); not normalized: the integer value. */
inline void read_floats(const View &v, size_t i, float *out)
{
    const unsigned char *p = v.base + i * v.stride;
    const int n = v.ncomp;
    switch (v.ctype) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: memcpy(out, p, sizeof(float) * size_t(n)); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        for (int k = 0; k < n; k++) out[k] = v.normalized ? float(p[k]) / 255.0f : float(p[k]);
        break;
    case TINYGLTF_COMPONENT_TYPE_BYTE:
        for (int k = 0; k < n; k++) {
            float x = float(int8_t(p[k]));
            out[k] = v.normalized ? std::max(x / 127.0f, -1.0f) : x;
        }
        break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        for (int k = 0; k < n; k++) {
            uint16_t x;
            memcpy(&x, p + 2 * k, 2);
            out[k] = v.normalized ? float(x) / 65535.0f : float(x);
        }
        break;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
        for (int k = 0; k < n; k++) {
            int16_t x;
            memcpy(&x, p + 2 * k, 2);
            out[k] = v.normalized ? std::max(float(x) / 32767.0f, -1.0f) : float(x);
        }
        break;
    default:
        for (int k = 0; k < n; k++) out[k] = 0;
    }
}

void check_finite(const float *v, int n, const View &view, const char *semantic, size_t i)
{
    for (int k = 0; k < n; k++)
        if (!std::isfinite(v[k]))
            gfail(strf("accessors[%d]: %s element %zu is not finite (%g)", view.index, semantic, i,
                       double(v[k])));
}


/* a primitive's vertex attributes: POSITION, and the optional ones (null when absent), each with
 * POSITION's element count n */
struct PrimAttrs {
    View pos;
    size_t n = 0;
    std::unique_ptr<View> nrm, tan, uv, uv1, col;
};

/* COLOR_1.. and TEXCOORD_2.. are ignored: the primitives that have them are counted (warned) */
static void count_ignored_attributes(Ctx &c, const tinygltf::Primitive &prim)
{
    bool has_color1 = false, has_uv2 = false;
    for (const auto &at : prim.attributes) {
        has_color1 = has_color1 || (at.first.compare(0, 6, "COLOR_") == 0 && at.first != "COLOR_0");
        has_uv2 = has_uv2 || (at.first.compare(0, 9, "TEXCOORD_") == 0 && at.first != "TEXCOORD_0" &&
                              at.first != "TEXCOORD_1");
    }
    c.color1_prims += has_color1;
    c.texcoord2_prims += has_uv2;
}

/* the attribute NAME's view, null when absent; as many elements as POSITION (n) */
static std::unique_ptr<View> optional_view(Ctx &c, const tinygltf::Primitive &prim, const char *name,
                                           size_t n, const std::string &pw)
{
    const int *ai = find_attr(prim, name);
    if (!ai) return nullptr;
    std::unique_ptr<View> v(new View(get_view(c, *ai)));
    if (v->count != n)
        gfail(strf("%s: %s (accessors[%d]) has %zu elements but POSITION has %zu", pw.c_str(),
                   name, *ai, v->count, n));
    return v;
}

/* COLOR_0: FLOAT, or normalized UNSIGNED_BYTE / UNSIGNED_SHORT (core glTF) */
static bool float_or_unorm(const View &v)
{
    return v.ctype == TINYGLTF_COMPONENT_TYPE_FLOAT ||
           (v.normalized && (v.ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                             v.ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
}

/* the attributes drawn, each checked for its glTF (and KHR_mesh_quantization) types */
static void read_attributes(Ctx &c, const tinygltf::Primitive &prim, const std::string &pw, PrimAttrs &a)
{
    const int *pa = find_attr(prim, "POSITION");
    if (!pa) gfail(pw + ".attributes: POSITION missing (required)");
    count_ignored_attributes(c, prim);
    const bool quant = c.quantization;
    a.pos = get_view(c, *pa);
    expect_attr(a.pos, "POSITION", TINYGLTF_TYPE_VEC3, ATTR_POSITION, quant);
    a.n = a.pos.count;
    a.nrm = optional_view(c, prim, "NORMAL", a.n, pw);
    if (a.nrm) expect_attr(*a.nrm, "NORMAL", TINYGLTF_TYPE_VEC3, ATTR_NORMAL, quant);
    a.tan = optional_view(c, prim, "TANGENT", a.n, pw);
    if (a.tan) expect_attr(*a.tan, "TANGENT", TINYGLTF_TYPE_VEC4, ATTR_TANGENT, quant);
    a.uv = optional_view(c, prim, "TEXCOORD_0", a.n, pw);
    if (a.uv) expect_attr(*a.uv, "TEXCOORD_0", TINYGLTF_TYPE_VEC2, ATTR_TEXCOORD, quant);
    a.uv1 = optional_view(c, prim, "TEXCOORD_1", a.n, pw);
    if (a.uv1) expect_attr(*a.uv1, "TEXCOORD_1", TINYGLTF_TYPE_VEC2, ATTR_TEXCOORD, quant);
    a.col = optional_view(c, prim, "COLOR_0", a.n, pw);
    const View *col = a.col.get();
    if (col && !((col->type == TINYGLTF_TYPE_VEC3 || col->type == TINYGLTF_TYPE_VEC4) && float_or_unorm(*col)))
        gfail(strf("accessors[%d]: COLOR_0 must be VEC3 or VEC4, FLOAT or normalized "
                   "UNSIGNED_BYTE/UNSIGNED_SHORT (got %s %s%s)",
                   col->index, type_name(col->type), col->normalized ? "normalized " : "",
                   ctype_name(col->ctype)));
}

/* the primitive's indices (local to it, each < n), or 0..n-1 without an indices accessor */
static std::vector<uint32_t> read_indices(Ctx &c, const tinygltf::Primitive &prim, size_t n,
                                          const std::string &pw)
{
    std::vector<uint32_t> ind;
    if (prim.indices < 0) {
        if (n > 0xFFFFFFFFull) fail(PG_ERR_LIMIT, pw + ": too many vertices");
        ind.resize(n);
        for (size_t i = 0; i < n; i++) ind[i] = uint32_t(i);
        return ind;
    }
    View iv = get_view(c, prim.indices);
    if (iv.type != TINYGLTF_TYPE_SCALAR ||
        (iv.ctype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         iv.ctype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         iv.ctype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        gfail(strf("accessors[%d]: indices must be SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or "
                   "UNSIGNED_INT (got %s %s)",
                   iv.index, type_name(iv.type), ctype_name(iv.ctype)));
    ind.resize(iv.count);
    for (size_t i = 0; i < iv.count; i++) {
        uint32_t x = read_index(iv, i);
        if (x >= n)
            gfail(strf("%s: index %u at position %zu is out of range (vertex count %zu)",
                       pw.c_str(), x, i, n));
        ind[i] = x;
    }
    return ind;
}

/* strips and fans become lists; a list must be whole triangles */
static void to_triangle_list(int mode, std::vector<uint32_t> &ind, const std::string &pw)
{
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        std::vector<uint32_t> list;
        for (size_t i = 2; i < ind.size(); i++) {
            if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
                list.insert(list.end(), {ind[0], ind[i - 1], ind[i]});
            } else if (i % 2 == 0) {
                list.insert(list.end(), {ind[i - 2], ind[i - 1], ind[i]});
            } else {
                list.insert(list.end(), {ind[i - 1], ind[i - 2], ind[i]});
            }
        }
        ind.swap(list);
    } else if (ind.size() % 3 != 0) {
        gfail(strf("%s: %zu indices is not a multiple of 3 (TRIANGLES)", pw.c_str(), ind.size()));
    }
}

/* transform: positions by M, normals by the inverse-transpose of M's upper 3x3, tangents by the
 * upper 3x3; a mirroring transform (det < 0) flips the winding and the tangent handedness */
struct Xform {
    const double *m;
    double cof[9]; /* cof[r*3+c] = cofactor(r,c); inverse-transpose = cof / det */
    double det, nsign;
};

static Xform node_xform(const Mat4 &M, const std::string &pw)
{
    Xform x;
    const double *m = x.m = M.m;
    double a00 = m[0], a01 = m[4], a02 = m[8], a10 = m[1], a11 = m[5], a12 = m[9], a20 = m[2],
           a21 = m[6], a22 = m[10];
    const double cof[9] = {a11 * a22 - a12 * a21, a12 * a20 - a10 * a22, a10 * a21 - a11 * a20,
                           a02 * a21 - a01 * a22, a00 * a22 - a02 * a20, a01 * a20 - a00 * a21,
                           a01 * a12 - a02 * a11, a02 * a10 - a00 * a12, a00 * a11 - a01 * a10};
    memcpy(x.cof, cof, sizeof cof);
    x.det = a00 * cof[0] + a01 * cof[1] + a02 * cof[2];
    if (!std::isfinite(x.det)) gfail(pw + ": node transform is not finite");
    x.nsign = x.det < 0 ? -1.0 : 1.0;
    return x;
}

/* POSITION element i under the transform (finite floats under a finite transform can still leave
 * the float range) */
static void emit_position(const PrimAttrs &a, const Xform &x, size_t i, const std::string &pw,
                          pg_vertex &vx)
{
    const double *m = x.m;
    float p[3];
    read_floats(a.pos, i, p);
    check_finite(p, 3, a.pos, "POSITION", i);
    for (int r = 0; r < 3; r++) {
        double v = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
        if (!(std::fabs(v) <= double(FLT_MAX)))
            gfail(strf("%s: POSITION element %zu (accessors[%d]) is outside the float range "
                       "after the node transform",
                       pw.c_str(), i, a.pos.index));
        vx.position[r] = float(v);
    }
}

/* NORMAL element i under the inverse-transpose, normalized (+Y when it vanishes) */
static void emit_normal(const View &nrm, const Xform &x, size_t i, const std::string &pw, pg_vertex &vx)
{
    float q[3];
    read_floats(nrm, i, q);
    check_finite(q, 3, nrm, "NORMAL", i);
    double t[3];
    for (int r = 0; r < 3; r++)
        t[r] = x.nsign * (x.cof[r * 3 + 0] * q[0] + x.cof[r * 3 + 1] * q[1] + x.cof[r * 3 + 2] * q[2]);
    double l = std::hypot(t[0], t[1], t[2]); /* no overflow in the squares */
    if (!std::isfinite(l))
        gfail(strf("%s: NORMAL element %zu (accessors[%d]) overflows under the node "
                   "transform",
                   pw.c_str(), i, nrm.index));
    if (l > 1e-30) {
        for (int r = 0; r < 3; r++) vx.normal[r] = float(t[r] / l);
    } else {
        vx.normal[0] = 0;
        vx.normal[1] = 1;
        vx.normal[2] = 0;
    }
}

/* TANGENT element i under the upper 3x3, normalized; handedness flipped by a mirroring transform */
static void emit_tangent(const View &tan, const Xform &x, size_t i, const std::string &pw, pg_vertex &vx)
{
    const double *m = x.m;
    float q[4];
    read_floats(tan, i, q);
    check_finite(q, 4, tan, "TANGENT", i);
    double t[3];
    for (int r = 0; r < 3; r++) t[r] = m[r] * q[0] + m[4 + r] * q[1] + m[8 + r] * q[2];
    double l = std::hypot(t[0], t[1], t[2]);
    if (!std::isfinite(l))
        gfail(strf("%s: TANGENT element %zu (accessors[%d]) overflows under the node "
                   "transform",
                   pw.c_str(), i, tan.index));
    if (l > 1e-30)
        for (int r = 0; r < 3; r++) vx.tangent[r] = float(t[r] / l);
    vx.tangent[3] = float((q[3] < 0 ? -1.0 : 1.0) * x.nsign);
}

/* the n vertices appended to o at `base` (the optional streams exist from the first primitive
 * that has the attribute on: white / TEXCOORD_0 for the vertices of primitives without it) */
static void emit_vertices(Out &o, const PrimAttrs &a, const Xform &x, const std::string &pw)
{
    const size_t n = a.n, base = o.verts.size();
    o.verts.resize(base + n);
    if (a.col || !o.colors.empty()) o.colors.resize((base + n) * 4, 1.0f);
    const bool uv1_fresh = a.uv1 && o.uv1.empty();
    if (a.uv1 || !o.uv1.empty()) o.uv1.resize((base + n) * 2, 0.0f);
    pg_vertex *V = o.verts.data() + base;
    for (size_t i = 0; i < n; i++) {
        pg_vertex &vx = V[i];
        emit_position(a, x, i, pw, vx);
        if (a.nrm) emit_normal(*a.nrm, x, i, pw, vx);
        if (a.uv) {
            read_floats(*a.uv, i, vx.uv);
            check_finite(vx.uv, 2, *a.uv, "TEXCOORD_0", i);
        }
        if (a.col) {
            float q[4] = {1, 1, 1, 1}; /* VEC3: alpha 1 */
            read_floats(*a.col, i, q);
            check_finite(q, a.col->ncomp, *a.col, "COLOR_0", i);
            memcpy(&o.colors[(base + i) * 4], q, sizeof q);
        }
        if (a.uv1) {
            read_floats(*a.uv1, i, &o.uv1[(base + i) * 2]);
            check_finite(&o.uv1[(base + i) * 2], 2, *a.uv1, "TEXCOORD_1", i);
        }
        if (a.tan) emit_tangent(*a.tan, x, i, pw, vx);
    }
    /* TEXCOORD_1 of the vertices of primitives without it: a copy of their TEXCOORD_0 (what a
     * texture reading set 1 then samples, as when no primitive has TEXCOORD_1; warned) */
    if (!o.uv1.empty()) {
        const size_t from = uv1_fresh ? 0 : base, to = a.uv1 ? base : base + n;
        for (size_t j = from; j < to; j++) memcpy(&o.uv1[j * 2], o.verts[j].uv, sizeof(float[2]));
    }
}

/* meshes[mi].primitives[pi] under the node transform M appended to o: its mode (points and lines
 * skipped, counted), attributes, indices as a triangle list, vertices, missing normals and
 * tangents computed, the pg_primitive */
void emit_primitive(Ctx &c, Out &o, int mi, int pi, const Mat4 &M)
{
    const tinygltf::Primitive &prim = c.model.meshes[size_t(mi)].primitives[size_t(pi)];
    const std::string pw = strf("meshes[%d].primitives[%d]", mi, pi);
    int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP) {
        c.skipped_prims++;
        return;
    }
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
        gfail(strf("%s.mode: %d is not a glTF primitive mode", pw.c_str(), mode));

    decode_draco(c, mi, pi);
    PrimAttrs a;
    read_attributes(c, prim, pw, a);
    const size_t n = a.n;
    std::vector<uint32_t> ind = read_indices(c, prim, n, pw);
    to_triangle_list(mode, ind, pw);
    if (ind.empty() || n == 0) return;

    const Xform x = node_xform(M, pw);
    if (o.verts.size() + n > 0xFFFFFFF0ull || o.idx.size() + ind.size() > 0xFFFFFFF0ull ||
        o.verts.size() > 0x7FFFFFFFull)
        fail(PG_ERR_LIMIT, pw + ": scene exceeds 2^32 vertices or indices");
    const size_t base = o.verts.size();
    emit_vertices(o, a, x, pw);
    if (x.det < 0)
        for (size_t t = 0; t + 2 < ind.size(); t += 3) std::swap(ind[t + 1], ind[t + 2]);

    pg_vertex *V = o.verts.data() + base;
    if (!a.nrm) pg_mesh_compute_normals(V, uint32_t(n), ind.data(), uint32_t(ind.size()));
    bool normal_mapped = prim.material >= 0 &&
                         c.model.materials[size_t(prim.material)].normalTexture.index >= 0;
    if (!a.tan && normal_mapped)
        pg_mesh_compute_tangents(V, uint32_t(n), ind.data(), uint32_t(ind.size()));

    pg_primitive pr;
    memset(&pr, 0, sizeof pr);
    pr.first_index = uint32_t(o.idx.size());
    pr.index_count = uint32_t(ind.size());
    pr.vertex_offset = int32_t(base);
    pr.material = 0;
    o.idx.insert(o.idx.end(), ind.begin(), ind.end());
    o.prims.push_back(pr);
    o.prim_gltf_material.push_back(prim.material >= 0 ? uint32_t(prim.material) : UINT32_MAX);
    o.prim_has_uv1.push_back(a.uv1 != nullptr);
}

} // namespace pg_gltf
