/* scene_gltf_mesh.cpp - step 4 of the glTF load (scene_gltf.cpp): vertex attributes (their glTF and
 * KHR_mesh_quantization types) and primitives baked into vertices and indices under their node
 * transform (a moving primitive kept in mesh space too: scene_gltf_anim.cpp).
 */
#include "scene_gltf_internal.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <memory>

namespace pg_gltf {

/* ------------------------------------------------------------------------------------------ */
/* step 4: attributes, primitives                                                               */

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
static void emit_vertices(Out &o, const PrimAttrs &a, const uint32_t *src, size_t n, const Xform &x,
                          const std::string &pw)
{
    const size_t base = o.verts.size();
    o.verts.resize(base + n);
    if (a.col || !o.colors.empty()) o.colors.resize((base + n) * 4, 1.0f);
    const bool uv1_fresh = a.uv1 && o.uv1.empty();
    if (a.uv1 || !o.uv1.empty()) o.uv1.resize((base + n) * 2, 0.0f);
    pg_vertex *V = o.verts.data() + base;
    for (size_t i = 0; i < n; i++) {
        pg_vertex &vx = V[i];
        const size_t e = src ? src[i] : i; /* the accessors' element */
        emit_position(a, x, e, pw, vx);
        if (a.nrm) emit_normal(*a.nrm, x, e, pw, vx);
        if (a.uv) {
            read_floats(*a.uv, e, vx.uv);
            check_finite(vx.uv, 2, *a.uv, "TEXCOORD_0", e);
        }
        if (a.col) {
            float q[4] = {1, 1, 1, 1}; /* VEC3: alpha 1 */
            read_floats(*a.col, e, q);
            check_finite(q, a.col->ncomp, *a.col, "COLOR_0", e);
            memcpy(&o.colors[(base + i) * 4], q, sizeof q);
        }
        if (a.uv1) {
            read_floats(*a.uv1, e, &o.uv1[(base + i) * 2]);
            check_finite(&o.uv1[(base + i) * 2], 2, *a.uv1, "TEXCOORD_1", e);
        }
        /* without NORMAL the given tangents are ignored (glTF 2.0 3.7.2.1): computed with the normals */
        if (a.tan && a.nrm) emit_tangent(*a.tan, x, e, pw, vx);
    }
    /* TEXCOORD_1 of the vertices of primitives without it: a copy of their TEXCOORD_0 (what a
     * texture reading set 1 then samples, as when no primitive has TEXCOORD_1; warned) */
    if (!o.uv1.empty()) {
        const size_t from = uv1_fresh ? 0 : base, to = a.uv1 ? base : base + n;
        for (size_t j = from; j < to; j++) memcpy(&o.uv1[j * 2], o.verts[j].uv, sizeof(float[2]));
    }
}

/* A vertex emitted in mesh space moved to the world by x (the rest pose of a moving primitive). */
static void xform_in_place(const Xform &x, pg_vertex &v)
{
    const double *m = x.m;
    double p[3], n[3], t[3];
    for (int r = 0; r < 3; r++) {
        p[r] = m[r] * v.position[0] + m[4 + r] * v.position[1] + m[8 + r] * v.position[2] + m[12 + r];
        n[r] = x.nsign * (x.cof[r * 3 + 0] * v.normal[0] + x.cof[r * 3 + 1] * v.normal[1] + x.cof[r * 3 + 2] * v.normal[2]);
        t[r] = m[r] * v.tangent[0] + m[4 + r] * v.tangent[1] + m[8 + r] * v.tangent[2];
    }
    const double nl = std::hypot(n[0], n[1], n[2]), tl = std::hypot(t[0], t[1], t[2]);
    for (int r = 0; r < 3; r++) {
        v.position[r] = float(p[r]);
        v.normal[r] = nl > 1e-30 ? float(n[r] / nl) : (r == 1 ? 1.0f : 0.0f);
        v.tangent[r] = tl > 1e-30 ? float(t[r] / tl) : 0.0f;
    }
    v.tangent[3] = float(v.tangent[3] * x.nsign);
}

/* Morph targets of other attributes than POSITION, NORMAL, TANGENT (not applied), counted for the
 * warnings once per node that draws the primitive, as the skipped ones. */
static void count_unread(Ctx &c, const tinygltf::Primitive &prim)
{
    bool other = false;
    for (const auto &t : prim.targets)
        for (const auto &at : t)
            other = other || (at.first != "POSITION" && at.first != "NORMAL" && at.first != "TANGENT");
    c.morph_other_prims += other;
}

/* A decoded primitive, placed once per node or instance (place_primitive) */
struct Decoded {
    const tinygltf::Primitive *prim;
    std::string pw;
    PrimAttrs a;
    size_t n = 0;               /* the vertices placed */
    std::vector<uint32_t> ind;  /* a triangle list of them */
    std::vector<uint32_t> src;  /* vertex -> accessor element; empty: the same (flat normals unweld) */
};

/* Tangents for materials[mi]'s normal map from the texture coordinates it is sampled with (glTF 2.0
 * 3.7.2.1): its UV set (texCoord, or KHR_texture_transform's) under the extension's transform
 * (texture_transform, as the material will get it), put in the vertices' uv for
 * pg_mesh_compute_tangents, then the uv put back. */
static void tangents_for_normal_map(const Ctx &c, Out &o, int mi, size_t base, pg_vertex *V, size_t n,
                                   const std::vector<uint32_t> &tri)
{
    const std::string mw = strf("materials[%d]", mi);
    const json *ti = opt_object(c.j.at("materials").at(size_t(mi)), "normalTexture", mw);
    int set = c.model.materials[size_t(mi)].normalTexture.texCoord;
    float m[6] = {1, 0, 0, 0, 1, 0};
    if (ti) texture_transform(*ti, mw + ".normalTexture", m, &set);
    const bool uv1 = set == 1 && o.uv1.size() >= (base + n) * 2;
    std::vector<float> keep(2 * n);
    for (size_t i = 0; i < n; i++) {
        const float *uv = uv1 ? &o.uv1[(base + i) * 2] : V[i].uv;
        const float u = uv[0], v = uv[1];
        keep[2 * i] = V[i].uv[0], keep[2 * i + 1] = V[i].uv[1];
        V[i].uv[0] = m[0] * u + m[1] * v + m[2];
        V[i].uv[1] = m[3] * u + m[4] * v + m[5];
    }
    pg_mesh_compute_tangents(V, uint32_t(n), tri.data(), uint32_t(tri.size()));
    for (size_t i = 0; i < n; i++) V[i].uv[0] = keep[2 * i], V[i].uv[1] = keep[2 * i + 1];
}

/* one placement of d under M (x *inst when instanced) appended to o */
static void place_primitive(Ctx &c, Out &o, const Decoded &d, int mi, int pi, const Mat4 &M, int ni, bool moving,
                            const Mat4 *inst)
{
    const tinygltf::Primitive &prim = *d.prim;
    const std::string &pw = d.pw;
    const size_t n = d.n;
    std::vector<uint32_t> ind = d.ind;
    const bool skinned = ni >= 0 && c.model.nodes[size_t(ni)].skin >= 0 && find_attr(prim, "JOINTS_0") &&
                         find_attr(prim, "WEIGHTS_0");
    if (ni >= 0 && c.model.nodes[size_t(ni)].skin >= 0 && !skinned) c.unskinned_prims++;
    const bool dyn = c.animated && (moving || skinned || !prim.targets.empty());
    /* the placement: M, or M x the instance's transform; a moving primitive keeps the instance's
     * transform in its mesh-space vertices (the pose applies the node's) */
    const Mat4 MI = inst ? mat_mul(M, *inst) : M;
    const Xform x = node_xform(MI, pw);
    if (o.verts.size() + n > 0xFFFFFFF0ull || o.idx.size() + ind.size() > 0xFFFFFFF0ull ||
        o.verts.size() > 0x7FFFFFFFull)
        fail(PG_ERR_LIMIT, pw + ": scene exceeds 2^32 vertices or indices");
    const size_t base = o.verts.size();
    Mat4 ident{};
    ident.m[0] = ident.m[5] = ident.m[10] = ident.m[15] = 1.0;
    const Xform xe = dyn ? node_xform(inst ? *inst : ident, pw) : x; /* the space the vertices are emitted in */
    const uint32_t *src = d.src.empty() ? nullptr : d.src.data();
    emit_vertices(o, d.a, src, n, xe, pw);
    pg_vertex *V = o.verts.data() + base;
    {   /* normals and tangents with the winding the emitted vertices have (mesh space of a moving
         * primitive: its node's mirroring applies when it is placed) */
        std::vector<uint32_t> tri = ind;
        if (xe.det < 0 && !skinned)
            for (size_t t = 0; t + 2 < tri.size(); t += 3) std::swap(tri[t + 1], tri[t + 2]);
        if (!d.a.nrm) pg_mesh_compute_normals(V, uint32_t(n), tri.data(), uint32_t(tri.size()));
        if ((!d.a.tan || !d.a.nrm) && prim.material >= 0 &&
            c.model.materials[size_t(prim.material)].normalTexture.index >= 0)
            tangents_for_normal_map(c, o, prim.material, base, V, n, tri);
    }
    if (x.det < 0 && !skinned) /* a skinned mesh ignores its node's transform */
        for (size_t t = 0; t + 2 < ind.size(); t += 3) std::swap(ind[t + 1], ind[t + 2]);
    if (c.animated) {
        o.vertex_prim.resize(base + n, PG_ANIM_STATIC);
        o.local.resize(base + n);
    }
    if (dyn) {
        memcpy(o.local.data() + base, V, n * sizeof(pg_vertex));
        anim_primitive(c, o, prim, ni, base, n, src, d.a.n, pw);
        const Xform xn = inst ? node_xform(M, pw) : x;
        o.aprims.back().wound_mirrored = xn.det < 0 && !skinned; /* the winding `ind` gets below */
        for (size_t i = 0; i < n; i++) xform_in_place(xn, V[i]); /* the rest pose */
    }

    pg_primitive pr;
    memset(&pr, 0, sizeof pr);
    pr.first_index = uint32_t(o.idx.size());
    pr.index_count = uint32_t(ind.size());
    pr.vertex_offset = int32_t(base);
    pr.material = 0;
    o.idx.insert(o.idx.end(), ind.begin(), ind.end());
    o.prims.push_back(pr);
    const int material = variant_material(c, mi, pi, prim.material); /* KHR_materials_variants */
    o.prim_gltf_material.push_back(material >= 0 ? uint32_t(material) : UINT32_MAX);
    o.prim_has_uv1.push_back(d.a.uv1 != nullptr);
    o.prim_has_uv0.push_back(d.a.uv != nullptr);
}

/* meshes[mi].primitives[pi] under the node transform M appended to o: its mode (points and lines
 * skipped, counted), attributes, indices as a triangle list, vertices, missing normals and
 * tangents computed, the pg_primitive. A primitive that moves (Ctx.animated: on an animated node,
 * skinned or morphed) is emitted in mesh space first (normals and tangents computed there), kept in
 * o.local with its skin and morph data, then placed by M for the rest pose. With EXT_mesh_gpu_instancing
 * (instances) it is decoded once and placed once per instance, by M x the instance's transform (a
 * moving one's mesh space includes the instance's). */
void emit_primitive(Ctx &c, Out &o, int mi, int pi, const Mat4 &M, int ni, bool moving,
                    const std::vector<Mat4> *instances)
{
    Decoded d;
    d.prim = &c.model.meshes[size_t(mi)].primitives[size_t(pi)];
    const tinygltf::Primitive &prim = *d.prim;
    d.pw = strf("meshes[%d].primitives[%d]", mi, pi);
    const size_t placements = instances ? instances->size() : 1;
    int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP) {
        c.skipped_prims += unsigned(placements);
        return;
    }
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
        gfail(strf("%s.mode: %d is not a glTF primitive mode", d.pw.c_str(), mode));

    decode_draco(c, mi, pi);
    read_attributes(c, prim, d.pw, d.a);
    count_unread(c, prim);
    d.n = d.a.n;
    d.ind = read_indices(c, prim, d.n, d.pw);
    to_triangle_list(mode, d.ind, d.pw);
    if (d.ind.empty() || d.n == 0) return;
    if (!d.a.nrm) { /* glTF 2.0 3.7.2.1: without normals, flat ones: each triangle its own vertices */
        d.src = d.ind;
        for (size_t j = 0; j < d.ind.size(); j++) d.ind[j] = uint32_t(j);
        d.n = d.ind.size();
    }
    if (!instances) place_primitive(c, o, d, mi, pi, M, ni, moving, nullptr);
    else
        for (const Mat4 &I : *instances) place_primitive(c, o, d, mi, pi, M, ni, moving, &I);
}

} // namespace pg_gltf
