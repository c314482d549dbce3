/* forward_naive.c - the exact reference: draws the scene once with depth, and every fragment
 * loops over every light (shaders/forward.frag without PG_CLUSTERED).
 * Slots: reads [lights] (storage buffer, fragment); writes [color, depth].
 * Options: shading, ambient, view (albedo, normal, depth) - see shading_common.h.
 * Variants: PG_ALPHA_MASK only if the scene has alpha-mask materials (a second pipeline for those
 * draws), PG_NORMAL_MAPS only if it has normal maps, PG_BLINN_PHONG for that shading, no light
 * loop (and no light buffer) with 0 lights. */
#include "forward_common.h"

static pg_result fn_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    pg_shading_opts o;
    pg_result r = pg_shading_opts_read(in->desc, false, NULL, &o, err);
    if (r) return r;
    pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
    pg_decl_write(out, "color", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    pg_decl_write(out, "depth", PG_RES_IMAGE, PG_ACCESS_DEPTH_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_DEPTH);
    pg_scene_draw_declare_features(in, out);
    pg_shading_declare(&o, in, out, false, 0, -1);
    return PG_OK;
}

static pg_result fn_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    return pg_forward_create(self, ctx, false, false, false, err);
}

const pg_pass_type pg_pass_forward_naive = {
    .name = "forward_naive",
    .summary = "graphics: draw the scene, every fragment shades with every light (exact reference)",
    .read_slots = "lights",
    .write_slots = "color, depth",
    .instance_size = sizeof(pg_forward_pass),
    .declare = fn_declare,
    .create = fn_create,
    .record = pg_forward_record,
    .destroy = pg_forward_destroy,
    .runtime_options = pg_shading_runtime_options,
    .update = pg_forward_update,
};
