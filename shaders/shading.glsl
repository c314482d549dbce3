// shading.glsl - the lighting loop every shading pass shares (forward naive, forward+, deferred).
// Needs common.glsl, lighting.glsl, and for PG_CLUSTERED cluster.glsl. Set 2 holds the lights:
//   binding 0 Lights, and with PG_CLUSTERED binding 1 cluster light counts (raw, may exceed
//   MAX_LIGHTS), binding 2 cluster light lists (MAX_LIGHTS indices per cluster, ascending).
// Without PG_HAS_LIGHTS (0 lights in the scene) no light buffer is declared or read.
// Debug views (PG_DEBUG_VIEW): 0 none, 1 cluster_heat, 2 cluster_x, 3 cluster_y, 4 cluster_z,
// 5 overflow, 6 albedo, 7 normal, 8 depth.

#ifdef PG_HAS_LIGHTS
layout(set = 2, binding = 0, std430) readonly buffer Lights { Light lights[]; };
#ifdef PG_CLUSTERED
layout(set = 2, binding = 1, std430) readonly buffer ClusterCounts { uint cluster_counts[]; };
layout(set = 2, binding = 2, std430) readonly buffer ClusterLights { uint cluster_lights[]; };
#endif
#endif

#ifndef PG_DEBUG_VIEW
#define PG_DEBUG_VIEW 0
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

// Shades one visible point. P: camera-relative position (world - camera); frag_xy: pixel centre
// (gl_FragCoord.xy); view_depth: positive distance along the view axis.
vec3 pg_shade_point(Surface s, vec3 P, float view_depth, vec2 frag_xy)
{
    vec3 V = normalize(-P);
    vec3 cam = frame.camera_pos.xyz;
    PgShade acc;
    acc.diffuse = vec3(0.0);
    acc.specular = vec3(0.0);
#if defined(PG_CLUSTERED)
    uvec3 grid = uvec3(GRID_X, GRID_Y, GRID_Z);
    uvec3 cc = pg_cluster_coord(frag_xy, vec2(frame.counts.zw), view_depth, frame.clip.x, frame.clip.y, grid);
    uint ci = pg_cluster_index(cc, grid);
#ifdef PG_HAS_LIGHTS
    uint raw = cluster_counts[ci];
#else
    uint raw = 0u;
#endif
#endif
#if PG_DEBUG_VIEW == 6
    return s.albedo;
#elif PG_DEBUG_VIEW == 7
    return s.normal * 0.5 + 0.5;
#elif PG_DEBUG_VIEW == 8
    return vec3(log2(max(view_depth / frame.clip.x, 1.0)) / max(log2(frame.clip.y / frame.clip.x), 1e-6));
#elif defined(PG_CLUSTERED) && PG_DEBUG_VIEW == 1
    return pg_heat(float(raw) / float(MAX_LIGHTS));
#elif defined(PG_CLUSTERED) && PG_DEBUG_VIEW == 2
    return pg_index_color(cc.x);
#elif defined(PG_CLUSTERED) && PG_DEBUG_VIEW == 3
    return pg_index_color(cc.y);
#elif defined(PG_CLUSTERED) && PG_DEBUG_VIEW == 4
    return pg_index_color(cc.z);
#elif defined(PG_CLUSTERED) && PG_DEBUG_VIEW == 5
    return raw > uint(MAX_LIGHTS) ? vec3(1.0, 0.0, 0.0) : s.albedo * 0.25;
#else
#ifdef PG_HAS_LIGHTS
    float min_dist = frame.light_params.w;
#ifdef PG_CLUSTERED
    uint n = min(raw, uint(MAX_LIGHTS));
    uint base = ci * uint(MAX_LIGHTS);
    for (uint k = 0u; k < n; k++)
        pg_accumulate_light(lights[cluster_lights[base + k]], cam, P, s.normal, V, s.shininess, min_dist, acc);
#else
    uint count = frame.counts.x;
    for (uint i = 0u; i < count; i++)
        pg_accumulate_light(lights[i], cam, P, s.normal, V, s.shininess, min_dist, acc);
#endif
#endif
    return pg_shade_combine(s, acc, vec3(PG_AMBIENT));
#endif
}
