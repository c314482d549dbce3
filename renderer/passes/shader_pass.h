/* shader_pass.h - the `shader` pass type's params block: what declare (shader_pass_declare.c) read
 * from the pipeline JSON and from the compiled shader's SPIR-V, for create/record (shader_pass.c).
 * docs/user-passes.md is the user's reference. */
#ifndef PG_SHADER_PASS_H
#define PG_SHADER_PASS_H

#include "pass_api.h"
#include "scene_draw.h"

#define SP_MAX_BINDINGS 16 /* set 2 bindings of one user shader */
#define SP_MAX_TARGETS 8   /* colour targets (fullscreen, draw) */
#define SP_PUSH_MAX 128    /* push-constant bytes (Vulkan's guaranteed minimum) */
#define SP_USER_SET 2      /* the descriptor set of the user's bindings (0 frame, 1 scene) */
#define SP_VIS_SET 1       /* "surface": "visibility": the vertex streams (visibility_common.h) */
#define SP_SCENE_SET 3     /* ... and the scene's materials and textures */

typedef enum sp_form { SP_COMPUTE = 0, SP_FULLSCREEN, SP_DRAW } sp_form;
typedef enum sp_dispatch { SP_DISPATCH_IMAGE = 0, SP_DISPATCH_BUFFER, SP_DISPATCH_GROUPS } sp_dispatch;
typedef enum sp_blend { SP_BLEND_NONE = 0, SP_BLEND_ADD, SP_BLEND_OVER } sp_blend;

typedef struct sp_binding {
    pg_slot slot;
    uint16_t type;   /* VkDescriptorType */
    uint16_t number; /* binding number in set 2 */
    uint32_t block_size; /* a buffer block's bytes without its runtime array (spirv_reflect.h): the
                          * bound buffer must hold at least these */
} sp_binding;

typedef struct sp_params {
    char path[PG_PATH_MAX];   /* the shader file, resolved and confined (pipeline_paths.h) */
    uint8_t form;             /* sp_form */
    uint8_t n_bindings, n_targets;
    uint8_t blend;            /* sp_blend (fullscreen and draw targets) */
    uint8_t dispatch;         /* sp_dispatch (compute) */
    uint8_t filter;           /* VkFilter of the sampler of sampled bindings */
    uint8_t address;          /* VkSamplerAddressMode */
    bool clear_targets;       /* targets written whole (color_write, cleared to 0) */
    bool vis_surface;         /* compute, "surface": "visibility": the scene's vertex streams in set 1
                               * and its materials in set 3, for visibility_surface.glsl */
    bool depth_clear;         /* the depth image is in the writes and cleared (depth_write access) */
    uint32_t depth_compare;   /* VkCompareOp (draw) */
    uint32_t local[3];        /* the compute shader's local size */
    uint32_t shared_bytes;    /* its shared memory (spirv_reflect.h: a lower bound), checked at create */
    uint32_t groups[3];       /* SP_DISPATCH_GROUPS */
    pg_slot dispatch_slot;    /* SP_DISPATCH_IMAGE / BUFFER: per pixel / element of this slot */
    uint32_t dispatch_stride; /* SP_DISPATCH_BUFFER: the buffer's element bytes */
    sp_binding bindings[SP_MAX_BINDINGS];
    pg_slot targets[SP_MAX_TARGETS];
    pg_slot depth;            /* draw: the depth attachment (PG_SLOT_NONE: none) */
    pg_scene_draw_features draw; /* draw: the scene's vertex path and surface variant */
    uint32_t push_size;       /* bytes of the shader's push-constant block (0: none) */
    uint64_t spirv_hash;      /* of the SPIR-V declare compiled: part of the plan's pipeline signature,
                               * so an edit of the shader (or of a file it includes) re-creates the pass */
    /* the push-constant values from options.params: a run-time value (a new value re-creates
     * nothing: pg_pass_type.runtime_options, update()) */
    _Alignas(16) unsigned char push[SP_PUSH_MAX];
} sp_params;

/* The type's declare (shader_pass_declare.c). */
pg_result pg_shader_pass_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err);

#endif
