/* scene_gltf_nodes.cpp - step 4 of the glTF load (scene_gltf.cpp): the node hierarchy from the
 * scene roots (cycles, depth and instance limits), node transforms, and the cameras it reaches.
 */
#include "node_place.h"
#include "scene_gltf_internal.h"
#include "scenario.h"

#include <cmath>
#include <cstring>

namespace pg_gltf {

/* ------------------------------------------------------------------------------------------ */
/* step 4: the node hierarchy                                                                   */

constexpr int kMaxNodeDepth = 1024;
constexpr size_t kMaxNodeVisits = size_t(1) << 20;
/* every node and instance bakes its mesh into the scene's arrays: 8 GiB of vertices and indices at
 * most, checked before anything is baked (Walker::count_only), so that a small file drawing a large
 * mesh at many nodes (a DAG of children) or instances is refused instead of exhausting memory */
constexpr uint64_t kMaxBakedBytes = uint64_t(8) << 30;

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
    if (n.rotation.size() == 4)
        for (int i = 0; i < 4; i++) q[i] = n.rotation[size_t(i)];
    return mat_trs(t, q, s, strf("nodes[%d].rotation", ni));
}

/* accessor ai's element count: range-checked against its data (get_view) when it has a bufferView
 * or sparse values, else (and for a Draco primitive, decoded later) as declared */
static uint64_t planned_count(Ctx &c, int ai, bool draco)
{
    const auto &acc = c.model.accessors;
    if (ai < 0 || size_t(ai) >= acc.size()) return 0;
    const tinygltf::Accessor &a = acc[size_t(ai)];
    if (draco || (a.bufferView < 0 && !a.sparse.isSparse)) return a.count;
    return get_view(c, ai).count;
}

/* The bytes one drawing of `mesh` bakes: 48 per vertex (twice in a file that animates: the
 * mesh-space copy), 4 per triangle-list index; points and lines none. A primitive without NORMAL
 * bakes a vertex per index (flat normals). Before anything is baked. */
static uint64_t planned_bytes(Ctx &c, const tinygltf::Mesh &mesh)
{
    uint64_t bytes = 0;
    for (const tinygltf::Primitive &p : mesh.primitives) {
        const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
        const int *pos = find_attr(p, "POSITION");
        if (mode < TINYGLTF_MODE_TRIANGLES || !pos) continue;
        const bool draco = p.extensions.count("KHR_draco_mesh_compression") != 0;
        const uint64_t n = planned_count(c, *pos, draco);
        uint64_t ni = p.indices >= 0 ? planned_count(c, p.indices, draco) : n;
        if (mode != TINYGLTF_MODE_TRIANGLES) ni = ni > 2 ? 3 * (ni - 2) : 0;
        const uint64_t nv = find_attr(p, "NORMAL") ? n : ni;
        bytes += nv * sizeof(pg_vertex) * (c.animated ? 2 : 1) + ni * sizeof(uint32_t);
    }
    return bytes;
}

void Walker::visit(int ni, const Mat4 &parent, int depth, bool moving)
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
    moving = moving || (c.animated && c.node_animated[size_t(ni)]);
    if (nd.mesh >= 0 && size_t(nd.mesh) >= c.model.meshes.size())
        gfail(strf("nodes[%d].mesh: %d out of range", ni, nd.mesh));
    std::vector<Mat4> inst; /* EXT_mesh_gpu_instancing */
    const size_t n_inst = node_instances(c, ni, &instances, count_only ? nullptr : &inst);
    if (nd.mesh >= 0 && count_only) {
        const uint64_t per = planned_bytes(c, c.model.meshes[size_t(nd.mesh)]);
        const uint64_t times = n_inst ? n_inst : 1;
        if (per > (kMaxBakedBytes - planned) / times)
            fail(PG_ERR_LIMIT, strf("nodes[%d]: the meshes drawn at every node and instance would bake more than %llu "
                                    "GiB of vertices and indices (passgraph's limit for a scene)",
                                    ni, (unsigned long long)(kMaxBakedBytes >> 30)));
        planned += per * times;
    } else if (nd.mesh >= 0) {
        const tinygltf::Mesh &mesh = c.model.meshes[size_t(nd.mesh)];
        for (size_t p = 0; p < mesh.primitives.size(); p++)
            emit_primitive(c, o, nd.mesh, int(p), world, ni, moving, n_inst ? &inst : nullptr);
    }
    for (int ch : nd.children) visit(ch, world, depth + 1, moving);
    on_path[size_t(ni)] = 0;
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
        pg_scene_camera sc = camera_object(c, nd.camera);
        pg_strlcpy(sc.node_name, nd.name.empty() ? strf("nodes[%d]", ni).c_str() : nd.name.c_str(),
                   sizeof sc.node_name);
        sc.gltf_node = ni;
        if (!pg_place_camera(world.m, &sc)) gfail(strf("nodes[%d]: camera node transform is singular", ni));
        out.push_back(sc);
    }
    for (int ch : nd.children) camera_visit(c, ch, world, out);
}

pg_scene_camera camera_object(const Ctx &c, int ci)
{
    const tinygltf::Camera &gc = c.model.cameras[size_t(ci)];
    const std::string cw = strf("cameras[%d]", ci);
    pg_scene_camera sc;
    memset(&sc, 0, sizeof sc);
    pg_strlcpy(sc.name, gc.name.empty() ? cw.c_str() : gc.name.c_str(), sizeof sc.name);
    sc.gltf_camera = ci;
    sc.gltf_node = -1;
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
        sc.xmag = float(std::fabs(o.xmag)); /* negative: the spec says it should not be; warned, its size used */
        sc.ymag = float(std::fabs(o.ymag));
        sc.znear = float(o.znear);
        sc.zfar = float(o.zfar);
    } else {
        gfail(cw + ".type: '" + gc.type + "': expected \"perspective\" or \"orthographic\"");
    }
    return sc;
}

/* one light object of the extension, checked (placement left 0) */
pg_scene_light light_object(const Ctx &c, int li)
{
    const tinygltf::Light &gl = c.model.lights[size_t(li)];
    const std::string lw = strf("KHR_lights_punctual.lights[%d]", li);
    pg_scene_light L;
    memset(&L, 0, sizeof L);
    pg_strlcpy(L.name, gl.name.empty() ? lw.c_str() : gl.name.c_str(), sizeof L.name);
    L.gltf_light = li;
    if (gl.type == "point") L.type = PG_LIGHT_POINT;
    else if (gl.type == "spot") L.type = PG_LIGHT_SPOT;
    else if (gl.type == "directional") L.type = PG_LIGHT_DIRECTIONAL;
    else gfail(lw + ".type: '" + gl.type + "': expected \"point\", \"spot\" or \"directional\"");
    if (gl.color.empty()) {
        L.color[0] = L.color[1] = L.color[2] = 1.0f;
    } else {
        if (gl.color.size() != 3) gfail(strf("%s.color: %zu numbers, expected 3", lw.c_str(), gl.color.size()));
        for (int k = 0; k < 3; k++) {
            if (!(std::isfinite(gl.color[size_t(k)]) && gl.color[size_t(k)] >= 0 && gl.color[size_t(k)] <= 3.4e38))
                gfail(lw + ".color: expected three finite numbers >= 0");
            L.color[k] = float(gl.color[size_t(k)]);
        }
    }
    if (!(std::isfinite(gl.intensity) && gl.intensity >= 0 && gl.intensity <= 1e30))
        gfail(lw + ".intensity: expected a finite number >= 0 (at most 1e30)");
    L.intensity = float(gl.intensity);
    const double peak = std::max(std::max(double(L.color[0]), double(L.color[1])), double(L.color[2])) * gl.intensity;
    if (L.type == PG_LIGHT_DIRECTIONAL && peak > PG_LIGHT_MAX_LUX)
        gfail(strf("%s: colour x intensity %g lux: over the %g lux a directional light may give (the sun gives "
                   "about 1.2e5)", lw.c_str(), peak, PG_LIGHT_MAX_LUX));
    if (peak > PG_LIGHT_MAX_CANDELA)
        gfail(strf("%s: colour x intensity %g candela: over the %g a light may give", lw.c_str(), peak,
                   PG_LIGHT_MAX_CANDELA));
    if (!(std::isfinite(gl.range) && gl.range >= 0 && gl.range <= 1e30))
        gfail(lw + ".range: expected a finite number > 0 (at most 1e30), or absent");
    L.range = L.type == PG_LIGHT_DIRECTIONAL ? 0.0f : float(gl.range);
    if (L.type == PG_LIGHT_SPOT) {
        double in = gl.spot.innerConeAngle, out = gl.spot.outerConeAngle;
        if (!(std::isfinite(out) && out > 0 && out <= 1.5707963267948966))
            gfail(lw + ".spot.outerConeAngle: expected an angle in (0, pi/2] radians");
        if (!(std::isfinite(in) && in >= 0 && in < out))
            gfail(lw + ".spot.innerConeAngle: expected an angle in [0, outerConeAngle) radians");
        L.inner_cone = float(in);
        L.outer_cone = float(out);
    }
    return L;
}

void light_visit(const Ctx &c, int ni, const Mat4 &parent, std::vector<pg_scene_light> &out)
{
    const tinygltf::Model &md = c.model;
    const tinygltf::Node &nd = md.nodes[size_t(ni)];
    Mat4 world = mat_mul(parent, node_local(nd, ni));
    auto ext = nd.extensions.find("KHR_lights_punctual");
    if (ext != nd.extensions.end()) {
        const std::string where = strf("nodes[%d].extensions.KHR_lights_punctual.light", ni);
        const tinygltf::Value &v = ext->second;
        if (!v.IsObject() || !v.Has("light") || !(v.Get("light").IsInt() || v.Get("light").IsNumber()))
            gfail(where + ": expected a light index");
        double li = v.Get("light").GetNumberAsDouble();
        if (!(li >= 0 && li < double(md.lights.size()) && li == std::floor(li)))
            gfail(strf("%s: %g out of range (%zu lights)", where.c_str(), li, md.lights.size()));
        pg_scene_light L = light_object(c, int(li));
        L.gltf_node = ni;
        L.direction[1] = -1.0f; /* a point light's default when its node has no -Z axis */
        if (!pg_place_light(world.m, &L) && L.type != PG_LIGHT_POINT)
            gfail(strf("nodes[%d]: light node transform is singular (no direction)", ni));
        for (int k = 0; k < 3; k++)
            if (!std::isfinite(L.position[k])) gfail(strf("nodes[%d]: light position is not finite", ni));
        out.push_back(L);
    }
    for (int ch : nd.children) light_visit(c, ch, world, out);
}

/* One record of the table: 8 little-endian float32, position xyz, range (0: none), colour rgb
 * (linear), intensity (candela). */
void table_lights(const Ctx &c, std::vector<pg_scene_light> &out)
{
    auto ext = c.model.extensions.find("PASSGRAPH_lights_table");
    if (ext == c.model.extensions.end()) return;
    const std::string w = "extensions.PASSGRAPH_lights_table";
    const tinygltf::Value &v = ext->second;
    auto num = [&](const char *key, double &x) {
        if (!v.IsObject() || !v.Has(key) || !(v.Get(key).IsInt() || v.Get(key).IsNumber()))
            gfail(w + "." + key + ": expected a number");
        x = v.Get(key).GetNumberAsDouble();
    };
    double bvd = 0, countd = 0;
    num("bufferView", bvd);
    num("count", countd);
    if (!(bvd >= 0 && bvd == std::floor(bvd) && bvd < double(c.model.bufferViews.size())))
        gfail(strf("%s.bufferView: %g out of range (%zu bufferViews)", w.c_str(), bvd, c.model.bufferViews.size()));
    if (!(countd >= 0 && countd == std::floor(countd) && countd <= double(PG_MAX_LIGHTS)))
        gfail(strf("%s.count: expected an integer in 0..%u", w.c_str(), PG_MAX_LIGHTS));
    const int bvi = int(bvd);
    const size_t count = size_t(countd), rec = 32;
    const tinygltf::BufferView &bv = c.model.bufferViews[size_t(bvi)];
    if (bv.byteStride != 0 && bv.byteStride != rec)
        gfail(strf("%s: bufferViews[%d].byteStride %zu (the records are 32 bytes, tightly packed)", w.c_str(), bvi,
                   bv.byteStride));
    auto bytes = view_bytes(c, bvi, w);
    if (bytes.second < count * rec)
        gfail(strf("%s.count: %zu lights need %zu bytes, bufferViews[%d] has %zu", w.c_str(), count, count * rec, bvi,
                   bytes.second));
    size_t base = out.size();
    out.resize(base + count);
    for (size_t i = 0; i < count; i++) {
        float f[8];
        memcpy(f, bytes.first + i * rec, sizeof f);
        pg_scene_light &L = out[base + i];
        memset(&L, 0, sizeof L);
        L.gltf_light = -1;
        L.gltf_node = -1;
        L.type = PG_LIGHT_POINT;
        for (int k = 0; k < 8; k++)
            if (!std::isfinite(f[k]) || (k >= 3 && f[k] < 0))
                gfail(strf("%s: light %zu: %s %g (expected finite numbers, range, colour and intensity >= 0)",
                           w.c_str(), i, k < 3 ? "position" : k == 3 ? "range" : k < 7 ? "colour" : "intensity",
                           double(f[k])));
        const double peak = double(std::max(std::max(f[4], f[5]), f[6])) * double(f[7]);
        if (peak > PG_LIGHT_MAX_CANDELA)
            gfail(strf("%s: light %zu: colour x intensity %g candela: over the %g a light may give", w.c_str(), i,
                       peak, PG_LIGHT_MAX_CANDELA));
        if (f[3] != 0 && !(std::isnormal(f[3]) && f[3] <= 1e30f)) /* as a KHR light's range */
            gfail(strf("%s: light %zu: range %g: expected 0 (none: infinite reach) or a number in [1.2e-38, 1e30]",
                       w.c_str(), i, double(f[3])));
        memcpy(L.position, f, sizeof L.position);
        L.range = f[3];
        memcpy(L.color, f + 4, sizeof L.color);
        L.intensity = f[7];
        L.direction[1] = -1.0f;
    }
}

} // namespace pg_gltf
