/* scene_gltf_compressed.cpp - compressed geometry of the glTF load (scene_gltf.cpp):
 * EXT_meshopt_compression bufferViews (step 3b, meshoptimizer) and KHR_draco_mesh_compression
 * primitives (step 4a, Draco).
 */
#include "scene_gltf_internal.h"

#include <draco/compression/decode.h>
#include <meshoptimizer.h>

#include <cstring>
#include <memory>

namespace pg_gltf {

/* ------------------------------------------------------------------------------------------ */
/* step 3b: EXT_meshopt_compression (prevalidate checked every parameter the decoders assert on:
 * ATTRIBUTES byteStride a multiple of 4 in 4..256, TRIANGLES/INDICES byteStride 2 or 4, TRIANGLES
 * count a multiple of 3, the filters' strides; the source range inside its buffer; count *
 * byteStride == the bufferView's byteLength). The decoders are safe on untrusted bytes.        */

constexpr uint64_t kMaxDecodedBytes = uint64_t(1) << 30;

const char *meshopt_rc(int rc)
{
    switch (rc) {
    case -1: return "unsupported encoding version";
    case -2: return "malformed or truncated data";
    case -3: return "data left over after the last element";
    default: return "decoding failed";
    }
}

void decode_meshopt(Ctx &c)
{
    uint64_t total = 0;
    for (const Ctx::Meshopt &m : c.meshopt) {
        const std::string mw = strf("bufferViews[%d].extensions.EXT_meshopt_compression", m.view);
        const uint64_t n = m.count * m.stride; /* no overflow: checked by prevalidate */
        total += n;
        if (total > kMaxDecodedBytes)
            fail(PG_ERR_LIMIT, strf("%s: decoded bufferViews exceed 1 GiB", mw.c_str()));
        const tinygltf::Buffer &buf = c.model.buffers[size_t(m.buffer)];
        if (m.offset > buf.data.size() || m.length > buf.data.size() - m.offset)
            gfail(strf("%s: byteOffset %llu + byteLength %llu exceeds buffers[%d] (%zu bytes)",
                       mw.c_str(), (unsigned long long)m.offset, (unsigned long long)m.length,
                       m.buffer, buf.data.size()));
        const unsigned char *src = buf.data.data() + m.offset;
        std::vector<unsigned char> out(n ? size_t(n) : 1); /* never a null destination */
        int rc = 0;
        const char *fn = "";
        switch (m.mode) {
        case 0:
            fn = "meshopt_decodeVertexBuffer";
            rc = meshopt_decodeVertexBuffer(out.data(), size_t(m.count), size_t(m.stride), src,
                                            size_t(m.length));
            break;
        case 1:
            fn = "meshopt_decodeIndexBuffer";
            rc = meshopt_decodeIndexBuffer(out.data(), size_t(m.count), size_t(m.stride), src,
                                           size_t(m.length));
            break;
        default:
            fn = "meshopt_decodeIndexSequence";
            rc = meshopt_decodeIndexSequence(out.data(), size_t(m.count), size_t(m.stride), src,
                                             size_t(m.length));
            break;
        }
        if (rc != 0)
            gfail(strf("%s: %s returned %d (%s)", mw.c_str(), fn, rc, meshopt_rc(rc)));
        if (m.count > 0) {
            if (m.filter == 1) meshopt_decodeFilterOct(out.data(), size_t(m.count), size_t(m.stride));
            if (m.filter == 2) meshopt_decodeFilterQuat(out.data(), size_t(m.count), size_t(m.stride));
            if (m.filter == 3) meshopt_decodeFilterExp(out.data(), size_t(m.count), size_t(m.stride));
        }
        out.resize(size_t(n));
        c.decoded[m.view].swap(out);
    }
}

/* ------------------------------------------------------------------------------------------ */
/* step 4a: KHR_draco_mesh_compression (prevalidate checked the extension's bufferView, that its
 * attribute ids are integers naming attributes the primitive has, and that it has indices). The
 * decoded points and faces become dense data of the primitive's accessors (their componentType,
 * type and count describe the decoded data), which get_view then reads instead of any bufferView
 * (the uncompressed fallback, if there is one, is not read).                                    */

template <class T>
void draco_fill(const draco::PointAttribute &pa, size_t np, int ncomp, unsigned char *out,
                const std::string &who)
{
    std::vector<T> tmp(static_cast<size_t>(ncomp));
    for (size_t i = 0; i < np; i++) {
        draco::AttributeValueIndex avi = pa.mapped_index(draco::PointIndex(uint32_t(i)));
        if (avi.value() >= pa.size() || !pa.ConvertValue<T>(avi, int8_t(ncomp), tmp.data()))
            gfail(strf("%s: cannot read point %zu of the Draco attribute", who.c_str(), i));
        memcpy(out + i * sizeof(T) * size_t(ncomp), tmp.data(), sizeof(T) * size_t(ncomp));
    }
}

void decode_draco(Ctx &c, int mi, int pi)
{
    if (c.draco_done.count({mi, pi})) return;
    c.draco_done[{mi, pi}] = true;
    const json &pj = c.j["meshes"][size_t(mi)]["primitives"][size_t(pi)];
    auto ex = pj.find("extensions");
    if (ex == pj.end()) return;
    auto dr = ex->find("KHR_draco_mesh_compression");
    if (dr == ex->end()) return;
    const tinygltf::Primitive &prim = c.model.meshes[size_t(mi)].primitives[size_t(pi)];
    const std::string dw =
        strf("meshes[%d].primitives[%d].extensions.KHR_draco_mesh_compression", mi, pi);
    const int bvi = (*dr)["bufferView"].get<int>();
    auto bytes = view_bytes(c, bvi, dw);
    draco::DecoderBuffer db;
    db.Init(reinterpret_cast<const char *>(bytes.first), bytes.second);
    auto gt = draco::Decoder::GetEncodedGeometryType(&db);
    if (!gt.ok())
        gfail(strf("%s: bufferViews[%d] is not Draco data (%s)", dw.c_str(), bvi,
                   gt.status().error_msg()));
    if (gt.value() != draco::TRIANGULAR_MESH)
        gfail(strf("%s: bufferViews[%d] holds a Draco point cloud, not a triangle mesh", dw.c_str(),
                   bvi));
    draco::Decoder dec;
    auto r = dec.DecodeMeshFromBuffer(&db);
    if (!r.ok())
        gfail(strf("%s: Draco decoding of bufferViews[%d] failed (%s)", dw.c_str(), bvi,
                   r.status().error_msg()));
    std::unique_ptr<draco::Mesh> mesh = std::move(r).value();
    if (!mesh) gfail(strf("%s: Draco decoding of bufferViews[%d] failed", dw.c_str(), bvi));
    const size_t np = mesh->num_points(), nf = mesh->num_faces();
    auto claim = [&](int ai) -> std::vector<unsigned char> * {
        auto owner = c.draco_view.find(ai);
        if (owner != c.draco_view.end()) {
            if (owner->second != bvi)
                gfail(strf("accessors[%d]: used by Draco primitives of different bufferViews (%d, "
                           "%d)",
                           ai, owner->second, bvi));
            return nullptr; /* already decoded from the same data */
        }
        c.draco_view[ai] = bvi;
        return &c.draco_data[ai];
    };
    const json &attrs = (*dr)["attributes"];
    for (auto it = attrs.begin(); it != attrs.end(); ++it) {
        const std::string &sem = it.key();
        const std::string aw = dw + ".attributes." + sem.substr(0, 40);
        const int *ai = find_attr(prim, sem.c_str());
        if (!ai || *ai < 0 || size_t(*ai) >= c.model.accessors.size())
            gfail(aw + ": the primitive has no such attribute");
        const tinygltf::Accessor &a = c.model.accessors[size_t(*ai)];
        const int uid = it->get<int>();
        const draco::PointAttribute *pa = mesh->GetAttributeByUniqueId(uint32_t(uid));
        if (!pa) gfail(strf("%s: the Draco data has no attribute with unique id %d", aw.c_str(), uid));
        if (a.count != np)
            gfail(strf("accessors[%d]: count %zu, but the Draco data of %s has %zu points", *ai,
                       a.count, sem.substr(0, 40).c_str(), np));
        const int ncomp = type_comps(a.type);
        const size_t csize = ctype_size(a.componentType);
        if (!ncomp || !csize || ncomp > 16)
            gfail(strf("accessors[%d]: invalid componentType %d or type", *ai, a.componentType));
        if (uint64_t(np) * csize * size_t(ncomp) > kMaxDecodedBytes)
            fail(PG_ERR_LIMIT, strf("%s: decoded attribute exceeds 1 GiB", aw.c_str()));
        std::vector<unsigned char> *out = claim(*ai);
        if (!out) continue;
        out->assign(np * csize * size_t(ncomp), 0);
        const std::string who = strf("%s (accessors[%d])", aw.c_str(), *ai);
        switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: draco_fill<int8_t>(*pa, np, ncomp, out->data(), who); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: draco_fill<uint8_t>(*pa, np, ncomp, out->data(), who); break;
        case TINYGLTF_COMPONENT_TYPE_SHORT: draco_fill<int16_t>(*pa, np, ncomp, out->data(), who); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: draco_fill<uint16_t>(*pa, np, ncomp, out->data(), who); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: draco_fill<uint32_t>(*pa, np, ncomp, out->data(), who); break;
        default: draco_fill<float>(*pa, np, ncomp, out->data(), who); break;
        }
    }
    /* indices from the faces */
    const int ii = prim.indices;
    if (ii < 0 || size_t(ii) >= c.model.accessors.size()) gfail(dw + ": the primitive has no indices");
    const tinygltf::Accessor &ia = c.model.accessors[size_t(ii)];
    if (nf > kMaxDecodedBytes / 12 || ia.count != nf * 3)
        gfail(strf("accessors[%d]: count %zu, but the Draco data has %zu triangles (%zu indices)", ii,
                   ia.count, nf, nf * 3));
    const size_t isz = ctype_size(ia.componentType);
    if (ia.type != TINYGLTF_TYPE_SCALAR ||
        (ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        gfail(strf("accessors[%d]: indices must be SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or "
                   "UNSIGNED_INT",
                   ii));
    std::vector<unsigned char> *out = claim(ii);
    if (!out) return;
    out->assign(nf * 3 * isz, 0);
    const uint64_t imax = isz == 1 ? 0xFFu : isz == 2 ? 0xFFFFu : 0xFFFFFFFFu;
    for (size_t f = 0; f < nf; f++) {
        const draco::Mesh::Face &face = mesh->face(draco::FaceIndex(uint32_t(f)));
        for (int k = 0; k < 3; k++) {
            uint64_t x = face[k].value();
            if (x >= np || x > imax)
                gfail(strf("%s: Draco face %zu has point %llu (%zu points, %s indices)", dw.c_str(), f,
                           (unsigned long long)x, np, ctype_name(ia.componentType)));
            uint32_t v = uint32_t(x);
            memcpy(out->data() + (f * 3 + size_t(k)) * isz, &v, isz); /* little-endian */
        }
    }
}

} // namespace pg_gltf
