/* light_animate.c - compute pass: writes the light buffer (32 bytes a light) from the seed and
 * the frame time (shaders/light_animate.comp). Slots: writes [lights]. No options. */
#include "light_compute.h"
#include "pass_api.h"
#include "scene_vars.h"

typedef struct la_params { /* filled once by declare, read by create (PG_PARAMS) */
    pg_slot lights;
} la_params;

typedef struct light_animate { /* the instance create builds: set, layout, pipeline */
    pg_light_compute lc;
} light_animate;

static pg_result la_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {NULL};
    pg_result r = pg_opt_check_known(in->desc, known, err);
    if (r) return r;
    la_params *p = pg_decl_params(out, sizeof *p);
    p->lights = pg_decl_write(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    if (pg_lights_of(in) == 0) pg_decl_explain(out, "0 lights: the animation dispatch records nothing");
    return PG_OK;
}

static pg_result la_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    light_animate *p = self;
    const la_params *pa = PG_PARAMS(ctx, la_params);
    const pg_phys_resource *buffers[1] = {pg_ctx_res(ctx, pa->lights)};
    return pg_light_compute_create(ctx, "light_animate.comp", buffers, 1, &p->lc, err);
}

static void la_record(void *self, const pg_pass_record_ctx *ctx)
{
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
