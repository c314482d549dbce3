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
    lights[i].pos_radius = vec4(pos, frame.light_box_min.w);
    lights[i].color = vec4(color, 0.0);
}
