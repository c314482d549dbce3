/* scene_gltf_validate.cpp - step 2 of the glTF load (scene_gltf.cpp): the JSON pre-validation
 * that must hold before tinygltf sees the file, and the glTF extensions passgraph implements.
 */
#include "scene_gltf_internal.h"
#include "pg_file.h"
#include "scenario.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include <cmath>
#include <cstdio>
#include <string>

namespace pg_gltf {

/* The glTF extensions passgraph implements: accepted in extensionsRequired, not warned in
 * extensionsUsed. */
constexpr const char *kImplementedExtensions[] = {"EXT_mesh_gpu_instancing", "EXT_meshopt_compression",
                                                  "EXT_texture_webp", "KHR_draco_mesh_compression",
                                                  "KHR_lights_punctual", "KHR_materials_emissive_strength",
                                                  "KHR_materials_unlit", "KHR_materials_variants",
                                                  "KHR_mesh_quantization", "KHR_texture_transform",
                                                  "PASSGRAPH_lights_table"};
bool extension_implemented(const std::string &e)
{
    for (const char *x : kImplementedExtensions)
        if (e == x) return true;
    return false;
}

/* ------------------------------------------------------------------------------------------ */
/* step 2: JSON pre-validation                                                                  */

/* tinygltf converts `extras`/`extensions` recursively: bound the nesting before any parser runs
 * (a non-recursive scan of the text, strings skipped). */
constexpr int kMaxJsonDepth = 200;

void check_json_depth(const std::string &t)
{
    int depth = 0;
    bool in_str = false;
    for (size_t i = 0; i < t.size(); i++) {
        char ch = t[i];
        if (in_str) {
            if (ch == '\\') i++;
            else if (ch == '"') in_str = false;
        } else if (ch == '"') {
            in_str = true;
        } else if (ch == '[' || ch == '{') {
            if (++depth > kMaxJsonDepth)
                fail(PG_ERR_LIMIT, strf("JSON nesting deeper than %d levels (at byte %zu)",
                                        kMaxJsonDepth, i));
        } else if (ch == ']' || ch == '}') {
            depth--;
        }
    }
}

const json *opt_array(const json &o, const char *key, const std::string &where)
{
    auto it = o.find(key);
    if (it == o.end()) return nullptr;
    if (!it->is_array())
        gfail(where.empty() ? strf("%s: expected an array", key)
                            : strf("%s.%s: expected an array", where.c_str(), key));
    return &*it;
}

const json *opt_object(const json &o, const char *key, const std::string &where)
{
    auto it = o.find(key);
    if (it == o.end()) return nullptr;
    if (!it->is_object()) gfail(strf("%s.%s: expected an object", where.c_str(), key));
    return &*it;
}

size_t arr_size(const json *a) { return a ? a->size() : 0; }

/* An index into an array of n objects called `plural`; -1 when absent and optional. */
long long ref(const json &o, const char *key, size_t n, const char *plural,
              const std::string &where_, bool required)
{
    /* messages read "WHERE.KEY: ..." (or "KEY: ..." at the root) */
    const std::string where = where_.empty() ? std::string() : where_;
    if (where.empty()) {
        auto it = o.find(key);
        if (it == o.end()) {
            if (required) gfail(strf("%s: missing (required)", key));
            return -1;
        }
        if (!it->is_number_unsigned() || it->get<uint64_t>() >= n)
            gfail(strf("%s: %s is not a valid index (%zu %s)", key, it->dump().c_str(), n, plural));
        return (long long)it->get<uint64_t>();
    }
    auto it = o.find(key);
    if (it == o.end()) {
        if (required) gfail(strf("%s.%s: missing (required)", where.c_str(), key));
        return -1;
    }
    if (!it->is_number_integer())
        gfail(strf("%s.%s: expected an index (a non-negative integer)", where.c_str(), key));
    if (it->is_number_unsigned()) {
        uint64_t u = it->get<uint64_t>();
        if (u >= n)
            gfail(strf("%s.%s: %s index %llu out of range (%zu %s)", where.c_str(), key, plural,
                       (unsigned long long)u, n, plural));
        return (long long)u;
    }
    long long v = it->get<long long>();
    gfail(strf("%s.%s: %s index %lld is negative", where.c_str(), key, plural, v));
}

/* A non-negative integer field (byteLength, byteOffset, count...); `def` when absent. */
uint64_t uint_field(const json &o, const char *key, const std::string &where, bool required,
                    uint64_t def)
{
    auto it = o.find(key);
    if (it == o.end()) {
        if (required) gfail(strf("%s.%s: missing (required)", where.c_str(), key));
        return def;
    }
    if (!it->is_number_unsigned())
        gfail(strf("%s.%s: expected a non-negative integer", where.c_str(), key));
    return it->get<uint64_t>();
}

/* An external buffer or image file: stat-checked (a FIFO, a device, a directory is named as
 * such; never opened here), each under PG_FILE_CAP_GLTF_RESOURCE and all of them together under
 * PG_FILE_CAP_GLTF_TOTAL (*total). Missing: "W: cannot open 'URI' (FILE)". */
uint64_t check_resource_file(const std::string &w, const std::string &uri, const std::string &file,
                             const char *kind, uint64_t *total)
{
    struct stat st;
    if (stat(file.c_str(), &st) != 0)
        gfail(strf("%s: cannot open '%s' (%s): %s", w.c_str(), uri.c_str(), file.c_str(), strerror(errno)));
    pg_error e;
    memset(&e, 0, sizeof e);
    uint64_t size = 0;
    if (pg_file_check(file.c_str(), kind, PG_FILE_CAP_GLTF_RESOURCE, &size, &e) != PG_OK) {
        std::string m = e.msg;
        size_t k = m.find("': ");
        gfail(strf("%s: '%s' (%s) %s", w.c_str(), uri.c_str(), file.c_str(),
                   k == std::string::npos ? m.c_str() : m.c_str() + k + 3));
    }
    *total += size;
    if (*total > PG_FILE_CAP_GLTF_TOTAL) {
        char t[32];
        pg_file_fmt_size(*total, t, sizeof t);
        gfail(strf("%s: '%s': the external buffers and images come to %s, over the %llu GiB cap "
                   "for one scene", w.c_str(), uri.c_str(), t,
                   (unsigned long long)(PG_FILE_CAP_GLTF_TOTAL / (1024ull * PG_MIB))));
    }
    return size;
}

bool is_regular_file(const std::string &p, uint64_t *size)
{
    struct stat st;
    if (stat(p.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
    if (size) *size = (uint64_t)st.st_size;
    return true;
}


/* emissiveFactor: 3 finite numbers >= 0; KHR_materials_emissive_strength.emissiveStrength: a
 * finite number >= 0 (materials[i] is `w`). */
void check_emissive(const json &o, const std::string &w)
{
    auto it = o.find("emissiveFactor");
    if (it != o.end()) {
        bool ok = it->is_array() && it->size() == 3;
        if (ok)
            for (const auto &x : *it)
                ok = ok && x.is_number() && std::isfinite(x.get<double>()) && x.get<double>() >= 0;
        if (!ok) gfail(w + ".emissiveFactor: expected 3 finite numbers >= 0, got " + it->dump().substr(0, 80));
    }
    const json *ext = opt_object(o, "extensions", w);
    const json *es = ext ? opt_object(*ext, "KHR_materials_emissive_strength", w + ".extensions") : nullptr;
    if (!es) return;
    auto st = es->find("emissiveStrength");
    if (st != es->end() && !(st->is_number() && std::isfinite(st->get<double>()) && st->get<double>() >= 0))
        gfail(w + ".extensions.KHR_materials_emissive_strength.emissiveStrength: expected a finite number >= 0, got " +
              st->dump().substr(0, 80));
}

/* asset.version 2.x (and minVersion 2.0 when given) */
static void check_asset(const json &j)
{
    auto ait = j.find("asset");
    if (ait == j.end() || !ait->is_object()) gfail("asset: missing (required)");
    auto vit = ait->find("version");
    if (vit == ait->end() || !vit->is_string()) gfail("asset.version: missing (required)");
    std::string ver = vit->get<std::string>();
    if (ver.compare(0, 2, "1.") == 0)
        gfail(strf("asset.version: '%s': glTF 1.0 is not supported, only 2.0", ver.c_str()));
    if (ver.compare(0, 2, "2.") != 0)
        gfail(strf("asset.version: '%s' is not supported (glTF 2.x only)", ver.c_str()));
    auto mvit = ait->find("minVersion");
    if (mvit != ait->end() && mvit->is_string() && mvit->get<std::string>() != "2.0")
        gfail(strf("asset.minVersion: '%s' is not supported",
                   mvit->get<std::string>().c_str()));
}

/* a required extension passgraph does not implement is refused, naming each */
static void check_required_extensions(const json &j)
{
    const json *req = opt_array(j, "extensionsRequired", "");
    if (!req) return;
    std::string names;
    size_t n_unsup = 0;
    for (const json &e : *req) {
        if (e.is_string() && extension_implemented(e.get<std::string>())) continue;
        if (!names.empty()) names += ", ";
        names += "'" + (e.is_string() ? e.get<std::string>() : e.dump()) + "'";
        n_unsup++;
    }
    if (n_unsup) {
        std::string impl;
        for (const char *x : kImplementedExtensions) impl += std::string(impl.empty() ? "" : ", ") + x;
        gfail(strf("extensionsRequired: %s %s not supported (passgraph implements only these glTF "
                   "extensions: %s)",
                   names.c_str(), n_unsup == 1 ? "is" : "are", impl.c_str()));
    }
}

/* The root's arrays (null when absent), and what the earlier steps learnt for the later ones. */
struct Arrays {
    const json *buffers, *views, *accessors, *meshes, *nodes, *scenes, *materials, *textures,
        *images, *samplers;
    std::vector<uint64_t> buf_len; /* byteLength per buffer */
    uint64_t ext_total = 0;        /* bytes of the external buffers and images */
    size_t image_index = 0;        /* the image check_image is checking */
};

/* fn(object, "NAME[i]", i) for each element of the array `a` (if any), each an object */
template <typename Fn> static void each_object(const json *a, const char *name, Fn fn)
{
    if (!a) return;
    for (size_t i = 0; i < a->size(); i++) {
        const json &o = (*a)[i];
        std::string where = strf("%s[%zu]", name, i);
        if (!o.is_object()) gfail(where + ": expected an object");
        fn(o, where, i);
    }
}

/* buffers[i].extensions.EXT_meshopt_compression.fallback (false when absent) */
static bool buffer_is_fallback(const json &o, const std::string &w)
{
    if (const json *ex = opt_object(o, "extensions", w))
        if (const json *mo = opt_object(*ex, "EXT_meshopt_compression", w + ".extensions")) {
            auto fb = mo->find("fallback");
            if (fb != mo->end() && !fb->is_boolean())
                gfail(w + ".extensions.EXT_meshopt_compression.fallback: expected true or false");
            return fb != mo->end() && fb->get<bool>();
        }
    return false;
}

/* buffers: present with exactly byteLength bytes */
static void check_buffer(Ctx &c, Arrays &a, const json &o, const std::string &w)
{
    uint64_t len = uint_field(o, "byteLength", w, true);
    a.buf_len.push_back(len);
    auto uit = o.find("uri");
    bool fallback = buffer_is_fallback(o, w);
    /* a fallback buffer is never loaded (only compressed bufferViews may use it, and those
     * are read from their decoded data), so its uri may be missing or name no file */
    c.buffer_no_data.push_back(fallback);
    if (fallback) return;
    if (uit == o.end()) {
        if (!c.is_glb) gfail(w + ".uri: missing (required outside .glb files)");
        if (a.buf_len.size() > 1) gfail(w + ".uri: missing (only buffers[0] may refer to the GLB BIN chunk)");
        if (!c.glb_has_bin) gfail(w + ": refers to the GLB BIN chunk, but there is none");
        if (len > c.glb_bin_size)
            gfail(strf("%s: byteLength %llu exceeds the GLB BIN chunk (%zu bytes)", w.c_str(),
                       (unsigned long long)len, c.glb_bin_size));
        return;
    }
    if (!uit->is_string()) gfail(w + ".uri: expected a string");
    std::string uri = uit->get<std::string>();
    if (uri.compare(0, 5, "data:") == 0) {
        if (!tinygltf::IsDataURI(uri))
            gfail(w + ".uri: unsupported data URI (need ;base64 and a known media type)");
        std::vector<unsigned char> tmp;
        std::string mime;
        if (!tinygltf::DecodeDataURI(&tmp, mime, uri, 0, false))
            gfail(w + ".uri: data URI holds no data");
        if (tmp.size() != len)
            gfail(strf("%s: data URI holds %zu bytes but byteLength is %llu", w.c_str(),
                       tmp.size(), (unsigned long long)len));
        return;
    }
    if (uri.empty()) gfail(w + ".uri: empty");
    std::string file = join_path(c.base_dir, url_decode(uri));
    uint64_t fsize = check_resource_file(w, uri, file, "glTF buffer", &a.ext_total);
    if (fsize != len)
        gfail(strf("%s: '%s' has %llu bytes but byteLength is %llu", w.c_str(), uri.c_str(),
                   (unsigned long long)fsize, (unsigned long long)len));
}

/* EXT_meshopt_compression's mode and filter names (the indices of Ctx::Meshopt::mode/filter) */
static const char *const kMeshoptModes[] = {"ATTRIBUTES", "TRIANGLES", "INDICES"};
static const char *const kMeshoptFilters[] = {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"};

/* the string field KEY of the extension object `mo` (at `mw`); "NONE" when absent and optional */
static std::string meshopt_string(const json &mo, const std::string &mw, const char *key,
                                  bool required)
{
    auto it = mo.find(key);
    if (it == mo.end()) {
        if (required) gfail(strf("%s.%s: missing (required)", mw.c_str(), key));
        return "NONE";
    }
    if (!it->is_string()) gfail(strf("%s.%s: expected a string", mw.c_str(), key));
    return it->get<std::string>();
}

/* mode and filter: known names, and the byteStride and count each needs; count * byteStride is
 * the compressed view's byteLength `len` */
static void check_meshopt_mode(Ctx::Meshopt &m, const json &mo, const std::string &mw,
                               uint64_t len)
{
    const std::string mode = meshopt_string(mo, mw, "mode", true);
    const std::string filter = meshopt_string(mo, mw, "filter", false);
    m.mode = m.filter = -1;
    for (int k = 0; k < 3; k++)
        if (mode == kMeshoptModes[k]) m.mode = k;
    for (int k = 0; k < 4; k++)
        if (filter == kMeshoptFilters[k]) m.filter = k;
    if (m.mode < 0)
        gfail(strf("%s.mode: '%s' is not ATTRIBUTES, TRIANGLES or INDICES", mw.c_str(),
                   mode.substr(0, 40).c_str()));
    if (m.filter < 0)
        gfail(strf("%s.filter: '%s' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL",
                   mw.c_str(), filter.substr(0, 40).c_str()));
    const uint64_t st = m.stride;
    if (m.mode == 0 && (st < 4 || st > 256 || st % 4))
        gfail(strf("%s.byteStride: %llu is not a multiple of 4 in 4..256 (ATTRIBUTES)",
                   mw.c_str(), (unsigned long long)st));
    if (m.mode != 0 && st != 2 && st != 4)
        gfail(strf("%s.byteStride: %llu is not 2 or 4 (%s)", mw.c_str(),
                   (unsigned long long)st, kMeshoptModes[m.mode]));
    if (m.mode == 1 && m.count % 3)
        gfail(strf("%s.count: %llu is not a multiple of 3 (TRIANGLES)", mw.c_str(),
                   (unsigned long long)m.count));
    if (m.filter != 0 && m.mode != 0)
        gfail(strf("%s.filter: %s needs mode ATTRIBUTES", mw.c_str(), kMeshoptFilters[m.filter]));
    if ((m.filter == 1 && st != 4 && st != 8) || (m.filter == 2 && st != 8))
        gfail(strf("%s.filter: %s needs byteStride %s (got %llu)", mw.c_str(),
                   kMeshoptFilters[m.filter], m.filter == 1 ? "4 or 8" : "8",
                   (unsigned long long)st));
    if (m.count > UINT64_MAX / st || m.count * st != len)
        gfail(strf("%s: count %llu * byteStride %llu is not the bufferView's byteLength %llu",
                   mw.c_str(), (unsigned long long)m.count, (unsigned long long)st,
                   (unsigned long long)len));
}

/* bufferViews[vi].extensions.EXT_meshopt_compression (`mo`): its source range inside a loaded
 * buffer, its mode and filter; recorded in c.meshopt */
static void check_meshopt_view(Ctx &c, const Arrays &a, const json &mo, const std::string &w,
                               size_t vi, uint64_t len)
{
    const std::string mw = w + ".extensions.EXT_meshopt_compression";
    Ctx::Meshopt m;
    m.view = int(vi);
    m.buffer = int(ref(mo, "buffer", arr_size(a.buffers), "buffers", mw, true));
    m.offset = uint_field(mo, "byteOffset", mw, false, 0);
    m.length = uint_field(mo, "byteLength", mw, true);
    m.stride = uint_field(mo, "byteStride", mw, true);
    m.count = uint_field(mo, "count", mw, true);
    if (c.buffer_no_data[size_t(m.buffer)])
        gfail(strf("%s.buffer: buffers[%d] is a fallback buffer (never loaded)", mw.c_str(),
                   m.buffer));
    const uint64_t sl = a.buf_len[size_t(m.buffer)];
    if (m.offset > sl || m.length > sl - m.offset)
        gfail(strf("%s: byteOffset %llu + byteLength %llu exceeds buffers[%d] (%llu bytes)",
                   mw.c_str(), (unsigned long long)m.offset, (unsigned long long)m.length,
                   m.buffer, (unsigned long long)sl));
    check_meshopt_mode(m, mo, mw, len);
    c.meshopt.push_back(m);
}

/* bufferViews inside their buffers; EXT_meshopt_compression parameters */
static void check_buffer_view(Ctx &c, const Arrays &a, const json &o, const std::string &w,
                              size_t vi)
{
    long long b = ref(o, "buffer", arr_size(a.buffers), "buffers", w, true);
    uint64_t off = uint_field(o, "byteOffset", w, false, 0);
    uint64_t len = uint_field(o, "byteLength", w, true);
    if (off > a.buf_len[(size_t)b] || len > a.buf_len[(size_t)b] - off)
        gfail(strf("%s: byteOffset %llu + byteLength %llu exceeds buffers[%lld] (%llu bytes)",
                   w.c_str(), (unsigned long long)off, (unsigned long long)len, b,
                   (unsigned long long)a.buf_len[(size_t)b]));
    if (o.contains("byteStride")) {
        uint64_t s = uint_field(o, "byteStride", w, false, 0);
        if (s < 4 || s > 252 || s % 4)
            gfail(strf("%s.byteStride: %llu is not a multiple of 4 in 4..252", w.c_str(),
                       (unsigned long long)s));
    }
    const json *mo = nullptr;
    if (const json *ex = opt_object(o, "extensions", w))
        mo = opt_object(*ex, "EXT_meshopt_compression", w + ".extensions");
    c.view_is_meshopt.push_back(mo != nullptr);
    if (!mo) {
        if (c.buffer_no_data[(size_t)b])
            gfail(strf("%s: uses buffers[%lld], an EXT_meshopt_compression fallback buffer "
                       "(never loaded), but is not compressed",
                       w.c_str(), b));
        return;
    }
    check_meshopt_view(c, a, *mo, w, vi, len);
}

/* accessors[i].sparse: count, indices and values (ranges are checked when a primitive uses the
 * accessor, in get_view) */
static void check_sparse(const Arrays &a, const json &sp, const std::string &sw)
{
    uint_field(sp, "count", sw, true);
    const json *si = opt_object(sp, "indices", sw);
    const json *sv = opt_object(sp, "values", sw);
    if (!si) gfail(sw + ".indices: missing (required)");
    if (!sv) gfail(sw + ".values: missing (required)");
    ref(*si, "bufferView", arr_size(a.views), "bufferViews", sw + ".indices", true);
    uint_field(*si, "byteOffset", sw + ".indices", false, 0);
    uint64_t ict = uint_field(*si, "componentType", sw + ".indices", true);
    if (ict != 5121 && ict != 5123 && ict != 5125)
        gfail(strf("%s.indices.componentType: %llu is not UNSIGNED_BYTE, UNSIGNED_SHORT or "
                   "UNSIGNED_INT",
                   sw.c_str(), (unsigned long long)ict));
    ref(*sv, "bufferView", arr_size(a.views), "bufferViews", sw + ".values", true);
    uint_field(*sv, "byteOffset", sw + ".values", false, 0);
}

static void check_accessor(const Arrays &a, const json &o, const std::string &w)
{
    ref(o, "bufferView", arr_size(a.views), "bufferViews", w, false);
    uint_field(o, "byteOffset", w, false, 0);
    uint_field(o, "count", w, true);
    uint64_t ct = uint_field(o, "componentType", w, true);
    if (!(ct == 5120 || ct == 5121 || ct == 5122 || ct == 5123 || ct == 5125 || ct == 5126))
        gfail(strf("%s.componentType: %llu is not a glTF component type", w.c_str(),
                   (unsigned long long)ct));
    auto t = o.find("type");
    static const char *types[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
    bool ok = false;
    if (t != o.end() && t->is_string())
        for (const char *ty : types) ok = ok || t->get<std::string>() == ty;
    if (!ok) gfail(w + ".type: missing or not SCALAR/VEC2/VEC3/VEC4/MAT2/MAT3/MAT4");
    if (const json *sp = opt_object(o, "sparse", w)) check_sparse(a, *sp, w + ".sparse");
}

/* images: a bufferView (not a compressed one) or a uri (a data URI, or a non-empty file) */
static void check_image(Ctx &c, Arrays &a, const json &o, const std::string &w)
{
    long long bv = ref(o, "bufferView", arr_size(a.views), "bufferViews", w, false);
    auto uit = o.find("uri");
    if (bv >= 0 && uit != o.end()) gfail(w + ": has both uri and bufferView");
    if (bv >= 0 && c.view_is_meshopt[size_t(bv)])
        gfail(strf("%s.bufferView: bufferViews[%lld] is EXT_meshopt_compression compressed "
                   "(images cannot be)",
                   w.c_str(), bv));
    if (bv < 0 && uit == o.end()) gfail(w + ": has neither uri nor bufferView");
    if (uit == o.end()) return;
    if (!uit->is_string()) gfail(w + ".uri: expected a string");
    std::string uri = uit->get<std::string>();
    if (uri.compare(0, 5, "data:") == 0) {
        static const char *const texture_media[] = {"data:image/webp;base64,", "data:image/ktx2;base64,",
                                                    "data:image/vnd-ms.dds;base64,", "data:image/avif;base64,"};
        for (const char *m : texture_media)
            if (uri.compare(0, strlen(m), m) == 0) {
                c.image_media_rewrite.push_back(a.image_index); /* for tinygltf: application/octet-stream */
                return;
            }
        if (!tinygltf::IsDataURI(uri)) gfail(w + ".uri: unsupported data URI media type");
        return;
    }
    if (uri.empty()) gfail(w + ".uri: empty");
    std::string file = join_path(c.base_dir, url_decode(uri));
    uint64_t fsize = check_resource_file(w, uri, file, "glTF image", &a.ext_total);
    if (fsize == 0) gfail(strf("%s: '%s' is empty", w.c_str(), uri.c_str()));
}

/* o.key: absent, or a number in [0, 1] (n 0) or n of them (the specification's ranges of the
 * metallic-roughness factors) */
static void check_unit_numbers(const json &o, const char *key, size_t n, const std::string &w)
{
    auto it = o.find(key);
    if (it == o.end()) return;
    bool ok = n ? it->is_array() && it->size() == n : it->is_number();
    if (ok && n)
        for (const auto &x : *it) ok = ok && x.is_number() && x.get<double>() >= 0 && x.get<double>() <= 1;
    else if (ok)
        ok = it->get<double>() >= 0 && it->get<double>() <= 1;
    if (!ok)
        gfail(strf("%s.%s: expected %s in [0, 1], got %s", w.c_str(), key, n ? strf("%zu numbers", n).c_str() : "a number",
                   it->dump().substr(0, 80).c_str()));
}

/* o.key: absent, or a finite number (a normal texture's scale) */
static void check_number(const json &o, const char *key, const std::string &w)
{
    auto it = o.find(key);
    if (it != o.end() && !(it->is_number() && std::isfinite(it->get<double>())))
        gfail(strf("%s.%s: expected a number, got %s", w.c_str(), key, it->dump().substr(0, 80).c_str()));
}

/* a material's textureInfo KEY of `o` (at `w`), if any: its index, its texCoord (a non-negative
 * integer), a normal texture's scale, an occlusion texture's strength in [0, 1] */
static void check_texture_info(const json &o, const char *key, size_t n_textures, const std::string &w)
{
    const json *ti = opt_object(o, key, w);
    if (!ti) return;
    const std::string tw = w + "." + key;
    ref(*ti, "index", n_textures, "textures", tw, true);
    uint_field(*ti, "texCoord", tw, false, 0);
    if (!strcmp(key, "normalTexture")) check_number(*ti, "scale", tw);
    if (!strcmp(key, "occlusionTexture")) check_unit_numbers(*ti, "strength", 0, tw);
}

static void check_material(const Arrays &a, const json &o, const std::string &w)
{
    const size_t nt = arr_size(a.textures);
    if (const json *pbr = opt_object(o, "pbrMetallicRoughness", w)) {
        const std::string pw = w + ".pbrMetallicRoughness";
        check_texture_info(*pbr, "baseColorTexture", nt, pw);
        check_texture_info(*pbr, "metallicRoughnessTexture", nt, pw);
    }
    for (const char *k : {"normalTexture", "occlusionTexture", "emissiveTexture"}) check_texture_info(o, k, nt, w);
    check_number(o, "alphaCutoff", w);
    auto ds = o.find("doubleSided");
    if (ds != o.end() && !ds->is_boolean())
        gfail(strf("%s.doubleSided: expected true or false, got %s", w.c_str(), ds->dump().substr(0, 80).c_str()));
    if (const json *ex = opt_object(o, "extensions", w)) {
        auto u = ex->find("KHR_materials_unlit");
        if (u != ex->end() && !u->is_object())
            gfail(w + ".extensions.KHR_materials_unlit: expected an object (empty: {})");
    }
    check_emissive(o, w);
    if (const json *pbr = opt_object(o, "pbrMetallicRoughness", w)) {
        const std::string pw = w + ".pbrMetallicRoughness";
        check_unit_numbers(*pbr, "baseColorFactor", 4, pw);
        check_unit_numbers(*pbr, "metallicFactor", 0, pw);
        check_unit_numbers(*pbr, "roughnessFactor", 0, pw);
    }
    auto am = o.find("alphaMode");
    if (am != o.end()) {
        std::string s = am->is_string() ? am->get<std::string>() : "";
        if (s != "OPAQUE" && s != "MASK" && s != "BLEND")
            gfail(w + ".alphaMode: expected \"OPAQUE\", \"MASK\" or \"BLEND\"");
    }
}

/* a primitive's KHR_draco_mesh_compression (`dr`, at `pw`): its bufferView, attribute ids that
 * the primitive's attributes (`attrs`) name, and indices */
static void check_draco(Ctx &c, const Arrays &a, const json &pr, const json &attrs,
                        const json &dr, const std::string &pw)
{
    const std::string dw = pw + ".extensions.KHR_draco_mesh_compression";
    ref(dr, "bufferView", arr_size(a.views), "bufferViews", dw, true);
    const json *da = opt_object(dr, "attributes", dw);
    if (!da) gfail(dw + ".attributes: missing (required)");
    for (auto it = da->begin(); it != da->end(); ++it) {
        if (!it->is_number_unsigned() || it->get<uint64_t>() > 0x7FFFFFFFu)
            gfail(strf("%s.attributes.%s: expected a Draco attribute id (a "
                       "non-negative integer)",
                       dw.c_str(), it.key().substr(0, 40).c_str()));
        if (!attrs.contains(it.key()))
            gfail(strf("%s.attributes.%s: the primitive has no %s attribute",
                       dw.c_str(), it.key().substr(0, 40).c_str(),
                       it.key().substr(0, 40).c_str()));
    }
    if (!pr.contains("indices"))
        gfail(pw + ".indices: missing (required with KHR_draco_mesh_compression)");
    /* tinygltf 2.7 refuses an indices accessor without a bufferView, which is
     * how a required Draco primitive's indices look: tinygltf is told it is the
     * Draco bufferView (never read: get_view serves the decoded faces) */
    const size_t ia = pr["indices"].get<size_t>();
    if (!(*a.accessors)[ia].contains("bufferView"))
        c.draco_index_fix[int(ia)] = int(dr["bufferView"].get<size_t>());
}

/* meshes[i].primitives[p] (at `pw`): attributes, indices, material, Draco, mode, targets */
static void check_primitive(Ctx &c, const Arrays &a, const json &pr, const std::string &pw)
{
    if (!pr.is_object()) gfail(pw + ": expected an object");
    const json *attrs = opt_object(pr, "attributes", pw);
    if (!attrs) gfail(pw + ".attributes: missing (required)");
    for (auto it = attrs->begin(); it != attrs->end(); ++it)
        ref(*attrs, it.key().c_str(), arr_size(a.accessors), "accessors", pw + ".attributes", true);
    ref(pr, "indices", arr_size(a.accessors), "accessors", pw, false);
    ref(pr, "material", arr_size(a.materials), "materials", pw, false);
    if (const json *ex = opt_object(pr, "extensions", pw))
        if (const json *dr = opt_object(*ex, "KHR_draco_mesh_compression", pw + ".extensions"))
            check_draco(c, a, pr, *attrs, *dr, pw);
    auto mit = pr.find("mode");
    if (mit != pr.end() && (!mit->is_number_unsigned() || mit->get<uint64_t>() > 6))
        gfail(pw + ".mode: " + mit->dump() + " is not a glTF primitive mode (0..6)");
    if (const json *targets = opt_array(pr, "targets", pw)) {
        for (size_t t = 0; t < targets->size(); t++) {
            const json &tg = (*targets)[t];
            std::string tw = strf("%s.targets[%zu]", pw.c_str(), t);
            if (!tg.is_object()) gfail(tw + ": expected an object");
            for (auto it = tg.begin(); it != tg.end(); ++it)
                ref(tg, it.key().c_str(), arr_size(a.accessors), "accessors", tw, true);
        }
    }
}

static void check_mesh(Ctx &c, const Arrays &a, const json &o, const std::string &w)
{
    const json *prims = opt_array(o, "primitives", w);
    if (!prims) gfail(w + ".primitives: missing (required)");
    if (const json *wt = opt_array(o, "weights", w))
        for (size_t k = 0; k < wt->size(); k++)
            if (!((*wt)[k].is_number() && std::isfinite((*wt)[k].get<double>())))
                gfail(strf("%s.weights[%zu]: expected a number, got %s", w.c_str(), k,
                           (*wt)[k].dump().substr(0, 80).c_str()));
    for (size_t p = 0; p < prims->size(); p++)
        check_primitive(c, a, (*prims)[p], strf("%s.primitives[%zu]", w.c_str(), p));
}

/* animations[i].channels (at `w`): each an object with a sampler and a target with a path (the
 * specification requires them; tinygltf drops a channel without them, and the later channels'
 * indices in its model no longer match the file's) */
static void check_animation_channels(const json &o, const std::string &w)
{
    const json *chs = opt_array(o, "channels", w);
    if (!chs) return;
    for (size_t k = 0; k < chs->size(); k++) {
        const json &ch = (*chs)[k];
        const std::string cw = strf("%s.channels[%zu]", w.c_str(), k);
        if (!ch.is_object()) gfail(cw + ": expected an object");
        uint_field(ch, "sampler", cw, true);
        const json *t = opt_object(ch, "target", cw);
        if (!t) gfail(cw + ".target: missing (required)");
        auto p = t->find("path");
        if (p == t->end() || !p->is_string())
            gfail(cw + ".target.path: missing or not a string (required)");
    }
}

/* the array KEY of `o` (at `w`), if any, holds valid node indices */
static void check_node_list(const Arrays &a, const json &o, const char *key, const std::string &w)
{
    const json *ns = opt_array(o, key, w);
    if (!ns) return;
    for (size_t k = 0; k < ns->size(); k++) {
        const json &v = (*ns)[k];
        if (!v.is_number_unsigned() || v.get<uint64_t>() >= arr_size(a.nodes))
            gfail(strf("%s.%s[%zu]: not a valid node index (%zu nodes)", w.c_str(), key, k,
                       arr_size(a.nodes)));
    }
}

/* nodes: mesh, children and finite transforms */
static void check_node(const Arrays &a, const json &o, const std::string &w)
{
    ref(o, "mesh", arr_size(a.meshes), "meshes", w, false);
    check_node_list(a, o, "children", w);
    static const struct {
        const char *key;
        size_t n;
    } tf[] = {{"matrix", 16}, {"translation", 3}, {"rotation", 4}, {"scale", 3}};
    for (const auto &f : tf) {
        auto it = o.find(f.key);
        if (it == o.end()) continue;
        bool ok = it->is_array() && it->size() == f.n;
        if (ok)
            for (const auto &x : *it) ok = ok && x.is_number() && std::isfinite(x.get<double>());
        if (!ok) gfail(strf("%s.%s: expected %zu finite numbers", w.c_str(), f.key, f.n));
    }
}

/* The JSON checks before tinygltf sees the file: the asset, extensionsRequired, then each array
 * kind in turn, each after the kinds it refers to (their sizes and facts are known by then). */
/* o.key: a finite number (> 0 when positive), required or absent */
static void check_number(const json &o, const char *key, const std::string &w, bool required, bool positive)
{
    auto it = o.find(key);
    if (it == o.end()) {
        if (required) gfail(strf("%s.%s: missing (required)", w.c_str(), key));
        return;
    }
    if (!it->is_number() || !std::isfinite(it->get<double>()) || (positive && !(it->get<double>() > 0)))
        gfail(strf("%s.%s: expected a finite number%s, got %s", w.c_str(), key, positive ? " > 0" : "",
                   it->dump().substr(0, 80).c_str()));
}

/* o.key: one of the strings in `names` (required) */
static std::string check_enum(const json &o, const char *key, const std::string &w,
                              std::initializer_list<const char *> names)
{
    auto it = o.find(key);
    std::string list;
    for (const char *n : names) list += std::string(list.empty() ? "\"" : ", \"") + n + "\"";
    if (it == o.end()) gfail(strf("%s.%s: missing (required: %s)", w.c_str(), key, list.c_str()));
    if (it->is_string())
        for (const char *n : names)
            if (it->get<std::string>() == n) return n;
    gfail(strf("%s.%s: %s is not one of %s", w.c_str(), key, it->dump().substr(0, 80).c_str(), list.c_str()));
}

/* cameras[i]: a type and its object with the specification's required numbers */
static void check_camera(const json &o, const std::string &w)
{
    const std::string type = check_enum(o, "type", w, {"perspective", "orthographic"});
    const json *k = opt_object(o, type.c_str(), w);
    if (!k) gfail(strf("%s.%s: missing (required by type \"%s\")", w.c_str(), type.c_str(), type.c_str()));
    const std::string kw = w + "." + type;
    if (type == "perspective") {
        check_number(*k, "yfov", kw, true, true);
        check_number(*k, "znear", kw, true, true);
        check_number(*k, "aspectRatio", kw, false, true);
        check_number(*k, "zfar", kw, false, true);
    } else {
        for (const char *key : {"xmag", "ymag", "zfar", "znear"}) check_number(*k, key, kw, true, false);
    }
}

/* extensions.KHR_lights_punctual.lights[i]: a type, and a spot light's spot object */
/* o.key, when present: n numbers (a wrongly typed value was read as the default: "red" as white) */
static void check_numbers(const json &o, const char *key, size_t n, const std::string &w)
{
    auto it = o.find(key);
    if (it == o.end()) return;
    bool ok = it->is_array() && it->size() == n;
    if (ok)
        for (const auto &x : *it) ok = ok && x.is_number();
    if (!ok) gfail(strf("%s.%s: expected %zu numbers, got %s", w.c_str(), key, n, it->dump().substr(0, 80).c_str()));
}

/* o.key, when present: a number (its range is checked where it is read) */
static void check_is_number(const json &o, const char *key, const std::string &w)
{
    auto it = o.find(key);
    if (it != o.end() && !it->is_number())
        gfail(strf("%s.%s: expected a number, got %s", w.c_str(), key, it->dump().substr(0, 80).c_str()));
}

/* extensions.PASSGRAPH_lights_table: an object of a bufferView index and a count of 1 .. 2^24
 * (an index or count of 2^32 and past was read modulo 2^32; an array was taken for no table) */
static void check_lights_table(const json &j, const Arrays &a)
{
    const json *ext = opt_object(j, "extensions", "(root)");
    const json *t = ext ? opt_object(*ext, "PASSGRAPH_lights_table", "extensions") : nullptr;
    if (!t) return;
    const std::string w = "extensions.PASSGRAPH_lights_table";
    for (auto it = t->begin(); it != t->end(); ++it)
        if (it.key() != "bufferView" && it.key() != "count" && it.key() != "extras" && it.key() != "extensions")
            gfail(strf("%s.%s: unknown key (expected bufferView and count)", w.c_str(), it.key().c_str()));
    ref(*t, "bufferView", arr_size(a.views), "bufferViews", w, true);
    auto c = t->find("count");
    if (c == t->end()) gfail(w + ".count: missing (required)");
    if (!c->is_number_unsigned() || c->get<uint64_t>() < 1 || c->get<uint64_t>() > PG_MAX_LIGHTS)
        gfail(strf("%s.count: %s: expected an integer in 1..%u", w.c_str(), c->dump().substr(0, 40).c_str(), PG_MAX_LIGHTS));
}

/* nodes[i].extensions.KHR_lights_punctual.light: an index into the lights (2^32 read as 0) */
static void check_light_nodes(const Arrays &a, size_t n_lights)
{
    each_object(a.nodes, "nodes", [&](const json &o, const std::string &w, size_t) {
        const json *ext = opt_object(o, "extensions", w);
        const json *lp = ext ? opt_object(*ext, "KHR_lights_punctual", w + ".extensions") : nullptr;
        if (lp) ref(*lp, "light", n_lights, "lights", w + ".extensions.KHR_lights_punctual", true);
    });
}

static void check_punctual_lights(const json &j, const Arrays &a)
{
    const json *ext = opt_object(j, "extensions", "(root)");
    const json *lp = ext ? opt_object(*ext, "KHR_lights_punctual", "extensions") : nullptr;
    const json *lights = lp ? opt_array(*lp, "lights", "KHR_lights_punctual") : nullptr;
    check_light_nodes(a, arr_size(lights));
    each_object(lights, "KHR_lights_punctual.lights", [&](const json &o, const std::string &w, size_t) {
        check_numbers(o, "color", 3, w);
        check_is_number(o, "intensity", w);
        if (const json *spot = opt_object(o, "spot", w)) {
            check_is_number(*spot, "innerConeAngle", w + ".spot");
            check_is_number(*spot, "outerConeAngle", w + ".spot");
        }
        auto t = o.find("type");
        const std::string type = t != o.end() && t->is_string() ? t->get<std::string>() : "";
        if (type != "point" && type != "spot" && type != "directional")
            gfail(w + ".type: " + (t == o.end() ? std::string("missing") : "'" + (t->is_string() ? type : t->dump()) + "'") +
                  ": expected \"point\", \"spot\" or \"directional\"");
        if (type == "spot" && !opt_object(o, "spot", w)) gfail(w + ".spot: missing (required by type \"spot\")");
        /* range: absent (infinite reach) or > 0; tinygltf reads 0 for absent, so a given 0, or one that
         * is 0 as a float (1e-46), became infinite reach */
        auto r = o.find("range");
        if (r != o.end()) {
            const double v = r->is_number() ? r->get<double>() : -1.0;
            if (!(v > 0 && v <= 1e30 && std::isnormal(float(v)))) /* v <= 1e30: the float conversion is defined */
                gfail(w + ".range: " + r->dump() + ": expected a number in [1.2e-38, 1e30] (> 0, and not 0 as a float), " +
                      "or absent for infinite reach");
        }
    });
}

void prevalidate(Ctx &c)
{
    const json &j = c.j;
    if (!j.is_object()) gfail("root: expected a JSON object");
    check_asset(j);
    check_required_extensions(j);

    Arrays a;
    a.buffers = opt_array(j, "buffers", "");
    a.views = opt_array(j, "bufferViews", "");
    a.accessors = opt_array(j, "accessors", "");
    a.meshes = opt_array(j, "meshes", "");
    a.nodes = opt_array(j, "nodes", "");
    a.scenes = opt_array(j, "scenes", "");
    a.materials = opt_array(j, "materials", "");
    a.textures = opt_array(j, "textures", "");
    a.images = opt_array(j, "images", "");
    a.samplers = opt_array(j, "samplers", "");

    each_object(a.buffers, "buffers", [&](const json &o, const std::string &w, size_t) {
        check_buffer(c, a, o, w);
    });
    each_object(a.views, "bufferViews", [&](const json &o, const std::string &w, size_t vi) {
        check_buffer_view(c, a, o, w, vi);
    });
    each_object(a.accessors, "accessors", [&](const json &o, const std::string &w, size_t) {
        check_accessor(a, o, w);
    });
    each_object(a.images, "images", [&](const json &o, const std::string &w, size_t ii) {
        a.image_index = ii;
        check_image(c, a, o, w);
    });
    each_object(a.samplers, "samplers", [&](const json &, const std::string &, size_t) {});
    each_object(a.textures, "textures", [&](const json &o, const std::string &w, size_t) {
        ref(o, "source", arr_size(a.images), "images", w, false);
        ref(o, "sampler", arr_size(a.samplers), "samplers", w, false);
    });
    each_object(a.materials, "materials", [&](const json &o, const std::string &w, size_t) {
        check_material(a, o, w);
    });
    each_object(a.meshes, "meshes", [&](const json &o, const std::string &w, size_t) {
        check_mesh(c, a, o, w);
    });
    each_object(a.nodes, "nodes", [&](const json &o, const std::string &w, size_t) {
        check_node(a, o, w);
    });
    each_object(opt_array(j, "cameras", ""), "cameras", [&](const json &o, const std::string &w, size_t) {
        check_camera(o, w);
    });
    each_object(opt_array(j, "animations", ""), "animations", [&](const json &o, const std::string &w, size_t) {
        check_animation_channels(o, w);
    });
    check_punctual_lights(j, a);
    check_lights_table(j, a);
    each_object(a.scenes, "scenes", [&](const json &o, const std::string &w, size_t) {
        check_node_list(a, o, "nodes", w);
    });
    ref(j, "scene", arr_size(a.scenes), "scenes", "", false);
}

} // namespace pg_gltf
