/* vk_pipeline.h - small builders passes share: pipeline layouts, graphics pipelines for dynamic
 * rendering, compute pipelines, a pass-private descriptor set over graph resources, and
 * vkCmdBeginRendering with sensible defaults. Descriptor structs: zero means default. */
#ifndef PG_VK_PIPELINE_H
#define PG_VK_PIPELINE_H

#include "vk_context.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The vertex streams a graphics pipeline reads (the caller's layout: e.g. the renderer's scene
 * vertices, renderer/common/scene_draw.c); NULL in pg_gfx_pipeline_desc: no vertex input. */
typedef struct pg_vertex_input {
    uint32_t n_bindings, n_attributes;
    VkVertexInputBindingDescription bindings[4];
    VkVertexInputAttributeDescription attributes[8];
} pg_vertex_input;

typedef struct pg_gfx_pipeline_desc {
    VkPipelineLayout layout;
    VkShaderModule vs, fs;
    uint32_t n_color;
    VkFormat color_formats[8];
    VkFormat depth_format;          /* VK_FORMAT_UNDEFINED: none */
    bool depth_test, depth_write;
    VkCompareOp depth_compare;      /* 0 (NEVER) -> LESS */
    float depth_bias_constant;      /* depth bias (both 0: off): constant * r + slope * max slope */
    float depth_bias_slope;
    VkCullModeFlags cull;           /* 0 -> none */
    bool dynamic_cull;              /* cull mode and front face set per draw (vkCmdSetCullMode,
                                     * vkCmdSetFrontFace) */
    const pg_vertex_input *vertex_input; /* NULL: no vertex input */
    bool blend_over;                /* every colour attachment: rgb = src.a*src + (1-src.a)*dst,
                                     * a = src.a + (1-src.a)*dst.a (non-premultiplied "over") */
    bool blend_add;                 /* every colour attachment: dst + src (rgb and a) */
} pg_gfx_pipeline_desc;

pg_result pg_gfx_pipeline_create(pg_gpu *gpu, const pg_gfx_pipeline_desc *d, const char *name,
                                 VkPipeline *out, pg_error *err);
pg_result pg_compute_pipeline_create(pg_gpu *gpu, VkPipelineLayout layout, VkShaderModule cs,
                                     const char *name, VkPipeline *out, pg_error *err);
/* A compute pipeline with options: spec_data/n_spec are uint32 specialization constants (ids
 * 0..n-1); subgroup_size != 0 requires exactly that subgroup size with full subgroups
 * (only when gpu->exact_subgroups; the local size must then be that size). */
typedef struct pg_compute_pipeline_desc {
    VkPipelineLayout layout;
    VkShaderModule cs;
    const uint32_t *spec_data;
    uint32_t n_spec;
    uint32_t subgroup_size;
} pg_compute_pipeline_desc;
pg_result pg_compute_pipeline_create_ex(pg_gpu *gpu, const pg_compute_pipeline_desc *d, const char *name,
                                        VkPipeline *out, pg_error *err);
/* The stages of the push-constant range every layout from pg_pipeline_layout_create declares:
 * vkCmdPushConstants must name all of them. */
#define PG_PUSH_STAGES (VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT)
/* A sampler with one filter (min, mag; mipmaps off) and one address mode on every axis. */
pg_result pg_sampler_create(pg_gpu *gpu, VkFilter filter, VkSamplerAddressMode address, VkSampler *out,
                            pg_error *err);
pg_result pg_pipeline_layout_create(pg_gpu *gpu, uint32_t n_sets, const VkDescriptorSetLayout *sets,
                                    uint32_t push_bytes, VkPipelineLayout *out, pg_error *err);

/* clear_colors NULL -> load. depth_view VK_NULL_HANDLE -> none. */
void pg_cmd_begin_rendering(VkCommandBuffer cmd, uint32_t w, uint32_t h, uint32_t n_color,
                            const VkImageView *color_views, const VkClearColorValue *clear_colors,
                            VkImageView depth_view, bool clear_depth, float depth_clear);
void pg_cmd_viewport(VkCommandBuffer cmd, uint32_t w, uint32_t h);

#ifdef __cplusplus
}
#endif
#endif
