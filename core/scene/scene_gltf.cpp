/* scene_gltf.cpp - pg_scene_load_gltf: a thin C++17 shim over tinygltf (Debian libtinygltf, whose
 * implementation lives in libtinygltf.so; images are decoded with stb_image from libstb.so).
 *
 * Load order:
 *   1. read the file (missing/unreadable: PG_ERR_IO); .glb is recognised by its magic bytes and
 *      its container header is checked here (PG_ERR_PARSE);
 *   2. parse the JSON with nlohmann::json (syntax errors: PG_ERR_PARSE) and PRE-VALIDATE it:
 *      root object, asset.version 2.x, no extensionsRequired but the implemented ones
 *      (kImplementedExtensions), emissiveFactor / emissiveStrength finite and >= 0, every
 *      cross-reference in range (sparse indices/values bufferViews, EXT_meshopt_compression and
 *      KHR_draco_mesh_compression parameters included),
 *      buffers present with exactly byteLength bytes, bufferViews inside their buffers, image
 *      files present. tinygltf 2.7 does not check all of these (and reads an image bufferView's
 *      bytes without a range check), so they must hold before tinygltf sees the file;
 *   3. tinygltf builds the Model; images go through our stb callback (RGBA8; PNG and JPEG only;
 *      sides > 16384, and JPEGs with more pixels than their size can code, are refused before
 *      decoding); then every EXT_meshopt_compression bufferView is decoded (decode_meshopt);
 *      KHR_draco_mesh_compression primitives are decoded when first drawn (decode_draco);
 *   4. walk the node hierarchy of `scene` (else scenes[0], else every root node) with cycle
 *      detection, validate every accessor a primitive uses (type, range within its bufferView,
 *      byteStride, index range, finite values), bake transforms, build materials and textures.
 * Every glTF-content error is PG_ERR_GLTF with "PATH: object: cause".
 *
 * Primitive modes: TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN are drawn (strips/fans become
 * lists); POINTS/LINES/LINE_LOOP/LINE_STRIP are skipped with one warning line; any other
 * mode value is an error. A scene left with no triangles is an error.
 * COLOR_0 (VEC3/VEC4, FLOAT or normalized UNSIGNED_BYTE/SHORT) fills pg_scene.colors when a drawn
 * primitive has it (white elsewhere); TEXCOORD_1 fills pg_scene.uv1 when a drawn primitive has it
 * and its material reads it. textureInfo texCoord 0/1 (and KHR_texture_transform's texCoord, which
 * overrides it) selects the set per slot; texCoord >= 2 reads TEXCOORD_0, warned.
 * Sparse accessors are applied to a dense copy (Ctx::sparse_data) of the accessor's data.
 *
 * Warnings (pg_scene.warnings, collect_warnings): everything the file uses that is not drawn as it
 * asks gets one line per kind (skins, morph targets, animations, each extension in
 * extensionsUsed that is not implemented, BLEND materials, emission / occlusion /
 * metallic-roughness textures, COLOR_1+, TEXCOORD_2+, texCoord >= 2, sampler values outside the
 * glTF enums, point/line primitives). The library never prints them. An extensionsRequired entry
 * that is not implemented is an error. A non-GLB file
 * whose first non-blank byte is not '{' or '[' is "not a glTF 2.0 file"; asset.version 1.x is
 * "glTF 1.0 is not supported, only 2.0".
 * Non-finite POSITION / NORMAL / TEXCOORD_0 / TANGENT values are errors, and so are positions that
 * leave the float range (or normals/tangents that overflow) under their node transform.
 *
 * Material mapping (glTF metallic-roughness -> passgraph Blinn-Phong):
 *   specular  = 0.04 + 0.5 * (1 - roughness) * (1 - metallic)      (0.04 .. 0.54)
 *   shininess = clamp(2 / (roughness^4 + 1e-4) - 2, 1, 512)         (Beckmann-like roughness
 *                                                                    to Blinn-Phong exponent)
 *   emissive  = emissiveFactor x KHR_materials_emissive_strength.emissiveStrength (default 1),
 *               linear, unclamped (a product past the float range is an error)
 * baseColorTexture -> sRGB texture, normalTexture -> linear texture; an image used both ways gets
 * two pg_texture entries, and so does one image used with two sampler states (TexKey); the
 * emissiveTexture is sRGB. Primitives without a material use an appended white "default"
 * material (glTF's default: metallic 1, roughness 1).
 *
 * Exceptions never leave this file: internal failures are thrown as LoadFail and turned into a
 * pg_result at the C boundary; everything is owned by RAII objects until the scene is handed out.
 */
#include "scene.h"

#include <draco/compression/decode.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <stb_image.h>
#include <tiny_gltf.h>

#include <sys/stat.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <new>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace {

using json = nlohmann::json;

constexpr int kMaxImageSide = 16384;
/* No real JPEG codes more than ~512 pixels per byte (at least one bit per 8x8 block, even
 * progressive); stb_image decodes a truncated JPEG stream as if it went on with zero bits, so a
 * 140-byte header claiming 16384x16384 would otherwise become a 1 GiB texture. */
constexpr uint64_t kMaxJpegPixelsPerByte = 1024;
constexpr int kMaxNodeDepth = 1024;
constexpr size_t kMaxNodeVisits = size_t(1) << 20;

/* The glTF extensions passgraph implements: accepted in extensionsRequired, not warned in
 * extensionsUsed. */
constexpr const char *kImplementedExtensions[] = {"EXT_meshopt_compression", "KHR_draco_mesh_compression",
                                                  "KHR_materials_emissive_strength", "KHR_mesh_quantization",
                                                  "KHR_texture_transform"};
bool extension_implemented(const std::string &e)
{
    for (const char *x : kImplementedExtensions)
        if (e == x) return true;
    return false;
}

struct LoadFail {
    pg_result code;
    std::string msg;
};

std::string strf(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
std::string strf(const char *fmt, ...)
{
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return buf;
}

[[noreturn]] void fail(pg_result code, std::string msg) { throw LoadFail{code, std::move(msg)}; }
[[noreturn]] void gfail(std::string msg) { fail(PG_ERR_GLTF, std::move(msg)); }

/* A short, printable form of a uri for messages (data URIs are not quoted whole). */
std::string uri_desc(const std::string &uri)
{
    if (uri.compare(0, 5, "data:") == 0) return "data URI";
    std::string s = uri.size() > 200 ? uri.substr(0, 200) + "..." : uri;
    return "'" + s + "'";
}

/* tinygltf decodes external uris with dlib::urldecode ('+' -> ' ', %XX); do the same. */
std::string url_decode(const std::string &s)
{
    auto hex = [](unsigned char c) -> unsigned {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return 0;
    };
    std::string r;
    for (size_t i = 0; i < s.size(); i++) {
        if (s[i] == '+') {
            r += ' ';
        } else if (s[i] == '%' && s.size() > i + 2) {
            r += char((hex((unsigned char)s[i + 1]) << 4) | hex((unsigned char)s[i + 2]));
            i += 2;
        } else {
            r += s[i];
        }
    }
    return r;
}

std::string join_path(const std::string &dir, const std::string &file)
{
    if (dir.empty()) return file;
    if (dir.back() == '/') return dir + file;
    return dir + "/" + file;
}

struct Ctx {
    std::string path;     /* as given (prefix of every message) */
    std::string base_dir; /* directory of the file ("." when none) */
    std::string dir_prefix;
    bool is_glb = false;
    size_t glb_bin_size = 0;
    bool glb_has_bin = false;
    json j;
    tinygltf::Model model;
    std::string image_err; /* set by the image callback */
    bool quantization = false; /* KHR_mesh_quantization in extensionsUsed */
    unsigned skipped_prims = 0;
    unsigned color1_prims = 0;   /* drawn primitives with COLOR_1.. (ignored) */
    unsigned texcoord2_prims = 0;/* drawn primitives with TEXCOORD_2.. (ignored) */
    std::vector<std::string> warnings; /* without the "PATH: " prefix */
    /* EXT_meshopt_compression: the compressed bufferViews (checked by prevalidate, decoded by
     * decode_meshopt into `decoded`, which view_bytes reads instead of the fallback buffer), and
     * the fallback buffers (never loaded: handed to tinygltf as 4-byte data URIs) */
    struct Meshopt {
        int view, buffer;
        uint64_t offset, length, stride, count;
        int mode;   /* 0 ATTRIBUTES, 1 TRIANGLES, 2 INDICES */
        int filter; /* 0 NONE, 1 OCTAHEDRAL, 2 QUATERNION, 3 EXPONENTIAL */
    };
    std::vector<Meshopt> meshopt;
    std::vector<char> view_is_meshopt;  /* per bufferView */
    std::vector<char> buffer_no_data;   /* per buffer: an EXT_meshopt_compression fallback */
    std::map<int, std::vector<unsigned char>> decoded;
    /* KHR_draco_mesh_compression: decoded accessor data (accessor index -> dense bytes in the
     * accessor's componentType/type) and the bufferView each came from; primitives done */
    std::map<int, std::vector<unsigned char>> draco_data;
    std::map<int, int> draco_view;
    std::map<std::pair<int, int>, bool> draco_done;
    std::map<int, int> draco_index_fix; /* indices accessor without bufferView -> Draco view */
    /* dense copies of sparse accessors (accessor index -> data), owned until hand-out */
    std::map<int, std::vector<unsigned char>> sparse_data;
};

/* ------------------------------------------------------------------------------------------ */
/* step 1: GLB container                                                                        */

uint32_t rd_u32(const unsigned char *p)
{
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

/* Returns the JSON chunk text. */
std::string glb_json(Ctx &c, const unsigned char *b, size_t n)
{
    if (n < 20) fail(PG_ERR_PARSE, strf("GLB: file too short (%zu bytes) for a header", n));
    uint32_t version = rd_u32(b + 4), length = rd_u32(b + 8);
    if (version != 2) fail(PG_ERR_PARSE, strf("GLB: container version %u (need 2)", version));
    if (length > n)
        fail(PG_ERR_PARSE, strf("GLB: header length %u exceeds the file size (%zu bytes)",
                                length, n));
    uint32_t clen = rd_u32(b + 12), ctype = rd_u32(b + 16);
    if (ctype != 0x4E4F534Au) fail(PG_ERR_PARSE, "GLB: first chunk is not JSON");
    if (clen < 1 || 20ull + clen > length)
        fail(PG_ERR_PARSE, strf("GLB: JSON chunk length %u exceeds the container (%u bytes)",
                                clen, length));
    uint64_t off = 20ull + clen;
    if (off < length) {
        if (off + 8 > length) fail(PG_ERR_PARSE, "GLB: truncated BIN chunk header");
        uint32_t blen = rd_u32(b + off), btype = rd_u32(b + off + 4);
        if (btype != 0x004E4942u) fail(PG_ERR_PARSE, "GLB: second chunk is not BIN");
        if (off + 8 + blen > length)
            fail(PG_ERR_PARSE, strf("GLB: BIN chunk length %u exceeds the container", blen));
        if (blen < 4 || blen % 4)
            fail(PG_ERR_PARSE, strf("GLB: BIN chunk length %u is not a positive multiple of 4",
                                    blen));
        c.glb_has_bin = true;
        c.glb_bin_size = blen;
    }
    return std::string(reinterpret_cast<const char *>(b + 20), clen);
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
                    uint64_t def = 0)
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

void prevalidate(Ctx &c)
{
    const json &j = c.j;
    if (!j.is_object()) gfail("root: expected a JSON object");

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

    /* a required extension passgraph does not implement is refused, naming each */
    if (const json *req = opt_array(j, "extensionsRequired", "")) {
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

    const json *buffers = opt_array(j, "buffers", "");
    const json *views = opt_array(j, "bufferViews", "");
    const json *accessors = opt_array(j, "accessors", "");
    const json *meshes = opt_array(j, "meshes", "");
    const json *nodes = opt_array(j, "nodes", "");
    const json *scenes = opt_array(j, "scenes", "");
    const json *materials = opt_array(j, "materials", "");
    const json *textures = opt_array(j, "textures", "");
    const json *images = opt_array(j, "images", "");
    const json *samplers = opt_array(j, "samplers", "");

    auto each_object = [](const json *a, const char *name, auto fn) {
        if (!a) return;
        for (size_t i = 0; i < a->size(); i++) {
            const json &o = (*a)[i];
            std::string where = strf("%s[%zu]", name, i);
            if (!o.is_object()) gfail(where + ": expected an object");
            fn(o, where, i);
        }
    };

    /* buffers: present with exactly byteLength bytes */
    std::vector<uint64_t> buf_len;
    each_object(buffers, "buffers", [&](const json &o, const std::string &w, size_t) {
        uint64_t len = uint_field(o, "byteLength", w, true);
        buf_len.push_back(len);
        auto uit = o.find("uri");
        bool fallback = false;
        if (const json *ex = opt_object(o, "extensions", w))
            if (const json *mo = opt_object(*ex, "EXT_meshopt_compression", w + ".extensions")) {
                auto fb = mo->find("fallback");
                if (fb != mo->end() && !fb->is_boolean())
                    gfail(w + ".extensions.EXT_meshopt_compression.fallback: expected true or false");
                fallback = fb != mo->end() && fb->get<bool>();
            }
        /* a fallback buffer is never loaded (only compressed bufferViews may use it, and those
         * are read from their decoded data), so its uri may be missing or name no file */
        c.buffer_no_data.push_back(fallback);
        if (fallback) return;
        if (uit == o.end()) {
            if (!c.is_glb) gfail(w + ".uri: missing (required outside .glb files)");
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
        uint64_t fsize = 0;
        if (!is_regular_file(file, &fsize))
            gfail(strf("%s: cannot open '%s' (%s)", w.c_str(), uri.c_str(), file.c_str()));
        if (fsize != len)
            gfail(strf("%s: '%s' has %llu bytes but byteLength is %llu", w.c_str(), uri.c_str(),
                       (unsigned long long)fsize, (unsigned long long)len));
    });

    /* bufferViews inside their buffers; EXT_meshopt_compression parameters */
    each_object(views, "bufferViews", [&](const json &o, const std::string &w, size_t vi) {
        long long b = ref(o, "buffer", arr_size(buffers), "buffers", w, true);
        uint64_t off = uint_field(o, "byteOffset", w, false, 0);
        uint64_t len = uint_field(o, "byteLength", w, true);
        if (off > buf_len[(size_t)b] || len > buf_len[(size_t)b] - off)
            gfail(strf("%s: byteOffset %llu + byteLength %llu exceeds buffers[%lld] (%llu bytes)",
                       w.c_str(), (unsigned long long)off, (unsigned long long)len, b,
                       (unsigned long long)buf_len[(size_t)b]));
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
        const std::string mw = w + ".extensions.EXT_meshopt_compression";
        Ctx::Meshopt m;
        m.view = int(vi);
        m.buffer = int(ref(*mo, "buffer", arr_size(buffers), "buffers", mw, true));
        m.offset = uint_field(*mo, "byteOffset", mw, false, 0);
        m.length = uint_field(*mo, "byteLength", mw, true);
        m.stride = uint_field(*mo, "byteStride", mw, true);
        m.count = uint_field(*mo, "count", mw, true);
        if (c.buffer_no_data[size_t(m.buffer)])
            gfail(strf("%s.buffer: buffers[%d] is a fallback buffer (never loaded)", mw.c_str(),
                       m.buffer));
        const uint64_t sl = buf_len[size_t(m.buffer)];
        if (m.offset > sl || m.length > sl - m.offset)
            gfail(strf("%s: byteOffset %llu + byteLength %llu exceeds buffers[%d] (%llu bytes)",
                       mw.c_str(), (unsigned long long)m.offset, (unsigned long long)m.length,
                       m.buffer, (unsigned long long)sl));
        auto str = [&](const char *key, bool required) -> std::string {
            auto it = mo->find(key);
            if (it == mo->end()) {
                if (required) gfail(strf("%s.%s: missing (required)", mw.c_str(), key));
                return "NONE";
            }
            if (!it->is_string()) gfail(strf("%s.%s: expected a string", mw.c_str(), key));
            return it->get<std::string>();
        };
        const std::string mode = str("mode", true), filter = str("filter", false);
        static const char *const modes[] = {"ATTRIBUTES", "TRIANGLES", "INDICES"};
        static const char *const filters[] = {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"};
        m.mode = m.filter = -1;
        for (int k = 0; k < 3; k++)
            if (mode == modes[k]) m.mode = k;
        for (int k = 0; k < 4; k++)
            if (filter == filters[k]) m.filter = k;
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
                       (unsigned long long)st, modes[m.mode]));
        if (m.mode == 1 && m.count % 3)
            gfail(strf("%s.count: %llu is not a multiple of 3 (TRIANGLES)", mw.c_str(),
                       (unsigned long long)m.count));
        if (m.filter != 0 && m.mode != 0)
            gfail(strf("%s.filter: %s needs mode ATTRIBUTES", mw.c_str(), filters[m.filter]));
        if ((m.filter == 1 && st != 4 && st != 8) || (m.filter == 2 && st != 8))
            gfail(strf("%s.filter: %s needs byteStride %s (got %llu)", mw.c_str(),
                       filters[m.filter], m.filter == 1 ? "4 or 8" : "8",
                       (unsigned long long)st));
        if (m.count > UINT64_MAX / st || m.count * st != len)
            gfail(strf("%s: count %llu * byteStride %llu is not the bufferView's byteLength %llu",
                       mw.c_str(), (unsigned long long)m.count, (unsigned long long)st,
                       (unsigned long long)len));
        c.meshopt.push_back(m);
    });

    each_object(accessors, "accessors", [&](const json &o, const std::string &w, size_t) {
        ref(o, "bufferView", arr_size(views), "bufferViews", w, false);
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
        if (const json *sp = opt_object(o, "sparse", w)) {
            /* ranges are checked when a primitive uses the accessor (get_view) */
            std::string sw = w + ".sparse";
            uint_field(*sp, "count", sw, true);
            const json *si = opt_object(*sp, "indices", sw);
            const json *sv = opt_object(*sp, "values", sw);
            if (!si) gfail(sw + ".indices: missing (required)");
            if (!sv) gfail(sw + ".values: missing (required)");
            ref(*si, "bufferView", arr_size(views), "bufferViews", sw + ".indices", true);
            uint_field(*si, "byteOffset", sw + ".indices", false, 0);
            uint64_t ict = uint_field(*si, "componentType", sw + ".indices", true);
            if (ict != 5121 && ict != 5123 && ict != 5125)
                gfail(strf("%s.indices.componentType: %llu is not UNSIGNED_BYTE, UNSIGNED_SHORT or "
                           "UNSIGNED_INT",
                           sw.c_str(), (unsigned long long)ict));
            ref(*sv, "bufferView", arr_size(views), "bufferViews", sw + ".values", true);
            uint_field(*sv, "byteOffset", sw + ".values", false, 0);
        }
    });

    each_object(images, "images", [&](const json &o, const std::string &w, size_t) {
        long long bv = ref(o, "bufferView", arr_size(views), "bufferViews", w, false);
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
            if (!tinygltf::IsDataURI(uri)) gfail(w + ".uri: unsupported data URI media type");
            return;
        }
        if (uri.empty()) gfail(w + ".uri: empty");
        std::string file = join_path(c.base_dir, url_decode(uri));
        uint64_t fsize = 0;
        if (!is_regular_file(file, &fsize))
            gfail(strf("%s: cannot open '%s' (%s)", w.c_str(), uri.c_str(), file.c_str()));
        if (fsize == 0) gfail(strf("%s: '%s' is empty", w.c_str(), uri.c_str()));
    });

    each_object(samplers, "samplers", [&](const json &, const std::string &, size_t) {});

    each_object(textures, "textures", [&](const json &o, const std::string &w, size_t) {
        ref(o, "source", arr_size(images), "images", w, false);
        ref(o, "sampler", arr_size(samplers), "samplers", w, false);
    });

    each_object(materials, "materials", [&](const json &o, const std::string &w, size_t) {
        if (const json *pbr = opt_object(o, "pbrMetallicRoughness", w)) {
            std::string pw = w + ".pbrMetallicRoughness";
            if (const json *ti = opt_object(*pbr, "baseColorTexture", pw))
                ref(*ti, "index", arr_size(textures), "textures", pw + ".baseColorTexture", true);
            if (const json *ti = opt_object(*pbr, "metallicRoughnessTexture", pw))
                ref(*ti, "index", arr_size(textures), "textures",
                    pw + ".metallicRoughnessTexture", true);
        }
        if (const json *ti = opt_object(o, "normalTexture", w))
            ref(*ti, "index", arr_size(textures), "textures", w + ".normalTexture", true);
        if (const json *ti = opt_object(o, "occlusionTexture", w))
            ref(*ti, "index", arr_size(textures), "textures", w + ".occlusionTexture", true);
        if (const json *ti = opt_object(o, "emissiveTexture", w))
            ref(*ti, "index", arr_size(textures), "textures", w + ".emissiveTexture", true);
        check_emissive(o, w);
        auto am = o.find("alphaMode");
        if (am != o.end()) {
            std::string s = am->is_string() ? am->get<std::string>() : "";
            if (s != "OPAQUE" && s != "MASK" && s != "BLEND")
                gfail(w + ".alphaMode: expected \"OPAQUE\", \"MASK\" or \"BLEND\"");
        }
    });

    each_object(meshes, "meshes", [&](const json &o, const std::string &w, size_t) {
        const json *prims = opt_array(o, "primitives", w);
        if (!prims) gfail(w + ".primitives: missing (required)");
        for (size_t p = 0; p < prims->size(); p++) {
            const json &pr = (*prims)[p];
            std::string pw = strf("%s.primitives[%zu]", w.c_str(), p);
            if (!pr.is_object()) gfail(pw + ": expected an object");
            const json *attrs = opt_object(pr, "attributes", pw);
            if (!attrs) gfail(pw + ".attributes: missing (required)");
            for (auto it = attrs->begin(); it != attrs->end(); ++it)
                ref(*attrs, it.key().c_str(), arr_size(accessors), "accessors",
                    pw + ".attributes", true);
            ref(pr, "indices", arr_size(accessors), "accessors", pw, false);
            ref(pr, "material", arr_size(materials), "materials", pw, false);
            if (const json *ex = opt_object(pr, "extensions", pw))
                if (const json *dr = opt_object(*ex, "KHR_draco_mesh_compression", pw + ".extensions")) {
                    const std::string dw = pw + ".extensions.KHR_draco_mesh_compression";
                    ref(*dr, "bufferView", arr_size(views), "bufferViews", dw, true);
                    const json *da = opt_object(*dr, "attributes", dw);
                    if (!da) gfail(dw + ".attributes: missing (required)");
                    for (auto it = da->begin(); it != da->end(); ++it) {
                        if (!it->is_number_unsigned() || it->get<uint64_t>() > 0x7FFFFFFFu)
                            gfail(strf("%s.attributes.%s: expected a Draco attribute id (a "
                                       "non-negative integer)",
                                       dw.c_str(), it.key().substr(0, 40).c_str()));
                        if (!attrs->contains(it.key()))
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
                    if (!(*accessors)[ia].contains("bufferView"))
                        c.draco_index_fix[int(ia)] = int((*dr)["bufferView"].get<size_t>());
                }
            auto mit = pr.find("mode");
            if (mit != pr.end() && (!mit->is_number_unsigned() || mit->get<uint64_t>() > 6))
                gfail(pw + ".mode: " + mit->dump() + " is not a glTF primitive mode (0..6)");
            if (const json *targets = opt_array(pr, "targets", pw)) {
                for (size_t t = 0; t < targets->size(); t++) {
                    const json &tg = (*targets)[t];
                    std::string tw = strf("%s.targets[%zu]", pw.c_str(), t);
                    if (!tg.is_object()) gfail(tw + ": expected an object");
                    for (auto it = tg.begin(); it != tg.end(); ++it)
                        ref(tg, it.key().c_str(), arr_size(accessors), "accessors", tw, true);
                }
            }
        }
    });

    each_object(nodes, "nodes", [&](const json &o, const std::string &w, size_t) {
        ref(o, "mesh", arr_size(meshes), "meshes", w, false);
        if (const json *ch = opt_array(o, "children", w)) {
            for (size_t k = 0; k < ch->size(); k++) {
                const json &v = (*ch)[k];
                if (!v.is_number_unsigned() || v.get<uint64_t>() >= arr_size(nodes))
                    gfail(strf("%s.children[%zu]: not a valid node index (%zu nodes)", w.c_str(),
                               k, arr_size(nodes)));
            }
        }
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
    });

    each_object(scenes, "scenes", [&](const json &o, const std::string &w, size_t) {
        if (const json *ns = opt_array(o, "nodes", w)) {
            for (size_t k = 0; k < ns->size(); k++) {
                const json &v = (*ns)[k];
                if (!v.is_number_unsigned() || v.get<uint64_t>() >= arr_size(nodes))
                    gfail(strf("%s.nodes[%zu]: not a valid node index (%zu nodes)", w.c_str(), k,
                               arr_size(nodes)));
            }
        }
    });
    ref(j, "scene", arr_size(scenes), "scenes", "", false);
}

/* ------------------------------------------------------------------------------------------ */
/* step 3: tinygltf with our image decoder and a file system confined to the asset's directory   */

bool fs_file_exists(const std::string &abs, void *user)
{
    const Ctx *c = static_cast<const Ctx *>(user);
    if (abs.compare(0, c->dir_prefix.size(), c->dir_prefix) != 0) return false;
    return is_regular_file(abs, nullptr);
}

std::string image_desc(const Ctx &c, int idx)
{
    std::string d = strf("images[%d]", idx);
    const json *images = c.j.is_object() && c.j.contains("images") ? &c.j["images"] : nullptr;
    if (images && images->is_array() && idx >= 0 && size_t(idx) < images->size()) {
        const json &im = (*images)[size_t(idx)];
        auto u = im.find("uri");
        if (u != im.end() && u->is_string()) return d + " (" + uri_desc(u->get<std::string>()) + ")";
        auto bv = im.find("bufferView");
        if (bv != im.end() && bv->is_number_integer())
            return d + strf(" (bufferView %lld)", bv->get<long long>());
    }
    return d;
}

/* Reads the pixel size from a PNG or JPEG header without decoding (stb_image refuses to report
 * absurd sizes, so this gives the clearer error). Returns false for other formats. */
bool peek_image_size(const unsigned char *b, size_t n, long long *w, long long *h)
{
    static const unsigned char png_sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (n >= 24 && memcmp(b, png_sig, 8) == 0 && memcmp(b + 12, "IHDR", 4) == 0) {
        *w = (long long)b[16] << 24 | b[17] << 16 | b[18] << 8 | b[19];
        *h = (long long)b[20] << 24 | b[21] << 16 | b[22] << 8 | b[23];
        return true;
    }
    if (n >= 4 && b[0] == 0xFF && b[1] == 0xD8) {
        size_t i = 2;
        while (i + 4 <= n) {
            if (b[i] != 0xFF) return false;
            unsigned char mk = b[i + 1];
            if (mk == 0xFF) { /* fill byte */
                i++;
                continue;
            }
            if (mk == 0xD8 || mk == 0x01 || (mk >= 0xD0 && mk <= 0xD7)) {
                i += 2;
                continue;
            }
            size_t len = size_t(b[i + 2]) << 8 | b[i + 3];
            bool sof = mk >= 0xC0 && mk <= 0xCF && mk != 0xC4 && mk != 0xC8 && mk != 0xCC;
            if (sof) {
                if (i + 9 > n) return false;
                *h = (long long)b[i + 5] << 8 | b[i + 6];
                *w = (long long)b[i + 7] << 8 | b[i + 8];
                return true;
            }
            if (len < 2) return false;
            i += 2 + len;
        }
    }
    return false;
}

struct StbFree {
    void operator()(unsigned char *p) const { stbi_image_free(p); }
};

bool load_image_cb(tinygltf::Image *image, const int idx, std::string *, std::string *, int, int,
                   const unsigned char *bytes, int size, void *user)
{
    Ctx *c = static_cast<Ctx *>(user);
    try {
        std::string where = image_desc(*c, idx);
        if (!bytes || size <= 0) {
            c->image_err = where + ": no image data";
            return false;
        }
        /* glTF 2.0 images are PNG or JPEG; stb_image's other decoders (TGA, BMP, PSD, GIF, HDR,
         * PIC, PNM) are not offered untrusted bytes (TGA RLE, like truncated JPEG, invents
         * pixels past the end of the data) */
        static const unsigned char png_magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
        const bool png = size >= 8 && memcmp(bytes, png_magic, 8) == 0;
        const bool jpeg = size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
        if (!png && !jpeg) {
            c->image_err = where + ": cannot decode (not a PNG or JPEG image; glTF 2.0 allows "
                                   "only image/png and image/jpeg)";
            return false;
        }
        long long pw = 0, ph = 0;
        if (peek_image_size(bytes, size_t(size), &pw, &ph) &&
            (pw < 1 || ph < 1 || pw > kMaxImageSide || ph > kMaxImageSide)) {
            c->image_err = where + strf(": size %lldx%lld is outside 1..%d on a side", pw, ph,
                                        kMaxImageSide);
            return false;
        }
        int w = 0, h = 0, comp = 0;
        if (!stbi_info_from_memory(bytes, size, &w, &h, &comp)) {
            const char *why = stbi_failure_reason();
            c->image_err = where + ": cannot decode (" + (why ? why : "unknown format") + ")";
            return false;
        }
        if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide) {
            c->image_err = where + strf(": size %dx%d is outside 1..%d on a side", w, h,
                                        kMaxImageSide);
            return false;
        }
        if (jpeg && uint64_t(w) * uint64_t(h) > uint64_t(size) * kMaxJpegPixelsPerByte) {
            c->image_err = where + strf(": cannot decode (a %dx%d JPEG cannot fit in %d bytes: "
                                        "truncated or corrupt)",
                                        w, h, size);
            return false;
        }
        std::unique_ptr<unsigned char, StbFree> px(
            stbi_load_from_memory(bytes, size, &w, &h, &comp, 4));
        if (!px) {
            const char *why = stbi_failure_reason();
            c->image_err = where + ": cannot decode (" + (why ? why : "unknown format") + ")";
            return false;
        }
        image->width = w;
        image->height = h;
        image->component = 4;
        image->bits = 8;
        image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
        image->image.assign(px.get(), px.get() + size_t(w) * size_t(h) * 4);
        return true;
    } catch (...) {
        c->image_err = strf("images[%d]: out of memory decoding", idx);
        return false;
    }
}

std::string first_lines(const std::string &s)
{
    std::string r;
    for (char ch : s) r += (ch == '\n' || ch == '\r') ? ' ' : ch;
    while (!r.empty() && r.back() == ' ') r.pop_back();
    if (r.size() > 400) r = r.substr(0, 400) + "...";
    return r;
}

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
int type_comps(int t)
{
    switch (t) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
    }
}
const char *ctype_name(int ct)
{
    switch (ct) {
    case 5120: return "BYTE";
    case 5121: return "UNSIGNED_BYTE";
    case 5122: return "SHORT";
    case 5123: return "UNSIGNED_SHORT";
    case 5125: return "UNSIGNED_INT";
    case 5126: return "FLOAT";
    default: return "?";
    }
}
size_t ctype_size(int ct)
{
    switch (ct) {
    case 5120:
    case 5121: return 1;
    case 5122:
    case 5123: return 2;
    case 5125:
    case 5126: return 4;
    default: return 0;
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

/* The bytes of bufferViews[bvi] (range-checked against its buffer). */
std::pair<const unsigned char *, size_t> view_bytes(const Ctx &c, int bvi, const std::string &who)
{
    const tinygltf::Model &m = c.model;
    if (bvi < 0 || size_t(bvi) >= m.bufferViews.size())
        gfail(strf("%s: bufferView %d out of range", who.c_str(), bvi));
    const tinygltf::BufferView &bv = m.bufferViews[size_t(bvi)];
    auto dec = c.decoded.find(bvi);
    if (dec != c.decoded.end()) return {dec->second.data(), dec->second.size()};
    if (bv.buffer < 0 || size_t(bv.buffer) >= m.buffers.size())
        gfail(strf("bufferViews[%d]: buffer %d out of range", bvi, bv.buffer));
    const tinygltf::Buffer &buf = m.buffers[size_t(bv.buffer)];
    uint64_t blen = buf.data.size();
    if (bv.byteOffset > blen || bv.byteLength > blen - bv.byteOffset)
        gfail(strf("bufferViews[%d]: byteOffset %zu + byteLength %zu exceeds buffers[%d] "
                   "(%llu bytes)",
                   bvi, bv.byteOffset, bv.byteLength, bv.buffer, (unsigned long long)blen));
    return {buf.data.data() + bv.byteOffset, bv.byteLength};
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

/* column-major 4x4, double */
struct Mat4 {
    double m[16];
};

Mat4 mat_identity()
{
    Mat4 r{};
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0;
    return r;
}

Mat4 mat_mul(const Mat4 &a, const Mat4 &b)
{
    Mat4 r{};
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += a.m[k * 4 + row] * b.m[col * 4 + k];
            r.m[col * 4 + row] = s;
        }
    return r;
}

Mat4 node_local(const tinygltf::Node &n, int ni)
{
    Mat4 r = mat_identity();
    if (n.matrix.size() == 16) {
        for (int i = 0; i < 16; i++) r.m[i] = n.matrix[size_t(i)];
        return r;
    }
    double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
    if (n.translation.size() == 3)
        for (int i = 0; i < 3; i++) t[i] = n.translation[size_t(i)];
    if (n.scale.size() == 3)
        for (int i = 0; i < 3; i++) s[i] = n.scale[size_t(i)];
    if (n.rotation.size() == 4) {
        for (int i = 0; i < 4; i++) q[i] = n.rotation[size_t(i)];
        double l = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        if (!(l > 1e-12)) gfail(strf("nodes[%d].rotation: zero-length quaternion", ni));
        for (double &x : q) x /= l;
    }
    double x = q[0], y = q[1], z = q[2], w = q[3];
    double R[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                   2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                   2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
    /* R is column-major: column c = R[c*3 .. c*3+2]; M = T * R * S */
    for (int col = 0; col < 3; col++)
        for (int row = 0; row < 3; row++) r.m[col * 4 + row] = R[col * 3 + row] * s[col];
    r.m[12] = t[0];
    r.m[13] = t[1];
    r.m[14] = t[2];
    return r;
}

struct Out {
    std::vector<pg_vertex> verts;
    std::vector<uint32_t> idx;
    std::vector<pg_primitive> prims;
    std::vector<uint32_t> prim_gltf_material; /* -1 (UINT32_MAX) = default material */
    std::vector<char> prim_has_uv1;           /* the primitive has TEXCOORD_1 */
    std::vector<float> colors;                /* COLOR_0, 4 per vertex; empty when no primitive has it */
    std::vector<float> uv1;                   /* TEXCOORD_1, 2 per vertex; empty when none has it */
};

void check_finite(const float *v, int n, const View &view, const char *semantic, size_t i)
{
    for (int k = 0; k < n; k++)
        if (!std::isfinite(v[k]))
            gfail(strf("accessors[%d]: %s element %zu is not finite (%g)", view.index, semantic, i,
                       double(v[k])));
}

const int *find_attr(const tinygltf::Primitive &p, const char *name)
{
    auto it = p.attributes.find(name);
    return it == p.attributes.end() ? nullptr : &it->second;
}

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
    const int *pa = find_attr(prim, "POSITION");
    if (!pa) gfail(pw + ".attributes: POSITION missing (required)");
    bool has_color1 = false, has_uv2 = false;
    for (const auto &at : prim.attributes) {
        has_color1 = has_color1 || (at.first.compare(0, 6, "COLOR_") == 0 && at.first != "COLOR_0");
        has_uv2 = has_uv2 || (at.first.compare(0, 9, "TEXCOORD_") == 0 && at.first != "TEXCOORD_0" &&
                              at.first != "TEXCOORD_1");
    }
    c.color1_prims += has_color1;
    c.texcoord2_prims += has_uv2;
    const bool quant = c.quantization;
    View pos = get_view(c, *pa);
    expect_attr(pos, "POSITION", TINYGLTF_TYPE_VEC3, ATTR_POSITION, quant);
    const size_t n = pos.count;

    auto optional_view = [&](const char *name) -> std::unique_ptr<View> {
        const int *ai = find_attr(prim, name);
        if (!ai) return nullptr;
        std::unique_ptr<View> v(new View(get_view(c, *ai)));
        if (v->count != n)
            gfail(strf("%s: %s (accessors[%d]) has %zu elements but POSITION has %zu", pw.c_str(),
                       name, *ai, v->count, n));
        return v;
    };
    std::unique_ptr<View> nrm = optional_view("NORMAL");
    if (nrm) expect_attr(*nrm, "NORMAL", TINYGLTF_TYPE_VEC3, ATTR_NORMAL, quant);
    std::unique_ptr<View> tan = optional_view("TANGENT");
    if (tan) expect_attr(*tan, "TANGENT", TINYGLTF_TYPE_VEC4, ATTR_TANGENT, quant);
    /* COLOR_0: FLOAT, or normalized UNSIGNED_BYTE / UNSIGNED_SHORT (core glTF) */
    auto float_or_unorm = [](const View &v) {
        return v.ctype == TINYGLTF_COMPONENT_TYPE_FLOAT ||
               (v.normalized && (v.ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                 v.ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
    };
    std::unique_ptr<View> uv = optional_view("TEXCOORD_0");
    if (uv) expect_attr(*uv, "TEXCOORD_0", TINYGLTF_TYPE_VEC2, ATTR_TEXCOORD, quant);
    std::unique_ptr<View> uv1 = optional_view("TEXCOORD_1");
    if (uv1) expect_attr(*uv1, "TEXCOORD_1", TINYGLTF_TYPE_VEC2, ATTR_TEXCOORD, quant);
    std::unique_ptr<View> col = optional_view("COLOR_0");
    if (col && !((col->type == TINYGLTF_TYPE_VEC3 || col->type == TINYGLTF_TYPE_VEC4) && float_or_unorm(*col)))
        gfail(strf("accessors[%d]: COLOR_0 must be VEC3 or VEC4, FLOAT or normalized "
                   "UNSIGNED_BYTE/UNSIGNED_SHORT (got %s %s%s)",
                   col->index, type_name(col->type), col->normalized ? "normalized " : "",
                   ctype_name(col->ctype)));

    /* indices (local to this primitive) */
    std::vector<uint32_t> ind;
    if (prim.indices >= 0) {
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
    } else {
        if (n > 0xFFFFFFFFull) fail(PG_ERR_LIMIT, pw + ": too many vertices");
        ind.resize(n);
        for (size_t i = 0; i < n; i++) ind[i] = uint32_t(i);
    }

    /* strips and fans become lists */
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
    if (ind.empty() || n == 0) return;

    /* transform: positions by M, normals by the inverse-transpose of M's upper 3x3, tangents by
     * the upper 3x3; a mirroring transform flips the winding and the tangent handedness */
    const double *m = M.m;
    double a00 = m[0], a01 = m[4], a02 = m[8], a10 = m[1], a11 = m[5], a12 = m[9], a20 = m[2],
           a21 = m[6], a22 = m[10];
    double cof[9] = {a11 * a22 - a12 * a21, a12 * a20 - a10 * a22, a10 * a21 - a11 * a20,
                     a02 * a21 - a01 * a22, a00 * a22 - a02 * a20, a01 * a20 - a00 * a21,
                     a01 * a12 - a02 * a11, a02 * a10 - a00 * a12, a00 * a11 - a01 * a10};
    /* cof[r*3+c] = cofactor(r,c); inverse-transpose = cof / det */
    double det = a00 * cof[0] + a01 * cof[1] + a02 * cof[2];
    if (!std::isfinite(det)) gfail(pw + ": node transform is not finite");
    const double nsign = det < 0 ? -1.0 : 1.0;

    if (o.verts.size() + n > 0xFFFFFFF0ull || o.idx.size() + ind.size() > 0xFFFFFFF0ull ||
        o.verts.size() > 0x7FFFFFFFull)
        fail(PG_ERR_LIMIT, pw + ": scene exceeds 2^32 vertices or indices");
    const size_t base = o.verts.size();
    o.verts.resize(base + n);
    /* the optional streams exist from the first primitive that has the attribute on (white /
     * TEXCOORD_0 for the vertices of primitives without it, below) */
    if (col || !o.colors.empty()) o.colors.resize((base + n) * 4, 1.0f);
    const bool uv1_fresh = uv1 && o.uv1.empty();
    if (uv1 || !o.uv1.empty()) o.uv1.resize((base + n) * 2, 0.0f);
    pg_vertex *V = o.verts.data() + base;
    for (size_t i = 0; i < n; i++) {
        pg_vertex &vx = V[i];
        float p[3];
        read_floats(pos, i, p);
        check_finite(p, 3, pos, "POSITION", i);
        for (int r = 0; r < 3; r++) {
            /* finite floats under a finite transform can still leave the float range */
            double x = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
            if (!(std::fabs(x) <= double(FLT_MAX)))
                gfail(strf("%s: POSITION element %zu (accessors[%d]) is outside the float range "
                           "after the node transform",
                           pw.c_str(), i, pos.index));
            vx.position[r] = float(x);
        }
        if (nrm) {
            float q[3];
            read_floats(*nrm, i, q);
            check_finite(q, 3, *nrm, "NORMAL", i);
            double t[3];
            for (int r = 0; r < 3; r++)
                t[r] = nsign * (cof[r * 3 + 0] * q[0] + cof[r * 3 + 1] * q[1] + cof[r * 3 + 2] * q[2]);
            double l = std::hypot(t[0], t[1], t[2]); /* no overflow in the squares */
            if (!std::isfinite(l))
                gfail(strf("%s: NORMAL element %zu (accessors[%d]) overflows under the node "
                           "transform",
                           pw.c_str(), i, nrm->index));
            if (l > 1e-30) {
                for (int r = 0; r < 3; r++) vx.normal[r] = float(t[r] / l);
            } else {
                vx.normal[0] = 0;
                vx.normal[1] = 1;
                vx.normal[2] = 0;
            }
        }
        if (uv) {
            read_floats(*uv, i, vx.uv);
            check_finite(vx.uv, 2, *uv, "TEXCOORD_0", i);
        }
        if (col) {
            float q[4] = {1, 1, 1, 1}; /* VEC3: alpha 1 */
            read_floats(*col, i, q);
            check_finite(q, col->ncomp, *col, "COLOR_0", i);
            memcpy(&o.colors[(base + i) * 4], q, sizeof q);
        }
        if (uv1) {
            read_floats(*uv1, i, &o.uv1[(base + i) * 2]);
            check_finite(&o.uv1[(base + i) * 2], 2, *uv1, "TEXCOORD_1", i);
        }
        if (tan) {
            float q[4];
            read_floats(*tan, i, q);
            check_finite(q, 4, *tan, "TANGENT", i);
            double t[3];
            for (int r = 0; r < 3; r++) t[r] = m[r] * q[0] + m[4 + r] * q[1] + m[8 + r] * q[2];
            double l = std::hypot(t[0], t[1], t[2]);
            if (!std::isfinite(l))
                gfail(strf("%s: TANGENT element %zu (accessors[%d]) overflows under the node "
                           "transform",
                           pw.c_str(), i, tan->index));
            if (l > 1e-30)
                for (int r = 0; r < 3; r++) vx.tangent[r] = float(t[r] / l);
            vx.tangent[3] = float((q[3] < 0 ? -1.0 : 1.0) * nsign);
        }
    }
    /* TEXCOORD_1 of the vertices of primitives without it: a copy of their TEXCOORD_0 (what a
     * texture reading set 1 then samples, as when no primitive has TEXCOORD_1; warned) */
    if (!o.uv1.empty()) {
        const size_t from = uv1_fresh ? 0 : base, to = uv1 ? base : base + n;
        for (size_t j = from; j < to; j++) memcpy(&o.uv1[j * 2], o.verts[j].uv, sizeof(float[2]));
    }
    if (det < 0)
        for (size_t t = 0; t + 2 < ind.size(); t += 3) std::swap(ind[t + 1], ind[t + 2]);

    if (!nrm) pg_mesh_compute_normals(V, uint32_t(n), ind.data(), uint32_t(ind.size()));
    bool normal_mapped = prim.material >= 0 &&
                         c.model.materials[size_t(prim.material)].normalTexture.index >= 0;
    if (!tan && normal_mapped)
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
    o.prim_has_uv1.push_back(uv1 != nullptr);
}

struct Walker {
    Ctx &c;
    Out &o;
    std::vector<char> on_path;
    size_t visits = 0;

    void visit(int ni, const Mat4 &parent, int depth)
    {
        const auto &nodes = c.model.nodes;
        if (ni < 0 || size_t(ni) >= nodes.size())
            gfail(strf("nodes[%d]: out of range (%zu nodes)", ni, nodes.size()));
        if (on_path[size_t(ni)])
            gfail(strf("nodes[%d]: cyclic node graph (nodes[%d] is its own ancestor)", ni, ni));
        if (depth > kMaxNodeDepth)
            fail(PG_ERR_LIMIT, strf("nodes[%d]: node hierarchy deeper than %d", ni, kMaxNodeDepth));
        if (++visits > kMaxNodeVisits)
            fail(PG_ERR_LIMIT, strf("nodes: more than %zu node instances", kMaxNodeVisits));
        const tinygltf::Node &nd = nodes[size_t(ni)];
        Mat4 world = mat_mul(parent, node_local(nd, ni));
        for (double x : world.m)
            if (!std::isfinite(x)) gfail(strf("nodes[%d]: world transform is not finite", ni));
        on_path[size_t(ni)] = 1;
        if (nd.mesh >= 0) {
            if (size_t(nd.mesh) >= c.model.meshes.size())
                gfail(strf("nodes[%d].mesh: %d out of range", ni, nd.mesh));
            const tinygltf::Mesh &mesh = c.model.meshes[size_t(nd.mesh)];
            for (size_t p = 0; p < mesh.primitives.size(); p++)
                emit_primitive(c, o, nd.mesh, int(p), world);
        }
        for (int ch : nd.children) visit(ch, world, depth + 1);
        on_path[size_t(ni)] = 0;
    }
};

float clamp01(double x) { return float(x < 0 ? 0 : x > 1 ? 1 : x); }

/* One pg_texture per (image, colour space, sampler state) use. */
struct TexKey {
    int image;
    bool srgb;
    pg_sampler_state sampler;
    std::tuple<int, bool, int, int, bool, bool, int> tie() const
    {
        return std::make_tuple(image, srgb, int(sampler.wrap_s), int(sampler.wrap_t), sampler.mag_nearest,
                               sampler.min_nearest, int(sampler.mip));
    }
    bool operator<(const TexKey &b) const { return tie() < b.tie(); }
};

pg_wrap wrap_of(int w)
{
    if (w == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return PG_WRAP_CLAMP;
    if (w == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return PG_WRAP_MIRROR;
    return PG_WRAP_REPEAT; /* REPEAT; unknown values are warned (collect_warnings) */
}

/* glTF sampler -> pg_sampler_state: absent filters are LINEAR / LINEAR_MIPMAP_LINEAR; the
 * minFilter values without MIPMAP sample level 0 only (PG_MIP_NONE). */
pg_sampler_state sampler_state(const tinygltf::Sampler &sm)
{
    pg_sampler_state st;
    memset(&st, 0, sizeof st);
    st.wrap_s = wrap_of(sm.wrapS);
    st.wrap_t = wrap_of(sm.wrapT);
    st.mag_nearest = sm.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
    switch (sm.minFilter) {
    case TINYGLTF_TEXTURE_FILTER_NEAREST: st.min_nearest = true; st.mip = PG_MIP_NONE; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR: st.mip = PG_MIP_NONE; break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: st.min_nearest = true; st.mip = PG_MIP_NEAREST; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: st.mip = PG_MIP_NEAREST; break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: st.min_nearest = true; break;
    default: break; /* LINEAR_MIPMAP_LINEAR, absent, unknown (warned) */
    }
    return st;
}

/* KHR_texture_transform of a textureInfo JSON object `ti` (at `where`): fills the 2x3 row-major
 * matrix M = T * R * S of the extension spec (rotation counter-clockwise in UV space):
 *   { sx cos r,  sy sin r, ox,
 *    -sx sin r,  sy cos r, oy }
 * and returns true when the extension is present; *tex_coord is replaced by its texCoord. */
bool texture_transform(const json &ti, const std::string &where, float m[6], int *tex_coord)
{
    const json *ext = opt_object(ti, "extensions", where);
    if (!ext) return false;
    const std::string xw = where + ".extensions";
    const json *tt = opt_object(*ext, "KHR_texture_transform", xw);
    if (!tt) return false;
    const std::string tw = xw + ".KHR_texture_transform";
    auto vec2 = [&](const char *key, double def, double out[2]) {
        out[0] = out[1] = def;
        auto it = tt->find(key);
        if (it == tt->end()) return;
        bool ok = it->is_array() && it->size() == 2;
        if (ok)
            for (const json &x : *it) ok = ok && x.is_number() && std::isfinite(x.get<double>());
        if (!ok) gfail(strf("%s.%s: expected 2 finite numbers", tw.c_str(), key));
        out[0] = (*it)[0].get<double>();
        out[1] = (*it)[1].get<double>();
    };
    double off[2], sc[2], rot = 0;
    vec2("offset", 0.0, off);
    vec2("scale", 1.0, sc);
    auto rit = tt->find("rotation");
    if (rit != tt->end()) {
        if (!rit->is_number() || !std::isfinite(rit->get<double>()))
            gfail(tw + ".rotation: expected a finite number (radians)");
        rot = rit->get<double>();
    }
    if (tt->contains("texCoord")) *tex_coord = int(std::min<uint64_t>(uint_field(*tt, "texCoord", tw, false), 1u << 20));
    const double cr = std::cos(rot), sr = std::sin(rot);
    m[0] = float(sc[0] * cr);
    m[1] = float(sc[1] * sr);
    m[2] = float(off[0]);
    m[3] = float(-sc[0] * sr);
    m[4] = float(sc[1] * cr);
    m[5] = float(off[1]);
    return true;
}

struct SceneDeleter {
    void operator()(pg_scene *s) const { pg_scene_free(s); }
};

template <class T> T *copy_out(const std::vector<T> &v)
{
    if (v.empty()) return nullptr;
    T *p = static_cast<T *>(malloc(sizeof(T) * v.size()));
    if (!p) throw std::bad_alloc();
    memcpy(p, v.data(), sizeof(T) * v.size());
    return p;
}

std::string file_stem(const std::string &path)
{
    size_t s = path.find_last_of("/\\");
    std::string b = s == std::string::npos ? path : path.substr(s + 1);
    size_t d = b.find_last_of('.');
    if (d != std::string::npos && d > 0) b = b.substr(0, d);
    return b;
}

std::string image_name(const tinygltf::Image &im, int idx)
{
    if (!im.name.empty()) return im.name;
    if (!im.uri.empty() && im.uri.compare(0, 5, "data:") != 0) return file_stem(im.uri);
    return strf("image%d", idx);
}

/* ---- cameras: every camera node reached from the scene roots, depth-first in node order (the
 * Walker above has already rejected cycles and out-of-range children) ---- */
void camera_visit(const Ctx &c, int ni, const Mat4 &parent, std::vector<pg_scene_camera> &out)
{
    const tinygltf::Model &md = c.model;
    const tinygltf::Node &nd = md.nodes[size_t(ni)];
    Mat4 world = mat_mul(parent, node_local(nd, ni));
    if (nd.camera >= 0) {
        if (size_t(nd.camera) >= md.cameras.size())
            gfail(strf("nodes[%d].camera: %d out of range (%zu cameras)", ni, nd.camera, md.cameras.size()));
        const tinygltf::Camera &gc = md.cameras[size_t(nd.camera)];
        const std::string cw = strf("cameras[%d]", nd.camera);
        pg_scene_camera sc;
        memset(&sc, 0, sizeof sc);
        pg_strlcpy(sc.name, gc.name.empty() ? cw.c_str() : gc.name.c_str(), sizeof sc.name);
        pg_strlcpy(sc.node_name, nd.name.empty() ? strf("nodes[%d]", ni).c_str() : nd.name.c_str(),
                   sizeof sc.node_name);
        sc.gltf_camera = nd.camera;
        sc.gltf_node = ni;
        if (gc.type == "perspective") {
            const auto &p = gc.perspective;
            if (!(std::isfinite(p.yfov) && p.yfov > 0 && p.yfov < 3.14159))
                gfail(cw + ".perspective.yfov: expected a finite angle in (0, pi) radians");
            if (!(std::isfinite(p.znear) && p.znear > 0))
                gfail(cw + ".perspective.znear: expected a finite number > 0");
            if (!(std::isfinite(p.zfar) && (p.zfar == 0 || p.zfar > p.znear)))
                gfail(cw + ".perspective.zfar: expected a finite number > znear (or absent: infinite)");
            if (!(std::isfinite(p.aspectRatio) && p.aspectRatio >= 0))
                gfail(cw + ".perspective.aspectRatio: expected a finite number > 0");
            sc.type = PG_CAMERA_PERSPECTIVE;
            sc.yfov_rad = float(p.yfov);
            sc.aspect_ratio = float(p.aspectRatio);
            sc.znear = float(p.znear);
            sc.zfar = float(p.zfar);
        } else if (gc.type == "orthographic") {
            const auto &o = gc.orthographic;
            if (!(std::isfinite(o.xmag) && o.xmag != 0 && std::isfinite(o.ymag) && o.ymag != 0))
                gfail(cw + ".orthographic.xmag/ymag: expected finite non-zero numbers");
            if (!(std::isfinite(o.znear) && o.znear >= 0 && std::isfinite(o.zfar) && o.zfar > o.znear))
                gfail(cw + ".orthographic.znear/zfar: expected finite 0 <= znear < zfar");
            sc.type = PG_CAMERA_ORTHOGRAPHIC;
            sc.xmag = float(o.xmag);
            sc.ymag = float(o.ymag);
            sc.znear = float(o.znear);
            sc.zfar = float(o.zfar);
        } else {
            gfail(cw + ".type: '" + gc.type + "': expected \"perspective\" or \"orthographic\"");
        }
        double f[3] = {-world.m[8], -world.m[9], -world.m[10]}, u[3] = {world.m[4], world.m[5], world.m[6]};
        double fl = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        if (!(fl > 1e-30)) gfail(strf("nodes[%d]: camera node transform is singular", ni));
        for (double &x : f) x /= fl;
        double fu = f[0] * u[0] + f[1] * u[1] + f[2] * u[2];
        for (int k = 0; k < 3; k++) u[k] -= fu * f[k];
        double ul = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        if (!(ul > 1e-12 * fl)) gfail(strf("nodes[%d]: camera node transform is singular", ni));
        for (int k = 0; k < 3; k++) {
            sc.position[k] = float(world.m[12 + k]);
            sc.forward[k] = float(f[k]);
            sc.up[k] = float(u[k] / ul);
        }
        out.push_back(sc);
    }
    for (int ch : nd.children) camera_visit(c, ch, world, out);
}

std::string plural(size_t n, const char *one, const char *many)
{
    return strf("%zu %s", n, n == 1 ? one : many);
}

/* "materials[2] 'glass'" */
std::string material_desc(const tinygltf::Model &md, size_t i)
{
    std::string d = strf("materials[%zu]", i);
    if (i < md.materials.size() && !md.materials[i].name.empty())
        d += " '" + md.materials[i].name.substr(0, 60) + "'";
    return d;
}

/* Up to 3 names, then ", ..." */
std::string name_list(const std::vector<std::string> &v)
{
    std::string r;
    for (size_t i = 0; i < v.size() && i < 3; i++) r += (i ? ", " : "") + v[i];
    if (v.size() > 3) r += ", ...";
    return r;
}

std::string wrap_name(int w)
{
    switch (w) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return "CLAMP_TO_EDGE";
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return "MIRRORED_REPEAT";
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return "REPEAT";
    default: return strf("%d", w);
    }
}

std::string filter_name(int f)
{
    switch (f) {
    case TINYGLTF_TEXTURE_FILTER_NEAREST: return "NEAREST";
    case TINYGLTF_TEXTURE_FILTER_LINEAR: return "LINEAR";
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: return "NEAREST_MIPMAP_NEAREST";
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: return "LINEAR_MIPMAP_NEAREST";
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: return "NEAREST_MIPMAP_LINEAR";
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR: return "LINEAR_MIPMAP_LINEAR";
    default: return strf("%d", f);
    }
}

/* What an extension in extensionsUsed (and not in extensionsRequired, which is refused) means
 * for the image. */
std::string extension_effect(const std::string &e)
{
    if (e == "KHR_texture_transform") return "texture offset/rotation/scale not applied";
    if (e == "KHR_lights_punctual") return "the file's lights are not used";
    if (e == "KHR_materials_variants") return "the default material of each primitive is drawn";
    if (e.compare(0, 14, "KHR_materials_") == 0) return "the core material is drawn without it";
    return "not supported";
}

/* Every feature the file uses that is not drawn as the file asks: one line each (see scene.h). */
void collect_warnings(Ctx &c)
{
    const tinygltf::Model &md = c.model;
    auto &W = c.warnings;
    if (c.skipped_prims)
        W.push_back(strf("skipped %u point/line primitive(s) (only triangles are drawn)",
                         c.skipped_prims));
    if (!md.skins.empty())
        W.push_back(plural(md.skins.size(), "skin", "skins") + " ignored: rendered in bind pose");
    size_t morph_meshes = 0, morph_targets = 0;
    for (const auto &m : md.meshes) {
        size_t t = 0;
        for (const auto &p : m.primitives) t = std::max(t, p.targets.size());
        morph_meshes += t > 0;
        morph_targets += t;
    }
    if (!md.animations.empty())
        W.push_back(plural(md.animations.size(), "animation", "animations") +
                    " ignored: the nodes are drawn at their static transforms");
    if (morph_meshes)
        W.push_back(plural(morph_targets, "morph target", "morph targets") + " in " +
                    plural(morph_meshes, "mesh", "meshes") +
                    " ignored: rendered with the base geometry (weights not applied)");
    constexpr size_t kMaxExtensionLines = 16;
    std::vector<std::string> unimpl;
    for (const std::string &e : md.extensionsUsed)
        if (!extension_implemented(e)) unimpl.push_back(e);
    for (size_t i = 0; i < unimpl.size() && i < kMaxExtensionLines; i++) {
        const std::string &e = unimpl[i];
        W.push_back("extensionsUsed: '" + e.substr(0, 80) + "' ignored: " + extension_effect(e));
    }
    if (unimpl.size() > kMaxExtensionLines)
        W.push_back(strf("extensionsUsed: %zu more extensions ignored (not supported)",
                         unimpl.size() - kMaxExtensionLines));

    std::vector<std::string> occlusion, mr, texcoord;
    for (size_t i = 0; i < md.materials.size(); i++) {
        const tinygltf::Material &m = md.materials[i];
        if ((m.pbrMetallicRoughness.baseColorTexture.index >= 0 &&
             m.pbrMetallicRoughness.baseColorTexture.texCoord > 1) ||
            (m.normalTexture.index >= 0 && m.normalTexture.texCoord > 1) ||
            (m.emissiveTexture.index >= 0 && m.emissiveTexture.texCoord > 1))
            texcoord.push_back(material_desc(md, i));
        if (m.occlusionTexture.index >= 0) occlusion.push_back(material_desc(md, i));
        if (m.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0)
            mr.push_back(material_desc(md, i));
    }
    if (!mr.empty())
        W.push_back("metallicRoughnessTexture of " + plural(mr.size(), "material", "materials") +
                    " (" + name_list(mr) + ") ignored: the metallic/roughness factors are used");
    if (!occlusion.empty())
        W.push_back("occlusionTexture of " + plural(occlusion.size(), "material", "materials") +
                    " (" + name_list(occlusion) + ") ignored");
    if (!texcoord.empty())
        W.push_back("textures of " + plural(texcoord.size(), "material", "materials") + " (" +
                    name_list(texcoord) + ") ask for a texCoord other than 0 or 1: read with TEXCOORD_0");
    if (c.color1_prims)
        W.push_back("COLOR_1 (and higher) in " +
                    plural(c.color1_prims, "primitive", "primitives") + " ignored: COLOR_0 is used");
    if (c.texcoord2_prims)
        W.push_back("TEXCOORD_2 (and higher) in " +
                    plural(c.texcoord2_prims, "primitive", "primitives") +
                    " ignored: textures read TEXCOORD_0 or TEXCOORD_1");

    std::vector<std::string> odd;
    for (size_t i = 0; i < md.samplers.size(); i++) {
        const tinygltf::Sampler &sm = md.samplers[i];
        /* the glTF values are drawn (sampler_state); only values outside the spec are warned */
        auto wrap_ok = [](int w) {
            return w == TINYGLTF_TEXTURE_WRAP_REPEAT || w == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ||
                   w == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
        };
        std::string d;
        if (!wrap_ok(sm.wrapS)) d += " wrapS " + wrap_name(sm.wrapS);
        if (!wrap_ok(sm.wrapT)) d += " wrapT " + wrap_name(sm.wrapT);
        if (sm.magFilter >= 0 && sm.magFilter != TINYGLTF_TEXTURE_FILTER_LINEAR &&
            sm.magFilter != TINYGLTF_TEXTURE_FILTER_NEAREST)
            d += " magFilter " + filter_name(sm.magFilter);
        if (sm.minFilter >= 0 && filter_name(sm.minFilter) == strf("%d", sm.minFilter))
            d += " minFilter " + filter_name(sm.minFilter);
        if (!d.empty()) odd.push_back(strf("samplers[%zu]:", i) + d);
    }
    if (!odd.empty())
        W.push_back(plural(odd.size(), "sampler", "samplers") + " with unknown wrap/filter values (" +
                    name_list(odd) + ") ignored: REPEAT / LINEAR (trilinear) used for them");
}

pg_scene *load(Ctx &c)
{
    /* 1. the file */
    char *raw = nullptr;
    size_t raw_size = 0;
    pg_error rerr;
    memset(&rerr, 0, sizeof rerr);
    if (pg_read_file_as(c.path.c_str(), "a glTF 2.0 .gltf/.glb file", &raw, &raw_size, &rerr) !=
        PG_OK) {
        /* keep pg_read_file's "PATH: cannot open: ..." message */
        throw LoadFail{rerr.code, std::string("\x01") + rerr.msg};
    }
    std::unique_ptr<char, decltype(&free)> raw_owner(raw, &free);
    const unsigned char *bytes = reinterpret_cast<const unsigned char *>(raw);
    if (raw_size == 0) fail(PG_ERR_PARSE, "empty file");
    c.is_glb = raw_size >= 4 && memcmp(raw, "glTF", 4) == 0;
    if (!c.is_glb) {
        /* a .gltf is a JSON object: anything else (an .obj, .fbx, .ply, a PNG...) is another
         * format, said plainly instead of a JSON syntax error */
        size_t k = 0;
        if (raw_size >= 3 && memcmp(raw, "\xEF\xBB\xBF", 3) == 0) k = 3; /* UTF-8 BOM */
        while (k < raw_size && (raw[k] == ' ' || raw[k] == '\t' || raw[k] == '\r' || raw[k] == '\n'))
            k++;
        if (k == raw_size) fail(PG_ERR_PARSE, "empty file");
        if (raw[k] != '{' && raw[k] != '[')
            fail(PG_ERR_PARSE, "not a glTF 2.0 file (passgraph reads .gltf and .glb only)");
    }

    /* 2. JSON + pre-validation */
    {
        std::string text = c.is_glb ? glb_json(c, bytes, raw_size) : std::string(raw, raw_size);
        check_json_depth(text);
        try {
            c.j = json::parse(text);
        } catch (const json::parse_error &e) {
            std::string w = e.what();
            size_t k = w.find("] ");
            if (k != std::string::npos) w = w.substr(k + 2);
            fail(PG_ERR_PARSE, "JSON syntax error: " + w);
        }
    }
    prevalidate(c);

    /* 3. tinygltf */
    {
        tinygltf::TinyGLTF loader;
        tinygltf::FsCallbacks fs;
        fs.FileExists = &fs_file_exists;
        fs.ExpandFilePath = &tinygltf::ExpandFilePath;
        fs.ReadWholeFile = &tinygltf::ReadWholeFile;
        fs.WriteWholeFile = &tinygltf::WriteWholeFile;
        fs.user_data = &c;
        loader.SetFsCallbacks(fs);
        loader.SetImageLoader(&load_image_cb, &c);
        std::string terr, twarn;
        if (raw_size > 0xFFFFFFFFull) fail(PG_ERR_LIMIT, "file larger than 4 GiB");
        /* EXT_meshopt_compression fallback buffers are not loaded: tinygltf would look for a
         * file (or refuse a missing uri), so it gets a copy of the file in which each is a
         * 4-byte data URI (never read: only
         * compressed bufferViews use it, and those are read from their decoded data); Draco
         * indices accessors without a bufferView get one (see prevalidate) */
        std::vector<unsigned char> rewritten;
        if (std::find(c.buffer_no_data.begin(), c.buffer_no_data.end(), 1) != c.buffer_no_data.end() ||
            !c.draco_index_fix.empty()) {
            json j2 = c.j;
            for (const auto &fx : c.draco_index_fix)
                j2["accessors"][size_t(fx.first)]["bufferView"] = fx.second;
            for (size_t i = 0; i < c.buffer_no_data.size(); i++)
                if (c.buffer_no_data[i]) {
                    j2["buffers"][i]["uri"] = "data:application/octet-stream;base64,AAAAAA==";
                    j2["buffers"][i]["byteLength"] = 4;
                }
            std::string t = j2.dump();
            if (!c.is_glb) {
                rewritten.assign(t.begin(), t.end());
            } else {
                while ((20 + t.size()) % 4) t += ' ';
                const size_t old_json_end = 20 + size_t(rd_u32(bytes + 12));
                const size_t old_len = rd_u32(bytes + 8);
                const size_t total = 20 + t.size() + (old_len - old_json_end);
                if (total > 0xFFFFFFFFull) fail(PG_ERR_LIMIT, "file larger than 4 GiB");
                rewritten.resize(total);
                auto put32 = [&](size_t at, uint32_t v) {
                    for (int k = 0; k < 4; k++) rewritten[at + size_t(k)] = (unsigned char)(v >> (8 * k));
                };
                memcpy(rewritten.data(), bytes, 8); /* magic, version */
                put32(8, uint32_t(total));
                put32(12, uint32_t(t.size()));
                put32(16, 0x4E4F534Au);
                memcpy(rewritten.data() + 20, t.data(), t.size());
                memcpy(rewritten.data() + 20 + t.size(), bytes + old_json_end, old_len - old_json_end);
            }
        }
        const unsigned char *tbytes = rewritten.empty() ? bytes : rewritten.data();
        const size_t tsize = rewritten.empty() ? raw_size : rewritten.size();
        if (tsize > 0xFFFFFFFFull) fail(PG_ERR_LIMIT, "file larger than 4 GiB");
        bool ok = c.is_glb ? loader.LoadBinaryFromMemory(&c.model, &terr, &twarn, tbytes,
                                                         unsigned(tsize), c.base_dir)
                           : loader.LoadASCIIFromString(&c.model, &terr, &twarn,
                                                        reinterpret_cast<const char *>(tbytes),
                                                        unsigned(tsize), c.base_dir);
        if (!c.image_err.empty()) gfail(c.image_err);
        if (!ok) {
            std::string why = first_lines(terr.empty() ? twarn : terr);
            gfail("tinygltf: " + (why.empty() ? std::string("load failed") : why));
        }
        for (size_t i = 0; i < c.model.images.size(); i++) {
            const tinygltf::Image &im = c.model.images[i];
            if (im.image.empty() || im.width < 1 || im.height < 1 ||
                im.image.size() != size_t(im.width) * size_t(im.height) * 4)
                gfail(image_desc(c, int(i)) + ": could not be loaded");
        }
    }
    raw_owner.reset();
    for (const std::string &e : c.model.extensionsUsed)
        c.quantization = c.quantization || e == "KHR_mesh_quantization";
    decode_meshopt(c);
    const tinygltf::Model &md = c.model;

    /* 4. node hierarchy -> geometry */
    Out o;
    std::vector<pg_scene_camera> cams;
    {
        std::vector<int> roots;
        if (md.defaultScene >= 0 && size_t(md.defaultScene) < md.scenes.size()) {
            roots = md.scenes[size_t(md.defaultScene)].nodes;
        } else if (!md.scenes.empty()) {
            roots = md.scenes[0].nodes;
        } else {
            std::vector<char> is_child(md.nodes.size(), 0);
            for (const auto &nd : md.nodes)
                for (int ch : nd.children)
                    if (ch >= 0 && size_t(ch) < md.nodes.size()) is_child[size_t(ch)] = 1;
            for (size_t i = 0; i < md.nodes.size(); i++)
                if (!is_child[i]) roots.push_back(int(i));
            if (roots.empty() && !md.nodes.empty())
                gfail("nodes: cyclic node graph (every node is some node's child)");
        }
        Walker w{c, o, std::vector<char>(md.nodes.size(), 0), 0};
        for (int r : roots) w.visit(r, mat_identity(), 0);
        for (int r : roots) camera_visit(c, r, mat_identity(), cams);
    }
    if (o.idx.empty()) gfail("the scene has no triangles");
    collect_warnings(c);

    /* 5. materials and textures */
    std::vector<pg_material> mats;
    std::map<TexKey, uint32_t> tex_of;
    std::vector<TexKey> tex_order;
    auto texture_for = [&](int tex_index, bool srgb, const std::string &where) -> int {
        if (tex_index < 0) return -1;
        if (size_t(tex_index) >= md.textures.size())
            gfail(strf("%s: texture %d out of range", where.c_str(), tex_index));
        int src = md.textures[size_t(tex_index)].source;
        if (src < 0 || size_t(src) >= md.images.size())
            gfail(strf("textures[%d]: no usable source image", tex_index));
        int smp = md.textures[size_t(tex_index)].sampler;
        TexKey k{src, srgb, {}};
        if (smp >= 0 && size_t(smp) < md.samplers.size()) k.sampler = sampler_state(md.samplers[size_t(smp)]);
        auto it = tex_of.find(k);
        if (it != tex_of.end()) return int(it->second);
        uint32_t id = uint32_t(tex_order.size());
        tex_of[k] = id;
        tex_order.push_back(k);
        return int(id);
    };
    for (size_t i = 0; i < md.materials.size(); i++) {
        const tinygltf::Material &gm = md.materials[i];
        const std::string mw = strf("materials[%zu]", i);
        pg_material pm;
        pg_material_init(&pm, gm.name.empty() ? mw.c_str() : gm.name.c_str());
        const auto &pbr = gm.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() != 4)
            gfail(mw + ".pbrMetallicRoughness.baseColorFactor: expected 4 numbers");
        for (int k = 0; k < 4; k++) {
            double x = pbr.baseColorFactor[size_t(k)];
            if (!std::isfinite(x))
                gfail(mw + ".pbrMetallicRoughness.baseColorFactor: not finite");
            pm.base_color[k] = clamp01(x);
        }
        pm.base_color_tex = texture_for(pbr.baseColorTexture.index, true,
                                        mw + ".pbrMetallicRoughness.baseColorTexture");
        pm.normal_tex = texture_for(gm.normalTexture.index, false, mw + ".normalTexture");
        pm.emissive_tex = texture_for(gm.emissiveTexture.index, true, mw + ".emissiveTexture");
        /* per slot: texCoord (0 or 1; higher is warned and reads TEXCOORD_0) and
         * KHR_texture_transform (whose texCoord overrides the textureInfo's) */
        {
            const json &jm = c.j.at("materials").at(i);
            const json *jpbr = opt_object(jm, "pbrMetallicRoughness", mw);
            const struct {
                int slot, index, tex_coord;
                const json *ti;
                std::string where;
            } slots[] = {
                {PG_TEXSLOT_BASE, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                 jpbr ? opt_object(*jpbr, "baseColorTexture", mw) : nullptr,
                 mw + ".pbrMetallicRoughness.baseColorTexture"},
                {PG_TEXSLOT_NORMAL, gm.normalTexture.index, gm.normalTexture.texCoord,
                 opt_object(jm, "normalTexture", mw), mw + ".normalTexture"},
                {PG_TEXSLOT_EMISSIVE, gm.emissiveTexture.index, gm.emissiveTexture.texCoord,
                 opt_object(jm, "emissiveTexture", mw), mw + ".emissiveTexture"},
            };
            for (const auto &sl : slots) {
                if (sl.index < 0 || !sl.ti) continue;
                int tc = sl.tex_coord;
                pm.has_uv_transform[sl.slot] =
                    texture_transform(*sl.ti, sl.where, pm.uv_transform[sl.slot], &tc);
                pm.tex_coord[sl.slot] = uint8_t(tc == 1 ? 1 : 0);
            }
        }
        pm.normal_scale = float(std::isfinite(gm.normalTexture.scale) ? gm.normalTexture.scale : 1.0);
        if (gm.alphaMode == "MASK") pm.alpha_mode = PG_ALPHA_MASK;
        else if (gm.alphaMode == "BLEND") pm.alpha_mode = PG_ALPHA_BLEND;
        else pm.alpha_mode = PG_ALPHA_OPAQUE;
        if (!std::isfinite(gm.alphaCutoff) || gm.alphaCutoff < 0)
            gfail(mw + ".alphaCutoff: expected a finite number >= 0");
        pm.alpha_cutoff = float(gm.alphaCutoff);
        double metal = std::isfinite(pbr.metallicFactor) ? clamp01(pbr.metallicFactor) : 1.0;
        double rough = std::isfinite(pbr.roughnessFactor) ? clamp01(pbr.roughnessFactor) : 1.0;
        pm.specular = float(0.04 + 0.5 * (1.0 - rough) * (1.0 - metal));
        double r4 = rough * rough * rough * rough;
        double sh = 2.0 / (r4 + 1e-4) - 2.0;
        pm.shininess = float(sh < 1 ? 1 : sh > 512 ? 512 : sh);
        pm.double_sided = gm.doubleSided;
        /* emissive = emissiveFactor x emissiveStrength (both checked finite >= 0 by prevalidate) */
        double strength = 1.0;
        auto es = gm.extensions.find("KHR_materials_emissive_strength");
        if (es != gm.extensions.end() && es->second.Has("emissiveStrength"))
            strength = es->second.Get("emissiveStrength").GetNumberAsDouble();
        for (int k = 0; k < 3 && size_t(k) < gm.emissiveFactor.size(); k++) {
            double e = gm.emissiveFactor[size_t(k)] * strength;
            if (!(e <= FLT_MAX))
                gfail(strf("%s.emissiveFactor: %g x emissiveStrength %g is outside the float range", mw.c_str(),
                           gm.emissiveFactor[size_t(k)], strength));
            pm.emissive[k] = float(e);
        }
        mats.push_back(pm);
    }
    bool need_default = false;
    for (size_t p = 0; p < o.prims.size(); p++) {
        uint32_t gmat = o.prim_gltf_material[p];
        if (gmat == UINT32_MAX) {
            need_default = true;
            o.prims[p].material = uint32_t(md.materials.size());
        } else {
            o.prims[p].material = gmat;
        }
    }
    if (need_default) {
        pg_material pm;
        pg_material_init(&pm, "default");
        mats.push_back(pm);
    }

    /* 6. hand out */
    std::unique_ptr<pg_scene, SceneDeleter> s(static_cast<pg_scene *>(calloc(1, sizeof(pg_scene))));
    if (!s) throw std::bad_alloc();
    pg_strlcpy(s->name, file_stem(c.path).c_str(), sizeof s->name);
    pg_strlcpy(s->path, c.path.c_str(), sizeof s->path);
    s->vertices = copy_out(o.verts);
    s->n_vertices = uint32_t(o.verts.size());
    s->indices = copy_out(o.idx);
    s->n_indices = uint32_t(o.idx.size());
    s->primitives = copy_out(o.prims);
    s->n_primitives = uint32_t(o.prims.size());
    s->materials = copy_out(mats);
    s->n_materials = uint32_t(mats.size());
    s->cameras = copy_out(cams);
    s->n_cameras = uint32_t(cams.size());
    /* COLOR_0 when a drawn primitive has it; TEXCOORD_1 when a drawn primitive has it and a
     * texture of its material reads it */
    if (!o.colors.empty()) {
        s->colors = static_cast<float(*)[4]>(malloc(o.colors.size() * sizeof(float)));
        if (!s->colors) throw std::bad_alloc();
        memcpy(s->colors, o.colors.data(), o.colors.size() * sizeof(float));
    }
    bool uv1_read = false;
    unsigned uv1_missing = 0; /* drawn primitives whose material reads TEXCOORD_1 they lack */
    for (size_t p = 0; p < o.prims.size(); p++) {
        if (!o.prims[p].index_count) continue;
        const pg_material &pm = mats[o.prims[p].material];
        const int tex[PG_TEXSLOT_COUNT] = {pm.base_color_tex, pm.normal_tex, pm.emissive_tex};
        bool reads = false;
        for (int t = 0; t < PG_TEXSLOT_COUNT; t++) reads = reads || (tex[t] >= 0 && pm.tex_coord[t] == 1);
        if (reads && o.prim_has_uv1[p]) uv1_read = true;
        if (reads && !o.prim_has_uv1[p]) uv1_missing++;
    }
    if (uv1_missing)
        c.warnings.push_back("TEXCOORD_1 missing in " + plural(uv1_missing, "primitive", "primitives") +
                             " whose material reads it (texCoord 1): TEXCOORD_0 used");
    if (uv1_read) {
        s->uv1 = static_cast<float(*)[2]>(malloc(o.uv1.size() * sizeof(float)));
        if (!s->uv1) throw std::bad_alloc();
        memcpy(s->uv1, o.uv1.data(), o.uv1.size() * sizeof(float));
    }
    if (!tex_order.empty()) {
        s->textures = static_cast<pg_texture *>(calloc(tex_order.size(), sizeof(pg_texture)));
        if (!s->textures) throw std::bad_alloc();
        for (const TexKey &k : tex_order) {
            const tinygltf::Image &im = md.images[size_t(k.image)];
            pg_error terr;
            memset(&terr, 0, sizeof terr);
            if (pg_texture_init(&s->textures[s->n_textures], image_name(im, k.image).c_str(),
                                im.image.data(), uint32_t(im.width), uint32_t(im.height), k.srgb,
                                &terr) != PG_OK)
                fail(terr.code, image_desc(c, k.image) + ": " + terr.msg);
            s->textures[s->n_textures].sampler = k.sampler;
            s->n_textures++;
        }
    }
    for (const std::string &wline : c.warnings) {
        pg_error werr;
        memset(&werr, 0, sizeof werr);
        if (pg_scene_add_warning(s.get(), (c.path + ": " + wline).c_str(), &werr) != PG_OK)
            throw std::bad_alloc();
    }
    pg_scene_finalize(s.get());
    return s.release();
}

} // namespace

extern "C" pg_result pg_scene_load_gltf(const char *path, pg_scene **out, pg_error *err)
{
    if (!out) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_scene_load_gltf: out is NULL");
    *out = nullptr;
    if (!path || !path[0])
        return pg_fail(err, PG_ERR_INVALID_ARG, "pg_scene_load_gltf: empty path");
    try {
        Ctx c;
        c.path = path;
        size_t slash = c.path.find_last_of('/');
        c.base_dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : c.path.substr(0, slash));
        c.dir_prefix = join_path(c.base_dir, "");
        *out = load(c);
        return PG_OK;
    } catch (const LoadFail &f) {
        if (!f.msg.empty() && f.msg[0] == '\x01')
            return pg_fail(err, f.code, "%s", f.msg.c_str() + 1);
        return pg_fail(err, f.code, "%s: %s", path, f.msg.c_str());
    } catch (const std::bad_alloc &) {
        return pg_fail(err, PG_ERR_OOM, "%s: out of memory", path);
    } catch (const std::exception &e) {
        return pg_fail(err, PG_ERR_GLTF, "%s: %s", path, e.what());
    } catch (...) {
        return pg_fail(err, PG_ERR_GLTF, "%s: unknown error", path);
    }
}
