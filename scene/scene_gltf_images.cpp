/* scene_gltf_images.cpp - step 3 of the glTF load (scene_gltf.cpp): tinygltf's file system (confined
 * to the asset's directory) and image callback (PNG and JPEG through stb_image, WebP through libwebp
 * for EXT_texture_webp, sizes checked before decoding; an image only undecoded texture extensions
 * name is left empty: scene_gltf_texture_sources.cpp); the glTF samplers and KHR_texture_transform
 * that materials use.
 */
#include "scene_gltf_internal.h"
#include "pg_file.h"

#include <stb_image.h>
#include <webp/decode.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

namespace pg_gltf {

constexpr int kMaxImageSide = 16384;
/* No real JPEG codes more than ~512 pixels per byte (at least one bit per 8x8 block, even
 * progressive); stb_image decodes a truncated JPEG stream as if it went on with zero bits, so a
 * 140-byte header claiming 16384x16384 would otherwise become a 1 GiB texture. */
constexpr uint64_t kMaxJpegPixelsPerByte = 1024;

/* ------------------------------------------------------------------------------------------ */
/* step 3: tinygltf with our image decoder and a file system confined to the asset's directory   */

bool fs_file_exists(const std::string &abs, void *user)
{
    const Ctx *c = static_cast<const Ctx *>(user);
    if (abs.compare(0, c->dir_prefix.size(), c->dir_prefix) != 0) return false;
    return is_regular_file(abs, nullptr);
}

/* tinygltf's file reader, through the same checks (regular file, cap, O_NONBLOCK open) */
bool fs_read_whole_file(std::vector<unsigned char> *out, std::string *err, const std::string &abs,
                        void *user)
{
    const Ctx *c = static_cast<const Ctx *>(user);
    if (abs.compare(0, c->dir_prefix.size(), c->dir_prefix) != 0) {
        if (err) *err = "'" + abs + "' is outside the scene's folder";
        return false;
    }
    char *buf = nullptr;
    size_t len = 0;
    pg_error e;
    memset(&e, 0, sizeof e);
    if (pg_file_read(abs.c_str(), "glTF resource", PG_FILE_CAP_GLTF_RESOURCE, &buf, &len, &e) != PG_OK) {
        if (err) *err = e.msg;
        return false;
    }
    out->assign(reinterpret_cast<unsigned char *>(buf), reinterpret_cast<unsigned char *>(buf) + len);
    free(buf);
    return true;
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

/* what every decoded image is for the loader: RGBA8 of w x h */
static void set_rgba8(tinygltf::Image *image, int w, int h)
{
    image->width = w;
    image->height = h;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
}

/* a WebP image (EXT_texture_webp) as RGBA8, its size checked before decoding */
static bool load_webp(tinygltf::Image *image, const std::string &where, const unsigned char *bytes, int size,
                      Ctx *c)
{
    int w = 0, h = 0;
    if (!WebPGetInfo(bytes, size_t(size), &w, &h)) {
        c->image_err = where + ": cannot decode (not a valid WebP image)";
        return false;
    }
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide) {
        c->image_err = where + strf(": size %dx%d is outside 1..%d on a side", w, h, kMaxImageSide);
        return false;
    }
    image->image.resize(size_t(w) * size_t(h) * 4);
    if (!WebPDecodeRGBAInto(bytes, size_t(size), image->image.data(), image->image.size(), w * 4)) {
        image->image.clear();
        c->image_err = where + ": cannot decode (corrupt or truncated WebP data)";
        return false;
    }
    set_rgba8(image, w, h);
    return true;
}

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
        const bool webp = size >= 12 && memcmp(bytes, "RIFF", 4) == 0 && memcmp(bytes + 8, "WEBP", 4) == 0;
        if (idx >= 0 && size_t(idx) < c->image_undecoded_only.size() && c->image_undecoded_only[size_t(idx)]) {
            image->width = image->height = 0; /* KTX2, DDS, AVIF: a fallback image is drawn instead */
            image->image.clear();
            return true;
        }
        if (webp) return load_webp(image, where, bytes, size, c);
        if (!png && !jpeg) {
            c->image_err = where + ": cannot decode (not a PNG, JPEG or WebP image; glTF 2.0 allows "
                                   "image/png and image/jpeg, EXT_texture_webp image/webp)";
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
        set_rgba8(image, w, h);
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
/* samplers and KHR_texture_transform (materials, step 5 of load())                            */

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
    pg_material_uv_transform(off, rot, sc, m);
    return true;
}

} // namespace pg_gltf
