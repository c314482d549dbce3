/* forward_plus.c - clustered forward shading: draws the scene once with depth; each fragment
 * finds its cluster (screen tile x exponential depth slice) and shades only the lights the
 * cluster_assign pass listed for it, in ascending light order - the same sum as naive whenever
 * no cluster overflowed.
 * Slots: reads [lights, cluster_counts, cluster_lights (storage buffers, fragment), environment
 *        (optional: the filtered environment, shading_common.h)];
 *        writes [color, depth].
 * Options: prepass (bool, default false): depth was drawn by a depth_prepass pass before this
 * one; the depth slot is then depth_rmw (loaded). prepass_test (with prepass; must match the
 * depth_prepass pass's test): "less" (default) - that depth is the opaque draws' one bias step
 * farther, tested LESS and written as without pre-pass, so the fragments behind the nearest
 * surface fail early and the ones that win are those that win without it; "equal" - tested EQUAL
 * without writes, and the alpha-mask draws drawn without discard (the pre-pass discarded them), an
 * approximation (depth_prepass.c says where it differs).
 * shading, ambient, view (every debug view). The cluster grid is the count of the resource bound to
 * cluster_counts (renderer/common/cluster_grid.h), as cluster_assign reads it. */
#include "forward_common.h"

static const char *const k_fp_options[] = {"prepass", "prepass_test", NULL};

/* prepass and prepass_test; prepass_test without prepass is refused (it would do nothing). */
static pg_result fp_prepass_opts(const pg_pass_desc *desc, bool *prepass, bool *equal, pg_error *err)
{
    int test;
    pg_result r = pg_opt_bool(desc, "prepass", false, prepass, err);
    if (!r) r = pg_opt_enum(desc, "prepass_test", pg_prepass_tests, PG_PREPASS_LESS, &test, err);
    if (r) return r;
    *equal = test == PG_PREPASS_EQUAL;
    if (*equal && !*prepass)
        return pg_fail(err, PG_ERR_SCHEMA, "%s: %s.options.prepass_test: \"equal\" needs prepass true", desc->file,
                       desc->json_path);
    return PG_OK;
}

static pg_result fp_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    pg_forward_params *p = pg_decl_params(out, sizeof *p);
    pg_result r = pg_shading_opts_read(in->desc, true, k_fp_options, &p->sh, err);
    if (r) return r;
    if ((r = fp_prepass_opts(in->desc, &p->prepass, &p->prepass_equal, err))) return r;
    const bool prepass = p->prepass, equal = p->prepass_equal;
    p->sh.lights = pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
    p->sh.cluster_counts =
        pg_decl_read(out, "cluster_counts", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
    p->sh.cluster_lists =
        pg_decl_read(out, "cluster_lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
    if ((r = pg_shading_grid_declare(&p->sh, in, err))) return r;
    p->color = pg_decl_write(out, "color", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    p->depth = pg_decl_write(out, "depth", PG_RES_IMAGE, prepass ? PG_ACCESS_DEPTH_RMW : PG_ACCESS_DEPTH_WRITE,
                  PG_STAGE_FRAGMENT, PG_FMTCLASS_DEPTH);
    if (equal) {
        pg_scene_draw_declare_vertex_features(in, out, &p->draw); /* no discard: the pre-pass decided coverage */
        pg_decl_explain(out, "prepass_test equal: depth loaded from the depth_prepass pass and tested EQUAL without "
                             "writes; alpha-mask draws shaded without discard (the pre-pass discarded them)");
    } else {
        pg_scene_draw_declare_features(in, out, &p->draw);
        if (prepass)
            pg_decl_explain(out, "prepass: depth loaded from the depth_prepass pass (one bias step farther) and "
                                 "tested LESS with writes: fragments behind the nearest opaque surface are not shaded");
    }
    pg_shading_declare(&p->sh, in, out);
    pg_environment_slot_declare(in, out, &p->sh, PG_STAGE_FRAGMENT, false);
    pg_geometry_slot_declare(in, out, &p->draw, false);
    return PG_OK;
}

const pg_pass_type pg_pass_forward_plus = {
    .name = "forward_plus",
    .summary = "graphics: clustered forward+ - each fragment shades the lights of its cluster",
    .instance_size = sizeof(pg_forward_pass),
    .params_size = sizeof(pg_forward_params),
    .declare = fp_declare,
    .create = pg_forward_create,
    .record = pg_forward_record,
    .destroy = pg_forward_destroy,
    .runtime_options = pg_shading_runtime_options,
    .update = pg_forward_update,
};
