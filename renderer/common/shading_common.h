/* shading_common.h - options, variant defines and the light descriptor set shared by the
 * shading passes (forward_naive, forward_plus, deferred_lighting).
 *
 * Options: shading "lambert" | "blinn_phong" | "pbr" | "auto" (default: pbr for a glTF file's
 * materials, lambert for the generated scenes, a scenario's "shading" where it gives one:
 * scene features auto_shading); ambient >= 0; view (debug view: none,
 * cluster_heat, cluster_x, cluster_y, cluster_z, overflow, albedo, normal, depth). The cluster
 * grid of a clustered pass is no option: it is the count of the resource bound to its
 * cluster_counts slot (pg_shading_grid_declare).
 * With 0 lights the light slots are declared unused (so light animation and cluster assignment
 * are culled) and the light loop is compiled out. */
#ifndef PG_SHADING_COMMON_H
#define PG_SHADING_COMMON_H

#include "graph_execute.h"
#include "scene_vars.h"
#include "scene_gpu.h"
#include "pass_api.h"
#include "pass_set.h"
#include "vk_pipeline.h"

typedef struct pg_shading_opts {
    int shading;         /* PG_SHADING_*: the option as given (PG_SHADING_AUTO resolved by
                            pg_shading_model) */
    double ambient;
    int view;            /* index into pg_debug_views */
    uint32_t grid[3];    /* clustered: the cluster grid (pg_shading_grid_declare) */
} pg_shading_opts;

extern const char *const pg_debug_views[]; /* NULL-terminated */
extern const char *const pg_shading_models[]; /* indexed by PG_SHADING_*, NULL-terminated */

/* The light model of a shading option (PG_SHADING_AUTO: the scene's features.auto_shading). */
int pg_shading_model(const pg_declare_in *in, int option);
/* The material variant of a light model: PG_BLINN_PHONG, or PG_PBR with the metallic-roughness and
 * occlusion textures the scene has (PG_METALLIC_ROUGHNESS_TEXTURES, PG_OCCLUSION_TEXTURES), and
 * PG_UNLIT when a material is unlit; explanations for what is left out. The shading passes and
 * the gbuffer pass (whose layout stores the model's values) call it. */
void pg_material_model_declare(const pg_declare_in *in, pg_pass_decl *out, int option);

/* The shading options and light slots a shading pass keeps in its params block (embedded in the
 * pass's own params): filled by declare (pg_shading_opts_read, the handles, pg_shading_declare),
 * read by create/update/record. */
typedef struct pg_shading_params {
    pg_shading_opts o;
    float ambient;       /* o.ambient as the float the shaders get (a run-time value) */
    bool clustered;      /* the pass reads cluster lists */
    bool has_lights;     /* declared with lights (PG_HAS_LIGHTS) */
    pg_slot lights, cluster_counts, cluster_lists; /* cluster_*: PG_SLOT_NONE unless clustered */
    pg_slot environment; /* the filtered environment (pg_environment_slot_declare), or none */
    bool has_env;        /* it is bound and used: PG_ENVIRONMENT, the last binding of set 2 */
} pg_shading_params;

/* known: the pass's other option keys (NULL-terminated, may be NULL). Fills sp->o, sp->ambient and
 * sp->clustered (declare only). */
pg_result pg_shading_opts_read(const pg_pass_desc *desc, bool clustered, const char *const *extra_known,
                               pg_shading_params *sp, pg_error *err);
/* The options of the shading passes that are run-time values (pg_pass_type.runtime_options):
 * "ambient", a push constant the shaders add to the frame's ambient (frame.clip.z). */
extern const char *const pg_shading_runtime_options[];
/* Clustered passes, after declaring the cluster slots (sp->cluster_counts, sp->cluster_lists): the grid
 * sp->o.grid from the cluster_counts resource's count, checked against cluster_lights'
 * (pg_cluster_grid_declare, renderer/common/cluster_grid.h). Does nothing for an unclustered pass. */
pg_result pg_shading_grid_declare(pg_shading_params *sp, const pg_declare_in *in, pg_error *err);
/* Adds defines (PG_BLINN_PHONG, PG_DEBUG_VIEW, PG_HAS_LIGHTS, PG_CLUSTERED, GRID_*) and explanations; marks
 * the light slots (sp->lights, and sp->cluster_counts/lists when clustered) unused with 0 lights; sets
 * sp->has_lights. */
void pg_shading_declare(pg_shading_params *sp, const pg_declare_in *in, pg_pass_decl *out);
/* The shader defines the light set's list binding needs (cluster_windows.h: the lists in windows),
 * appended to defs; returns how many (0, or 2 written into buf). Every pass that creates a light set
 * compiles its shaders with them. */
uint32_t pg_light_set_defines(const pg_pass_create_ctx *ctx, const pg_shading_params *sp, char buf[2][40],
                              const char **defs);

/* Set 2: lights (+ cluster counts and lists). Leaves *out zeroed when the pass has no lights. */
pg_result pg_light_set_create(const pg_pass_create_ctx *ctx, const pg_shading_params *sp, pg_pass_set *out,
                              pg_error *err);
/* The same with one more storage buffer after them (binding 1, or 3 when clustered), if extra. */
pg_result pg_light_set_create_ex(const pg_pass_create_ctx *ctx, const pg_shading_params *sp,
                                 const pg_phys_resource *extra, pg_pass_set *out, pg_error *err);
/* The optional environment slot: the filtered environment buffer (environment_filter's output,
 * shaders/environment.glsl), the last read of a shading pass (forward_naive, forward_plus,
 * forward_transparent, deferred_lighting), declared next (after every other read). Bound:
 * declared (storage read in `stages`), and used when the scene has an environment and the pass
 * shades (no debug view): defines PG_ENVIRONMENT, PG_ENVIRONMENT_FILTERED and PG_ENV_BINDING, its
 * binding in set 2 after the light bindings and the pass's extra one (pg_light_set_create_ex);
 * otherwise marked unused (the filter pass and the buffer are culled). Not bound: nothing is
 * declared, and with an environment an explain line says the pass does not get it. */
void pg_environment_slot_declare(const pg_declare_in *in, pg_pass_decl *out, pg_shading_params *sp, uint32_t stages,
                                 bool extra);

/* The optional emissive G-buffer slot (gb_emissive): the last write of a gbuffer pass, the last read of
 * deferred_lighting and reference_lighting, declared next (after the slots declared so far). Bound when the
 * pass desc has a slot there: declared (colour attachment written in the fragment stage, or sampled in
 * compute; *slot gets its handle), its resource must be rgba16f or rgba32f (rgba32f with full_precision),
 * and without emissive materials it is marked unused (so the resource is culled and not allocated). Not
 * bound: nothing is declared (*slot = PG_SLOT_NONE), and with emissive materials an explain line says they
 * are not drawn. *used: bound and the scene has emissive materials (the pass then compiles its emissive
 * variant). */
/* The hdr slot of a compute pass that writes it as a storage image: rgba16f or rgba32f (the format its
 * shader's PG_HDR_FORMAT names), else PG_ERR_FORMAT "...: pass 'P' slot hdr: WHAT writes rgba16f or
 * rgba32f, not F (resource 'R')". */
pg_result pg_hdr_storage_check(const pg_declare_in *in, pg_slot hdr, const char *what, pg_error *err);
/* "PG_HDR_FORMAT=<format>" for the bound hdr image, written into buf. */
const char *pg_hdr_format_define(const pg_phys_resource *hdr, char *buf, size_t size);

pg_result pg_emissive_slot_declare(const pg_declare_in *in, pg_pass_decl *out, bool is_write, bool full_precision,
                                   pg_slot *slot, bool *used, pg_error *err);

#endif
