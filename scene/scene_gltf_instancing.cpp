/* scene_gltf_instancing.cpp - EXT_mesh_gpu_instancing: a node's instance transforms.
 *
 * The extension gives a node with a mesh accessors of per-instance TRANSLATION (VEC3), ROTATION
 * (VEC4 unit quaternion) and SCALE (VEC3), all of one count; the node's mesh is drawn once per
 * instance, at node world x T x R x S of that instance (the node's own transform applied after
 * the instance's). passgraph bakes each instance into the scene's vertices like a node of its own
 * (scene_gltf_nodes.cpp), so every pipeline draws them with nothing new on the GPU; an instanced
 * mesh on an animated node moves with it. Custom attributes (names starting with '_') are ignored,
 * as the extension allows. Refused, naming the field: a mesh-less node, an attribute that is not
 * an accessor index, a wrong type, counts that differ, no transform attribute, a skinned or
 * morphed mesh (not supported), more than 2^20 instances in the scene (PG_ERR_LIMIT).
 */
#include "scene_gltf_internal.h"

#include <cmath>

namespace pg_gltf {

constexpr size_t kMaxInstances = size_t(1) << 20;

/* the attribute's accessor, type-checked: FLOAT, or what the extension (and KHR_mesh_quantization)
 * allow besides */
static View instance_view(Ctx &c, const json &attrs, const char *name, int type, const std::string &w)
{
    auto it = attrs.find(name);
    if (it == attrs.end()) return View{};
    if (!it->is_number_unsigned() || it->get<uint64_t>() >= c.model.accessors.size())
        gfail(strf("%s.attributes.%s: expected an accessor index (%zu accessors)", w.c_str(), name,
                   c.model.accessors.size()));
    View v = get_view(c, int(it->get<uint64_t>()));
    const bool rotation = type == TINYGLTF_TYPE_VEC4;
    const bool i8_16 = v.ctype == TINYGLTF_COMPONENT_TYPE_BYTE || v.ctype == TINYGLTF_COMPONENT_TYPE_SHORT ||
                       v.ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                       v.ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    const bool signed_norm = v.normalized && (v.ctype == TINYGLTF_COMPONENT_TYPE_BYTE ||
                                              v.ctype == TINYGLTF_COMPONENT_TYPE_SHORT);
    bool ok = v.ctype == TINYGLTF_COMPONENT_TYPE_FLOAT || (rotation ? signed_norm : c.quantization && i8_16);
    if (v.type != type || !ok)
        gfail(strf("%s.attributes.%s: accessors[%d] must be %s %s (got %s %s%s)", w.c_str(), name, v.index,
                   type_name(type),
                   rotation ? "FLOAT or normalized BYTE/SHORT"
                            : (c.quantization ? "FLOAT or (normalized) BYTE/UNSIGNED_BYTE/SHORT/UNSIGNED_SHORT"
                                              : "FLOAT (other types need KHR_mesh_quantization)"),
                   type_name(v.type), v.normalized ? "normalized " : "", ctype_name(v.ctype)));
    return v;
}

size_t node_instances(Ctx &c, int ni, size_t *total, std::vector<Mat4> *out)
{
    const json &jn = c.j["nodes"][size_t(ni)];
    const json *ex = jn.is_object() ? opt_object(jn, "extensions", strf("nodes[%d]", ni)) : nullptr;
    const std::string w = strf("nodes[%d].extensions.EXT_mesh_gpu_instancing", ni);
    const json *ext = ex ? opt_object(*ex, "EXT_mesh_gpu_instancing", strf("nodes[%d].extensions", ni)) : nullptr;
    if (!ext) return 0;
    const tinygltf::Node &nd = c.model.nodes[size_t(ni)];
    if (nd.mesh < 0) gfail(w + ": the node has no mesh to instance");
    const json *attrs = opt_object(*ext, "attributes", w);
    if (!attrs) gfail(w + ".attributes: missing (required)");
    for (auto it = attrs->begin(); it != attrs->end(); ++it)
        if (it.key() != "TRANSLATION" && it.key() != "ROTATION" && it.key() != "SCALE" && it.key().rfind('_', 0) != 0)
            gfail(strf("%s.attributes: '%.60s' is not TRANSLATION, ROTATION, SCALE or a custom '_' attribute",
                       w.c_str(), it.key().c_str()));
    const View tv = instance_view(c, *attrs, "TRANSLATION", TINYGLTF_TYPE_VEC3, w);
    const View rv = instance_view(c, *attrs, "ROTATION", TINYGLTF_TYPE_VEC4, w);
    const View sv = instance_view(c, *attrs, "SCALE", TINYGLTF_TYPE_VEC3, w);
    const View *given[3] = {&tv, &rv, &sv};
    size_t count = SIZE_MAX;
    for (const View *v : given) {
        if (v->index < 0) continue;
        if (count != SIZE_MAX && v->count != count)
            gfail(strf("%s.attributes: accessors of %zu and %zu instances (every attribute needs the same count)",
                       w.c_str(), count, v->count));
        count = v->count;
    }
    if (count == SIZE_MAX) gfail(w + ".attributes: none of TRANSLATION, ROTATION, SCALE");
    if (nd.skin >= 0) gfail(w + ": instancing a skinned mesh is not supported");
    for (const tinygltf::Primitive &p : c.model.meshes[size_t(nd.mesh)].primitives)
        if (!p.targets.empty()) gfail(w + ": instancing a mesh with morph targets is not supported");
    if (count > kMaxInstances - *total)
        fail(PG_ERR_LIMIT, strf("%s: more than %zu instances in the scene", w.c_str(), kMaxInstances));
    *total += count;
    if (!out) return count;
    out->reserve(count);
    for (size_t i = 0; i < count; i++) {
        float f[4];
        double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
        if (tv.index >= 0) {
            read_floats(tv, i, f);
            for (int k = 0; k < 3; k++) t[k] = f[k];
        }
        if (rv.index >= 0) {
            read_floats(rv, i, f);
            for (int k = 0; k < 4; k++) q[k] = f[k];
        }
        if (sv.index >= 0) {
            read_floats(sv, i, f);
            for (int k = 0; k < 3; k++) s[k] = f[k];
        }
        for (double x : t)
            if (!std::isfinite(x)) gfail(strf("%s: instance %zu: TRANSLATION is not finite", w.c_str(), i));
        for (double x : s)
            if (!std::isfinite(x)) gfail(strf("%s: instance %zu: SCALE is not finite", w.c_str(), i));
        for (double x : q)
            if (!std::isfinite(x)) gfail(strf("%s: instance %zu: ROTATION is not finite", w.c_str(), i));
        if (!(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] > 1e-24)) /* as mat_trs would refuse it */
            gfail(strf("%s: instance %zu: ROTATION: zero-length quaternion", w.c_str(), i));
        out->push_back(mat_trs(t, q, s, w));
    }
    return count;
}

} // namespace pg_gltf
