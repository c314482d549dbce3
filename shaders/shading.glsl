// shading.glsl - the lighting loop every shading pass shares (forward naive, forward+, deferred).
// Needs common.glsl, lighting.glsl, and for PG_CLUSTERED cluster.glsl. Set 2 holds the lights:
//   binding 0 Lights, and with PG_CLUSTERED binding 1 the per-cluster records (uvec4: list
//   offset, lights stored, lights reaching the cluster, 0; see cluster_light.glsl), binding 2 the
//   lists (light indices, ascending within each cluster).
// Without PG_HAS_LIGHTS (0 lights in the scene) no light buffer is declared or read.
// Debug views (PG_DEBUG_VIEW): 0 none, 1 cluster_heat, 2 cluster_x, 3 cluster_y, 4 cluster_z,
// 5 overflow, 6 albedo, 7 normal, 8 depth.
// PG_AMBIENT: the pass option "ambient", a run-time value: the including shader defines it to its
// push-constant member (not a define per value, so a new ambient compiles no variant).
#ifndef PG_AMBIENT
#error "define PG_AMBIENT (the push-constant member holding the pass's ambient) before shading.glsl"
#endif

#if defined(PG_HAS_LIGHTS) && defined(PG_LIGHTCUT)
// the light tree (shaders/light_tree.comp: 4 vec4 a node, root 1, leaves np .. 2np - 1)
layout(set = 2, binding = 0, std430) readonly buffer LightTree { vec4 tree[]; };
#elif defined(PG_HAS_LIGHTS)
layout(set = 2, binding = 0, std430) readonly buffer Lights { Light lights[]; };
#ifdef PG_CLUSTERED
layout(set = 2, binding = 1, std430) readonly buffer ClusterRecords { uvec4 cluster_records[]; };
#define PG_LISTS_SET 2
#include "cluster_list_windows.glsl"
#endif
#endif

#ifndef PG_DEBUG_VIEW
#define PG_DEBUG_VIEW 0
#endif

// PG_ENVIRONMENT: the filtered environment (environment_filter's buffer) at set 2, binding
// PG_ENV_BINDING (after the light bindings); its light is added to every shaded point.
#ifdef PG_ENVIRONMENT
layout(set = 2, binding = PG_ENV_BINDING, std430) readonly buffer EnvironmentFiltered { vec4 env_filtered[]; };
#define PG_ENV_FETCH(i) env_filtered[i]
#include "environment.glsl"
#endif

// A shaded point's colour: the light sums combined with the material, the ambient term and the
// emission (pg_shade_combine), plus the environment's light (V: unit, toward the eye).
vec3 pg_shade_final(Surface s, PgShade acc, vec3 V)
{
    vec3 c = pg_shade_combine(s, acc, vec3(PG_AMBIENT + frame.clip.z));
#ifdef PG_ENVIRONMENT_FILTERED
    c += pg_env_light(s, V);
#endif
    return c;
}

// PG_COUNT_EVALS (deferred_lighting): pg_evals counts the light evaluations of this invocation
// (every light of a list a pixel walks, RIS candidates, lightcut leaves and representatives); the
// pass sums them per frame into the buffer at set 2, binding PG_EVALS_BINDING (64-bit: low, high).
#if defined(PG_COUNT_EVALS) && defined(PG_HAS_LIGHTS)
layout(set = 2, binding = PG_EVALS_BINDING, std430) buffer Evals { uint evals_lo; uint evals_hi; };
uint pg_evals = 0u;
#define PG_COUNT(n) (pg_evals += uint(n))
#else
#define PG_COUNT(n)
#endif

vec3 pg_heat(float t)
{
    // blue -> cyan -> green -> yellow -> red -> white for t in [0,1], > 1 stays white
    t = clamp(t, 0.0, 1.2);
    vec3 c = clamp(vec3(1.5 - abs(4.0 * t - 3.0), 1.5 - abs(4.0 * t - 2.0), 1.5 - abs(4.0 * t - 1.0)), 0.0, 1.0);
    return t > 1.0 ? vec3(1.0) : c;
}

vec3 pg_index_color(uint i)
{
    uint h = i * 2654435761u;
    return vec3(float((h >> 8) & 255u), float((h >> 16) & 255u), float((h >> 24) & 255u)) / 255.0 * 0.8 + 0.2;
}

#if defined(PG_RIS) && defined(PG_CLUSTERED) && defined(PG_HAS_LIGHTS)
// ---- resampled importance sampling of the cluster's list (approximation knob, PG_RIS) --------
// RIS (Talbot, Cline, Egbert 2005; the per-pixel resampling of ReSTIR DI, Bitterli et al. 2020,
// without spatial or temporal reuse). Per sample: PG_RIS_M candidates drawn uniformly from the
// pixel's cluster list (n lights, source pdf 1/n), target p^ = luminance of the light's
// unshadowed contribution to the final colour (albedo x diffuse term + specular x specular
// term, the exact model of lighting.glsl), one candidate y kept by weighted reservoir sampling
// with weights w = p^ n; estimate f(y) / p^(y) x (1/M) sum w. E[estimate] = sum over the list of f,
// the exact sum, wherever p^ > 0 where f != 0 (true: f >= 0 per channel, luminance weights > 0)
// and the list holds every light that reaches the pixel (exact lists: no overflow). PG_RIS_S
// independent samples are averaged. Random numbers: PCG hash of pixel, frame.noise.x (sample
// index) and frame.noise.y (seed): the same inputs give the same image.
float pg_rand01(inout uint st) // [0, 1), 24 bits
{
    st = pg_pcg(st);
    return float(st >> 8u) * (1.0 / 16777216.0);
}

// The light's contribution to the pixel's colour (no ambient, no emissive).
vec3 pg_light_contribution(Surface s, uint li, vec3 cam, vec3 P, vec3 V, float inv_md2)
{
    Light L = lights[li];
    float R2 = L.pos_radius.w * L.pos_radius.w;
    PgShade one = pg_shade_zero();
    pg_accumulate_light_rel(L.pos_radius.xyz - cam, R2, pg_light_inv_r2(L.color.w * L.color.w), L.color.rgb,
                            PG_SPOT_OF(li), P, s.normal, V, pg_light_mat(s, V), inv_md2, one);
    return pg_shade_lights(s, one);
}

vec3 pg_ris_estimate(Surface s, uvec4 rec, vec3 P, vec3 V, vec2 frag_xy)
{
    uint n = rec.y;
    if (n == 0u) return vec3(0.0);
    vec3 cam = frame.camera_pos.xyz;
    float md = frame.light_params.w;
    float inv_md2 = 1.0 / (md * md);
    uvec2 px = uvec2(frag_xy);
    uint st = pg_pcg(px.x + pg_pcg(px.y + pg_pcg(frame.noise.x + pg_pcg(frame.noise.y))));
    vec3 sum = vec3(0.0);
    PG_COUNT(PG_RIS_M * PG_RIS_S);
    for (int k = 0; k < PG_RIS_S; k++) {
        float wsum = 0.0, p_y = 0.0;
        vec3 f_y = vec3(0.0);
        for (int m = 0; m < PG_RIS_M; m++) {
            uint i = min(uint(pg_rand01(st) * float(n)), n - 1u);
            vec3 f = pg_light_contribution(s, PG_LIST_READ(rec.x + i), cam, P, V, inv_md2);
            float ph = pg_luminance(f);
            float w = ph * float(n);
            wsum += w;
            if (w > 0.0 && pg_rand01(st) * wsum < w) {
                f_y = f;
                p_y = ph;
            }
        }
        if (p_y > 0.0) sum += f_y * (wsum / (float(PG_RIS_M) * p_y));
    }
    return sum / float(PG_RIS_S);
}
#endif

#if defined(PG_LIGHTCUT) && defined(PG_HAS_LIGHTS)
// ---- lightcut over the light tree (approximation knob with a per-pixel bound, PG_LIGHTCUT) ----
// A depth-first walk of the tree (shared by a subgroup's pixels: pg_lightcut), nearer child first.
// A node's contribution lies in [0, U] per channel, U = summed colour x min(1/dmin^2,
// 1/dmin_light^2) x falloff(dmin / Rmax) x (albedo (+ specular with Blinn-Phong)) x cos_max (pbr:
// below) where dmin is the distance from the point to the box of the node's light centres, Rmax the
// node's largest radius and cos_max = min(1, max over the box's corners of N.(c - P) / dmin) bounds
// N.L; U = 0 (skipped: exact) when dmin >= Rmax (every light's falloff is 0) or every light centre
// lies behind the surface's tangent plane (every N.L <= 0). A leaf is summed exactly (the model of
// lighting.glsl) into E; a node may instead be approximated by its representative light (summed
// colour at the weighted centroid, largest radius) clamped to [0, U], with error bound b = max(U -
// est, est), only while B + b <= eps E in every channel (B: the bounds spent so far). E only grows
// and every contribution is >= 0, so the result's error is at most B <= eps E <= eps x the exact
// sum, per channel and pixel: the stated bound (float rounding aside; tests/gpu/
// test_gpu_lightcut.c). PG_LC_EPS_PPM: eps in parts per million. The walk needs no random numbers.
// PG_LC_BUCKET (option lightcut_bucket, a power of two): a node the walk refines whose subtree holds
// at most that many leaves has them all summed exactly (a loop over its leaves, which are contiguous)
// instead of walked down node by node: no error, so the bound holds as before, with more but far
// cheaper evaluations than the bounds, votes and pushes of the walk they replace. 1: the plain walk.
#ifndef PG_LC_STACK
#define PG_LC_STACK 64
#endif
#ifndef PG_LC_BUCKET
#define PG_LC_BUCKET 1
#endif
float pg_lc_box_d2(vec3 lo, vec3 hi, vec3 P)
{
    vec3 d = max(lo - P, vec3(0.0)) + max(P - hi, vec3(0.0));
    return dot(d, d);
}

// The distance dm from P to the box of node n's light centres, shrunk by float margins: never above
// a light's true distance (the rounding of camera-relative values); scale: the size of the values;
// reach: false when the node is empty or dm is past its largest radius (no light of it reaches P:
// each adds exactly 0). The walk orders a node's children by dm^2 and pushes only those that reach.
float pg_lc_dmin(uint n, vec3 P, vec3 cam, out vec3 rl, out vec3 rh, out float scale, out bool reach)
{
    vec4 lo = tree[4u * n];
    rl = lo.xyz - cam;
    rh = tree[4u * n + 1u].xyz - cam;
    float d2 = pg_lc_box_d2(rl, rh, P);
    scale = length(P) + max(length(rl), length(rh));
    float dm = max(sqrt(d2) * (1.0 - 1e-4) - 1e-6 * scale, 0.0);
    reach = rh.x >= rl.x && dm < lo.w * (1.0 + 1e-4);
    return dm;
}

// The node's bound U (rgb).
vec3 pg_lc_upper(uint n, Surface s, vec3 P, vec3 cam, float inv_md2)
{
    vec4 cw = tree[4u * n + 2u];
    vec3 c = cw.rgb;
    vec3 rl, rh;
    float scale;
    bool reach;
    float dm = pg_lc_dmin(n, P, cam, rl, rh, scale, reach);
    float dmin2 = dm * dm;
    if (!reach) return vec3(0.0); // empty, or out of every range
    float front = -3.0e38;                                                // max over corners of N.(c - P)
    for (int k = 0; k < 8; k++) {
        vec3 corner = vec3((k & 1) != 0 ? rh.x : rl.x, (k & 2) != 0 ? rh.y : rl.y, (k & 4) != 0 ? rh.z : rl.z);
        front = max(front, dot(s.normal, corner - P));
    }
    float slack = 1e-5 * scale + 1e-6;
    if (front < -slack) return vec3(0.0);
    // N.L <= N.(x - P) / |x - P| <= (front + slack) / dm for every centre x of the box
    float cos_max = dm > 0.0 ? min(1.0, (front + slack) / dm) : 1.0;
    // falloff(d / R) <= falloff(dm / Rmax): it falls with d and rises with R (the falloff's R, cw.w:
    // the largest of the node's; squared for PG_GLTF_FALLOFF it is only smaller)
    float t = dmin2 / (cw.w * cw.w);
    float falloff = clamp(1.0 - t * t, 0.0, 1.0) * (1.0 + 1e-5) + 1e-6;
    float att = min(dm > 0.0 ? 1.0 / dmin2 : 3.0e38, inv_md2) * min(falloff, 1.0);
#if defined(PG_PBR)
    // (1 - F0)(1 - w) <= 1, F0 (1 - w) + w <= 1 and pi D V N.L <= 0.5 / a^3 (lighting.glsl)
    float a = pg_pbr_alpha(s.shininess);
    return c * (att * (s.albedo * (1.0 - s.specular) * cos_max + vec3(0.5 / (a * a * a))));
#elif defined(PG_BLINN_PHONG)
    return c * (att * cos_max) * (s.albedo + vec3(s.specular)); // (N.H)^n <= 1, N.L <= cos_max
#else
    return c * (att * cos_max) * s.albedo;
#endif
}

// R: where the light stops; Rf: its falloff's range (Light.color.w); spot: its spot record
vec3 pg_lc_light(Surface s, vec3 pos, float R, float Rf, vec3 color, vec4 spot, vec3 cam, vec3 P, vec3 V,
                 float inv_md2)
{
    float R2 = R * R;
    PgShade one = pg_shade_zero();
    pg_accumulate_light_rel(pos - cam, R2, pg_light_inv_r2(Rf * Rf), color, spot, P, s.normal, V,
                            pg_light_mat(s, V), inv_md2,
                            one);
    return pg_shade_lights(s, one);
}

// Leaf n's light, exactly.
vec3 pg_lc_leaf(uint n, Surface s, vec3 cam, vec3 P, vec3 V, float inv_md2)
{
    PG_COUNT(1);
    vec4 pr = tree[4u * n];
    vec4 lc = tree[4u * n + 2u];
#ifdef PG_SPOT_LIGHTS
    vec4 sp4 = tree[4u * n + 3u]; // a leaf keeps its light's spot record there (light_tree.comp)
#else
    vec4 sp4 = vec4(0.0, 0.0, 0.0, 1.0);
#endif
    return pg_lc_light(s, pr.xyz, pr.w, lc.w, lc.rgb, sp4, cam, P, V, inv_md2);
}

// True when x is true in any invocation of the subgroup that runs this call (a ballot: no vote
// extension needed).
bool pg_lc_any(bool x)
{
    return subgroupBallot(x) != uvec4(0u);
}

// The walk is shared by the subgroup's pixels (a tile's 8 x 4 block on a GPU with 32-wide
// subgroups): every invocation pops the same node, so the nodes' loads are one broadcast and the
// branches do not diverge. Each invocation keeps its own sums (E, A, B) and decides for itself: a
// node it approximates (or finds out of reach) it skips with its whole subtree, marked by the stack
// depth (skip_at: the subtree's nodes are popped while the stack holds at least skip_at - 1
// entries). A node is refined when any invocation refines it; the children are pushed when any
// refining invocation reaches them, nearer first for most of those invocations. Whatever the other
// invocations do, a pixel sums each of its leaves exactly once or within a node it approximated
// under its own test, so the stated bound holds per pixel (and with diverged invocations, which
// then walk apart: each call below involves only invocations at the same point of the loop).
vec3 pg_lightcut(Surface s, vec3 P, vec3 V)
{
    uint count = frame.counts.x;
    uint np = count <= 1u ? 1u : 1u << uint(findMSB(count - 1u) + 1);
    vec3 cam = frame.camera_pos.xyz;
    float md = frame.light_params.w;
    float inv_md2 = 1.0 / (md * md);
    const float eps = float(PG_LC_EPS_PPM) * 1e-6;
    vec3 E = vec3(0.0), A = vec3(0.0), B = vec3(0.0);
    uint stack[PG_LC_STACK];
    int sp = 0;
    stack[sp++] = 1u;
    int skip_at = 0; // 0: taking part; else the subtree being skipped (above)
    while (sp > 0) {
        uint n = stack[--sp];
        if (sp + 1 < skip_at) skip_at = 0; // past the skipped subtree
        bool taking_part = skip_at == 0;
        if (n >= np) { // a leaf: one light, exactly (past count: an empty padding leaf)
            if (taking_part && n - np < count) E += pg_lc_leaf(n, s, cam, P, V, inv_md2);
            continue;
        }
        bool refine = false;
        if (taking_part) {
            vec3 U = pg_lc_upper(n, s, P, cam, inv_md2);
            refine = U != vec3(0.0);
            // b >= U / 2 whatever the estimate (in float too: rounding is monotonic, U / 2 exact or
            // flushed to 0), so a node that fails B + U / 2 <= eps E fails the test below: refined
            // without evaluating its representative
            if (refine && all(lessThanEqual(B + 0.5 * U, eps * E))) {
                PG_COUNT(1);
                vec4 nc = tree[4u * n + 2u];
                // the representative has no cone: its estimate stays clamped to [0, U], and U bounds a cone too
                vec3 est = clamp(pg_lc_light(s, tree[4u * n + 3u].xyz, tree[4u * n].w, nc.w, nc.rgb,
                                             vec4(0.0, 0.0, 0.0, 1.0), cam, P, V, inv_md2),
                                 vec3(0.0), U);
                vec3 b = max(U - est, est);
                if (all(lessThanEqual(B + b, eps * E))) {
                    A += est;
                    B += b;
                    refine = false;
                }
            }
            if (!refine) skip_at = sp + 1; // approximated or out of reach: its subtree adds nothing here
        }
        if (!pg_lc_any(refine)) continue;
        uint k = uint(findMSB(np) - findMSB(n)); // n's subtree: the leaves [n << k, (n + 1) << k)
        if ((1u << k) <= uint(PG_LC_BUCKET)) {    // small: its leaves summed exactly, no walk below
            // (the padding leaves past count, up to the power of two np, hold no light: not evaluated)
            for (uint l = n << k, end = min((n + 1u) << k, np + count); l < end; l++)
                if (refine) E += pg_lc_leaf(l, s, cam, P, V, inv_md2);
            continue;
        }
        uint c0 = 2u * n, c1 = c0 + 1u;
        bool r0 = false, r1 = false, first0 = true;
        if (refine) {
            vec3 rl, rh;
            float scale;
            float d0 = pg_lc_dmin(c0, P, cam, rl, rh, scale, r0), d1 = pg_lc_dmin(c1, P, cam, rl, rh, scale, r1);
            first0 = d0 <= d1;
        }
        uint votes0 = subgroupBallotBitCount(subgroupBallot(refine && first0));
        uint votes1 = subgroupBallotBitCount(subgroupBallot(refine && !first0));
        bool push0 = pg_lc_any(refine && r0), push1 = pg_lc_any(refine && r1);
        // depth <= log2(np) + 1 entries: never past PG_LC_STACK (np <= 2^32)
        if (votes0 >= votes1) { // c0 popped first
            if (push1) stack[sp++] = c1;
            if (push0) stack[sp++] = c0;
        } else {
            if (push0) stack[sp++] = c0;
            if (push1) stack[sp++] = c1;
        }
    }
    return E + A;
}
#endif

// Shades one visible point. P: camera-relative position (world - camera); frag_xy: pixel centre
// (gl_FragCoord.xy); view_depth: positive distance along the view axis.
vec3 pg_shade_point(Surface s, vec3 P, float view_depth, vec2 frag_xy)
{
    vec3 V = PG_VIEW_DIR(P);
    vec3 cam = frame.camera_pos.xyz;
    PgShade acc = pg_shade_zero();
#if defined(PG_CLUSTERED)
    uvec3 grid = uvec3(GRID_X, GRID_Y, GRID_Z);
    uvec3 cc = pg_cluster_coord(frag_xy, vec2(frame.counts.zw), view_depth, frame.clip.x, frame.clip.y, grid);
    uint ci = pg_cluster_index(cc, grid);
#ifdef PG_HAS_LIGHTS
    uvec4 rec = cluster_records[ci];
#else
    uvec4 rec = uvec4(0u);
#endif
    uint raw = rec.z;
#endif
#if PG_DEBUG_VIEW == 6
    return s.albedo;
#elif PG_DEBUG_VIEW == 7
    return s.normal * 0.5 + 0.5;
#elif PG_DEBUG_VIEW == 8
    return vec3(log2(max(view_depth / frame.clip.x, 1.0)) / max(log2(frame.clip.y / frame.clip.x), 1e-6));
#elif defined(PG_CLUSTERED) && PG_DEBUG_VIEW == 1
    return pg_heat(log2(1.0 + float(raw)) / 16.0);   // log scale: 1 .. 65535 lights
#elif defined(PG_CLUSTERED) && PG_DEBUG_VIEW == 2
    return pg_index_color(cc.x);
#elif defined(PG_CLUSTERED) && PG_DEBUG_VIEW == 3
    return pg_index_color(cc.y);
#elif defined(PG_CLUSTERED) && PG_DEBUG_VIEW == 4
    return pg_index_color(cc.z);
#elif defined(PG_CLUSTERED) && PG_DEBUG_VIEW == 5
    return rec.y < raw ? vec3(1.0, 0.0, 0.0) : s.albedo * 0.25;
#else
#if defined(PG_RIS) && defined(PG_CLUSTERED) && defined(PG_HAS_LIGHTS)
    return pg_shade_final(s, acc, V) + pg_ris_estimate(s, rec, P, V, frag_xy);
#endif
#ifdef PG_HAS_LIGHTS
    float min_dist = frame.light_params.w;
    PgLightMat lm = pg_light_mat(s, V);
#ifdef PG_CLUSTERED
    PG_COUNT(rec.y);
    for (uint k = 0u; k < rec.y; k++) {
        uint li = PG_LIST_READ(rec.x + k);
        pg_accumulate_light(lights[li], PG_SPOT_OF(li), cam, P, s.normal, V, lm, min_dist, acc);
    }
#elif defined(PG_LIGHTCUT)
    return pg_shade_final(s, acc, V) + pg_lightcut(s, P, V);
#else
    uint count = frame.counts.x;
    PG_COUNT(count);
    for (uint i = 0u; i < count; i++)
        pg_accumulate_light(lights[i], PG_SPOT_OF(i), cam, P, s.normal, V, lm, min_dist, acc);
#endif
#endif
    return pg_shade_final(s, acc, V);
#endif
}

#if defined(PG_TILE_LIGHTS) && defined(PG_CLUSTERED) && defined(PG_HAS_LIGHTS) && PG_DEBUG_VIEW == 0
// Tile-refined clustered shading for a compute workgroup of PG_TILE x PG_TILE invocations (one per
// pixel of a tile; every invocation of the workgroup must call it, in uniform control flow). For
// each distinct cluster among the tile's lit pixels (smallest index first), the workgroup streams
// the cluster's list through shared memory PG_TILE_N lights at a time, keeps only the lights whose
// sphere reaches the bounding box of the tile's pixels in that cluster (their camera-relative
// positions: a light that reaches a pixel reaches that box), and the pixels of the cluster sum
// the kept lights in list order. Lights dropped by the box test would have added exactly nothing
// (pg_accumulate_light_rel_select adds exactly 0 for d >= R), so the sum is bit-identical to
// the per-pixel loop of pg_shade_point, with far fewer evaluations and each light read once per
// tile instead of once per pixel. Three barriers a chunk (one shared buffer: measured faster on an
// H200 than two alternating buffers with two barriers, 3.5 vs 4.4 ms at 100,000 lights).
// PG_TILE_BACKFACE (option tile_backface): a light also leaves the chunk when it lies behind every
// pixel of the cluster's part of the tile: dot(N_i, light - P_i) < 0 for all of them, bounded by
// dot(a, r) + E |r| + H < -tol with a the normal of one of the pixels, E = max |N_i - a|,
// r = light - box centre Pc and H = max dot(N_i, Pc - P_i). Such a light has max(N.L, 0) = 0 (and no
// Blinn-Phong term) at every one of those pixels: it adds exactly 0, so the sum stays bit-identical;
// tol covers the rounding of both sides.
// PG_SPOT_LIGHTS: a spot light also leaves the chunk when its cone misses the bounding sphere of the
// cluster's part of the tile (pg_spot_reaches_sphere): it would add exactly 0 there.
// PG_TILE_SUBGROUPS: the pipeline requires full subgroups (gpu->exact_subgroups), so subgroup
// ballots give the order within a subgroup; otherwise a shared-memory scan.
#ifndef PG_TILE
#define PG_TILE 8
#endif
#define PG_TILE_N (PG_TILE * PG_TILE)
shared uint s_tl_cluster;
shared uint s_tl_box[6];                     // ordered-uint min xyz, max xyz
shared vec4 s_tl_light[2 * PG_TILE_N];       // pos_radius, color of the kept lights
#ifdef PG_SPOT_LIGHTS
shared vec4 s_tl_spot[PG_TILE_N];            // their spot records
#endif
shared uint s_tl_count[PG_TILE_N];
#ifdef PG_TILE_BACKFACE
shared uint s_tb_first;                      // the lowest invocation of the cluster: its normal is the axis
shared uint s_tb_e, s_tb_h;                  // E (float bits, >= 0) and H (ordered uint)
shared float s_tb_axis[3];
#endif

#ifdef PG_SPOT_LIGHTS
// false when a spot light (record sp: axis x scale, offset = -cos(outer) x scale; lighting.glsl) at
// `pos` gives every point of the sphere (c, r) a cone factor of exactly 0: the angle between its axis
// and the sphere's centre, less the angle the sphere spans from the light, exceeds the outer cone by
// a margin (2e-3 rad, far above the float rounding of these angles). Such a light adds exactly 0 to
// every pixel of the tile, so leaving it out keeps the sum bit-identical. A point light's record
// (0, 0, 0, 1) has no cone: always true.
bool pg_spot_reaches_sphere(vec4 sp, vec3 pos, vec3 c, float r)
{
    float scale = length(sp.xyz);
    if (!(scale > 0.0)) return true;
    vec3 d = c - pos;
    float dl = length(d);
    if (!(dl > r * 1.001 + 1e-6)) return true;                // the light is in (or at) the sphere
    float cos_outer = clamp(-sp.w / scale, -1.0, 1.0);
    float theta = acos(clamp(dot(sp.xyz, d) / (scale * dl), -1.0, 1.0));
    float spread = asin(min(r / dl, 1.0));
    return theta - spread <= acos(cos_outer) + 2e-3;
}
#endif

uint pg_tl_order(float f)                    // float -> uint with the same order
{
    uint b = floatBitsToUint(f);
    return (b & 0x80000000u) != 0u ? ~b : b | 0x80000000u;
}

float pg_tl_unorder(uint u)
{
    return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u);
}

vec3 pg_shade_tile(bool lit, Surface s, vec3 P, float view_depth, vec2 frag_xy)
{
    uint lid = gl_LocalInvocationIndex;
    vec3 cam = frame.camera_pos.xyz;
    float min_dist = frame.light_params.w;
    float inv_md2 = 1.0 / (min_dist * min_dist);
    PgShade acc = pg_shade_zero();
    uvec3 grid = uvec3(GRID_X, GRID_Y, GRID_Z);
    uint ci = 0xffffffffu;
    if (lit) ci = pg_cluster_index(pg_cluster_coord(frag_xy, vec2(frame.counts.zw), view_depth, frame.clip.x,
                                                    frame.clip.y, grid), grid);
    vec3 V = lit ? PG_VIEW_DIR(P) : vec3(0.0, 0.0, 1.0);
    PgLightMat lm = pg_light_mat(s, V);
    bool pending = lit;
#ifdef PG_TILE_SUBGROUPS
    uint slot = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID; // a permutation of the tile
#else
    uint slot = lid;
#endif
    for (;;) {
        if (lid == 0u) {
            s_tl_cluster = 0xffffffffu;
            s_tl_box[0] = s_tl_box[1] = s_tl_box[2] = 0xffffffffu;
            s_tl_box[3] = s_tl_box[4] = s_tl_box[5] = 0u;
#ifdef PG_TILE_BACKFACE
            s_tb_first = 0xffffffffu;
            s_tb_e = 0u;
            s_tb_h = 0u;
#endif
        }
        barrier();
        if (pending) atomicMin(s_tl_cluster, ci);
        barrier();
        uint c = s_tl_cluster;
        if (c == 0xffffffffu) break;                  // uniform: every invocation read the same
        bool mine = pending && ci == c;
        if (mine) {
            for (int k = 0; k < 3; k++) {
                atomicMin(s_tl_box[k], pg_tl_order(P[k]));
                atomicMax(s_tl_box[3 + k], pg_tl_order(P[k]));
            }
#ifdef PG_TILE_BACKFACE
            atomicMin(s_tb_first, lid);
#endif
        }
        barrier();
        vec3 bmin = vec3(pg_tl_unorder(s_tl_box[0]), pg_tl_unorder(s_tl_box[1]), pg_tl_unorder(s_tl_box[2]));
        vec3 bmax = vec3(pg_tl_unorder(s_tl_box[3]), pg_tl_unorder(s_tl_box[4]), pg_tl_unorder(s_tl_box[5]));
#ifdef PG_TILE_BACKFACE
        if (lid == s_tb_first) {
            s_tb_axis[0] = s.normal.x;
            s_tb_axis[1] = s.normal.y;
            s_tb_axis[2] = s.normal.z;
        }
        barrier();
        vec3 tb_a = vec3(s_tb_axis[0], s_tb_axis[1], s_tb_axis[2]);
        vec3 tb_c = 0.5 * (bmin + bmax);
        if (mine) {
            atomicMax(s_tb_e, floatBitsToUint(length(s.normal - tb_a)));
            atomicMax(s_tb_h, pg_tl_order(dot(s.normal, tb_c - P)));
        }
        barrier();
        float tb_e = uintBitsToFloat(s_tb_e) * (1.0 + 1e-5);
        float tb_h = pg_tl_unorder(s_tb_h);
        // rounding: the shader's dot(N, light - P) and this bound, both of magnitude <= |light| + |P|
        float tb_tol = 1e-5 * (4.0 + length(tb_c) + length(bmax - bmin)) + abs(tb_h) * 1e-5;
#endif
        uvec4 rec = cluster_records[c];
        for (uint base = 0u; base < rec.y; base += uint(PG_TILE_N)) {
            uint k = base + slot;
            bool keep = false;
            Light L;
            L.pos_radius = vec4(0.0);
            L.color = vec4(0.0);
            if (k < rec.y) {
                L = lights[PG_LIST_READ(rec.x + k)]; // whole record: one 32-byte sector anyway
                L.pos_radius.xyz -= cam;
                keep = pg_sphere_intersects_aabb(L.pos_radius.xyz, L.pos_radius.w, bmin, bmax);
#ifdef PG_TILE_BACKFACE
                vec3 r = L.pos_radius.xyz - tb_c;
                float lr = length(r);
                keep = keep && !(dot(tb_a, r) + tb_e * lr * (1.0 + 1e-5) + tb_h
                                 < -(tb_tol + 1e-5 * (lr + length(L.pos_radius.xyz))));
#endif
#ifdef PG_SPOT_LIGHTS
                if (keep) keep = pg_spot_reaches_sphere(PG_SPOT_OF(PG_LIST_READ(rec.x + k)), L.pos_radius.xyz,
                                                        0.5 * (bmin + bmax), 0.5 * length(bmax - bmin));
#endif
            }
            uint pos, total;
#ifdef PG_TILE_SUBGROUPS
            uvec4 bal = subgroupBallot(keep);
            if (subgroupElect()) s_tl_count[gl_SubgroupID] = subgroupBallotBitCount(bal);
            barrier();
            pos = subgroupBallotExclusiveBitCount(bal);
            total = 0u;
            for (uint g = 0u; g < gl_NumSubgroups; g++) {
                uint n = s_tl_count[g];
                pos += g < gl_SubgroupID ? n : 0u;
                total += n;
            }
#else
            s_tl_count[lid] = keep ? 1u : 0u;
            barrier();
            for (uint d = 1u; d < uint(PG_TILE_N); d <<= 1u) {
                uint add = lid >= d ? s_tl_count[lid - d] : 0u;
                barrier();
                s_tl_count[lid] += add;
                barrier();
            }
            pos = s_tl_count[lid] - (keep ? 1u : 0u);
            total = s_tl_count[PG_TILE_N - 1];
#endif
            if (keep) {   // what pg_accumulate_light_rel reads, computed once per tile
                float R2 = L.pos_radius.w * L.pos_radius.w;
                s_tl_light[2u * pos] = vec4(L.pos_radius.xyz, pg_light_inv_r2(L.color.w * L.color.w)); // falloff's R
                s_tl_light[2u * pos + 1u] = vec4(L.color.rgb, R2);
#ifdef PG_SPOT_LIGHTS
                s_tl_spot[pos] = PG_SPOT_OF(PG_LIST_READ(rec.x + k));
#endif
            }
            barrier();
            if (mine) {
                PG_COUNT(total);
                uint j = 0u;
#if defined(PG_LAMBERT_PAIRS)
                for (; j + 1u < total; j += 2u)   // two lights at once, in list order (lighting.glsl)
                    pg_accumulate_lambert_pair(s_tl_light[2u * j], s_tl_light[2u * j + 1u], s_tl_light[2u * j + 2u],
                                               s_tl_light[2u * j + 3u], P, s.normal, inv_md2, acc);
#endif
                for (; j < total; j++) {            // the rest one at a time
                    vec4 a = s_tl_light[2u * j];
                    vec4 b = s_tl_light[2u * j + 1u];
#ifdef PG_SPOT_LIGHTS
                    vec4 sp = s_tl_spot[j];
#else
                    vec4 sp = vec4(0.0, 0.0, 0.0, 1.0);
#endif
                    pg_accumulate_light_rel_select(a.xyz, b.w, a.w, b.rgb, sp, P, s.normal, V, lm, inv_md2,
                                                   acc);
                }
            }
            barrier();   // before the next chunk overwrites the shared lights and counts
        }
        pending = pending && !mine;
        barrier();       // before the next round resets the cluster and box (a cluster may have no chunk)
    }
    return pg_shade_final(s, acc, V);
}
#endif
