/* forward_plus.c - clustered forward shading: draws the scene once with depth; each fragment
 * finds its cluster (screen tile x exponential depth slice) and shades only the lights the
 * cluster_assign pass listed for it, in ascending light order - the same sum as naive whenever
 * no cluster overflowed.
 * Slots: reads [lights, cluster_counts, cluster_lights] (storage buffers, fragment);
 *        writes [color, depth].
 * Options: prepass (bool, default false): depth was drawn by a depth_prepass pass before this
 * one (its opaque draws, one depth-bias step farther); the depth slot is then depth_rmw (loaded,
 * tested LESS and written as without pre-pass), so the fragments behind the nearest surface fail
 * early and the ones that win are those that win without it (depth_prepass.c says why).
 * shading, ambient, view (every debug view), grid_x/y/z (must match the
 * cluster_assign pass and the buffer sizes; the shared fragment pipelines/fragments/clusters.json
 * wires all three from the same parameters). */
#include "forward_common.h"

static const char *const k_fp_options[] = {"prepass", NULL};

static pg_result fp_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    pg_shading_opts o;
    pg_result r = pg_shading_opts_read(in->desc, true, k_fp_options, &o, err);
    if (r) return r;
    bool prepass;
    if ((r = pg_opt_bool(in->desc, "prepass", false, &prepass, err))) return r;
    pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
    pg_decl_read(out, "cluster_counts", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
    pg_decl_read(out, "cluster_lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
    pg_decl_write(out, "color", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    pg_decl_write(out, "depth", PG_RES_IMAGE, prepass ? PG_ACCESS_DEPTH_RMW : PG_ACCESS_DEPTH_WRITE,
                  PG_STAGE_FRAGMENT, PG_FMTCLASS_DEPTH);
    pg_scene_draw_declare_features(in, out);
    if (prepass)
        pg_decl_explain(out, "prepass: depth loaded from the depth_prepass pass (one bias step farther) and tested "
                             "LESS with writes: fragments behind the nearest opaque surface are not shaded");
    pg_shading_declare(&o, in, out, true, 0, 1);
    return PG_OK;
}

static pg_result fp_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    bool prepass;
    pg_result r = pg_opt_bool(ctx->desc, "prepass", false, &prepass, err);
    if (r) return r;
    return pg_forward_create(self, ctx, true, prepass, err);
}

const pg_pass_type pg_pass_forward_plus = {
    .name = "forward_plus",
    .summary = "graphics: clustered forward+ - each fragment shades the lights of its cluster",
    .read_slots = "lights, cluster_counts, cluster_lights",
    .write_slots = "color, depth",
    .instance_size = sizeof(pg_forward_pass),
    .declare = fp_declare,
    .create = fp_create,
    .record = pg_forward_record,
    .destroy = pg_forward_destroy,
    .runtime_options = pg_shading_runtime_options,
    .update = pg_forward_update,
};
