/* stochastic_lights.c - compute pass: stochastic light culling (shaders/stochastic_lights.comp):
 * each light's range is cut to a random r(xi) where its contribution falls below a threshold, and
 * the shading pass rescales what it keeps (deferred_lighting option stochastic_threshold, the same
 * value), so the expectation of every pixel is exact. Slots: reads [lights], writes
 * [lights_stochastic] (same layout: position and random range; colour and the falloff's range in w).
 * Options: threshold (luminance of one light's attenuated colour below which it is kept at random;
 * > 0). The random numbers come from the frame's sample index and seed. */
#include "light_compute.h"
#include "pass_api.h"
#include "scene_vars.h"

typedef struct sl_params { /* filled once by declare, read by create (PG_PARAMS) */
    pg_slot lights, out;
} sl_params;

typedef struct stochastic_lights { /* the instance create builds */
    pg_light_compute lc;
} stochastic_lights;

static pg_result sl_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {"threshold", NULL};
    pg_result r = pg_opt_check_known(in->desc, known, err);
    if (r) return r;
    double tau;
    if ((r = pg_opt_float(in->desc, "threshold", 0.05, 1e-6, 1e6, &tau, err))) return r;
    sl_params *p = pg_decl_params(out, sizeof *p);
    p->lights = pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_COMPUTE, 0);
    p->out = pg_decl_write(out, "lights_stochastic", PG_RES_BUFFER, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, 0);
    pg_decl_define_float(out, "PG_SC_TAU_MICRO", (double)(int64_t)(tau * 1e6 + 0.5));
    if (pg_scene_features_of(in).has_file_lights) pg_decl_define(out, "PG_GLTF_FALLOFF");
    if (pg_scene_features_of(in).has_spot_lights) pg_decl_define(out, "PG_SPOT_LIGHTS"); /* copy the records */
    pg_decl_explain(out, "threshold %g: lights are cut to random ranges below it (unbiased, noisy)", tau);
    if (pg_lights_of(in) == 0) pg_decl_explain(out, "0 lights: the culling dispatch records nothing");
    return PG_OK;
}

static pg_result sl_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    stochastic_lights *p = self;
    const sl_params *pa = PG_PARAMS(ctx, sl_params);
    const pg_phys_resource *buffers[2] = {pg_ctx_res(ctx, pa->lights), pg_ctx_res(ctx, pa->out)};
    return pg_light_compute_create(ctx, "stochastic_lights.comp", buffers, 2, &p->lc, err);
}

static void sl_record(void *self, const pg_pass_record_ctx *ctx)
{
    pg_light_compute_record(&((stochastic_lights *)self)->lc, ctx);
}

static void sl_destroy(void *self, pg_gpu *gpu)
{
    pg_light_compute_destroy(&((stochastic_lights *)self)->lc, gpu);
}

const pg_pass_type pg_pass_stochastic_lights = {
    .name = "stochastic_lights",
    .summary = "compute: stochastic light culling, a random range per light below a threshold (unbiased)",
    .instance_size = sizeof(stochastic_lights),
    .params_size = sizeof(sl_params),
    .declare = sl_declare,
    .create = sl_create,
    .record = sl_record,
    .destroy = sl_destroy,
};
