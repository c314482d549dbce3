/* forward_common.h - the params block and create/record/destroy shared by the two forward shading
 * pass types (forward_naive.c, forward_plus.c); each file keeps its own declare() and type table.
 * Slot layout: reads [lights (, cluster_counts, cluster_lights)], writes [color, depth]. */
#ifndef PG_FORWARD_COMMON_H
#define PG_FORWARD_COMMON_H

#include "scene_draw.h"
#include "shading_common.h"

/* Filled once by declare (both types), read by create/update/record. */
typedef struct pg_forward_params {
    pg_shading_params sh;          /* options, light (and cluster) slots */
    pg_scene_draw_features draw;   /* the surface variant */
    pg_slot color, depth;
    bool prepass;       /* forward_plus option "prepass": depth was drawn by a depth_prepass pass */
    bool prepass_equal; /* forward_plus option prepass_test "equal" */
} pg_forward_params;

typedef struct pg_forward_pass {
    bool prepass;
    uint32_t color_slot, depth_slot; /* plan slots of color and depth (pg_pass_begin_rendering) */
    pg_pass_set lights;
    pg_scene_draw draw;
} pg_forward_pass;

/* prepass: the depth slot is depth_rmw, loaded (the depth_prepass pass's depth); tested LESS with
 * writes as without pre-pass, or with prepass_equal EQUAL without writes (pg_scene_draw_desc.depth_equal). */
pg_result pg_forward_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err);
/* update(): the run-time options (pg_shading_runtime_options: ambient) from the new params */
pg_result pg_forward_update(void *self, const void *params, pg_error *err);
void pg_forward_record(void *self, const pg_pass_record_ctx *ctx);
void pg_forward_destroy(void *self, pg_gpu *gpu);

#endif
