#version 460
// light_animate.comp - writes every light from (seed, index, time) alone, so every pipeline
// rendering the same --time sees the same lights. Positions follow a smooth (C1) triangle-wave
// path per axis inside the light box: u = fract(phase + freq*speed*t), p = smoothstep(tri(u)).
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
    float hue = pg_rand(seed, i, 6u);
    vec3 rgb = clamp(abs(mod(hue * 6.0 + vec3(0.0, 4.0, 2.0), 6.0) - 3.0) - 1.0, 0.0, 1.0);
    vec3 color = mix(vec3(1.0), rgb, frame.light_params.x) * frame.light_box_max.w;
    lights[i].pos_radius = vec4(pos, frame.light_box_min.w);
    lights[i].color = vec4(color, 0.0);
}
