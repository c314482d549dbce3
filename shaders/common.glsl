// common.glsl - declarations shared by every passgraph shader.
// FrameUniforms mirrors pg_frame_uniforms (renderer/frame.h); GpuMaterial mirrors pg_gpu_material
// (core/runtime/scene_gpu.h); Light is the 32-byte record the light_animate pass writes.

struct Light {
    vec4 pos_radius;   // xyz world position, w range R: where the light stops (lists, culling)
    vec4 color;        // rgb radiant colour (already times intensity), w the falloff's range (the
                       // window's R: equal to pos_radius.w for generated lights; 3e38 = no window
                       // for a file light without a range; the true range under stochastic culling)
};

struct GpuMaterial {
    vec4 base_color;
    ivec4 tex;         // base colour texture, normal texture (-1 none), alpha mode, double sided
    vec4 params;       // alpha cutoff, normal scale, specular, shininess
    vec4 emissive;     // rgb emissive (factor x strength)
    ivec4 tex2;        // emissive texture (-1 none), texcoord set bits (bit s: slot s reads
                       // TEXCOORD_1; slots 0 base, 1 normal, 2 emissive, 3 metallic-roughness,
                       // 4 occlusion), 0, 0
    vec4 pbr;          // metallic, roughness, occlusion strength, 1 = unlit (KHR_materials_unlit)
    ivec4 tex3;        // metallic-roughness texture, occlusion texture (-1 none), 0, 0
    vec4 uv_xform[10]; // per slot s: rows 2s and 2s+1 of its 2x3 KHR_texture_transform matrix
};

// What shading needs of a visible point (from the material in forward, from the G-buffer in
// deferred).
// With PG_PBR (the glTF metallic-roughness model) specular holds the metallic value and shininess
// the (perceptual) roughness, so every G-buffer variant carries them in the same channels.
struct Surface {
    vec3 albedo;    // base colour
    float alpha;    // base colour alpha (BLEND materials: coverage)
    vec3 normal;    // unit, facing the camera side that is seen
    float specular; // Blinn-Phong strength; PG_PBR: metallic
    float shininess;// Blinn-Phong exponent; PG_PBR: roughness
    vec3 emissive;  // added to the lit colour (0 without PG_EMISSIVE)
    float occlusion;// PG_PBR: ambient occlusion (occlusionTexture), scales the ambient term; else 1
};

// What a fragment shader knows of the surface before the material (surface_inputs.glsl).
struct SurfaceInput {
    vec3 normal;    // interpolated world normal (not normalized)
    vec2 uv0, uv1;  // TEXCOORD_0, TEXCOORD_1 (0 without PG_UV1)
    vec4 tangent;
    vec4 color;     // COLOR_0 (1 without PG_VERTEX_COLORS)
    bool front_facing;
    vec4 duv0, duv1; // screen-space derivatives of uv0/uv1: d(uv)/dx in xy, d(uv)/dy in zw
};

// Rec.709 luminance of a linear colour.
float pg_luminance(vec3 c)
{
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

// PCG hash (a 32-bit permutation): the random streams of the stochastic passes.
uint pg_pcg(uint v)
{
    uint s = v * 747796405u + 2891336453u;
    uint w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (w >> 22u) ^ w;
}

vec3 pg_srgb_encode(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

vec3 pg_srgb_decode(vec3 c)
{
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

#define FRAME_UNIFORMS_BLOCK                                                                  \
    layout(set = 0, binding = 0, std140) uniform FrameUniforms {                                 \
        mat4 view; mat4 proj; mat4 view_proj; mat4 inv_view; mat4 inv_proj;                      \
        vec4 camera_pos;    /* w = time */                                                       \
        vec4 light_box_min; /* w = radius */                                                     \
        vec4 light_box_max; /* w = intensity */                                                  \
        vec4 light_params;  /* saturation, speed, motion (0 noise, 1 static), min distance */    \
        uvec4 counts;       /* light count, seed, width, height */                               \
        vec4 clip;          /* near, far, ambient (light set-up, run time), 1 = orthographic */                                                      \
        uvec4 noise;        /* sample index, seed (stochastic passes' random stream), 0, 0 */    \
        vec4 light_keep_min; /* the box lights stay out of, w = 1 when they do */                \
        vec4 light_keep_max;                                                                     \
        uvec4 light_src;    /* x: lights from the scene file (the first x of counts.x) */        \
        vec4 environment;   /* intensity, rotation about +Y (radians), 0, 0 */                   \
    } frame;

// Camera-relative rendering (use after FRAME_UNIFORMS_BLOCK): shading works on positions
// relative to the camera ("rel" = world - camera), so scenes far from the origin (~1e5) keep
// their precision: view * vec4(world, 1) would cancel large terms and make depth - and every
// position rebuilt from it - useless there, and 1/d^2 would see the 0.008 quantization of fp32
// world coordinates at 1e5.
#define PG_REL_TO_VIEW(r) (mat3(frame.view) * (r))
#define PG_VIEW_TO_REL(v) (mat3(frame.inv_view) * (v))
// Orthographic camera (core/scene/scene.h pg_camera.ortho_height): a uniform flag, so one shader
// variant serves both projections.
#define PG_ORTHO (frame.clip.w > 0.5)
// Unit direction from a camera-relative point P to the eye: -P normalized for perspective; the
// view axis (camera +Z in world space) for orthographic, where every view ray is parallel.
#define PG_VIEW_DIR(P) (PG_ORTHO ? normalize(PG_VIEW_TO_REL(vec3(0.0, 0.0, 1.0))) : normalize(-(P)))

const float PG_HDR_MAX = 65000.0;

// Keeps HDR values finite and inside half-float range (NaN -> 0). With PG_HDR_KEEP_NAN
// (PASSGRAPH_KEEP_NAN=1 in the environment: core/vk/shader.c) a NaN is stored as it is, so that the
// tools' `nonfinite` count sees what a shader computed instead of a black pixel.
vec3 pg_hdr_sanitize(vec3 c)
{
#ifdef PG_HDR_KEEP_NAN
    return mix(clamp(c, vec3(0.0), vec3(PG_HDR_MAX)), c, isnan(c));
#else
    c = mix(c, vec3(0.0), isnan(c));
    return clamp(c, vec3(0.0), vec3(PG_HDR_MAX));
#endif
}
