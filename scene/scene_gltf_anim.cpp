/* scene_gltf_anim.cpp - the glTF load's animation data (scene/animation.h): which nodes animation
 * moves, the skins' joint slots, each moving primitive's JOINTS_0 / WEIGHTS_0 and morph targets,
 * and at hand-out the node table, skins and animation channels of pg_scene_anim. Bad values fail
 * naming the object ("animations[0].samplers[1].input: ..."). */
#include "scene_gltf_internal.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>

namespace pg_gltf {

static pg_anim_path channel_path(const std::string &p, bool *known)
{
    *known = true;
    if (p == "translation") return PG_ANIM_TRANSLATION;
    if (p == "rotation") return PG_ANIM_ROTATION;
    if (p == "scale") return PG_ANIM_SCALE;
    if (p == "weights") return PG_ANIM_WEIGHTS;
    *known = false;
    return PG_ANIM_TRANSLATION;
}

/* Has animations[ai].channels[ci] no target.node in the file? */
static bool channel_nodeless(const Ctx &c, size_t ai, size_t ci)
{
    const auto an = c.j.find("animations");
    if (an == c.j.end() || !an->is_array() || ai >= an->size() || !(*an)[ai].is_object()) return false;
    const auto ch = (*an)[ai].find("channels");
    if (ch == (*an)[ai].end() || !ch->is_array() || ci >= ch->size() || !(*ch)[ci].is_object()) return false;
    const auto t = (*ch)[ci].find("target");
    return t != (*ch)[ci].end() && t->is_object() && !t->contains("node");
}

/* The path of a material property a pointer names after "/materials/N/" (false: one passgraph does
 * not animate, warned). */
static bool material_property(const std::string &prop, pg_anim_path *path)
{
    static const struct { const char *name; pg_anim_path path; } props[] = {
        {"pbrMetallicRoughness/baseColorFactor", PG_ANIM_MAT_BASE_COLOR},
        {"pbrMetallicRoughness/metallicFactor", PG_ANIM_MAT_METALLIC},
        {"pbrMetallicRoughness/roughnessFactor", PG_ANIM_MAT_ROUGHNESS},
        {"emissiveFactor", PG_ANIM_MAT_EMISSIVE},
        {"extensions/KHR_materials_emissive_strength/emissiveStrength", PG_ANIM_MAT_EMISSIVE_STRENGTH},
        {"alphaCutoff", PG_ANIM_MAT_ALPHA_CUTOFF},
        {"normalTexture/scale", PG_ANIM_MAT_NORMAL_SCALE},
        {"occlusionTexture/strength", PG_ANIM_MAT_OCCLUSION_STRENGTH}};
    for (const auto &pr : props)
        if (prop == pr.name) {
            *path = pr.path;
            return true;
        }
    static const char *const slots[PG_TEXSLOT_COUNT] = {
        "pbrMetallicRoughness/baseColorTexture", "normalTexture", "emissiveTexture",
        "pbrMetallicRoughness/metallicRoughnessTexture", "occlusionTexture"};
    static const char *const uv[3] = {"offset", "rotation", "scale"};
    for (int sl = 0; sl < PG_TEXSLOT_COUNT; sl++)
        for (int k = 0; k < 3; k++)
            if (prop == std::string(slots[sl]) + "/extensions/KHR_texture_transform/" + uv[k]) {
                *path = pg_anim_path(PG_ANIM_MAT_UV + 3 * sl + k);
                return true;
            }
    return false;
}

/* A channel's target and path: target.node and target.path, or with target.path "pointer" the
 * KHR_animation_pointer JSON pointer: "/nodes/N/translation|rotation|scale|weights" (the same
 * animation), "/extensions/KHR_lights_punctual/lights/N/<property>", "/cameras/N/<projection
 * property>" or "/materials/N/<property>" (material_property; *node is then the light's, camera's
 * or material's index). false: another pointer (*pointer names it, for the warning) or an unknown
 * path (*why names the channel and the cause). A pointer that is not a string is refused. */
static bool channel_target(const tinygltf::AnimationChannel &ch, bool nodeless, const std::string &cw, int *node,
                           pg_anim_path *path, std::string *pointer, std::string *why)
{
    bool known = false;
    *node = nodeless ? -1 : ch.target_node; /* nodeless: the copy tinygltf read says 0 (nodeless_targets) */
    pointer->clear();
    if (ch.target_path != "pointer") {
        *path = channel_path(ch.target_path, &known);
        if (!known) *why = cw + " (unknown target.path '" + ch.target_path.substr(0, 40) + "')";
        else if (*node < 0) *why = cw + " (no target.node: the specification leaves its target to an extension)";
        return known && *node >= 0;
    }
    const auto ext = ch.target_extensions.find("KHR_animation_pointer");
    if (ext == ch.target_extensions.end() || !ext->second.IsObject() || !ext->second.Has("pointer") ||
        !ext->second.Get("pointer").IsString())
        gfail(cw + ".target: path 'pointer' without a KHR_animation_pointer extension giving a \"pointer\" string");
    *pointer = ext->second.Get("pointer").Get<std::string>();
    const std::string lights = "/extensions/KHR_lights_punctual/lights/", cameras = "/cameras/",
                      materials = "/materials/";
    const bool light = pointer->compare(0, lights.size(), lights) == 0;
    const bool camera = pointer->compare(0, cameras.size(), cameras) == 0;
    const bool material = pointer->compare(0, materials.size(), materials) == 0;
    const std::string pre = light ? lights : camera ? cameras : material ? materials : "/nodes/";
    if (pointer->compare(0, pre.size(), pre) != 0) return false;
    size_t i = pre.size(), j = i;
    while (j < pointer->size() && j - i < 10 && (*pointer)[j] >= '0' && (*pointer)[j] <= '9') j++;
    if (j == i || j >= pointer->size() || (*pointer)[j] != '/' || (j - i > 1 && (*pointer)[i] == '0')) return false;
    const unsigned long n = strtoul(pointer->c_str() + i, nullptr, 10);
    if (n > 0x7fffffffUL) return false;
    *node = int(n);
    if (material) return material_property(pointer->substr(j + 1), path);
    if (light || camera) {
        static const struct { const char *name; pg_anim_path path; } props[] = {
            {"color", PG_ANIM_LIGHT_COLOR},
            {"intensity", PG_ANIM_LIGHT_INTENSITY},
            {"range", PG_ANIM_LIGHT_RANGE},
            {"spot/innerConeAngle", PG_ANIM_SPOT_INNER},
            {"spot/outerConeAngle", PG_ANIM_SPOT_OUTER},
            {"perspective/yfov", PG_ANIM_CAM_YFOV},
            {"perspective/aspectRatio", PG_ANIM_CAM_ASPECT},
            {"orthographic/xmag", PG_ANIM_CAM_XMAG},
            {"orthographic/ymag", PG_ANIM_CAM_YMAG},
            {"perspective/znear", PG_ANIM_CAM_ZNEAR},
            {"orthographic/znear", PG_ANIM_CAM_ZNEAR},
            {"perspective/zfar", PG_ANIM_CAM_ZFAR},
            {"orthographic/zfar", PG_ANIM_CAM_ZFAR}};
        for (const auto &pr : props)
            if (pointer->substr(j + 1) == pr.name && (pr.path >= PG_ANIM_CAM_YFOV) == camera) {
                *path = pr.path;
                return true;
            }
        return false;
    }
    *path = channel_path(pointer->substr(j + 1), &known);
    return known;
}

static bool light_path(pg_anim_path p)
{
    return p >= PG_ANIM_LIGHT_COLOR && p < PG_ANIM_CAM_YFOV;
}

static bool camera_path(pg_anim_path p)
{
    return p >= PG_ANIM_CAM_YFOV && p <= PG_ANIM_CAM_ZFAR;
}

static bool material_path(pg_anim_path p)
{
    return p >= PG_ANIM_MAT_BASE_COLOR && p <= PG_ANIM_MAT_LAST;
}

void anim_prepare(Ctx &c)
{
    const tinygltf::Model &md = c.model;
    bool morphs = false;
    for (const auto &m : md.meshes)
        for (const auto &p : m.primitives) morphs = morphs || !p.targets.empty();
    c.animated = !md.animations.empty() || !md.skins.empty() || morphs;
    c.node_animated.assign(md.nodes.size(), 0);
    for (size_t ai = 0; ai < md.animations.size(); ai++) {
        const auto &an = md.animations[ai];
        for (size_t ci = 0; ci < an.channels.size(); ci++) {
            const auto &ch = an.channels[ci];
            const std::string cw = strf("animations[%zu].channels[%zu]", ai, ci);
            int node = -1;
            pg_anim_path path = PG_ANIM_TRANSLATION;
            std::string pointer, why;
            if (!channel_target(ch, channel_nodeless(c, ai, ci), cw, &node, &path, &pointer, &why)) continue; /* counted at hand-out */
            if (light_path(path) || camera_path(path) || material_path(path)) {
                const char *what = light_path(path) ? "light" : camera_path(path) ? "camera" : "material";
                const size_t have = light_path(path)    ? md.lights.size()
                                    : camera_path(path) ? md.cameras.size()
                                                        : md.materials.size();
                if (size_t(node) >= have)
                    gfail(strf("%s.target.extensions.KHR_animation_pointer.pointer: %s %d out of range (%zu %ss)",
                               cw.c_str(), what, node, have, what));
                continue;
            }
            if (size_t(node) >= md.nodes.size())
                gfail(strf("%s.target.%s%d out of range (%zu nodes)", cw.c_str(),
                           pointer.empty() ? "node: " : "extensions.KHR_animation_pointer.pointer: node ", node,
                           md.nodes.size()));
            if (path != PG_ANIM_WEIGHTS && md.nodes[size_t(node)].matrix.size() != 16) c.node_animated[size_t(node)] = 1;
        }
    }
    c.skin_slot_base.assign(md.skins.size(), 0);
    uint64_t slots = 0;
    for (size_t s = 0; s < md.skins.size(); s++) {
        c.skin_slot_base[s] = uint32_t(slots);
        if (md.skins[s].joints.empty()) gfail(strf("skins[%zu].joints: empty (a skin needs at least one joint)", s));
        slots += md.skins[s].joints.size();
        for (size_t j = 0; j < md.skins[s].joints.size(); j++) {
            const int jn = md.skins[s].joints[j];
            if (jn < 0 || size_t(jn) >= md.nodes.size())
                gfail(strf("skins[%zu].joints[%zu]: node %d out of range (%zu nodes)", s, j, jn, md.nodes.size()));
        }
    }
    if (slots > PG_ANIM_MAX_JOINT_SLOTS)
        fail(PG_ERR_LIMIT, strf("skins: %llu joints in all (at most %u)", (unsigned long long)slots,
                                PG_ANIM_MAX_JOINT_SLOTS));
    c.joint_slots = uint32_t(slots);
}

/* JOINTS_n / WEIGHTS_n (n = set) of a skinned primitive, checked: its two views */
static void skin_views(Ctx &c, const tinygltf::Primitive &prim, int set, size_t n, const std::string &pw, View &jv,
                       View &wv)
{
    const std::string J = strf("JOINTS_%d", set), Wn = strf("WEIGHTS_%d", set);
    jv = get_view(c, *find_attr(prim, J.c_str()));
    wv = get_view(c, *find_attr(prim, Wn.c_str()));
    if (jv.count != n || wv.count != n)
        gfail(strf("%s: %s / %s have %zu / %zu elements but POSITION has %zu", pw.c_str(), J.c_str(), Wn.c_str(),
                   jv.count, wv.count, n));
    if (jv.type != TINYGLTF_TYPE_VEC4 || jv.normalized ||
        (jv.ctype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && jv.ctype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))
        gfail(strf("accessors[%d]: %s must be VEC4 UNSIGNED_BYTE or UNSIGNED_SHORT (got %s %s)", jv.index, J.c_str(),
                   type_name(jv.type), ctype_name(jv.ctype)));
    const bool wf = wv.ctype == TINYGLTF_COMPONENT_TYPE_FLOAT && !wv.normalized;
    const bool wu = wv.normalized && (wv.ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                      wv.ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    if (wv.type != TINYGLTF_TYPE_VEC4 || !(wf || wu))
        gfail(strf("accessors[%d]: %s must be VEC4 FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT "
                   "(got %s %s%s)",
                   wv.index, Wn.c_str(), type_name(wv.type), wv.normalized ? "normalized " : "", ctype_name(wv.ctype)));
}

/* JOINTS_0 / WEIGHTS_0 and, when present, JOINTS_1 / WEIGHTS_1 of a skinned primitive into
 * o.joints / o.weights (PG_ANIM_MAX_INFLUENCES a vertex: absolute joint slots, weights normalised
 * over all of them) */
static void skin_attributes(Ctx &c, Out &o, const tinygltf::Primitive &prim, int skin, size_t base, size_t n,
                            const uint32_t *src, size_t src_n, const std::string &pw)
{
    const tinygltf::Skin &sk = c.model.skins[size_t(skin)];
    const bool set1_j = find_attr(prim, "JOINTS_1") != nullptr, set1_w = find_attr(prim, "WEIGHTS_1") != nullptr;
    if (set1_j != set1_w)
        gfail(strf("%s: %s without %s (a joint set needs both)", pw.c_str(), set1_j ? "JOINTS_1" : "WEIGHTS_1",
                   set1_j ? "WEIGHTS_1" : "JOINTS_1"));
    const int sets = set1_j ? 2 : 1;
    View jv[2], wv[2];
    for (int t = 0; t < sets; t++) skin_views(c, prim, t, src_n, pw, jv[t], wv[t]);
    for (const auto &at : prim.attributes)
        if ((at.first.compare(0, 7, "JOINTS_") == 0 || at.first.compare(0, 8, "WEIGHTS_") == 0) &&
            at.first != "JOINTS_0" && at.first != "JOINTS_1" && at.first != "WEIGHTS_0" && at.first != "WEIGHTS_1") {
            c.joints2_prims++;
            break;
        }
    const size_t K = PG_ANIM_MAX_INFLUENCES;
    o.joints.resize((base + n) * K, 0);
    o.weights.resize((base + n) * K, 0.0f);
    const uint32_t slot0 = c.skin_slot_base[size_t(skin)];
    for (size_t i = 0; i < n; i++) {
        float j[PG_ANIM_MAX_INFLUENCES] = {0}, w[PG_ANIM_MAX_INFLUENCES] = {0};
        double sum = 0;
        const size_t e = src ? src[i] : i; /* the accessors' element */
        for (int t = 0; t < sets; t++) {
            view_floats(jv[t], e, j + 4 * t);
            view_floats(wv[t], e, w + 4 * t);
            for (int k = 4 * t; k < 4 * t + 4; k++) {
                if (!(std::isfinite(w[k]) && w[k] >= 0))
                    gfail(strf("accessors[%d]: WEIGHTS_%d element %zu: %g (expected finite weights >= 0)",
                               wv[t].index, t, e, double(w[k])));
                if (w[k] > 0 && !(j[k] < float(sk.joints.size())))
                    gfail(strf("accessors[%d]: JOINTS_%d element %zu: joint %g out of range (skins[%d] has %zu joints)",
                               jv[t].index, t, e, double(j[k]), skin, sk.joints.size()));
                sum += w[k];
            }
        }
        uint16_t *J = &o.joints[(base + i) * K];
        float *W = &o.weights[(base + i) * K];
        for (size_t k = 0; k < K; k++) {
            J[k] = uint16_t(slot0 + (w[k] > 0 ? uint32_t(j[k]) : 0u));
            W[k] = sum > 0 ? float(w[k] / sum) : (k == 0 ? 1.0f : 0.0f);
            if (k >= 4 && W[k] > 0) c.influences8 = true;
        }
    }
}

/* the node's morph weights (allocated on first use: node.weights, else mesh.weights, else 0) */
static uint32_t node_weights(Ctx &c, Out &o, int ni, int mi, size_t targets, const std::string &pw)
{
    auto it = o.node_weights.find(ni);
    if (it != o.node_weights.end()) {
        if (targets > it->second.second)
            gfail(strf("%s.targets: %zu targets, but the mesh's other primitives have %u", pw.c_str(), targets,
                       it->second.second));
        return it->second.first;
    }
    const tinygltf::Mesh &mesh = c.model.meshes[size_t(mi)];
    size_t count = targets;
    for (const auto &p : mesh.primitives) count = std::max(count, p.targets.size());
    const tinygltf::Node &nd = c.model.nodes[size_t(ni)];
    const std::vector<double> &def = !nd.weights.empty() ? nd.weights : mesh.weights;
    if (!def.empty() && def.size() != count)
        gfail(strf("%s.weights: %zu weights for %zu morph targets", !nd.weights.empty() ? strf("nodes[%d]", ni).c_str()
                                                                                       : strf("meshes[%d]", mi).c_str(),
                   def.size(), count));
    const uint32_t b = uint32_t(o.rest_weights.size());
    for (size_t k = 0; k < count; k++) {
        const double w = k < def.size() ? def[k] : 0.0;
        if (!std::isfinite(w)) gfail(strf("meshes[%d].weights: not finite", mi));
        o.rest_weights.push_back(float(w));
    }
    o.node_weights[ni] = {b, uint32_t(count)};
    return b;
}

/* one morph target attribute (VEC3) of target t into the deltas at `first` (field 0 position,
 * 1 normal, 2 tangent) */
static void target_attribute(Ctx &c, Out &o, const std::map<std::string, int> &tg, const char *name, int field,
                             size_t first, size_t n, const uint32_t *src, size_t src_n, const std::string &tw)
{
    auto f = tg.find(name);
    if (f == tg.end()) return;
    View v = get_view(c, f->second);
    if (v.type != TINYGLTF_TYPE_VEC3 || v.count != src_n)
        gfail(strf("%s.%s: accessors[%d] must be VEC3 with %zu elements (got %s, %zu)", tw.c_str(), name, v.index,
                   src_n, type_name(v.type), v.count));
    for (size_t i = 0; i < n; i++) {
        float d[3];
        const size_t e = src ? src[i] : i;
        view_floats(v, e, d);
        for (int k = 0; k < 3; k++)
            if (!std::isfinite(d[k])) gfail(strf("%s.%s: element %zu is not finite", tw.c_str(), name, e));
        pg_anim_delta &D = o.deltas[first + i];
        float *dst = field == 0 ? D.position : field == 1 ? D.normal : D.tangent;
        memcpy(dst, d, sizeof d);
    }
}

void anim_primitive(Ctx &c, Out &o, const tinygltf::Primitive &prim, int ni, size_t base, size_t n,
                    const uint32_t *src, size_t src_n, const std::string &pw)
{
    const tinygltf::Node &nd = c.model.nodes[size_t(ni)];
    pg_anim_prim ap;
    memset(&ap, 0, sizeof ap);
    ap.node = uint32_t(ni);
    ap.skin = -1;
    ap.first_vertex = uint32_t(base);
    ap.n_vertices = uint32_t(n);
    if (nd.skin >= 0 && find_attr(prim, "JOINTS_0") && find_attr(prim, "WEIGHTS_0")) {
        if (size_t(nd.skin) >= c.model.skins.size())
            gfail(strf("nodes[%d].skin: %d out of range (%zu skins)", ni, nd.skin, c.model.skins.size()));
        ap.skin = nd.skin;
        skin_attributes(c, o, prim, nd.skin, base, n, src, src_n, pw);
    }
    if (!prim.targets.empty()) {
        const size_t nt = prim.targets.size();
        if (o.deltas.size() + nt * n > (size_t(1) << 26))
            fail(PG_ERR_LIMIT, pw + ".targets: more than 2^26 morph target vertices in the scene");
        ap.n_targets = uint32_t(nt);
        ap.target_base = uint32_t(o.deltas.size());
        ap.weight_base = node_weights(c, o, ni, c.model.nodes[size_t(ni)].mesh, nt, pw);
        pg_anim_delta zero;
        memset(&zero, 0, sizeof zero);
        o.deltas.resize(o.deltas.size() + nt * n, zero);
        for (size_t t = 0; t < nt; t++) {
            const std::string tw = strf("%s.targets[%zu]", pw.c_str(), t);
            const size_t first = ap.target_base + t * n;
            target_attribute(c, o, prim.targets[t], "POSITION", 0, first, n, src, src_n, tw);
            target_attribute(c, o, prim.targets[t], "NORMAL", 1, first, n, src, src_n, tw);
            target_attribute(c, o, prim.targets[t], "TANGENT", 2, first, n, src, src_n, tw);
        }
    }
    const uint32_t index = uint32_t(o.aprims.size());
    o.aprims.push_back(ap);
    for (size_t i = 0; i < n; i++) o.vertex_prim[base + i] = index;
}

/* ---- hand-out ---- */

template <typename T> static T *dup(const std::vector<T> &v)
{
    if (v.empty()) return nullptr;
    T *p = static_cast<T *>(malloc(v.size() * sizeof(T)));
    if (!p) throw std::bad_alloc();
    memcpy(p, v.data(), v.size() * sizeof(T));
    return p;
}

struct AnimDeleter {
    void operator()(pg_scene_anim *a) const { pg_scene_anim_free(a); }
};

static void hand_out_nodes(const Ctx &c, const Out &o, pg_scene_anim *a)
{
    const tinygltf::Model &md = c.model;
    a->n_nodes = uint32_t(md.nodes.size());
    a->nodes = static_cast<pg_anim_node *>(calloc(md.nodes.size() + 1, sizeof(pg_anim_node)));
    if (!a->nodes) throw std::bad_alloc();
    for (size_t i = 0; i < md.nodes.size(); i++) a->nodes[i].parent = -1;
    for (size_t i = 0; i < md.nodes.size(); i++) {
        const tinygltf::Node &nd = md.nodes[i];
        pg_anim_node &N = a->nodes[i];
        for (int ch : nd.children)
            if (ch >= 0 && size_t(ch) < md.nodes.size() && a->nodes[ch].parent < 0 && size_t(ch) != i)
                a->nodes[ch].parent = int32_t(i); /* the first parent (glTF allows one) */
        N.rotation[3] = 1;
        N.scale[0] = N.scale[1] = N.scale[2] = 1;
        if (nd.matrix.size() == 16) {
            N.has_matrix = true;
            for (int k = 0; k < 16; k++) N.matrix[k] = float(nd.matrix[size_t(k)]);
        }
        for (size_t k = 0; k < 3 && nd.translation.size() == 3; k++) N.translation[k] = float(nd.translation[k]);
        for (size_t k = 0; k < 3 && nd.scale.size() == 3; k++) N.scale[k] = float(nd.scale[k]);
        if (nd.rotation.size() == 4) { /* normalised, as the rest pose's node_local does */
            const double l = std::sqrt(nd.rotation[0] * nd.rotation[0] + nd.rotation[1] * nd.rotation[1] +
                                       nd.rotation[2] * nd.rotation[2] + nd.rotation[3] * nd.rotation[3]);
            if (!(l > 1e-12)) gfail(strf("nodes[%zu].rotation: zero-length quaternion", i));
            for (size_t k = 0; k < 4; k++) N.rotation[k] = float(nd.rotation[k] / l);
        }
        auto w = o.node_weights.find(int(i));
        if (w != o.node_weights.end()) {
            N.weight_base = w->second.first;
            N.n_weights = w->second.second;
        }
    }
    /* a parent chain that loops (a file without scenes whose nodes are never walked) is cut */
    for (size_t i = 0; i < md.nodes.size(); i++) {
        size_t steps = 0;
        for (int32_t p = a->nodes[i].parent; p >= 0; p = a->nodes[p].parent)
            if (++steps > md.nodes.size()) {
                a->nodes[i].parent = -1;
                break;
            }
    }
}

static void hand_out_skins(Ctx &c, pg_scene_anim *a)
{
    const tinygltf::Model &md = c.model;
    a->n_skins = uint32_t(md.skins.size());
    a->n_joint_slots = c.joint_slots;
    if (md.skins.empty()) return;
    a->skins = static_cast<pg_anim_skin *>(calloc(md.skins.size(), sizeof(pg_anim_skin)));
    if (!a->skins) throw std::bad_alloc();
    for (size_t s = 0; s < md.skins.size(); s++) {
        const tinygltf::Skin &sk = md.skins[s];
        pg_anim_skin &S = a->skins[s];
        const size_t nj = sk.joints.size();
        S.n_joints = uint32_t(nj);
        S.slot_base = c.skin_slot_base[s];
        S.joints = static_cast<uint32_t *>(calloc(nj + 1, sizeof(uint32_t)));
        S.inverse_bind = static_cast<float(*)[16]>(calloc(nj + 1, sizeof(float[16])));
        if (!S.joints || !S.inverse_bind) throw std::bad_alloc();
        for (size_t j = 0; j < nj; j++) {
            S.joints[j] = uint32_t(sk.joints[j]);
            for (int k = 0; k < 4; k++) S.inverse_bind[j][k * 5] = 1.0f;
        }
        if (sk.inverseBindMatrices < 0) continue;
        View v = get_view(c, sk.inverseBindMatrices);
        if (v.type != TINYGLTF_TYPE_MAT4 || v.ctype != TINYGLTF_COMPONENT_TYPE_FLOAT || v.count < nj)
            gfail(strf("skins[%zu].inverseBindMatrices: accessors[%d] must be MAT4 FLOAT with at least %zu elements "
                       "(got %s %s, %zu)",
                       s, v.index, nj, type_name(v.type), ctype_name(v.ctype), v.count));
        for (size_t j = 0; j < nj; j++) {
            view_floats(v, j, S.inverse_bind[j]);
            for (int k = 0; k < 16; k++)
                if (!std::isfinite(S.inverse_bind[j][k]))
                    gfail(strf("skins[%zu].inverseBindMatrices: matrix %zu is not finite", s, j));
        }
    }
}

/* one channel: its sampler's keys and values, checked */
static bool hand_out_channel(Ctx &c, const pg_scene_anim *a, size_t ai, size_t ci, pg_anim_channel &C)
{
    const tinygltf::Animation &an = c.model.animations[ai];
    const tinygltf::AnimationChannel &ch = an.channels[ci];
    const std::string cw = strf("animations[%zu].channels[%zu]", ai, ci);
    int node = -1;
    std::string pointer;
    std::string why;
    if (!channel_target(ch, channel_nodeless(c, ai, ci), cw, &node, &C.path, &pointer, &why)) {
        if (!pointer.empty()) c.ignored_pointers.push_back(pointer);
        else c.ignored_why.push_back(why);
        return false;
    }
    C.node = uint32_t(node);
    const bool lp = light_path(C.path) || camera_path(C.path) || material_path(C.path);
    if (!lp && C.path != PG_ANIM_WEIGHTS && a->nodes[C.node].has_matrix) { /* glTF forbids: ignored */
        c.ignored_why.push_back(cw + strf(" (nodes[%d] is given by a matrix)", node));
        return false;
    }
    if (C.path == PG_ANIM_WEIGHTS && a->nodes[C.node].n_weights == 0) { /* not a drawn morph */
        c.ignored_why.push_back(cw + strf(" (weights of nodes[%d], which draws no morph targets)", node));
        return false;
    }
    if (ch.sampler < 0 || size_t(ch.sampler) >= an.samplers.size())
        gfail(strf("%s.sampler: %d out of range (%zu samplers)", cw.c_str(), ch.sampler, an.samplers.size()));
    const tinygltf::AnimationSampler &sm = an.samplers[size_t(ch.sampler)];
    const std::string sw = strf("animations[%zu].samplers[%d]", ai, ch.sampler);
    if (sm.interpolation == "STEP") C.interp = PG_INTERP_STEP;
    else if (sm.interpolation == "CUBICSPLINE") C.interp = PG_INTERP_CUBICSPLINE;
    else if (sm.interpolation == "LINEAR" || sm.interpolation.empty()) C.interp = PG_INTERP_LINEAR;
    else gfail(sw + ".interpolation: '" + sm.interpolation + "': expected LINEAR, STEP or CUBICSPLINE");
    View in = get_view(c, sm.input), out = get_view(c, sm.output);
    if (in.type != TINYGLTF_TYPE_SCALAR || in.ctype != TINYGLTF_COMPONENT_TYPE_FLOAT || in.count < 1)
        gfail(strf("%s.input: accessors[%d] must be SCALAR FLOAT with at least one key", sw.c_str(), in.index));
    C.n_keys = uint32_t(in.count);
    uint32_t mat_width = 0;
    if (material_path(C.path)) pg_anim_material_offset(C.path, &mat_width);
    C.width = C.path == PG_ANIM_ROTATION                         ? 4
              : C.path == PG_ANIM_WEIGHTS                        ? a->nodes[C.node].n_weights
              : material_path(C.path)                            ? mat_width
              : lp && C.path != PG_ANIM_LIGHT_COLOR              ? 1
                                                                 : 3;
    const size_t per_key = (C.interp == PG_INTERP_CUBICSPLINE ? 3 : 1) * size_t(C.width);
    const int want_type = C.path == PG_ANIM_ROTATION || (C.width == 4 && C.path != PG_ANIM_WEIGHTS)
                              ? TINYGLTF_TYPE_VEC4
                          : C.path == PG_ANIM_WEIGHTS || C.width == 1 ? TINYGLTF_TYPE_SCALAR
                          : C.width == 2                              ? TINYGLTF_TYPE_VEC2
                                                                      : TINYGLTF_TYPE_VEC3;
    const size_t comps = C.path == PG_ANIM_WEIGHTS ? 1 : C.width;
    if (out.type != want_type || out.count * comps != in.count * per_key)
        gfail(strf("%s.output: accessors[%d] must be %s with %zu elements for %zu keys of '%s' (got %s, %zu)",
                   sw.c_str(), out.index, type_name(want_type), in.count * per_key / comps, in.count,
                   pointer.empty() ? ch.target_path.c_str() : pointer.c_str(), type_name(out.type), out.count));
    C.times = static_cast<float *>(malloc(in.count * sizeof(float)));
    C.values = static_cast<float *>(malloc(in.count * per_key * sizeof(float)));
    if (!C.times || !C.values) throw std::bad_alloc();
    for (size_t k = 0; k < in.count; k++) {
        view_floats(in, k, &C.times[k]);
        if (!std::isfinite(C.times[k]) || C.times[k] < 0 || (k > 0 && C.times[k] < C.times[k - 1]))
            gfail(strf("%s.input: key %zu: time %g (expected finite, >= 0, not decreasing)", sw.c_str(), k,
                       double(C.times[k])));
    }
    for (size_t e = 0; e < out.count; e++) {
        view_floats(out, e, &C.values[e * comps]);
        for (size_t k = 0; k < comps; k++)
            if (!std::isfinite(C.values[e * comps + k]))
                gfail(strf("%s.output: element %zu is not finite", sw.c_str(), e));
    }
    /* rotation keys as unit quaternions (the specification's; a normalized BYTE key or a file's
     * 0.5 x q is not one, and slerp between such keys turns by the wrong angle). A cubic spline's
     * tangents stay as given: only its values (the middle of each key's three) are keys. */
    if (C.path == PG_ANIM_ROTATION)
        for (size_t e = 0; e < out.count; e++) {
            if (C.interp == PG_INTERP_CUBICSPLINE && e % 3 != 1) continue;
            float *q = &C.values[e * 4];
            const double l = std::sqrt(double(q[0]) * q[0] + double(q[1]) * q[1] + double(q[2]) * q[2] + double(q[3]) * q[3]);
            if (l > 1e-30)
                for (int k = 0; k < 4; k++) q[k] = float(q[k] / l);
        }
    return true;
}

/* materials[m]'s animatable values as the file gives them (glTF's defaults where it does not):
 * the layout of pg_scene_anim.material_rest (animation.h PG_ANIM_MATERIAL_PROPS) */
static void material_rest(const Ctx &c, uint32_t m, float r[PG_ANIM_MATERIAL_PROPS])
{
    const tinygltf::Material &gm = c.model.materials[m];
    const auto &pbr = gm.pbrMetallicRoughness;
    for (int k = 0; k < 4; k++) r[k] = size_t(k) < pbr.baseColorFactor.size() ? float(pbr.baseColorFactor[size_t(k)]) : 1.0f;
    r[4] = float(pbr.metallicFactor);
    r[5] = float(pbr.roughnessFactor);
    for (int k = 0; k < 3; k++) r[6 + k] = size_t(k) < gm.emissiveFactor.size() ? float(gm.emissiveFactor[size_t(k)]) : 0.0f;
    r[9] = 1.0f;
    auto es = gm.extensions.find("KHR_materials_emissive_strength");
    if (es != gm.extensions.end() && es->second.Has("emissiveStrength"))
        r[9] = float(es->second.Get("emissiveStrength").GetNumberAsDouble());
    r[10] = float(gm.alphaCutoff);
    r[11] = float(gm.normalTexture.scale);
    r[12] = float(gm.occlusionTexture.strength);
    const json &jm = c.j.at("materials").at(m);
    const std::string mw = strf("materials[%u]", m);
    const json *jpbr = opt_object(jm, "pbrMetallicRoughness", mw);
    const json *ti[PG_TEXSLOT_COUNT] = {};
    ti[PG_TEXSLOT_BASE] = jpbr ? opt_object(*jpbr, "baseColorTexture", mw) : nullptr;
    ti[PG_TEXSLOT_NORMAL] = opt_object(jm, "normalTexture", mw);
    ti[PG_TEXSLOT_EMISSIVE] = opt_object(jm, "emissiveTexture", mw);
    ti[PG_TEXSLOT_METALLIC_ROUGHNESS] = jpbr ? opt_object(*jpbr, "metallicRoughnessTexture", mw) : nullptr;
    ti[PG_TEXSLOT_OCCLUSION] = opt_object(jm, "occlusionTexture", mw);
    for (int sl = 0; sl < PG_TEXSLOT_COUNT; sl++) {
        float *u = r + PG_ANIM_MAT_UV_BASE + 5 * sl; /* offset u v, rotation, scale u v */
        u[0] = u[1] = u[2] = 0.0f;
        u[3] = u[4] = 1.0f;
        const json *tt = nullptr;
        if (ti[sl] && ti[sl]->contains("extensions") && (*ti[sl])["extensions"].is_object() &&
            (*ti[sl])["extensions"].contains("KHR_texture_transform"))
            tt = &(*ti[sl])["extensions"]["KHR_texture_transform"];
        if (!tt || !tt->is_object()) continue; /* the loader checked the values (texture_transform) */
        auto num = [&](const char *key, int i, float *out) {
            auto it = tt->find(key);
            if (it == tt->end()) return;
            const json &v = i < 0 ? *it : (it->is_array() && it->size() == 2 ? (*it)[size_t(i)] : *it);
            if (v.is_number()) *out = float(v.get<double>());
        };
        num("offset", 0, &u[0]);
        num("offset", 1, &u[1]);
        num("rotation", -1, &u[2]);
        num("scale", 0, &u[3]);
        num("scale", 1, &u[4]);
    }
}

static void hand_out_animations(Ctx &c, pg_scene_anim *a)
{
    const tinygltf::Model &md = c.model;
    if (md.animations.empty()) return;
    if (!md.lights.empty()) {
        a->n_lights = uint32_t(md.lights.size());
        a->light_animated = static_cast<uint8_t *>(calloc(md.lights.size(), 1));
        a->light_rest = static_cast<float(*)[PG_ANIM_LIGHT_PROPS]>(calloc(md.lights.size(), sizeof *a->light_rest));
        if (!a->light_animated || !a->light_rest) throw std::bad_alloc();
    }
    if (!md.materials.empty()) {
        a->n_materials = uint32_t(md.materials.size());
        a->material_animated = static_cast<uint32_t *>(calloc(md.materials.size(), sizeof *a->material_animated));
        a->material_rest =
            static_cast<float(*)[PG_ANIM_MATERIAL_PROPS]>(calloc(md.materials.size(), sizeof *a->material_rest));
        if (!a->material_animated || !a->material_rest) throw std::bad_alloc();
    }
    if (!md.cameras.empty()) {
        a->n_cameras = uint32_t(md.cameras.size());
        a->camera_animated = static_cast<uint8_t *>(calloc(md.cameras.size(), 1));
        a->camera_rest = static_cast<float(*)[PG_ANIM_CAMERA_PROPS]>(calloc(md.cameras.size(), sizeof *a->camera_rest));
        if (!a->camera_animated || !a->camera_rest) throw std::bad_alloc();
    }
    a->animations = static_cast<pg_animation *>(calloc(md.animations.size(), sizeof(pg_animation)));
    if (!a->animations) throw std::bad_alloc();
    for (size_t ai = 0; ai < md.animations.size(); ai++) {
        const tinygltf::Animation &an = md.animations[ai];
        pg_animation &A = a->animations[a->n_animations++];
        pg_strlcpy(A.name, an.name.empty() ? strf("animations[%zu]", ai).c_str() : an.name.c_str(), sizeof A.name);
        A.channels = static_cast<pg_anim_channel *>(calloc(an.channels.size() + 1, sizeof(pg_anim_channel)));
        if (!A.channels) throw std::bad_alloc();
        for (size_t ci = 0; ci < an.channels.size(); ci++) {
            pg_anim_channel &C = A.channels[A.n_channels];
            memset(&C, 0, sizeof C);
            bool kept = false;
            try {
                kept = hand_out_channel(c, a, ai, ci, C);
            } catch (...) { /* the channel is not counted yet: free what it allocated before the refusal */
                free(C.times);
                free(C.values);
                memset(&C, 0, sizeof C);
                throw;
            }
            if (!kept) {
                free(C.times);
                free(C.values);
                memset(&C, 0, sizeof C);
                c.ignored_channels++;
                continue;
            }
            A.end = std::max(A.end, C.times[C.n_keys - 1]);
            for (uint32_t k = 0; k < A.n_channels; k++) /* glTF: each target at most once an animation */
                if (A.channels[k].node == C.node && A.channels[k].path == C.path) {
                    c.duplicate_targets.push_back(strf("animations[%zu].channels[%zu] (the target of an earlier channel)",
                                                       ai, ci));
                    break;
                }
            A.n_channels++; /* counted (freed with the animation) before light_object may refuse the light */
            if (light_path(C.path) && C.node < a->n_lights && !a->light_animated[C.node]) {
                a->light_animated[C.node] = 1;
                const pg_scene_light L = light_object(c, int(C.node)); /* its rest values, checked */
                float *r = a->light_rest[C.node];
                memcpy(r, L.color, sizeof L.color);
                r[3] = L.intensity, r[4] = L.range, r[5] = L.inner_cone, r[6] = L.outer_cone;
            }
            if (material_path(C.path) && C.node < a->n_materials) {
                if (!a->material_animated[C.node]) {
                    material_rest(c, C.node, a->material_rest[C.node]);
                    a->n_animated_materials++;
                }
                a->material_animated[C.node] |= 1u << (C.path - PG_ANIM_MAT_BASE_COLOR);
            }
            if (camera_path(C.path) && C.node < a->n_cameras && !a->camera_animated[C.node]) {
                a->camera_animated[C.node] = 1;
                const pg_scene_camera K = camera_object(c, int(C.node)); /* its rest values, checked */
                float *r = a->camera_rest[C.node];
                r[0] = K.yfov_rad, r[1] = K.aspect_ratio, r[2] = K.xmag, r[3] = K.ymag, r[4] = K.znear, r[5] = K.zfar;
            }
        }
    }
}

pg_scene_anim *anim_hand_out(Ctx &c, const Out &o)
{
    /* kept when a drawn primitive moves, or when the file has animations (a light or camera on an
     * animated node moves too); features.has_animation only for moving geometry */
    if (!c.animated || (o.aprims.empty() && c.model.animations.empty())) return nullptr;
    std::unique_ptr<pg_scene_anim, AnimDeleter> a(static_cast<pg_scene_anim *>(calloc(1, sizeof(pg_scene_anim))));
    if (!a) throw std::bad_alloc();
    hand_out_nodes(c, o, a.get());
    hand_out_skins(c, a.get());
    hand_out_animations(c, a.get());
    const size_t n = o.verts.size();
    a->n_vertices = uint32_t(n);
    a->local = dup(o.local);
    a->vertex_prim = dup(o.vertex_prim);
    for (size_t v = 0; v < n; v++)
        if (a->vertex_prim[v] == PG_ANIM_STATIC) a->local[v] = o.verts[v];
    if (!o.joints.empty()) {
        std::vector<uint16_t> j(o.joints);
        std::vector<float> w(o.weights);
        j.resize(n * PG_ANIM_MAX_INFLUENCES, 0);
        w.resize(n * PG_ANIM_MAX_INFLUENCES, 0.0f);
        a->joints = reinterpret_cast<uint16_t(*)[PG_ANIM_MAX_INFLUENCES]>(dup(j));
        a->weights = reinterpret_cast<float(*)[PG_ANIM_MAX_INFLUENCES]>(dup(w));
    }
    a->influences = c.influences8 ? 8u : 4u;
    a->prims = dup(o.aprims);
    a->n_prims = uint32_t(o.aprims.size());
    a->deltas = dup(o.deltas);
    a->n_deltas = uint32_t(o.deltas.size());
    a->rest_weights = dup(o.rest_weights);
    a->n_weights = uint32_t(o.rest_weights.size());
    return a.release();
}

} // namespace pg_gltf
