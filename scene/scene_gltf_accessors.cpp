/* scene_gltf_accessors.cpp - step 4 of the glTF load (scene_gltf.cpp): accessors as range-checked
 * views (sparse accessors substituted, Draco and meshopt data read where they were decoded) and
 * their elements as numbers, for the mesh (scene_gltf_mesh.cpp) and animation (scene_gltf_anim.cpp)
 * readers.
 */
#include "scene_gltf_internal.h"

#include <algorithm>
#include <cstring>

namespace pg_gltf {

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



uint32_t read_index(const View &v, size_t i)
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
static void apply_sparse(Ctx &c, int ai, const tinygltf::Accessor &a, View &v, size_t elem)
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

/* Reads element i as floats, converted as glTF 2.0 and KHR_mesh_quantization say: FLOAT as is;
 * normalized UNSIGNED_BYTE c / 255, UNSIGNED_SHORT c / 65535, BYTE max(c / 127, -1), SHORT
 * max(c / 32767, -1); not normalized: the integer value. */
void read_floats(const View &v, size_t i, float *out)
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

void view_floats(const View &v, size_t i, float *out)
{
    read_floats(v, i, out);
}

} // namespace pg_gltf
