/* forward_naive.c - the exact reference: draws the scene once with depth, and every fragment
 * loops over every light (shaders/forward.frag without PG_CLUSTERED).
 * Slots: reads [lights (storage buffer, fragment), environment (optional: the filtered environment,
 * shading_common.h)]; writes [color, depth].
 * Options: shading, ambient, view (albedo, normal, depth) - see shading_common.h.
 * Variants: PG_ALPHA_MASK only if the scene has alpha-mask materials (a second pipeline for those
 * draws), PG_NORMAL_MAPS only if it has normal maps, PG_BLINN_PHONG for that shading, no light
 * loop (and no light buffer) with 0 lights. */
#include "forward_common.h"

static pg_result fn_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    pg_forward_params *p = pg_decl_params(out, sizeof *p);
    pg_result r = pg_shading_opts_read(in->desc, false, NULL, &p->sh, err);
    if (r) return r;
    p->sh.lights = pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
    p->color = pg_decl_write(out, "color", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    p->depth = pg_decl_write(out, "depth", PG_RES_IMAGE, PG_ACCESS_DEPTH_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_DEPTH);
    pg_scene_draw_declare_features(in, out, &p->draw);
    pg_shading_declare(&p->sh, in, out);
    pg_environment_slot_declare(in, out, &p->sh, PG_STAGE_FRAGMENT, false);
    pg_geometry_slot_declare(in, out, &p->draw, false);
    return PG_OK;
}

const pg_pass_type pg_pass_forward_naive = {
    .name = "forward_naive",
    .summary = "graphics: draw the scene, every fragment shades with every light (exact reference)",
    .instance_size = sizeof(pg_forward_pass),
    .params_size = sizeof(pg_forward_params),
    .declare = fn_declare,
    .create = pg_forward_create,
    .record = pg_forward_record,
    .destroy = pg_forward_destroy,
    .runtime_options = pg_shading_runtime_options,
    .update = pg_forward_update,
};
