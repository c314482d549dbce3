#version 460
// reference_lighting.comp - the exact reference as a compute pass: one thread per pixel shades the
// surface the G-buffer holds (float packing, camera-relative position: gbuffer position_space
// "camera") with every light, in ascending light index order, with the same operations as
// forward naive (pg_accumulate_light, pg_shade_combine): bit-identical to naive when the HDR
// targets have the same format.
//
// Lights are streamed through shared memory: the workgroup (LIGHT_TILE threads) loads LIGHT_TILE
// lights cooperatively, one per thread, then every thread walks the tile in order; one barrier
// pair per tile. A dispatch covers the lights [pc.first, pc.end). The pass splits large light
// counts over several dispatches (renderer/passes/reference_lighting.c); the running sums then wait in
// rgba32f images (acc_diffuse, acc_specular for Blinn-Phong), fp32 like the registers they
// come from, so splitting does not change a bit. pc.mode bits: 1 = start from the sums stored
// there (else from 0), 2 = store the sums and stop (else combine and write the HDR pixel).
// Background pixels (position.w == 0) are black with alpha 1, as forward clears them.
// PG_REFERENCE_EMISSIVE: the G-buffer's emissive target (rgba32f, the last binding) is s.emissive,
// added once by pg_shade_combine as forward adds it.
// PG_REFERENCE_CULL (option cull_lights, default on): the workgroup first takes the bounding box of
// its covered pixels' camera-relative positions; each light of a tile is kept only if its sphere
// reaches that box (pg_sphere_intersects_aabb, conservative), and the kept lights are packed in
// ascending index order (subgroup ballots, subgroups in order of gl_SubgroupID) before the pixels
// walk them. A light that is not kept reaches no pixel of the workgroup and would have added
// exactly +0 (pg_accumulate_light returns before adding for d >= R), so the sums and the image are
// bit-identical to walking every light; only the evaluations are fewer.
#ifdef PG_REFERENCE_CULL
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#endif
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
#include "lighting.glsl"
#include "octahedral.glsl"
#include "gbuffer_pack.glsl"

#ifndef LIGHT_TILE_X
#define LIGHT_TILE_X 16
#endif
#ifndef LIGHT_TILE_Y
#define LIGHT_TILE_Y 16
#endif
#define LIGHT_TILE (LIGHT_TILE_X * LIGHT_TILE_Y)
layout(local_size_x = LIGHT_TILE_X, local_size_y = LIGHT_TILE_Y) in;

layout(set = 1, binding = 0) uniform sampler2D g_position; // camera-relative xyz, w 1 (0: nothing drawn)
layout(set = 1, binding = 1) uniform sampler2D g_normal;   // xyz normal, w shininess
layout(set = 1, binding = 2) uniform sampler2D g_albedo;   // rgb albedo, a specular
layout(set = 1, binding = 3, PG_HDR_FORMAT) uniform writeonly image2D hdr_out;
#ifdef PG_REFERENCE_ACCUM
layout(set = 1, binding = 4, rgba32f) uniform image2D acc_diffuse; // running diffuse sum (rgb)
#ifdef PG_BLINN_PHONG
layout(set = 1, binding = 5, rgba32f) uniform image2D acc_specular; // running specular sum (rgb)
#endif
#endif
#ifdef PG_REFERENCE_EMISSIVE
#if defined(PG_REFERENCE_ACCUM) && defined(PG_BLINN_PHONG)
#define EMISSIVE_BINDING 6
#elif defined(PG_REFERENCE_ACCUM)
#define EMISSIVE_BINDING 5
#else
#define EMISSIVE_BINDING 4
#endif
layout(set = 1, binding = EMISSIVE_BINDING) uniform sampler2D g_emissive; // rgb emissive, scene-linear
#endif

layout(push_constant) uniform Push {
    uint first; // first light of this dispatch
    uint end;   // one past its last light
    uint mode;  // 1: load the running sums, 2: store them instead of writing hdr_out
    float ambient; // the pass option "ambient" (a run-time value)
} pc;
#define PG_AMBIENT pc.ambient

#include "shading.glsl" // the Lights buffer (set 2) and the debug views

// PG_REFERENCE_ENV: the environment light by Monte Carlo over the scene's level-0 texels (set 1,
// binding PG_REFERENCE_ENV_BINDING; PG_ENV_SRC_W x PG_ENV_SRC_H; with PG_REFERENCE_ENV_IS the next
// binding holds its importance-sampling tables, scene/environment.h cdf). Each of PG_REF_ENV_SAMPLES
// rounds draws one direction from each strategy: cosine around N, a GGX half vector (pbr), the
// environment's texels by luminance x sin(theta) (when it is not black); a direction L drawn by any
// of them adds f(L) L_env(L) N.L / (p_cos(L) + p_ggx(L) + p_env(L)) (multiple importance sampling
// with the balance heuristic, Veach 1997): unbiased wherever one strategy can draw L. The rounds are
// Hammersley points rotated per pixel (Cranley-Patterson, a hash of the pixel and frame.noise.y).
// Lambert and Blinn-Phong: f = albedo / pi (their environment term has no specular part).
#ifdef PG_REFERENCE_ENV
layout(set = 1, binding = PG_REFERENCE_ENV_BINDING, std430) readonly buffer EnvSource { vec4 env_src[]; };
#define PG_ENV_FETCH(i) env_src[i]
#include "environment.glsl"
#ifdef PG_REFERENCE_ENV_IS
layout(set = 1, binding = PG_REFERENCE_ENV_BINDING + 1, std430) readonly buffer EnvCdf { float env_cdf[]; };
#endif

const uint REF_ENV_W = uint(PG_ENV_SRC_W), REF_ENV_H = uint(PG_ENV_SRC_H);

vec3 ref_env_radiance(vec3 d)
{
    vec2 uv = pg_env_dir_to_uv(pg_env_unrotate(d, frame.environment.y));
    return pg_env_bilinear(0u, REF_ENV_W, REF_ENV_H, uv);
}

#ifdef PG_REFERENCE_ENV_IS
// the largest k < n with env_cdf[base + k] <= x (env_cdf[base] = 0)
uint ref_cdf_search(uint base, uint n, float x)
{
    uint lo = 0u, hi = n;
    while (hi - lo > 1u) {
        uint mid = (lo + hi) / 2u;
        if (env_cdf[base + mid] <= x) lo = mid;
        else hi = mid;
    }
    return lo;
}

// A world direction drawn by the tables from xi (uniform within the drawn texel).
vec3 ref_env_draw(vec2 xi)
{
    uint j = ref_cdf_search(0u, REF_ENV_H, xi.y);
    float fy = (xi.y - env_cdf[j]) / max(env_cdf[j + 1u] - env_cdf[j], 1e-30);
    uint rb = REF_ENV_H + 1u + j * (REF_ENV_W + 1u);
    uint i = ref_cdf_search(rb, REF_ENV_W, xi.x);
    float fx = (xi.x - env_cdf[rb + i]) / max(env_cdf[rb + i + 1u] - env_cdf[rb + i], 1e-30);
    vec2 uv = vec2((float(i) + clamp(fx, 0.0, 1.0)) / float(REF_ENV_W), (float(j) + clamp(fy, 0.0, 1.0)) / float(REF_ENV_H));
    return pg_env_unrotate(pg_env_uv_to_dir(uv), -frame.environment.y);
}

// The tables' solid-angle density of world direction d.
float ref_env_pdf(vec3 d)
{
    vec3 s = pg_env_unrotate(d, frame.environment.y);
    vec2 uv = pg_env_dir_to_uv(s);
    uint i = min(uint(uv.x * float(REF_ENV_W)), REF_ENV_W - 1u), j = min(uint(uv.y * float(REF_ENV_H)), REF_ENV_H - 1u);
    uint rb = REF_ENV_H + 1u + j * (REF_ENV_W + 1u);
    float p = (env_cdf[j + 1u] - env_cdf[j]) * (env_cdf[rb + i + 1u] - env_cdf[rb + i]);
    float sin_t = sqrt(max(1.0 - s.y * s.y, 0.0));
    return sin_t > 0.0 ? p * float(REF_ENV_W) * float(REF_ENV_H) / (2.0 * PG_ENV_PI * PG_ENV_PI * sin_t) : 0.0;
}
#else
float ref_env_pdf(vec3 d) { return 0.0; }
#endif

struct RefEnvSurface {
    vec3 N, V;
    float nv, a;
    vec3 f0, cdiff;
};

// f(L) N.L (pbr: the glTF BRDF; otherwise 1 / pi, the albedo applied by the caller) and the
// strategies' summed density of L.
vec3 ref_env_term(RefEnvSurface r, vec3 L, out float pdf)
{
    float nl = dot(r.N, L);
    pdf = 0.0;
    if (nl <= 0.0) return vec3(0.0);
    pdf = nl / PG_ENV_PI + ref_env_pdf(L);
#ifdef PG_PBR
    vec3 H = normalize(r.V + L);
    float vh = max(dot(r.V, H), 0.0), nh = dot(r.N, H);
    float a2 = r.a * r.a, q = nh * nh * (a2 - 1.0) + 1.0;
    float D = a2 / (PG_ENV_PI * q * q);
    if (nh > 0.0 && vh > 0.0) pdf += D * nh / (4.0 * vh);
    vec3 F = r.f0 + (1.0 - r.f0) * pow(clamp(1.0 - vh, 0.0, 1.0), 5.0); // vh rounds past 1: pow(< 0) is NaN
    return ((1.0 - F) * r.cdiff / PG_ENV_PI + F * (D * pg_env_smith_v(nl, r.nv, r.a))) * nl;
#else
    return vec3(nl / PG_ENV_PI);
#endif
}

vec3 ref_env_add(RefEnvSurface r, vec3 L)
{
    float pdf;
    vec3 f = ref_env_term(r, L, pdf);
    return pdf > 0.0 ? f * ref_env_radiance(L) / pdf : vec3(0.0);
}

vec3 ref_env_light(Surface s, vec3 V, uvec2 px)
{
    RefEnvSurface r;
    V = pg_env_view(s.normal, V);
    r.N = s.normal;
    r.V = V;
    r.nv = clamp(dot(s.normal, V), 0.0, 1.0);
    r.a = pg_env_alpha(s.shininess);
    r.f0 = mix(vec3(0.04), s.albedo, s.specular);
    r.cdiff = s.albedo * (1.0 - s.specular);
    uint h = pg_pcg(px.x * 73856093u ^ px.y * 19349663u ^ frame.noise.y * 83492791u);
    vec2 shift = vec2(float(h >> 8u), float(pg_pcg(h) >> 8u)) * (1.0 / 16777216.0);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < uint(PG_REF_ENV_SAMPLES); i++) {
        vec2 xi = fract(pg_env_hammersley(i, uint(PG_REF_ENV_SAMPLES)) + shift);
        sum += ref_env_add(r, pg_env_cosine_dir(r.N, xi));
#ifdef PG_PBR
        vec3 H = pg_env_ggx_half(r.N, r.a, xi);
        sum += ref_env_add(r, 2.0 * dot(V, H) * H - V);
#endif
#ifdef PG_REFERENCE_ENV_IS
        sum += ref_env_add(r, ref_env_draw(fract(xi.yx + shift.yx)));
#endif
    }
    sum /= float(PG_REF_ENV_SAMPLES);
#ifdef PG_PBR
    return frame.environment.x * max(s.occlusion, 0.0) * sum;
#else
    return frame.environment.x * s.albedo * sum;
#endif
}
#endif
#ifdef PG_REFERENCE_CULL
#include "cluster.glsl"     // pg_sphere_intersects_aabb
#endif


#ifdef PG_HAS_LIGHTS
shared vec4 s_pos_radius[LIGHT_TILE];
shared vec4 s_color[LIGHT_TILE];
#ifdef PG_SPOT_LIGHTS
shared vec4 s_spot[LIGHT_TILE];    // the staged lights' spot records (lighting.glsl)
#endif
#ifdef PG_REFERENCE_CULL
shared uint s_box[6];              // ordered-uint min xyz, max xyz of the covered pixels
shared uint s_sg_count[LIGHT_TILE]; // kept lights per subgroup of the current tile

uint pg_ref_order(float f) // float -> uint with the same order
{
    uint b = floatBitsToUint(f);
    return (b & 0x80000000u) != 0u ? ~b : b | 0x80000000u;
}

float pg_ref_unorder(uint u)
{
    return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u);
}
#endif
#endif

void main()
{
    ivec2 size = imageSize(hdr_out);
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    // Threads outside the image still load lights and reach every barrier.
    bool inside = px.x < size.x && px.y < size.y;
    vec4 p4 = inside ? texelFetch(g_position, px, 0) : vec4(0.0);
    bool covered = inside && p4.w > 0.0;
    vec3 P = p4.xyz; // camera-relative
    Surface s;
    vec4 n = covered ? texelFetch(g_normal, px, 0) : vec4(0.0, 0.0, 1.0, 1.0);
    vec4 a = covered ? texelFetch(g_albedo, px, 0) : vec4(0.0);
    s.normal = n.xyz;
    s.shininess = n.w;
    s.albedo = a.rgb;
    s.specular = a.a;
    s.alpha = 1.0;
    s.emissive = vec3(0.0);
    s.occlusion = pg_gb_occlusion_from_float(p4.w); // the float G-buffer's w (gbuffer.frag; PG_PBR only)
#ifdef PG_REFERENCE_EMISSIVE
    if (covered) s.emissive = texelFetch(g_emissive, px, 0).rgb;
#endif
#if PG_DEBUG_VIEW != 0
    if (!inside) return;
    float view_depth = -PG_REL_TO_VIEW(P).z;
    vec3 c = covered ? pg_shade_point(s, P, view_depth, vec2(px) + 0.5) : vec3(0.0);
    imageStore(hdr_out, px, vec4(pg_hdr_sanitize(c), 1.0));
#else
    PgShade acc = pg_shade_zero();
#ifdef PG_HAS_LIGHTS
#ifdef PG_REFERENCE_ACCUM
    if ((pc.mode & 1u) != 0u && covered) {
        acc.diffuse = imageLoad(acc_diffuse, px).rgb;
#ifdef PG_BLINN_PHONG
        acc.specular = imageLoad(acc_specular, px).rgb;
#endif
    }
#endif
    vec3 V = PG_VIEW_DIR(P);
    PgLightMat lm = pg_light_mat(s, V);
    vec3 cam = frame.camera_pos.xyz;
    float min_dist = frame.light_params.w;
    uint lid = gl_LocalInvocationIndex;
#ifdef PG_REFERENCE_CULL
    if (lid == 0u) {
        for (int i = 0; i < 3; i++) {
            s_box[i] = pg_ref_order(3.0e38);
            s_box[3 + i] = pg_ref_order(-3.0e38);
        }
    }
    barrier();
    if (covered)
        for (int i = 0; i < 3; i++) {
            atomicMin(s_box[i], pg_ref_order(P[i]));
            atomicMax(s_box[3 + i], pg_ref_order(P[i]));
        }
    barrier();
    vec3 bmin = vec3(pg_ref_unorder(s_box[0]), pg_ref_unorder(s_box[1]), pg_ref_unorder(s_box[2]));
    vec3 bmax = vec3(pg_ref_unorder(s_box[3]), pg_ref_unorder(s_box[4]), pg_ref_unorder(s_box[5]));
    // the light slot of this invocation: subgroups in order, so kept lights stay in index order
    uint slot = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
#endif
    for (uint base = pc.first; base < pc.end; base += uint(LIGHT_TILE)) {
        uint count = min(uint(LIGHT_TILE), pc.end - base);
#ifdef PG_REFERENCE_CULL
        Light lt;
        bool keep = false;
        if (slot < count) {
            lt = lights[base + slot];
            keep = bmin.x <= bmax.x && pg_sphere_intersects_aabb(lt.pos_radius.xyz - cam, lt.pos_radius.w, bmin, bmax);
        }
        uvec4 bal = subgroupBallot(keep);
        if (subgroupElect()) s_sg_count[gl_SubgroupID] = subgroupBallotBitCount(bal);
        barrier();
        uint pos = subgroupBallotExclusiveBitCount(bal), total = 0u;
        for (uint g = 0u; g < gl_NumSubgroups; g++) {
            uint c = s_sg_count[g];
            pos += g < gl_SubgroupID ? c : 0u;
            total += c;
        }
        if (keep) {
            s_pos_radius[pos] = lt.pos_radius;
            s_color[pos] = lt.color;
#ifdef PG_SPOT_LIGHTS
            s_spot[pos] = PG_SPOT_OF(base + slot);
#endif
        }
        count = total;
#else
        if (lid < count) {
            s_pos_radius[lid] = lights[base + lid].pos_radius;
            s_color[lid] = lights[base + lid].color;
#ifdef PG_SPOT_LIGHTS
            s_spot[lid] = PG_SPOT_OF(base + lid);
#endif
        }
#endif
        memoryBarrierShared();
        barrier();
        if (covered) {
            for (uint k = 0u; k < count; k++) {
                Light l;
                l.pos_radius = s_pos_radius[k];
                l.color = s_color[k];
#ifdef PG_SPOT_LIGHTS
                vec4 sp = s_spot[k];
#else
                vec4 sp = vec4(0.0, 0.0, 0.0, 1.0);
#endif
                pg_accumulate_light(l, sp, cam, P, s.normal, V, lm, min_dist, acc);
            }
        }
        memoryBarrierShared();
        barrier(); // the tile is read by every thread before the next one overwrites it
    }
#ifdef PG_REFERENCE_ACCUM
    if ((pc.mode & 2u) != 0u) {
        // every pixel is written (0 for background), so no dispatch reads undefined contents
        if (inside) {
            imageStore(acc_diffuse, px, vec4(acc.diffuse, 0.0));
#ifdef PG_BLINN_PHONG
            imageStore(acc_specular, px, vec4(acc.specular, 0.0));
#endif
        }
        return;
    }
#endif
#endif
    if (!inside) return;
    vec3 c = covered ? pg_shade_combine(s, acc, vec3(PG_AMBIENT + frame.clip.z)) : vec3(0.0);
#ifdef PG_REFERENCE_ENV
    if (covered) c += ref_env_light(s, PG_VIEW_DIR(P), uvec2(px));
#endif
    imageStore(hdr_out, px, vec4(pg_hdr_sanitize(c), 1.0));
#endif
}
