/* light_animate.c - compute pass: writes the light buffer (32 bytes a light): first the scene
 * file's KHR_lights_punctual lights (pg_scene_gpu.file_lights), then the generated ones from the
 * seed and the frame time (shaders/light_animate.comp). Slots: writes [lights].
 * Options (file lights only):
 *   "reach": "cutoff" (default) | "infinite": where a file light without a range stops: where its
 *            contribution falls below "cutoff", or nowhere (the reference: the extension's rule)
 *   "cutoff": scene-linear contribution (per channel, N.L = 1) below which such a light is cut,
 *            1e-9..1, default 1e-4: an approximation knob (clustering needs a finite range) */
#include "light_compute.h"
#include "pass_api.h"
#include "frame.h"
#include "scene_gpu.h"
#include "scene_gpu_anim.h"
#include "scene_vars.h"

#include <string.h>

typedef struct la_params { /* filled once by declare, read by create (PG_PARAMS) */
    pg_slot lights;
    bool file_lights; /* the scene has KHR_lights_punctual lights: binding 1 is their table */
} la_params;

typedef struct light_animate { /* the instance create builds: set, layout, pipeline */
    pg_light_compute lc;
} light_animate;

static pg_result la_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {"reach", "cutoff", NULL};
    static const char *const reaches[] = {"cutoff", "infinite", NULL};
    pg_result r = pg_opt_check_known(in->desc, known, err);
    if (r) return r;
    int reach = 0;
    double cutoff = 1e-4;
    if ((r = pg_opt_enum(in->desc, "reach", reaches, 0, &reach, err))) return r;
    if ((r = pg_opt_float(in->desc, "cutoff", 1e-4, 1e-9, 1.0, &cutoff, err))) return r;
    la_params *p = pg_decl_params(out, sizeof *p);
    p->lights = pg_decl_write(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    p->file_lights = pg_scene_features_of(in).has_file_lights;
    if (p->file_lights) {
        pg_decl_define(out, "PG_FILE_LIGHTS");
        if (pg_scene_features_of(in).has_spot_lights) pg_decl_define(out, "PG_SPOT_LIGHTS");
        if (reach == 1) {
            pg_decl_define(out, "PG_INFINITE_REACH");
            pg_decl_explain(out, "file lights without a range reach everything (reach infinite)");
        } else {
            pg_decl_define_int(out, "PG_LIGHT_CUTOFF_NANO", (int64_t)(cutoff * 1e9 + 0.5));
            pg_decl_explain(out, "file lights without a range stop where they add < %g (cutoff: an approximation)",
                            cutoff);
        }
    }
    if (pg_lights_of(in) == 0) pg_decl_explain(out, "0 lights: the animation dispatch records nothing");
    return PG_OK;
}

static pg_result la_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    light_animate *p = self;
    const la_params *pa = PG_PARAMS(ctx, la_params);
    const pg_phys_resource *buffers[2] = {pg_ctx_res(ctx, pa->lights), NULL};
    pg_phys_resource table; /* the scene's file-light table, bound as binding 1 */
    if (pa->file_lights) {
        const pg_scene_gpu *sg = PG_SCENE_OF(ctx);
        if (!sg || !sg->file_lights.buffer)
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s: the scene has file lights but no uploaded table",
                           ctx->pass->name);
        memset(&table, 0, sizeof table);
        table.kind = PG_RES_BUFFER;
        table.buffer = sg->file_lights.buffer;
        table.size = sg->file_lights.size;
        buffers[1] = &table;
    }
    return pg_light_compute_create(ctx, "light_animate.comp", buffers, pa->file_lights ? 2 : 1, &p->lc, err);
}

static void la_record(void *self, const pg_pass_record_ctx *ctx)
{
    const pg_scene_gpu *sg = PG_SCENE_OF(ctx);
    if (sg && sg->anim && sg->anim->n_moving_lights) { /* file lights on animated nodes: placed for this frame */
        const pg_frame_uniforms *fu = PG_FRAME_OF(ctx);
        const int32_t animation = pg_frame_animation(fu);
        pg_scene_gpu_anim_update_lights(sg->anim, sg->file_lights.buffer, animation, fu->camera_pos[3], ctx->cmd);
    }
    pg_light_compute_record(&((light_animate *)self)->lc, ctx); /* one thread a light */
}

static void la_destroy(void *self, pg_gpu *gpu)
{
    pg_light_compute_destroy(&((light_animate *)self)->lc, gpu);
}

const pg_pass_type pg_pass_light_animate = {
    .name = "light_animate",
    .summary = "compute: animate N point lights from (seed, time) into a buffer",
    .instance_size = sizeof(light_animate),
    .params_size = sizeof(la_params),
    .declare = la_declare,
    .create = la_create,
    .record = la_record,
    .destroy = la_destroy,
};
