/* scene_gltf_variants.cpp - KHR_materials_variants: the file's named material variants, and which
 * material each primitive draws.
 *
 * The root extension lists the variants (each with a name); a primitive's extension maps variants
 * to materials ({"material": M, "variants": [V...]}). Without a choice the primitives draw their
 * default `material`, as the extension says; pg_scene_load_opts.gltf_variant (`--variant N|NAME`)
 * picks variant N (or the one named NAME): each primitive that maps it draws that material, the
 * others their default. Read before the node walk; refused naming the field: a variant without a
 * name, a mapping whose material or variant index is out of range, a variant mapped twice in one
 * primitive; an unknown --variant lists the file's variants.
 */
#include "scene_gltf_internal.h"

#include <cstdlib>

namespace pg_gltf {

static const json *variants_ext(const json &o, const std::string &w)
{
    auto ex = o.find("extensions");
    if (ex == o.end() || !ex->is_object()) return nullptr;
    return opt_object(*ex, "KHR_materials_variants", w + ".extensions");
}

/* "0 'red', 1 'blue'" (at most 8, then ", ...") */
static std::string variant_list(const std::vector<std::string> &names)
{
    std::string s;
    for (size_t i = 0; i < names.size() && i < 8; i++)
        s += strf("%s%zu '%.40s'", i ? ", " : "", i, names[i].c_str());
    if (names.size() > 8) s += ", ...";
    return s;
}

/* the root's variant names, checked */
static void read_names(Ctx &c)
{
    const json *root = variants_ext(c.j, "");
    if (!root) return;
    const std::string w = "extensions.KHR_materials_variants";
    auto v = root->find("variants");
    if (v == root->end() || !v->is_array()) gfail(w + ".variants: expected an array");
    for (size_t i = 0; i < v->size(); i++) {
        const json &e = (*v)[i];
        auto n = e.is_object() ? e.find("name") : e.end();
        if (!e.is_object() || n == e.end() || !n->is_string())
            gfail(strf("%s.variants[%zu].name: expected a string", w.c_str(), i));
        c.variant_names.push_back(n->get<std::string>());
    }
}

/* c.want_variant (an index or a name) -> c.variant */
static void choose(Ctx &c)
{
    const std::string &want = c.want_variant;
    if (want.empty()) return;
    const size_t n = c.variant_names.size();
    if (n == 0) throw LoadFail{PG_ERR_INVALID_ARG, strf("--variant '%.60s': the file has no material variants "
                                                        "(KHR_materials_variants)", want.c_str())};
    char *end = nullptr;
    const unsigned long idx = strtoul(want.c_str(), &end, 10);
    if (end && !*end && want.find_first_not_of("0123456789") == std::string::npos && idx < n) {
        c.variant = int(idx);
        return;
    }
    for (size_t i = 0; i < n; i++)
        if (c.variant_names[i] == want) {
            c.variant = int(i);
            return;
        }
    throw LoadFail{PG_ERR_INVALID_ARG, strf("--variant '%.60s': not a variant of the file (%zu: %s)", want.c_str(), n,
                                            variant_list(c.variant_names).c_str())};
}

/* each primitive's mappings, checked; the chosen variant's material per (mesh, primitive) */
static void read_mappings(Ctx &c)
{
    auto meshes = c.j.find("meshes");
    if (meshes == c.j.end() || !meshes->is_array()) return;
    const size_t n_mat = c.model.materials.size(), n_var = c.variant_names.size();
    for (size_t mi = 0; mi < meshes->size(); mi++) {
        auto prims = (*meshes)[mi].is_object() ? (*meshes)[mi].find("primitives") : (*meshes)[mi].end();
        if (prims == (*meshes)[mi].end() || !prims->is_array()) continue;
        for (size_t pi = 0; pi < prims->size(); pi++) {
            const std::string w = strf("meshes[%zu].primitives[%zu]", mi, pi);
            const json *ext = (*prims)[pi].is_object() ? variants_ext((*prims)[pi], w) : nullptr;
            if (!ext) continue;
            const std::string ew = w + ".extensions.KHR_materials_variants";
            auto maps = ext->find("mappings");
            if (maps == ext->end() || !maps->is_array()) gfail(ew + ".mappings: expected an array");
            std::vector<char> seen(n_var, 0);
            for (size_t k = 0; k < maps->size(); k++) {
                const json &m = (*maps)[k];
                const std::string mw = strf("%s.mappings[%zu]", ew.c_str(), k);
                if (!m.is_object()) gfail(mw + ": expected an object");
                const uint64_t mat = uint_field(m, "material", mw, true);
                if (mat >= n_mat) gfail(strf("%s.material: %llu out of range (%zu materials)", mw.c_str(),
                                             (unsigned long long)mat, n_mat));
                auto vs = m.find("variants");
                if (vs == m.end() || !vs->is_array()) gfail(mw + ".variants: expected an array of variant indices");
                for (const json &v : *vs) {
                    if (!v.is_number_unsigned() || v.get<uint64_t>() >= n_var)
                        gfail(strf("%s.variants: expected variant indices below %zu", mw.c_str(), n_var));
                    const size_t vi = size_t(v.get<uint64_t>());
                    if (seen[vi]) gfail(strf("%s.variants: variant %zu is mapped twice in this primitive", mw.c_str(), vi));
                    seen[vi] = 1;
                    if (int(vi) == c.variant) c.variant_material[{int(mi), int(pi)}] = int(mat);
                }
            }
        }
    }
}

void variants_prepare(Ctx &c)
{
    read_names(c);
    choose(c);
    read_mappings(c);
}

int variant_material(const Ctx &c, int mi, int pi, int dflt)
{
    auto it = c.variant_material.find({mi, pi});
    return it == c.variant_material.end() ? dflt : it->second;
}

std::string variant_list_line(const Ctx &c)
{
    return variant_list(c.variant_names);
}

} // namespace pg_gltf
