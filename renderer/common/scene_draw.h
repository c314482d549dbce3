/* scene_draw.h - what every pass that rasterizes the scene shares (forward_naive, forward_plus,
 * gbuffer): the pipeline layout (set 0 frame, set 1 scene materials/textures, set 2 the pass's
 * own), an opaque pipeline and, only when the scene has alpha-mask materials, a second pipeline
 * compiled with PG_ALPHA_MASK for those draws; and the draw loop (per-draw material push
 * constant, back-face culling unless the material is double-sided). */
#ifndef PG_SCENE_DRAW_H
#define PG_SCENE_DRAW_H

#include "graph_execute.h"
#include "scene_vars.h"
#include "scene_gpu.h"
#include "pass_set.h"
#include "vk_pipeline.h"

/* What declare chose for the surface variant (pg_scene_draw_declare_features): kept in the pass's
 * params block, read by pg_scene_draw_create / pg_vis_geometry_create (nothing parses the defines). */
typedef struct pg_scene_draw_features {
    bool alpha_mask;      /* PG_ALPHA_MASK declared: a second pipeline for the alpha-mask draws */
    bool vertex_colors;   /* PG_VERTEX_COLORS: vertex stream 1 */
    bool uv1;             /* PG_UV1: vertex stream 2 */
    uint8_t mask_define;  /* 1 + the position of PG_ALPHA_MASK among the pass's defines (0: none): the
                           * opaque pipelines compile every other define */
    bool has_geometry;    /* pg_geometry_slot_declare bound the read slot `geometry` (the deformed
                           * vertices of geometry_animate) and the scene is animated: the pass draws
                           * from it instead of the static vertex buffer */
    pg_slot geometry;
} pg_scene_draw_features;

typedef struct pg_scene_draw {
    VkPipelineLayout layout;
    VkPipeline opaque, masked;
    float ambient;                    /* pushed with each draw's material (DrawPush.ambient) */
    bool vertex_colors, uv1;          /* the pipelines read vertex streams 1 / 2 (PG_VERTEX_COLORS, PG_UV1) */
    bool depth_equal;                 /* pg_scene_draw_desc.depth_equal */
    bool has_geometry;                /* vertex stream 0 is the graph's `geometry` buffer (features) */
    pg_slot geometry;
    bool push_draw_key;               /* the visibility pass: DrawPush's second word is
                                       * draw index << draw_key_shift instead of the ambient */
    uint32_t draw_key_shift;
} pg_scene_draw;

typedef struct pg_scene_draw_desc {
    const char *fragment_shader;      /* e.g. "forward.frag" */
    bool fragment_user;               /* fragment_shader is a user's file (pg_shader_compile_user) */
    const pg_scene_draw_features *features; /* what the pass's declare chose (its params) */
    VkDescriptorSetLayout pass_layout;/* set 2 (may be VK_NULL_HANDLE) */
    uint32_t n_color;
    VkFormat color_formats[8];
    VkFormat depth_format;
    const char *extra_defines[4];     /* added to the pass's declared defines */
    uint32_t n_extra_defines;
    bool blend;                       /* the pipeline for the BLEND draws (forward_transparent):
                                       * "over" blending, depth test without depth write, no
                                       * alpha-mask pipeline */
    bool depth_equal;                 /* the shading pass after an EQUAL-test depth pre-pass: depth
                                       * tested EQUAL without writes, and the alpha-mask draws drawn
                                       * with the opaque pipeline (the pre-pass discarded them; no
                                       * masked pipeline is made) */
    bool position_only_opaque;        /* the opaque pipeline's vertex shader fetches and writes the
                                       * position alone (a fragment shader that reads no input:
                                       * the visibility pass); the alpha-mask one keeps them all */
    float depth_bias_constant;        /* depth bias of the pipelines (both 0: none) */
    float depth_bias_slope;
} pg_scene_draw_desc;

/* Compiles the pass's declared defines (d->features->alpha_mask selects whether the masked pipeline
 * is made) plus TEXTURE_COUNT for the scene. */
pg_result pg_scene_draw_create(const pg_pass_create_ctx *ctx, const pg_scene_draw_desc *d,
                               pg_scene_draw *out, pg_error *err);
/* Binds sets 0..2 (pass_set may be VK_NULL_HANDLE when there is no set 2) and draws every
 * opaque and alpha-masked draw of the scene (BLEND draws are left to forward_transparent).
 * Rendering must have begun. */
void pg_scene_draw_record(const pg_scene_draw *sd, const pg_pass_record_ctx *ctx, VkDescriptorSet pass_set);
/* Binds like pg_scene_draw_record and draws the BLEND draws sc->draws[order[0..n)] in that order
 * with the `opaque` pipeline (made with desc.blend). */
void pg_scene_draw_record_list(const pg_scene_draw *sd, const pg_pass_record_ctx *ctx, VkDescriptorSet pass_set,
                               const uint32_t *order, uint32_t n);
void pg_scene_draw_destroy(pg_gpu *gpu, pg_scene_draw *sd);
/* declare(): the surface variant the scene needs (PG_ALPHA_MASK, PG_NORMAL_MAPS, PG_EMISSIVE,
 * PG_VERTEX_COLORS, PG_UV1, PG_UV_TRANSFORM) and, for what it lacks, why that path is left out. */
void pg_scene_draw_declare_features(const pg_declare_in *in, pg_pass_decl *out, pg_scene_draw_features *f);
/* The same without the alpha-mask variant: the defines that shape the vertex path and the surface
 * (for a pass that draws no alpha-mask draws but must run the same vertex shader). */
void pg_scene_draw_declare_vertex_features(const pg_declare_in *in, pg_pass_decl *out, pg_scene_draw_features *f);
/* declare(), after every other read: the optional trailing read slot `geometry` (the scene's
 * vertices at the frame's pose, written by geometry_animate: pipelines/fragments/geometry.json) when
 * the pass's description binds one more read than declared so far; marked unused (so the animation
 * pass can be culled) when the scene has no animation. storage: the pass reads it as a storage
 * buffer in compute (the visibility passes that rebuild surfaces) instead of as its vertex stream.
 * Fills f->has_geometry / f->geometry; a scene that is animated while the pass binds no such slot
 * is drawn in its rest pose (said by an explain line). */
void pg_geometry_slot_declare(const pg_declare_in *in, pg_pass_decl *out, pg_scene_draw_features *f, bool storage);
/* The pass's declared defines without PG_ALPHA_MASK (f->mask_define) into out (max entries); returns how
 * many. */
uint32_t pg_scene_draw_define_list(const pg_pass_decl *decl, const pg_scene_draw_features *f, const char **out,
                                   uint32_t max);
/* The depth tests of a depth pre-pass and the shading pass after it (depth_prepass's option test,
 * forward_plus's prepass_test): index 0 "less" (biased pre-pass, LESS with writes), 1 "equal"
 * (pg_scene_draw_desc.depth_equal); NULL-terminated for pg_opt_enum. */
extern const char *const pg_prepass_tests[];
enum { PG_PREPASS_LESS = 0, PG_PREPASS_EQUAL = 1 };

#endif
