#version 460
// light_animate.comp - writes every light from (seed, index, time) alone, so every pipeline
// rendering the same --time sees the same lights. Positions follow a smooth (C1) triangle-wave
// path per axis inside the light box: u = fract(phase + freq*speed*t), p = smoothstep(tri(u)).
// With a keep-out box (frame.light_keep_min.w = 1, an object's lights: scene/scenario.h), the
// light box is then mapped onto the shell between the two boxes (pg_keep_out), continuously, so
// moving lights still move smoothly and none comes nearer the object than the keep-out box.
#include "common.glsl"
FRAME_UNIFORMS_BLOCK
layout(local_size_x = 64) in;
layout(set = 1, binding = 0, std430) writeonly buffer Lights { Light lights[]; };
#ifdef PG_FILE_LIGHTS
// The scene file's KHR_lights_punctual lights (renderer/scene_gpu.h pg_gpu_file_light): the first
// frame.light_src.x lights are these, the generated ones follow.
struct FileLight {
    vec4 position_range; // world position, the file's range (0: none)
    vec4 color_type;     // colour x intensity / pi (linear), type (0 point, 1 spot, 2 directional)
    vec4 direction;      // where it points (unit, world), 0; spot: axis x scale, offset (its record)
};
layout(set = 1, binding = 1, std430) readonly buffer FileLights { FileLight file_lights[]; };
#ifdef PG_LIGHT_CUTOFF_NANO
#define PG_LIGHT_CUTOFF (float(PG_LIGHT_CUTOFF_NANO) * 1e-9)
#else
#define PG_LIGHT_CUTOFF 1e-4
#endif
// Distance of a directional light, stored as a point light this far along -direction with its
// colour times PG_SUN_DIST^2 and no window: across a scene of size s its direction varies by
// s / 1e15 rad and its 1/d^2 by 2 s / 1e15, below float precision for s < 1e7.
const float PG_SUN_DIST = 1e15;
const float PG_NO_WINDOW = 3e38; // a window range whose (d/R)^4 is 0 for any finite d

Light pg_file_light(uint i)
{
    FileLight f = file_lights[i];
    Light L;
    vec3 c = f.color_type.rgb;
    uint type = uint(f.color_type.w + 0.5);
    if (type == 2u) { // directional: no position, no falloff, reaches everything
        L.pos_radius = vec4(-f.direction.xyz * PG_SUN_DIST, PG_NO_WINDOW);
        L.color = vec4(c * (PG_SUN_DIST * PG_SUN_DIST), PG_NO_WINDOW);
        return L;
    }
    // point and spot (a spot is a point light times its cone: its record, written by main)
    float range = f.position_range.w;
#ifdef PG_INFINITE_REACH
    // the reference: a light without a range reaches everything (the extension's rule)
    float reach = range > 0.0 ? range : PG_NO_WINDOW;
#else
    // a light without a range stops where its unshadowed contribution falls below PG_LIGHT_CUTOFF
    // (scene-linear, per channel): max(c) / d^2 = cutoff
    float reach = range > 0.0 ? range : sqrt(max(c.r, max(c.g, c.b)) / float(PG_LIGHT_CUTOFF));
#endif
    L.pos_radius = vec4(f.position_range.xyz, reach);
    L.color = vec4(c, range > 0.0 ? range : PG_NO_WINDOW);
    return L;
}
#endif

uint pg_hash(uint x)
{
    uint state = x * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

float pg_rand(uint seed, uint i, uint k)
{
    return float(pg_hash(pg_hash(seed ^ pg_hash(i * 16u + k)) + k) >> 8) * (1.0 / 16777216.0);
}

// Maps a point of the light box onto the shell between the keep-out box and the light box (both
// centred on c): along the ray from c through the point, the fraction n of the way to the light
// box's surface (Chebyshev norm in box units) becomes t_in + (1 - t_in) n, t_in where the ray
// leaves the keep-out box. The centre itself (measure zero) goes straight up.
vec3 pg_keep_out(vec3 pos)
{
    vec3 c = 0.5 * (frame.light_box_min.xyz + frame.light_box_max.xyz);
    vec3 h = max(0.5 * (frame.light_box_max.xyz - frame.light_box_min.xyz), vec3(1e-30));
    vec3 a = min(0.5 * (frame.light_keep_max.xyz - frame.light_keep_min.xyz) / h, vec3(0.999));
    vec3 q = (pos - c) / h;
    float n = max(abs(q.x), max(abs(q.y), abs(q.z)));
    vec3 u = n > 0.0 ? q / n : vec3(0.0, 1.0, 0.0);
    vec3 au = max(abs(u), vec3(1e-30));
    float t_in = min(a.x / au.x, min(a.y / au.y, a.z / au.z));
    float t = t_in + (1.0 - t_in) * n;
    return c + h * u * t;
}

void main()
{
    uint i = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * 64u) + gl_GlobalInvocationID.x;
    uint count = frame.counts.x;
    if (i >= count) return;
#ifdef PG_SPOT_LIGHTS
    // every light's spot record, after the lights (lighting.glsl): a file spot light's cone, else
    // (0, 0, 0, 1), a factor of 1
    bool spot = i < frame.light_src.x && uint(file_lights[i].color_type.w + 0.5) == 1u;
    lights[count + i].pos_radius = spot ? file_lights[i].direction : vec4(0.0, 0.0, 0.0, 1.0);
    lights[count + i].color = vec4(0.0);
#endif
#ifdef PG_FILE_LIGHTS
    if (i < frame.light_src.x) {
        lights[i] = pg_file_light(i);
        return;
    }
    i -= frame.light_src.x; // the generated lights follow the file's, numbered from 0
    uint out_i = i + frame.light_src.x;
#else
    uint out_i = i;
#endif
    uint seed = frame.counts.y;
    float t = frame.camera_pos.w;
    float speed = frame.light_params.y;
    bool moving = frame.light_params.z < 0.5;
    vec3 p;
    for (int a = 0; a < 3; a++) {
        float phase = pg_rand(seed, i, uint(a));
        float u = phase;
        if (moving) {
            float freq = 0.02 + 0.08 * pg_rand(seed, i, 3u + uint(a)); // cycles per second
            float tri = 1.0 - abs(2.0 * fract(phase + freq * speed * t) - 1.0);
            u = tri * tri * (3.0 - 2.0 * tri);
        }
        p[a] = u;
    }
    vec3 pos = mix(frame.light_box_min.xyz, frame.light_box_max.xyz, p);
    if (frame.light_keep_min.w > 0.5) pos = pg_keep_out(pos);
    float hue = pg_rand(seed, i, 6u);
    vec3 rgb = clamp(abs(mod(hue * 6.0 + vec3(0.0, 4.0, 2.0), 6.0) - 3.0) - 1.0, 0.0, 1.0);
    vec3 color = mix(vec3(1.0), rgb, frame.light_params.x) * frame.light_box_max.w;
    lights[out_i].pos_radius = vec4(pos, frame.light_box_min.w);
    lights[out_i].color = vec4(color, frame.light_box_min.w); // the window's range: the same
}
