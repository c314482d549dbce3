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
 * extensionsUsed that is not implemented, BLEND materials, COLOR_1+, TEXCOORD_2+, texCoord >= 2, sampler values outside the
 * glTF enums, point/line primitives). The library never prints them. An extensionsRequired entry
 * that is not implemented is an error. A non-GLB file
 * whose first non-blank byte is not '{' or '[' is "not a glTF 2.0 file"; asset.version 1.x is
 * "glTF 1.0 is not supported, only 2.0".
 * Non-finite POSITION / NORMAL / TEXCOORD_0 / TANGENT values are errors, and so are positions that
 * leave the float range (or normals/tangents that overflow) under their node transform.
 *
 * Materials keep the glTF metallic-roughness values (metallic, roughness, their texture, occlusion
 * texture and strength: the pbr light model, shaders/lighting.glsl) and KHR_materials_unlit; for the
 * blinn_phong model they are also mapped to Blinn-Phong:
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
 *
 * The steps live in the files scene_gltf_internal.h lists; this one holds the load order (load()),
 * the GLB container, materials and textures, the hand-out and pg_scene_load_gltf (the helpers
 * every step uses are scene_gltf_util.cpp).
 */
#include "scene_gltf_internal.h"
#include "pg_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

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

namespace pg_gltf {

/* ------------------------------------------------------------------------------------------ */
/* step 1: GLB container                                                                        */

uint32_t rd_u32(const unsigned char *p)
{
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

/* Returns the JSON chunk text. */
std::string glb_json(Ctx &c, const unsigned char *b, size_t n)
{
    if (n < 12) fail(PG_ERR_PARSE, strf("GLB: file too short (%zu bytes) for the 12-byte header", n));
    if (n < 20) fail(PG_ERR_PARSE, strf("GLB: no JSON chunk after the header (%zu bytes in all)", n));
    uint32_t version = rd_u32(b + 4), length = rd_u32(b + 8);
    if (version != 2) fail(PG_ERR_PARSE, strf("GLB: container version %u (need 2)", version));
    if (length > n)
        fail(PG_ERR_PARSE, strf("GLB: header length %u exceeds the file size (%zu bytes)",
                                length, n));
    uint32_t clen = rd_u32(b + 12), ctype = rd_u32(b + 16);
    if (ctype != 0x4E4F534Au) fail(PG_ERR_PARSE, "GLB: first chunk is not JSON");
    if (clen < 1) fail(PG_ERR_PARSE, "GLB: the JSON chunk is empty (length 0)");
    if (20ull + clen > length)
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

/* whether a (regular) file starts with the GLB magic; opened non-blocking */
bool starts_with_glb_magic(const char *path)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return false;
    struct stat st;
    char m[4] = {0, 0, 0, 0};
    bool ok = fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && read(fd, m, 4) == 4 && memcmp(m, "glTF", 4) == 0;
    close(fd);
    return ok;
}

/* the file's bytes, owned (freed by free) */
struct RawFile {
    std::unique_ptr<char, decltype(&free)> owner{nullptr, &free};
    size_t size = 0;
    const unsigned char *bytes() const { return reinterpret_cast<const unsigned char *>(owner.get()); }
};

/* step 1: read the file under its cap (stat first: a regular file under the .glb cap; one over
 * the .gltf cap must be a .glb); sets c.is_glb. A .gltf is a JSON object: anything else (an
 * .obj, .fbx, .ply, a PNG...) is another format, said plainly instead of a JSON syntax error. */
static void read_file(Ctx &c, RawFile &f)
{
    char *raw = nullptr;
    size_t raw_size = 0;
    pg_error rerr;
    memset(&rerr, 0, sizeof rerr);
    uint64_t fsize = 0;
    if (pg_file_check(c.path.c_str(), "scene", PG_FILE_CAP_GLB, &fsize, &rerr) != PG_OK)
        throw LoadFail{rerr.code, std::string("\x01") + rerr.msg};
    if (fsize > PG_FILE_CAP_GLTF_JSON && !starts_with_glb_magic(c.path.c_str())) {
        char got[32];
        pg_file_fmt_size(fsize, got, sizeof got);
        throw LoadFail{PG_ERR_LIMIT, strf("\x01scene '%s': is %s, over the %llu MiB cap for glTF JSON files",
                                          c.path.c_str(), got,
                                          (unsigned long long)(PG_FILE_CAP_GLTF_JSON / PG_MIB))};
    }
    if (pg_file_read(c.path.c_str(), "scene", PG_FILE_CAP_GLB, &raw, &raw_size, &rerr) != PG_OK)
        throw LoadFail{rerr.code, std::string("\x01") + rerr.msg};
    f.owner.reset(raw);
    f.size = raw_size;
    if (raw_size == 0) fail(PG_ERR_PARSE, "empty file");
    c.is_glb = raw_size >= 4 && memcmp(raw, "glTF", 4) == 0;
    if (c.is_glb) return;
    size_t k = 0;
    if (raw_size >= 3 && memcmp(raw, "\xEF\xBB\xBF", 3) == 0) k = 3; /* UTF-8 BOM */
    while (k < raw_size && (raw[k] == ' ' || raw[k] == '\t' || raw[k] == '\r' || raw[k] == '\n'))
        k++;
    if (k == raw_size) fail(PG_ERR_PARSE, "empty file");
    if (raw[k] != '{' && raw[k] != '[')
        fail(PG_ERR_PARSE, "not a glTF 2.0 file (passgraph reads .gltf and .glb only)");
}

/* step 2: the JSON (of the GLB's JSON chunk) into c.j, its nesting bounded first */
static void parse_json(Ctx &c, const RawFile &f)
{
    std::string text = c.is_glb ? glb_json(c, f.bytes(), f.size) : std::string(f.owner.get(), f.size);
    check_json_depth(text);
    try {
        c.j = json::parse(text);
    } catch (const json::parse_error &e) {
        std::string w = e.what();
        size_t k = w.find("] ");
        if (k != std::string::npos) w = w.substr(k + 2);
        size_t lr = w.find("; last read:"); /* the file's own text: never echoed */
        if (lr != std::string::npos) w = w.substr(0, lr);
        fail(PG_ERR_PARSE, "JSON syntax error: " + w);
    }
}

/* The animation channel targets without a "node" (KHR_animation_pointer's, or left to another
 * extension), as (animation, channel): tinygltf 2.7 drops such a channel (and the later channels'
 * indices shift), so the copy it reads gives each "node": 0 (unused: a pointer names the target, and
 * another path is ignored with its reason, scene_gltf_anim.cpp channel_target). */
static std::vector<std::pair<size_t, size_t>> nodeless_targets(const json &j)
{
    std::vector<std::pair<size_t, size_t>> out;
    const auto an = j.find("animations");
    if (an == j.end() || !an->is_array()) return out;
    for (size_t ai = 0; ai < an->size(); ai++) {
        const json &a = (*an)[ai];
        const auto ch = a.is_object() ? a.find("channels") : a.end();
        if (!a.is_object() || ch == a.end() || !ch->is_array()) continue;
        for (size_t ci = 0; ci < ch->size(); ci++) {
            const json &c = (*ch)[ci];
            const auto t = c.is_object() ? c.find("target") : c.end();
            if (c.is_object() && t != c.end() && t->is_object() && !t->contains("node") && t->contains("path"))
                out.emplace_back(ai, ci);
        }
    }
    return out;
}

/* The file as tinygltf is to see it, when it must differ (else empty): EXT_meshopt_compression
 * fallback buffers are not loaded: tinygltf would look for a file (or refuse a missing uri), so
 * it gets a copy of the file in which each is a 4-byte data URI (never read: only compressed
 * bufferViews use it, and those are read from their decoded data); data URIs of the image media
 * types tinygltf does not know (image/webp, image/ktx2, ...) become application/octet-stream (the
 * image callback tells the formats by their bytes); Draco indices accessors
 * without a bufferView get one (see prevalidate); animation targets without a node get one
 * (nodeless_targets). A GLB keeps its BIN chunk after the new JSON. */
static std::vector<unsigned char> rewrite_for_tinygltf(const Ctx &c, const unsigned char *bytes)
{
    std::vector<unsigned char> rewritten;
    const std::vector<std::pair<size_t, size_t>> nodeless = nodeless_targets(c.j);
    if (std::find(c.buffer_no_data.begin(), c.buffer_no_data.end(), 1) == c.buffer_no_data.end() &&
        c.draco_index_fix.empty() && nodeless.empty() && c.image_media_rewrite.empty())
        return rewritten;
    json j2 = c.j;
    for (size_t i : c.image_media_rewrite) { /* image/webp, image/ktx2, ...: tinygltf decodes only some */
        const std::string uri = c.j["images"][i]["uri"].get<std::string>();
        j2["images"][i]["uri"] = "data:application/octet-stream" + uri.substr(uri.find(';'));
    }
    for (const auto &nc : nodeless) j2["animations"][nc.first]["channels"][nc.second]["target"]["node"] = 0;
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
        return rewritten;
    }
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
    return rewritten;
}

/* step 3: tinygltf builds c.model over our file system and image callbacks; every image decoded */
static void tinygltf_load(Ctx &c, const RawFile &f)
{
    tinygltf::TinyGLTF loader;
    tinygltf::FsCallbacks fs;
    fs.FileExists = &fs_file_exists;
    fs.ExpandFilePath = &tinygltf::ExpandFilePath;
    fs.ReadWholeFile = &fs_read_whole_file;
    fs.WriteWholeFile = &tinygltf::WriteWholeFile;
    fs.user_data = &c;
    loader.SetFsCallbacks(fs);
    loader.SetImageLoader(&load_image_cb, &c);
    std::string terr, twarn;
    if (f.size > 0xFFFFFFFFull) fail(PG_ERR_LIMIT, "file larger than 4 GiB");
    std::vector<unsigned char> rewritten = rewrite_for_tinygltf(c, f.bytes());
    const unsigned char *tbytes = rewritten.empty() ? f.bytes() : rewritten.data();
    const size_t tsize = rewritten.empty() ? f.size : rewritten.size();
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
        if (i < c.image_undecoded_only.size() && c.image_undecoded_only[i]) continue; /* never drawn */
        if (im.image.empty() || im.width < 1 || im.height < 1 ||
            im.image.size() != size_t(im.width) * size_t(im.height) * 4)
            gfail(image_desc(c, int(i)) + ": could not be loaded");
    }
}

/* the root nodes drawn: those of the chosen scene (c.want_scene), else of `scene`, else of
 * scenes[0], else every node nobody's child; c.drawn_scene says which */
static std::vector<int> root_nodes(Ctx &c)
{
    const tinygltf::Model &md = c.model;
    if (c.want_scene >= 0) {
        if (size_t(c.want_scene) >= md.scenes.size()) {
            std::string names;
            for (size_t i = 0; i < md.scenes.size() && i < 8; i++)
                names += strf("%s%zu '%s'", i ? ", " : ": ", i,
                              md.scenes[i].name.empty() ? strf("scenes[%zu]", i).c_str() : md.scenes[i].name.c_str());
            throw LoadFail{PG_ERR_INVALID_ARG, strf("--gltf-scene %d: out of range (the file has %zu scene%s%s)",
                                                    c.want_scene, md.scenes.size(),
                                                    md.scenes.size() == 1 ? "" : "s", names.c_str())};
        }
        c.drawn_scene = c.want_scene;
        return md.scenes[size_t(c.want_scene)].nodes;
    }
    if (md.defaultScene >= 0 && size_t(md.defaultScene) < md.scenes.size()) {
        c.drawn_scene = md.defaultScene;
        return md.scenes[size_t(md.defaultScene)].nodes;
    }
    if (!md.scenes.empty()) {
        c.drawn_scene = 0;
        return md.scenes[0].nodes;
    }
    std::vector<int> roots;
    std::vector<char> is_child(md.nodes.size(), 0);
    for (const auto &nd : md.nodes)
        for (int ch : nd.children)
            if (ch >= 0 && size_t(ch) < md.nodes.size()) is_child[size_t(ch)] = 1;
    for (size_t i = 0; i < md.nodes.size(); i++)
        if (!is_child[i]) roots.push_back(int(i));
    if (roots.empty() && !md.nodes.empty())
        gfail("nodes: cyclic node graph (every node is some node's child)");
    return roots;
}

/* The pg_textures the materials use, one per TexKey, numbered in first-use order. */
struct TextureTable {
    const Ctx &c;
    const tinygltf::Model &md;
    std::map<TexKey, uint32_t> tex_of;
    std::vector<TexKey> order;

    /* the pg_texture index of glTF texture `tex_index` read as sRGB or linear; -1 for none */
    int texture_for(int tex_index, bool srgb, const std::string &where)
    {
        if (tex_index < 0) return -1;
        if (size_t(tex_index) >= md.textures.size())
            gfail(strf("%s: texture %d out of range", where.c_str(), tex_index));
        int src = md.textures[size_t(tex_index)].source; /* EXT_texture_webp's, when given */
        if (size_t(tex_index) < c.texture_webp.size() && c.texture_webp[size_t(tex_index)] >= 0)
            src = c.texture_webp[size_t(tex_index)];
        const std::string *ext =
            size_t(tex_index) < c.texture_undecoded.size() ? &c.texture_undecoded[size_t(tex_index)] : nullptr;
        if ((src < 0 || size_t(src) >= md.images.size()) && ext && !ext->empty())
            gfail(strf("textures[%d]: no usable source image (its image is only in %s, which passgraph does not "
                       "decode, and it has no fallback source)",
                       tex_index, ext->c_str()));
        if (src < 0 || size_t(src) >= md.images.size())
            gfail(strf("textures[%d]: no usable source image", tex_index));
        int smp = md.textures[size_t(tex_index)].sampler;
        TexKey k{src, srgb, {}};
        if (smp >= 0 && size_t(smp) < md.samplers.size()) k.sampler = sampler_state(md.samplers[size_t(smp)]);
        auto it = tex_of.find(k);
        if (it != tex_of.end()) return int(it->second);
        uint32_t id = uint32_t(order.size());
        tex_of[k] = id;
        order.push_back(k);
        return int(id);
    }
};

/* per slot of materials[i]: texCoord (0 or 1; higher is warned and reads TEXCOORD_0) and
 * KHR_texture_transform (whose texCoord overrides the textureInfo's) */
static void material_tex_coords(const Ctx &c, const tinygltf::Material &gm, size_t i,
                                const std::string &mw, pg_material &pm)
{
    const auto &pbr = gm.pbrMetallicRoughness;
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
        {PG_TEXSLOT_METALLIC_ROUGHNESS, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
         jpbr ? opt_object(*jpbr, "metallicRoughnessTexture", mw) : nullptr,
         mw + ".pbrMetallicRoughness.metallicRoughnessTexture"},
        {PG_TEXSLOT_OCCLUSION, gm.occlusionTexture.index, gm.occlusionTexture.texCoord,
         opt_object(jm, "occlusionTexture", mw), mw + ".occlusionTexture"},
    };
    for (const auto &sl : slots) {
        if (sl.index < 0 || !sl.ti) continue;
        int tc = sl.tex_coord;
        pm.has_uv_transform[sl.slot] =
            texture_transform(*sl.ti, sl.where, pm.uv_transform[sl.slot], &tc);
        pm.tex_coord[sl.slot] = uint8_t(tc == 1 ? 1 : 0);
    }
}

/* metallic-roughness -> Blinn-Phong specular and shininess (the mapping in this file's header) */
static void material_specular(const tinygltf::PbrMetallicRoughness &pbr, pg_material &pm)
{
    double metal = std::isfinite(pbr.metallicFactor) ? clamp01(pbr.metallicFactor) : 1.0;
    double rough = std::isfinite(pbr.roughnessFactor) ? clamp01(pbr.roughnessFactor) : 1.0;
    pg_material_specular_from(metal, rough, &pm.specular, &pm.shininess);
}

/* emissive = emissiveFactor x emissiveStrength (both checked finite >= 0 by prevalidate) */
static void material_emissive(const tinygltf::Material &gm, const std::string &mw, pg_material &pm)
{
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
}

/* KHR_materials_pbrSpecularGlossiness (archived; older files) on a material without
 * pbrMetallicRoughness, whose core material would be the default white metal: approximated as
 * metallic-roughness: diffuse (factor x texture, its texCoord and KHR_texture_transform) as the base
 * colour, roughness = 1 - glossiness, metallic 0. The specular colour and specularGlossinessTexture
 * are not applied (the extensionsUsed warning says so). A material that also has
 * pbrMetallicRoughness draws that, its author's fallback. */
static void material_spec_gloss(const Ctx &c, size_t i, const std::string &mw, TextureTable &tex, pg_material &pm)
{
    const json &jm = c.j.at("materials").at(i);
    auto ex = jm.find("extensions");
    if (jm.contains("pbrMetallicRoughness") || ex == jm.end() || !ex->is_object()) return;
    const json *sg = opt_object(*ex, "KHR_materials_pbrSpecularGlossiness", mw + ".extensions");
    if (!sg) return;
    const std::string w = mw + ".extensions.KHR_materials_pbrSpecularGlossiness";
    auto df = sg->find("diffuseFactor");
    for (int k = 0; k < 4; k++) {
        const json *x = df != sg->end() && df->is_array() && df->size() == 4 ? &(*df)[size_t(k)] : nullptr;
        if (df != sg->end() && !(x && x->is_number() && std::isfinite(x->get<double>())))
            gfail(w + ".diffuseFactor: expected 4 finite numbers");
        pm.base_color[k] = x ? float(clamp01(x->get<double>())) : 1.0f;
    }
    double gloss = 1.0;
    auto gf = sg->find("glossinessFactor");
    if (gf != sg->end()) {
        if (!gf->is_number() || !std::isfinite(gf->get<double>())) gfail(w + ".glossinessFactor: expected a number");
        gloss = clamp01(gf->get<double>());
    }
    pm.metallic = 0.0f;
    pm.roughness = float(1.0 - gloss);
    pg_material_specular_from(0.0, 1.0 - gloss, &pm.specular, &pm.shininess);
    if (const json *dt = opt_object(*sg, "diffuseTexture", w)) {
        const std::string tw = w + ".diffuseTexture";
        int tc = int(uint_field(*dt, "texCoord", tw, false, 0));
        pm.base_color_tex = tex.texture_for(int(uint_field(*dt, "index", tw, true)), true, tw);
        pm.has_uv_transform[PG_TEXSLOT_BASE] = texture_transform(*dt, tw, pm.uv_transform[PG_TEXSLOT_BASE], &tc);
        pm.tex_coord[PG_TEXSLOT_BASE] = uint8_t(tc == 1 ? 1 : 0);
    }
}

/* step 5: materials[i] as a pg_material; its textures numbered in `tex` */
static pg_material material_from_gltf(const Ctx &c, size_t i, TextureTable &tex)
{
    const tinygltf::Material &gm = c.model.materials[i];
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
    pm.base_color_tex = tex.texture_for(pbr.baseColorTexture.index, true,
                                        mw + ".pbrMetallicRoughness.baseColorTexture");
    pm.normal_tex = tex.texture_for(gm.normalTexture.index, false, mw + ".normalTexture");
    pm.emissive_tex = tex.texture_for(gm.emissiveTexture.index, true, mw + ".emissiveTexture");
    pm.metallic_roughness_tex = tex.texture_for(pbr.metallicRoughnessTexture.index, false,
                                                mw + ".pbrMetallicRoughness.metallicRoughnessTexture");
    pm.occlusion_tex = tex.texture_for(gm.occlusionTexture.index, false, mw + ".occlusionTexture");
    pm.metallic = float(std::isfinite(pbr.metallicFactor) ? clamp01(pbr.metallicFactor) : 1.0);
    pm.roughness = float(std::isfinite(pbr.roughnessFactor) ? clamp01(pbr.roughnessFactor) : 1.0);
    pm.occlusion_strength = float(std::isfinite(gm.occlusionTexture.strength) ? clamp01(gm.occlusionTexture.strength) : 1.0);
    pm.unlit = gm.extensions.find("KHR_materials_unlit") != gm.extensions.end();
    material_tex_coords(c, gm, i, mw, pm);
    pm.normal_scale = float(std::isfinite(gm.normalTexture.scale) ? gm.normalTexture.scale : 1.0);
    if (gm.alphaMode == "MASK") pm.alpha_mode = PG_ALPHA_MASK;
    else if (gm.alphaMode == "BLEND") pm.alpha_mode = PG_ALPHA_BLEND;
    else pm.alpha_mode = PG_ALPHA_OPAQUE;
    if (!std::isfinite(gm.alphaCutoff) || gm.alphaCutoff < 0)
        gfail(mw + ".alphaCutoff: expected a finite number >= 0");
    pm.alpha_cutoff = float(gm.alphaCutoff);
    material_specular(pbr, pm);
    pm.double_sided = gm.doubleSided;
    material_emissive(gm, mw, pm);
    material_spec_gloss(c, i, mw, tex, pm);
    return pm;
}

/* each primitive's material index; primitives without one get an appended "default" material */
static void assign_materials(const tinygltf::Model &md, Out &o, std::vector<pg_material> &mats)
{
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
}

/* TEXCOORD_1 is handed out when a drawn primitive has it and a texture of its material reads it;
 * drawn primitives whose material reads a TEXCOORD_1 they lack are warned */
static void hand_out_uv1(Ctx &c, const Out &o, const std::vector<pg_material> &mats, pg_scene *s)
{
    bool uv1_read = false;
    unsigned uv1_missing = 0, uv0_missing = 0;
    for (size_t p = 0; p < o.prims.size(); p++) {
        if (!o.prims[p].index_count) continue;
        const pg_material &pm = mats[o.prims[p].material];
        bool reads = false, reads0 = false;
        for (int t = 0; t < PG_TEXSLOT_COUNT; t++) {
            reads = reads || (pg_material_slot_texture(&pm, t) >= 0 && pm.tex_coord[t] == 1);
            reads0 = reads0 || (pg_material_slot_texture(&pm, t) >= 0 && pm.tex_coord[t] == 0);
        }
        if (reads && o.prim_has_uv1[p]) uv1_read = true;
        if (reads && !o.prim_has_uv1[p]) uv1_missing++;
        if ((reads0 || (reads && !o.prim_has_uv1[p])) && !o.prim_has_uv0[p]) uv0_missing++;
    }
    if (uv1_missing)
        c.warnings.push_back("TEXCOORD_1 missing in " + plural(uv1_missing, "primitive", "primitives") +
                             " whose material reads it (texCoord 1): TEXCOORD_0 used");
    if (uv0_missing) /* its uv are 0: every pixel samples one spot of each texture */
        c.warnings.push_back(plural(uv0_missing, "primitive", "primitives") +
                             " without TEXCOORD_0 under a material that reads a texture with it: every pixel samples "
                             "the texture at (0, 0)");
    if (uv1_read) {
        s->uv1 = static_cast<float(*)[2]>(malloc(o.uv1.size() * sizeof(float)));
        if (!s->uv1) throw std::bad_alloc();
        memcpy(s->uv1, o.uv1.data(), o.uv1.size() * sizeof(float));
    }
}

/* one pg_texture per TexKey, in `order` */
static void hand_out_textures(const Ctx &c, const std::vector<TexKey> &order, pg_scene *s)
{
    if (order.empty()) return;
    s->textures = static_cast<pg_texture *>(calloc(order.size(), sizeof(pg_texture)));
    if (!s->textures) throw std::bad_alloc();
    for (const TexKey &k : order) {
        const tinygltf::Image &im = c.model.images[size_t(k.image)];
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

/* A scene 32-bit floats cannot draw: far smaller than float shading resolves (a unit cube scaled by
 * 1e-15 was lit wrong, by 1e-20 not drawn at all: squared distances underflow), far larger (scaled
 * by 1e20: squared distances overflow) or far from the origin for its size (a unit cube at 1e7:
 * its corners round to one float). Said in one line; the load goes on. */
static void warn_float_range(const Ctx &c, pg_scene *s)
{
    if (!s->n_primitives) return;
    double d2 = 0, far = 0;
    for (int k = 0; k < 3; k++) {
        const double e = (double)s->bounds_max[k] - (double)s->bounds_min[k];
        d2 += e * e;
        far = fmax(far, fmax(fabs((double)s->bounds_min[k]), fabs((double)s->bounds_max[k])));
    }
    const double diag = sqrt(d2);
    char line[400];
    if (!(diag <= 1e18) || !(far <= 1e18))
        snprintf(line, sizeof line,
                 "%s: the scene reaches %.3g units: 32-bit float shading overflows past about 1e18 units (squared "
                 "distances; a unit cube scaled by 1e20 drew nothing); scale it down, e.g. by a root node's scale",
                 c.path.c_str(), fmax(diag, far));
    else if (far > 1e6 * diag)
        snprintf(line, sizeof line,
                 "%s: the scene is %.3g units across and lies %.3g units from the origin: 32-bit positions there "
                 "are %.3g units apart, so its shape collapses (a unit cube at 1e7 drew nothing); move it toward "
                 "the origin, e.g. by a root node's translation",
                 c.path.c_str(), diag, far, far * 0x1p-23);
    else if (diag < 1e-14)
        snprintf(line, sizeof line,
                 "%s: the scene is %.3g units across: 32-bit float shading loses lights and geometry below about "
                 "1e-14 units (a unit cube scaled by 1e-20 drew nothing); scale it up, e.g. by a root node's scale",
                 c.path.c_str(), diag);
    else
        return;
    pg_error werr;
    memset(&werr, 0, sizeof werr);
    pg_scene_add_warning(s, line, &werr); /* out of memory: the line is lost, the scene still loads */
}

/* step 6: the pg_scene, owning copies of everything built; the warnings prefixed with the path */
static pg_scene *hand_out(Ctx &c, const Out &o, const std::vector<pg_material> &mats,
                          const std::vector<pg_scene_camera> &cams, const std::vector<pg_scene_light> &lights,
                          const std::vector<TexKey> &tex_order, pg_scene_anim *anim)
{
    std::unique_ptr<pg_scene, SceneDeleter> s(static_cast<pg_scene *>(calloc(1, sizeof(pg_scene))));
    if (!s) throw std::bad_alloc();
    pg_strlcpy(s->name, file_stem(c.path).c_str(), sizeof s->name);
    pg_strlcpy(s->path, c.path.c_str(), sizeof s->path);
    s->n_gltf_scenes = uint32_t(c.model.scenes.size());
    s->gltf_scene = c.drawn_scene;
    s->gltf_scene_chosen = c.want_scene >= 0;
    s->gltf_scene_named = c.model.defaultScene >= 0; /* the file's "scene" key */
    if (c.drawn_scene >= 0) {
        const std::string &nm = c.model.scenes[size_t(c.drawn_scene)].name;
        pg_strlcpy(s->gltf_scene_name, nm.empty() ? strf("scenes[%d]", c.drawn_scene).c_str() : nm.c_str(),
                   sizeof s->gltf_scene_name);
    }
    for (size_t k = 0; k < c.model.scenes.size() && k < PG_SCENE_GLTF_SCENE_NAMES; k++) {
        const std::string &nm = c.model.scenes[k].name;
        pg_strlcpy(s->gltf_scene_names[k], nm.empty() ? strf("scenes[%zu]", k).c_str() : nm.c_str(),
                   sizeof s->gltf_scene_names[k]);
    }
    s->n_gltf_variants = uint32_t(c.variant_names.size());
    s->gltf_variant = c.variant;
    if (c.variant >= 0) pg_strlcpy(s->gltf_variant_name, c.variant_names[size_t(c.variant)].c_str(),
                                   sizeof s->gltf_variant_name);
    pg_strlcpy(s->gltf_variant_list, variant_list_line(c).c_str(), sizeof s->gltf_variant_list);
    for (size_t k = 0; k < c.variant_names.size() && k < PG_SCENE_VARIANT_NAMES; k++)
        pg_strlcpy(s->gltf_variant_names[k], c.variant_names[k].c_str(), sizeof s->gltf_variant_names[k]);
    s->vertices = copy_out(o.verts);
    s->n_vertices = uint32_t(o.verts.size());
    s->indices = copy_out(o.idx);
    s->n_indices = uint32_t(o.idx.size());
    s->primitives = copy_out(o.prims);
    s->n_primitives = uint32_t(o.prims.size());
    s->materials = copy_out(mats);
    s->n_materials = uint32_t(mats.size());
    s->gltf_materials = true; /* the pbr light model by default (features.auto_shading) */
    s->cameras = copy_out(cams);
    s->n_cameras = uint32_t(cams.size());
    s->lights = copy_out(lights);
    s->n_lights = uint32_t(lights.size());
    /* COLOR_0 when a drawn primitive has it */
    if (!o.colors.empty()) {
        s->colors = static_cast<float(*)[4]>(malloc(o.colors.size() * sizeof(float)));
        if (!s->colors) throw std::bad_alloc();
        memcpy(s->colors, o.colors.data(), o.colors.size() * sizeof(float));
    }
    hand_out_uv1(c, o, mats, s.get());
    hand_out_textures(c, tex_order, s.get());
    for (const std::string &wline : c.warnings) {
        pg_error werr;
        memset(&werr, 0, sizeof werr);
        if (pg_scene_add_warning(s.get(), (c.path + ": " + wline).c_str(), &werr) != PG_OK)
            throw std::bad_alloc();
    }
    s->anim = anim; /* owned by the scene from here (nothing below throws) */
    pg_scene_finalize(s.get());
    warn_float_range(c, s.get());
    return s.release();
}

/* The load order of this file's header: each step a call. */
pg_scene *load(Ctx &c)
{
    {
        RawFile f;
        read_file(c, f);  /* 1 */
        parse_json(c, f); /* 2 */
        prevalidate(c);
        texture_sources(c);  /* EXT_texture_webp, the undecoded texture extensions */
        tinygltf_load(c, f); /* 3 */
    }
    for (const std::string &e : c.model.extensionsUsed)
        c.quantization = c.quantization || e == "KHR_mesh_quantization";
    decode_meshopt(c);
    const tinygltf::Model &md = c.model;

    /* 4. node hierarchy -> geometry */
    Out o;
    std::vector<pg_scene_camera> cams;
    std::vector<pg_scene_light> lights;
    {
        std::vector<int> roots = root_nodes(c);
        anim_prepare(c);
        variants_prepare(c); /* KHR_materials_variants: the materials primitives draw */
        Walker plan{c, o, std::vector<char>(md.nodes.size(), 0), 0};
        plan.count_only = true; /* PG_ERR_LIMIT before baking what memory cannot hold */
        for (int r : roots) plan.visit(r, mat_identity(), 0);
        Walker w{c, o, std::vector<char>(md.nodes.size(), 0), 0};
        for (int r : roots) w.visit(r, mat_identity(), 0);
        for (int r : roots) camera_visit(c, r, mat_identity(), cams);
        for (int r : roots) light_visit(c, r, mat_identity(), lights);
        table_lights(c, lights);
    }
    if (o.idx.empty())
        gfail(c.drawn_scene >= 0 ? strf("scenes[%d] has no triangles%s", c.drawn_scene,
                                        c.model.scenes.size() > 1 ? " (--gltf-scene picks another)" : "")
                                 : std::string("the scene has no triangles"));
    std::unique_ptr<pg_scene_anim, void (*)(pg_scene_anim *)> anim(anim_hand_out(c, o), pg_scene_anim_free);
    collect_warnings(c);

    /* 5. materials and textures */
    std::vector<pg_material> mats;
    TextureTable tex{c, md, {}, {}};
    for (size_t i = 0; i < md.materials.size(); i++) mats.push_back(material_from_gltf(c, i, tex));
    assign_materials(md, o, mats);

    pg_scene *s = hand_out(c, o, mats, cams, lights, tex.order, anim.get()); /* 6 */
    anim.release();
    return s;
}

} // namespace pg_gltf

using namespace pg_gltf;

extern "C" pg_result pg_scene_load_gltf(const char *path, pg_scene **out, pg_error *err)
{
    return pg_scene_load_gltf_ex(path, nullptr, out, err);
}

extern "C" pg_result pg_scene_load_gltf_ex(const char *path, const pg_scene_load_opts *opts, pg_scene **out,
                                           pg_error *err)
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
        if (opts) c.want_scene = opts->gltf_scene;
        if (opts && opts->gltf_variant) c.want_variant = opts->gltf_variant;
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
