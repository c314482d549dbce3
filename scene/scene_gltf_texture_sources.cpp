/* scene_gltf_texture_sources.cpp - which image each texture draws, with the texture-source
 * extensions (read before tinygltf parses the file, so that its image callback knows them).
 *
 * - EXT_texture_webp: textures[i].extensions.EXT_texture_webp.source names a WebP image; passgraph
 *   decodes WebP (libwebp) and draws it, as a viewer that implements the extension does; the core
 *   `source`, if any, is its fallback and is not drawn.
 * - KHR_texture_basisu, MSFT_texture_dds, EXT_texture_avif: their images are not decoded. A texture
 *   with a core `source` draws that fallback; an image that only these extensions name is neither
 *   decoded nor refused (the loader's image callback leaves it empty), and the extension's
 *   extensionsUsed warning says the fallback is drawn. A texture without a fallback is refused when
 *   a material uses it, naming the extension. Listed in extensionsRequired, they are refused as
 *   every unimplemented extension is.
 * A source that is not an image index in range is refused naming the field.
 */
#include "scene_gltf_internal.h"

namespace pg_gltf {

static const char *const kUndecodedSources[] = {"KHR_texture_basisu", "MSFT_texture_dds", "EXT_texture_avif"};

/* extensions.NAME.source of texture object t (-1 when absent), range-checked */
static int ext_source(const json &t, const char *name, size_t n_images, const std::string &w)
{
    auto ex = t.find("extensions");
    if (ex == t.end() || !ex->is_object()) return -1;
    auto e = ex->find(name);
    if (e == ex->end()) return -1;
    const std::string ew = strf("%s.extensions.%s", w.c_str(), name);
    if (!e->is_object()) gfail(ew + ": expected an object");
    auto s = e->find("source");
    if (s == e->end()) gfail(ew + ".source: missing (required)");
    if (!s->is_number_unsigned() || s->get<uint64_t>() >= n_images)
        gfail(strf("%s.source: expected an image index (%zu images)", ew.c_str(), n_images));
    return int(s->get<uint64_t>());
}

void texture_sources(Ctx &c)
{
    const json &j = c.j;
    auto ti = j.find("textures"), ii = j.find("images");
    const size_t n_images = ii != j.end() && ii->is_array() ? ii->size() : 0;
    c.image_undecoded_only.assign(n_images, 0);
    if (ti == j.end() || !ti->is_array()) return;
    std::vector<char> drawn(n_images, 0); /* an image some texture draws: decoded (or refused) */
    c.texture_webp.assign(ti->size(), -1);
    c.texture_undecoded.assign(ti->size(), std::string());
    for (size_t t = 0; t < ti->size(); t++) {
        const json &tx = (*ti)[t];
        if (!tx.is_object()) continue; /* prevalidate refused it */
        const std::string w = strf("textures[%zu]", t);
        const int webp = ext_source(tx, "EXT_texture_webp", n_images, w);
        c.texture_webp[t] = webp;
        auto s = tx.find("source");
        const int core = s != tx.end() && s->is_number_unsigned() ? int(s->get<uint64_t>()) : -1;
        if (webp >= 0) drawn[size_t(webp)] = 1;
        else if (core >= 0 && size_t(core) < n_images) drawn[size_t(core)] = 1;
        for (const char *name : kUndecodedSources) {
            const int other = ext_source(tx, name, n_images, w);
            if (other < 0) continue;
            c.image_undecoded_only[size_t(other)] = 1;
            if (c.texture_undecoded[t].empty()) c.texture_undecoded[t] = name;
        }
    }
    for (size_t i = 0; i < n_images; i++)
        if (drawn[i]) c.image_undecoded_only[i] = 0;
}

} // namespace pg_gltf
