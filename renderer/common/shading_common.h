/* shading_common.h - options, variant defines and the light descriptor set shared by the
 * shading passes (forward_naive, forward_plus, deferred_lighting).
 *
 * Options: shading "lambert" | "blinn_phong"; ambient >= 0; view (debug view: none,
 * cluster_heat, cluster_x, cluster_y, cluster_z, overflow, albedo, normal, depth); clustered
 * passes also grid_x, grid_y, grid_z (cluster grid; must match cluster_assign's).
 * With 0 lights the light slots are declared unused (so light animation and cluster assignment
 * are culled) and the light loop is compiled out. */
#ifndef PG_SHADING_COMMON_H
#define PG_SHADING_COMMON_H

#include "graph_execute.h"
#include "scene_gpu.h"
#include "pass_api.h"
#include "pass_set.h"
#include "vk_pipeline.h"

typedef struct pg_shading_opts {
    int shading;         /* 0 lambert, 1 blinn_phong */
    double ambient;
    int view;            /* index into pg_debug_views */
    uint32_t grid[3];
} pg_shading_opts;

extern const char *const pg_debug_views[]; /* NULL-terminated */

/* known: the pass's other option keys (NULL-terminated, may be NULL). */
pg_result pg_shading_opts_read(const pg_pass_desc *desc, bool clustered, const char *const *extra_known,
                               pg_shading_opts *o, pg_error *err);
/* The options of the shading passes that are run-time values (pg_pass_type.runtime_options):
 * "ambient", a push constant the shaders add to the frame's ambient (frame.clip.z). */
extern const char *const pg_shading_runtime_options[];
/* The option "ambient" of desc (default 0) as the float the shaders get. */
pg_result pg_shading_ambient(const pg_pass_desc *desc, float *out, pg_error *err);
/* Adds defines (PG_BLINN_PHONG, PG_DEBUG_VIEW, PG_HAS_LIGHTS, PG_CLUSTERED, GRID_*) and explanations; marks the light slots unused with 0 lights. light_slot and
 * cluster_slot are read-slot indices (cluster_slot: counts, cluster_slot+1: lists; -1 if none). */
void pg_shading_declare(const pg_shading_opts *o, const pg_declare_in *in, pg_pass_decl *out, bool clustered,
                        int light_slot, int cluster_slot);
/* true when the pass was declared with lights (PG_HAS_LIGHTS among its defines). */
bool pg_shading_has_lights(const pg_plan_pass *pass);
/* Set 2: lights (+ cluster counts and lists). Leaves *out zeroed when the pass has no lights. */
pg_result pg_light_set_create(const pg_pass_create_ctx *ctx, bool clustered, int light_slot, int cluster_slot,
                              pg_pass_set *out, pg_error *err);
/* Checks cluster buffers are big enough for the grid (a mismatch between the pipeline's buffer
 * sizes and the pass options would read out of bounds). */
pg_result pg_check_cluster_buffers(const pg_pass_create_ctx *ctx, const pg_shading_opts *o, int cluster_slot,
                                   pg_error *err);
/* The optional emissive G-buffer slot (gb_emissive): the last write of a gbuffer pass, the last read of
 * deferred_lighting and reference_lighting, at slot `index` (of the writes or the reads). Bound when the
 * pass desc has a slot there: declared (colour attachment written in the fragment stage, or sampled in
 * compute), its resource must be rgba16f or rgba32f (rgba32f with full_precision), and without emissive
 * materials it is marked unused (so the resource is culled and not allocated). Not bound: nothing is
 * declared, and with emissive materials an explain line says they are not drawn. *used: bound and the
 * scene has emissive materials (the pass then compiles its emissive variant). */
pg_result pg_emissive_slot_declare(const pg_declare_in *in, pg_pass_decl *out, bool is_write, uint32_t index,
                                   bool full_precision, bool *used, pg_error *err);

#endif
