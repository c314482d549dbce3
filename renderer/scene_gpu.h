/* scene_gpu.h - a pg_scene uploaded for drawing: vertex/index buffers (plus the optional COLOR_0
 * stream, vec4 float, only when features.has_vertex_colors, and TEXCOORD_1, vec2 float, only when
 * features.has_uv1), a material storage buffer, every texture with its mips, one VkSampler per
 * distinct pg_sampler_state (the glTF sampler of each texture), and a descriptor set (set 1 of
 * scene-drawing passes):
 *   binding 0: readonly buffer Materials { GpuMaterial materials[]; }
 *   binding 1: sampler2D textures[texture_count]   (index 0 is a 1x1 white texture, default
 *              sampler; texture i+1 with the sampler of scene->textures[i])
 * Draws are sorted opaque first, then alpha-masked, then alpha-blended (drawn only by the
 * transparent pass, which sorts them back to front by their bounds centre). Static after upload (made visible with one
 * barrier at upload time), so the graph does not track it. */
#ifndef PG_SCENE_GPU_H
#define PG_SCENE_GPU_H

#include "scene.h"
#include "vk_context.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pg_gpu_material { /* std430, matches shaders/common.glsl */
    float base_color[4];
    int32_t tex[4];              /* base colour texture, normal texture, alpha mode, double sided */
    float params[4];             /* alpha cutoff, normal scale, specular, shininess */
    float emissive[4];           /* rgb emissive (factor x strength), w unused */
    int32_t tex2[4];             /* emissive texture (-1 none), texcoord set bits (bit s = slot s
                                    reads TEXCOORD_1), 0, 0 */
    float pbr[4];                /* metallic, roughness, occlusion strength, 1 = unlit */
    int32_t tex3[4];             /* metallic-roughness texture, occlusion texture (-1 none), 0, 0 */
    float uv_xform[PG_TEXSLOT_COUNT][2][4]; /* per slot: rows (m00 m01 m02 0), (m10 m11 m12 0) */
} pg_gpu_material;              /* 272 bytes */
_Static_assert(sizeof(pg_gpu_material) == 272, "pg_gpu_material must match GpuMaterial (std430)");
/* a material as the shaders read it */
void pg_gpu_material_from(const pg_material *m, pg_gpu_material *out);

typedef struct pg_draw {
    uint32_t first_index, index_count;
    int32_t vertex_offset;
    uint32_t material;
    bool alpha_mask;
    bool blend;              /* alphaMode BLEND: the transparent pass draws it, no other pass */
    bool double_sided;       /* draw without back-face culling */
    float center[3];         /* centre of the primitive's world-space bounds (for sorting) */
    int32_t anim_prim;       /* a rigid moving primitive: its pg_scene_anim.prims index, whose pose
                                may mirror it (pg_scene_gpu_anim_flipped); -1 otherwise */
} pg_draw;

/* A file light as shaders/light_animate.comp reads it (48 bytes). */
typedef struct pg_gpu_file_light {
    float position_range[4]; /* world position, the file's range (0: none) */
    float color_type[4];     /* colour x intensity / pi (linear RGB), type (pg_light_type) */
    float direction[4];      /* where it points (unit, world), 0; a spot light: the axis x scale and
                                offset of its cone (lighting.glsl PG_SPOT_LIGHTS) */
} pg_gpu_file_light;

typedef struct pg_scene_gpu {
    pg_buffer vertices, indices, materials;
    pg_buffer colors;            /* binding 1 stream (float4 per vertex); buffer NULL when absent */
    pg_buffer uv1;               /* binding 2 stream (float2 per vertex); buffer NULL when absent */
    uint32_t n_images;
    pg_image *images;            /* n_images; [0] = white */
    uint32_t n_samplers;
    VkSampler *samplers;         /* distinct states; [0] = the glTF default (repeat, trilinear) */
    pg_sampler_state *sampler_states; /* n_samplers */
    VkDescriptorSetLayout set_layout;
    VkDescriptorPool pool;
    VkDescriptorSet set;
    /* draws[0, n_opaque) opaque, [n_opaque, n_draws - n_blend) alpha-masked,
     * [n_draws - n_blend, n_draws) alpha-blended */
    uint32_t n_draws, n_opaque_draws, n_blend_draws;
    pg_draw *draws;
    pg_scene_features features;
    /* the file's lights (KHR_lights_punctual, PASSGRAPH_lights_table) as light_animate reads them
     * (pg_gpu_file_light, device-local, uploaded once); buffer NULL when the scene has none */
    pg_buffer file_lights;
    uint32_t n_file_lights;
    /* the environment light's texels (scene/environment.h: vec4 per texel, every level one after the
     * other), device-local, uploaded once; buffer NULL without an environment. env_id: the
     * pg_environment's id, what environment_filter remembers it filtered */
    pg_buffer environment;
    pg_buffer env_cdf;           /* its importance-sampling tables (environment.h cdf); NULL when black */
    uint32_t env_levels, env_width, env_height;
    uint64_t env_id;
    /* the animation's buffers (scene_gpu_anim.h) for the geometry_animate pass; NULL for a scene
     * without animation. It points into the pg_scene, which must outlive this upload. */
    struct pg_scene_gpu_anim *anim;
    float bounds_min[3], bounds_max[3];
    uint64_t bytes;
} pg_scene_gpu;

/* The uploaded scene of a pass's create or record context: the renderer hands its pg_scene_gpu to
 * the runtime as the user block (pg_runtime_set_plan), which the runtime passes on unread. */
#define PG_SCENE_OF(ctx) ((const pg_scene_gpu *)(ctx)->user)

pg_result pg_scene_gpu_create(pg_gpu *gpu, const pg_scene *scene, pg_scene_gpu **out, pg_error *err);
/* A file light as the table holds it (colour x intensity / pi, the spot record's axis scale). */
void pg_gpu_file_light_from(const pg_scene_light *L, pg_gpu_file_light *out);
void pg_scene_gpu_destroy(pg_gpu *gpu, pg_scene_gpu *sg);
/* The VkSampler of a glTF sampler state: wrap S/T, mag/min filter, mipmap mode; PG_MIP_NONE
 * samples level 0 only (maxLod 0); no anisotropy; maxLod unclamped otherwise. */
pg_result pg_scene_sampler_create(pg_gpu *gpu, const pg_sampler_state *st, VkSampler *out, pg_error *err);

#ifdef __cplusplus
}
#endif
#endif
