/* scene_gltf_warnings.cpp - the warning lines of the glTF load (pg_scene.warnings; scene_gltf.cpp
 * lists what is warned): one line per kind of feature the file uses that is not drawn as it asks.
 */
#include "scene_gltf_internal.h"

#include <algorithm>

namespace pg_gltf {

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
 * for the image, as the warning's words after the name ("ignored: ...", "approximated: ..."); ""
 * for none: metadata (KHR_xmp_json_ld), and KHR_animation_pointer, whose channels are warned one by
 * one (collect_warnings) */
std::string extension_effect(const std::string &e)
{
    if (e == "KHR_xmp_json_ld" || e == "KHR_animation_pointer") return "";
    if (e == "KHR_texture_transform") return "ignored: texture offset/rotation/scale not applied";
    if (e == "KHR_texture_basisu" || e == "MSFT_texture_dds" || e == "EXT_texture_avif")
        return "ignored: its images are not decoded; each texture's fallback source image is drawn";
    if (e == "KHR_materials_pbrSpecularGlossiness")
        return "approximated: materials without pbrMetallicRoughness draw the diffuse colour as their base colour, "
               "roughness = 1 - glossiness, metallic 0 (the specular colour and specularGlossinessTexture are not "
               "applied); the others draw their core material";
    if (e.compare(0, 14, "KHR_materials_") == 0) return "ignored: the core material is drawn without it";
    return "ignored: not supported";
}

/* The extension names of every "extensions" object in the JSON (root, materials, nodes, textures,
 * ...) that the file's extensionsUsed does not list, in first-seen order. */
static void undeclared_extensions(const json &j, const std::vector<std::string> &used, std::vector<std::string> &out)
{
    if (j.is_array()) {
        for (const json &e : j) undeclared_extensions(e, used, out);
        return;
    }
    if (!j.is_object()) return;
    for (auto it = j.begin(); it != j.end(); ++it) {
        if (it.key() == "extensions" && it.value().is_object())
            for (auto e = it.value().begin(); e != it.value().end(); ++e)
                if (std::find(used.begin(), used.end(), e.key()) == used.end() &&
                    std::find(out.begin(), out.end(), e.key()) == out.end())
                    out.push_back(e.key().substr(0, 80));
        if (it.key() != "extras") undeclared_extensions(it.value(), used, out);
    }
}

/* The texCoord a textureInfo's texture is read with: its KHR_texture_transform's texCoord when the
 * transform gives one (it overrides the textureInfo's, as material_tex_coords applies it) */
static uint64_t effective_tex_coord(const json *ti, int tex_coord)
{
    if (ti && ti->is_object() && ti->contains("extensions") && (*ti)["extensions"].is_object()) {
        const json &e = (*ti)["extensions"];
        if (e.contains("KHR_texture_transform") && e["KHR_texture_transform"].is_object()) {
            const json &tt = e["KHR_texture_transform"];
            if (tt.contains("texCoord") && tt["texCoord"].is_number_unsigned()) return tt["texCoord"].get<uint64_t>();
        }
    }
    return tex_coord < 0 ? 0 : uint64_t(tex_coord);
}

/* Does a texture of materials[i] ask for a texCoord past 1 (read with TEXCOORD_0)? */
static bool material_texcoord_past_1(const Ctx &c, size_t i)
{
    const tinygltf::Material &m = c.model.materials[i];
    const auto &pbr = m.pbrMetallicRoughness;
    const json *jm = c.j.contains("materials") && c.j["materials"].is_array() && i < c.j["materials"].size()
                         ? &c.j["materials"][i] : nullptr;
    auto sub = [](const json *o, const char *k) -> const json * {
        return o && o->is_object() && o->contains(k) ? &(*o)[k] : nullptr;
    };
    const json *jpbr = sub(jm, "pbrMetallicRoughness");
    const struct { int index, tex_coord; const json *ti; } slots[] = {
        {pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, sub(jpbr, "baseColorTexture")},
        {m.normalTexture.index, m.normalTexture.texCoord, sub(jm, "normalTexture")},
        {m.emissiveTexture.index, m.emissiveTexture.texCoord, sub(jm, "emissiveTexture")},
        {pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, sub(jpbr, "metallicRoughnessTexture")},
        {m.occlusionTexture.index, m.occlusionTexture.texCoord, sub(jm, "occlusionTexture")},
    };
    for (const auto &sl : slots)
        if (sl.index >= 0 && effective_tex_coord(sl.ti, sl.tex_coord) > 1) return true;
    return false;
}

/* Every feature the file uses that is not drawn as the file asks: one line each (see scene.h). */
void collect_warnings(Ctx &c)
{
    const tinygltf::Model &md = c.model;
    auto &W = c.warnings;
    std::vector<std::string> undeclared; /* the specification: every extension used is listed */
    undeclared_extensions(c.j, md.extensionsUsed, undeclared);
    if (!undeclared.empty()) {
        std::vector<std::string> drawn, ignored;
        for (const std::string &e : undeclared) (extension_implemented(e) ? drawn : ignored).push_back(e);
        W.push_back("extensions not listed in extensionsUsed (the specification requires it): " +
                    (drawn.empty() ? std::string() : name_list(drawn) + " applied") +
                    (!drawn.empty() && !ignored.empty() ? "; " : "") +
                    (ignored.empty() ? std::string() : name_list(ignored) + " ignored"));
    }
    if (md.scenes.empty() && !md.nodes.empty())
        W.push_back("no scenes: every root node is drawn (the specification leaves such a file's display to the "
                    "application: a library of nodes)");
    std::vector<std::string> neg_mag;
    for (size_t i = 0; i < md.cameras.size(); i++)
        if (md.cameras[i].type == "orthographic" && (md.cameras[i].orthographic.xmag < 0 || md.cameras[i].orthographic.ymag < 0))
            neg_mag.push_back(strf("cameras[%zu]", i));
    if (!neg_mag.empty())
        W.push_back(plural(neg_mag.size(), "orthographic camera", "orthographic cameras") + " (" + name_list(neg_mag) +
                    ") with a negative xmag or ymag (the specification says it should not be): drawn with its magnitude");
    if (c.skipped_prims)
        W.push_back(strf("skipped %u point/line primitive(s) (only triangles are drawn)",
                         c.skipped_prims));
    if (c.unskinned_prims)
        W.push_back(strf("%u primitive(s) of skinned nodes without JOINTS_0/WEIGHTS_0: drawn by their node's transform, "
                         "unskinned",
                         c.unskinned_prims));
    if (c.joints2_prims)
        W.push_back(strf("%u skinned primitive(s) with JOINTS_2/WEIGHTS_2 or more ignored: 8 joints per vertex are "
                         "applied (JOINTS_0, JOINTS_1)",
                         c.joints2_prims));
    const unsigned n_ptr = unsigned(c.ignored_pointers.size());
    if (c.ignored_channels > n_ptr)
        W.push_back(strf("%u animation channel(s) ignored: ", c.ignored_channels - n_ptr) + name_list(c.ignored_why));
    if (!c.duplicate_targets.empty())
        W.push_back(plural(c.duplicate_targets.size(), "animation channel targets", "animation channels target") +
                    " what an earlier channel of its animation does (the specification forbids it; the later one is "
                    "applied): " + name_list(c.duplicate_targets));
    if (n_ptr) {
        std::vector<std::string> shown;
        for (const std::string &p : c.ignored_pointers)
            if (std::find(shown.begin(), shown.end(), p.substr(0, 80)) == shown.end()) shown.push_back(p.substr(0, 80));
        W.push_back("KHR_animation_pointer: " + plural(n_ptr, "channel", "channels") + " ignored (" +
                    name_list(shown) + "): only node TRS and weights, KHR_lights_punctual light properties, camera projections "
                    "and material factors and texture transforms are animated");
    }
    constexpr size_t kMaxExtensionLines = 16;
    std::vector<std::string> unimpl;
    for (const std::string &e : md.extensionsUsed)
        /* KHR_animation_pointer is played in part: its channels are warned one by one (above); a file
           that requires it is refused (extensionsRequired) */
        if (!extension_implemented(e) && !extension_effect(e).empty()) unimpl.push_back(e);
    for (size_t i = 0; i < unimpl.size() && i < kMaxExtensionLines; i++) {
        const std::string &e = unimpl[i];
        W.push_back("extensionsUsed: '" + e.substr(0, 80) + "' " + extension_effect(e));
    }
    if (unimpl.size() > kMaxExtensionLines)
        W.push_back(strf("extensionsUsed: %zu more extensions ignored (not supported)",
                         unimpl.size() - kMaxExtensionLines));

    std::vector<std::string> texcoord;
    for (size_t i = 0; i < md.materials.size(); i++)
        if (material_texcoord_past_1(c, i)) texcoord.push_back(material_desc(md, i));
    if (!texcoord.empty())
        W.push_back("textures of " + plural(texcoord.size(), "material", "materials") + " (" +
                    name_list(texcoord) + ") ask for a texCoord other than 0 or 1: read with TEXCOORD_0");
    if (c.color1_prims)
        W.push_back("COLOR_1 (and higher) in " +
                    plural(c.color1_prims, "primitive", "primitives") + " ignored: COLOR_0 is used");
    if (c.morph_other_prims)
        W.push_back("morph targets of TEXCOORD_n or COLOR_n in " + plural(c.morph_other_prims, "primitive", "primitives") +
                    " ignored: POSITION, NORMAL and TANGENT targets are applied");
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

} // namespace pg_gltf
