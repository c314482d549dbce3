/* reference_lighting.c - the exact reference for any light count, as a compute pass: every pixel
 * of a full-precision G-buffer is shaded with every light, summed in ascending light index order
 * with the same operations as forward_naive (shaders/reference_lighting.comp: pg_accumulate_light
 * and pg_shade_combine of lighting.glsl), so its HDR image is bit-identical to naive's in the same
 * format (tests/test_reference.c). What differs from naive is only the cost model: the lights are
 * streamed through shared memory in tiles of REF_TILE (256, one per thread of a 16x16 workgroup,
 * one barrier pair per tile), and the light loop is split over several dispatches so that none
 * runs long enough to trip a driver watchdog.
 *
 * Split: a dispatch shades the lights [first, first + C) for every pixel. C is the option
 * lights_per_dispatch, or with 0 (auto) the largest multiple of REF_TILE that keeps a dispatch
 * at or below REF_EVALS_PER_DISPATCH = 2^34 light evaluations (pixels x lights; >= one tile):
 * 8192 lights at 1920x1080, 123 dispatches for 1,000,000 lights. A dispatch then takes ~3.4 ms
 * at ~5e12 evaluations/s (~0.4 s a frame) and still only ~0.7 s at 2.5e10/s (what naive's
 * fragment loop reaches on an H100, docs/performance.md), under the 2 s a Windows (TDR) or X
 * watchdog allows. C never exceeds REF_MAX_LIGHTS_PER_DISPATCH (32768, below).
 * With more than one dispatch the running fp32 sums wait in rgba32f storage images: diffuse (the
 * pbr model's one sum) in `accum_diffuse`, Blinn-Phong's specular in `accum_specular`. The first
 * dispatch starts
 * from zero and writes every pixel of them, the middle ones load, add and store, the last one
 * loads, adds, combines and writes the HDR pixel; the pass places its own compute -> compute
 * barrier on them between dispatches (a read and a write of 16 B a pixel each, 2 x 33 MB at
 * 1080p: ~15 us at 4.8 TB/s). fp32 in memory is what the registers held: any split gives the
 * same bits. (Images, not a buffer: a 1080p buffer of 32 B a pixel is 66 MB, past lavapipe's
 * maxStorageBufferRange of 128 MiB from 2048x2048 on; image size limits are per side.)
 *
 * Slots: reads [lights (storage buffer), position (rgba32f, camera-relative: a gbuffer pass with
 *        packing "float" and position_space "camera"), normal (rgba32f), albedo (rgba32f),
 *        emissive (optional, rgba32f: the gbuffer pass's emissive target, added once per pixel by
 *        pg_shade_combine as forward adds it, so the image stays bit-identical to naive's; unused -
 *        not allocated - without emissive materials; not bound: no emission drawn, explain line)]
 *        writes [hdr (storage image, rgba16f or rgba32f, every pixel written),
 *                accum_diffuse, accum_specular (rgba32f storage images of hdr's size, written by
 *                the first dispatch before any other reads them; declared unused - so not
 *                allocated - when one dispatch does: 0 lights, a debug view, or no more lights
 *                than one dispatch takes at the compiled output size; accum_specular also with
 *                lambert and pbr shading)].
 * Options: shading, ambient, view (none, albedo, normal, depth) as forward_naive;
 *          lights_per_dispatch (0 = auto, default; else 1..32768);
 *          environment_samples (1..1024, default 256): with an environment light in the scene, the
 *          pixel's environment term is a Monte Carlo integral over its full-resolution texels, that
 *          many rounds of a cosine, a GGX and an environment-table sample combined by multiple
 *          importance sampling (shaders/reference_lighting.comp PG_REFERENCE_ENV): unbiased, and its
 *          noise is the reference's error there (at most 1024: lavapipe ends a shader's loops after
 *          65535 iterations in all, and a dispatch's light loop may take 32896 of them) (the other pipelines use the filtered
 *          environment: environment_filter). */
#include <stdio.h>
#include <string.h>

#include "frame.h"
#include "shader.h"
#include "shading_common.h"
#include "scene_vars.h"

#define REF_TILE_X 16u
#define REF_TILE_Y 16u
#define REF_TILE (REF_TILE_X * REF_TILE_Y)
#define REF_EVALS_PER_DISPATCH (1ull << 34)
/* llvmpipe (lavapipe) ends every loop of a shader invocation once all its loops together have
 * run 65535 iterations (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS, "shared between every loop in a
 * shader"); a dispatch of 32768 lights runs 32768 + 128 iterations, well inside it. */
#define REF_MAX_LIGHTS_PER_DISPATCH 32768u

enum { REF_MODE_LOAD = 1u, REF_MODE_STORE = 2u };

typedef struct ref_params { /* filled once by declare, read by create/update/record */
    pg_shading_params sh;         /* options, the light slot */
    uint32_t lights_per_dispatch; /* 0: auto */
    pg_slot surface[3];           /* position, normal, albedo */
    pg_slot emissive;             /* PG_SLOT_NONE when not bound */
    pg_slot hdr, accum[2];        /* accum_diffuse, accum_specular */
    bool env;                     /* the scene's environment by Monte Carlo (PG_REFERENCE_ENV) */
} ref_params;

typedef struct reference_lighting {
    uint32_t lights_per_dispatch; /* 0: auto */
    float ambient;                /* option "ambient" (a run-time value): push constant */
    bool has_lights, has_accum, has_emissive, has_env;
    uint32_t n_accum;             /* sum images bound: 1 (diffuse), 2 (+ specular) */
    pg_slot light_slot, hdr, accum[2];
    VkSampler sampler;
    pg_pass_set surface, lights;
    VkPipelineLayout layout;
    VkPipeline pipeline;
} reference_lighting;

static const char *const k_extra[] = {"lights_per_dispatch", "cull_lights", "environment_samples", NULL};
static const char *const k_surface_slots[3] = {"position", "normal", "albedo"};

static pg_result ref_options(const pg_pass_desc *desc, pg_shading_params *sp, uint32_t *lpd, pg_error *err)
{
    int64_t v;
    pg_result r;
    if ((r = pg_shading_opts_read(desc, false, k_extra, sp, err))) return r;
    if ((r = pg_opt_int(desc, "lights_per_dispatch", 0, 0, REF_MAX_LIGHTS_PER_DISPATCH, &v, err))) return r;
    *lpd = (uint32_t)v;
    return PG_OK;
}

/* The exact shading needs the surface in full precision and the position camera-relative as the
 * forward shaders see it: rgba32f targets, the position written by a gbuffer pass with packing
 * "float" and position_space "camera" (a world-space position would round when the camera is
 * subtracted again, an rgba16f one much more). */
static pg_result ref_check_surface(const pg_declare_in *in, pg_error *err)
{
    const pg_pass_desc *d = in->desc;
    pg_result r;
    if (d->n_reads != 4 && d->n_reads != 5) return PG_OK; /* the compiler reports the slot count */
    for (uint32_t k = 1; k < 4; k++) {
        const pg_resource_desc *rd = pg_pipeline_find_resource(in->pipeline, d->reads[k]);
        if (rd && rd->kind == PG_RES_IMAGE && rd->format != PG_FMT_RGBA32F)
            return pg_fail(err, PG_ERR_FORMAT,
                           "%s: %s.reads[%u]: reference_lighting reads the %s target as rgba32f (full precision), "
                           "resource '%s' is %s",
                           d->file, d->json_path, k, k_surface_slots[k - 1], rd->name, pg_format_get(rd->format)->name);
    }
    for (uint32_t k = 1; k < 3 && d->n_writes == 3; k++) {
        const pg_resource_desc *rd = pg_pipeline_find_resource(in->pipeline, d->writes[k]);
        if (rd && rd->kind == PG_RES_IMAGE && rd->format != PG_FMT_RGBA32F)
            return pg_fail(err, PG_ERR_FORMAT,
                           "%s: %s.writes[%u]: reference_lighting keeps its running sums in rgba32f (any other format "
                           "would round them between dispatches), resource '%s' is %s",
                           d->file, d->json_path, k, rd->name, pg_format_get(rd->format)->name);
    }
    const char *pos = d->reads[1];
    for (uint32_t i = 0; i < in->pipeline->n_passes; i++) {
        const pg_pass_desc *q = &in->pipeline->passes[i];
        bool writes = false;
        for (uint32_t k = 0; k < q->n_writes && !writes; k++) writes = strcmp(q->writes[k], pos) == 0;
        if (!writes) continue;
        char packing[PG_NAME_MAX] = "", space[PG_NAME_MAX] = "";
        const bool gbuffer = !strcmp(q->type, "gbuffer"), resolve = !strcmp(q->type, "visibility_resolve");
        if (gbuffer || resolve)
            if ((r = pg_opt_string(q, "packing", gbuffer ? "float" : "packed", packing, sizeof packing, err))) return r;
        if (gbuffer && (r = pg_opt_string(q, "position_space", "world", space, sizeof space, err))) return r;
        /* visibility_resolve's float layout is camera-relative */
        if (resolve && !strcmp(packing, "float")) continue;
        if (!gbuffer || strcmp(packing, "float") || strcmp(space, "camera"))
            return pg_fail(err, PG_ERR_SCHEMA,
                           "%s: %s.reads[1]: reference_lighting needs camera-relative positions: '%s' must be written "
                           "by a gbuffer pass with options packing \"float\" and position_space \"camera\", or by a "
                           "visibility_resolve pass with packing \"float\", but pass '%s' (%s%s%s%s%s) writes it",
                           d->file, d->json_path, pos, q->name, q->type, packing[0] ? ", packing " : "", packing,
                           space[0] ? ", position_space " : "", space);
    }
    return PG_OK;
}

/* Lights a dispatch takes: the option, or (auto) the most whole tiles within the evaluation
 * budget at the output size, at least one tile. declare() and record() both use it, with the
 * size the graph was compiled for. */
static uint32_t ref_chunk(uint32_t lights_per_dispatch, uint32_t width, uint32_t height)
{
    if (lights_per_dispatch) return lights_per_dispatch;
    uint64_t pixels = (uint64_t)width * height;
    uint64_t c = REF_EVALS_PER_DISPATCH / (pixels ? pixels : 1) / REF_TILE * REF_TILE;
    if (c < REF_TILE) c = REF_TILE;
    return c > REF_MAX_LIGHTS_PER_DISPATCH ? REF_MAX_LIGHTS_PER_DISPATCH : (uint32_t)c;
}

static uint32_t ref_dispatches(uint32_t lights, uint32_t chunk)
{
    return lights ? (uint32_t)(((uint64_t)lights + chunk - 1) / chunk) : 1;
}

/* The images sized like hdr (the surface, the emissive target, the running sums: those in use) must have
 * its extent for the output size the graph is compiled for. */
static pg_result ref_check_sizes(const pg_declare_in *in, pg_pass_decl *out, const ref_params *p, bool emissive,
                                 pg_error *err)
{
    const pg_resource_desc *hdr = pg_decl_slot_resource(in, p->hdr, PG_RES_IMAGE, NULL, 0);
    if (!hdr) return PG_OK;
    uint64_t hw, hh;
    pg_resource_extent(hdr, in->output_width, in->output_height, &hw, &hh);
    pg_slot sized[6];
    uint32_t n_sized = 0;
    for (uint32_t t = 0; t < 3; t++) sized[n_sized++] = p->surface[t];
    if (emissive) sized[n_sized++] = p->emissive;
    for (uint32_t t = 0; t < 2; t++)
        if (pg_decl_slot(out, p->accum[t]) && !pg_decl_slot(out, p->accum[t])->unused) sized[n_sized++] = p->accum[t];
    for (uint32_t k = 0; k < n_sized; k++) {
        char where[32];
        const pg_resource_desc *im = pg_decl_slot_resource(in, sized[k], PG_RES_IMAGE, where, sizeof where);
        if (!im) continue;
        uint64_t w, h;
        pg_resource_extent(im, in->output_width, in->output_height, &w, &h);
        if (w != hw || h != hh)
            return pg_fail(err, PG_ERR_INVALID_ARG,
                           "%s: %s.%s: pass '%s' slot %s: '%s' is %llux%llu, hdr is %llux%llu: the G-buffer and the "
                           "running sums must have the size of the image they are shaded into",
                           in->desc->file, in->desc->json_path, where, in->desc->name, pg_decl_slot(out, sized[k])->name,
                           im->name, (unsigned long long)w, (unsigned long long)h, (unsigned long long)hw,
                           (unsigned long long)hh);
    }
    return PG_OK;
}

/* The environment light by Monte Carlo over the scene's texels (option environment_samples). */
static pg_result ref_env_declare(const pg_declare_in *in, pg_pass_decl *out, ref_params *p, pg_error *err)
{
    int64_t samples;
    pg_result r = pg_opt_int(in->desc, "environment_samples", 256, 1, 1024, &samples, err);
    if (r) return r;
    p->env = pg_scene_features_of(in).has_environment && p->sh.o.view == 0;
    if (!p->env) return PG_OK;
    pg_decl_define(out, "PG_REFERENCE_ENV");
    pg_decl_define_int(out, "PG_REF_ENV_SAMPLES", samples);
    pg_decl_explain(out, "environment light: Monte Carlo over the full-resolution environment, %lld rounds a pixel of "
                         "cosine, %sand environment-table samples with multiple importance sampling "
                         "(environment_samples; unbiased, its noise is the reference's error)",
                    (long long)samples, pg_shading_model(in, p->sh.o.shading) == PG_SHADING_PBR ? "GGX " : "");
    return PG_OK;
}

static pg_result ref_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    ref_params *p = pg_decl_params(out, sizeof *p);
    uint32_t lpd;
    pg_result r;
    if ((r = ref_options(in->desc, &p->sh, &lpd, err))) return r;
    const pg_shading_opts o = p->sh.o;
    p->lights_per_dispatch = lpd;
    if ((r = ref_check_surface(in, err))) return r;
    p->sh.lights = pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_COMPUTE, 0);
    for (uint32_t t = 0; t < 3; t++)
        p->surface[t] =
            pg_decl_read(out, k_surface_slots[t], PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_COMPUTE, PG_FMTCLASS_FLOAT);
    bool emissive;
    if ((r = pg_emissive_slot_declare(in, out, false, true, &p->emissive, &emissive, err))) return r;
    if (emissive) pg_decl_define(out, "PG_REFERENCE_EMISSIVE");
    p->hdr = pg_decl_write(out, "hdr", PG_RES_IMAGE, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, PG_FMTCLASS_FLOAT);
    if ((r = pg_hdr_storage_check(in, p->hdr, "reference lighting", err))) return r;
    /* read and written by the later dispatches, written in full by the first one before any
     * later one reads them: the pass initializes them itself */
    p->accum[0] =
        pg_decl_write(out, "accum_diffuse", PG_RES_IMAGE, PG_ACCESS_STORAGE_RW, PG_STAGE_COMPUTE, PG_FMTCLASS_FLOAT);
    pg_decl_mark_initializes(out, p->accum[0]);
    p->accum[1] =
        pg_decl_write(out, "accum_specular", PG_RES_IMAGE, PG_ACCESS_STORAGE_RW, PG_STAGE_COMPUTE, PG_FMTCLASS_FLOAT);
    pg_decl_mark_initializes(out, p->accum[1]);
    const int model = pg_shading_model(in, o.shading);
    pg_decl_define_int(out, "LIGHT_TILE_X", REF_TILE_X);
    pg_decl_define_int(out, "LIGHT_TILE_Y", REF_TILE_Y);
    pg_shading_declare(&p->sh, in, out);
    bool cull;
    if ((r = pg_opt_bool(in->desc, "cull_lights", true, &cull, err))) return r;
    if (cull && p->sh.has_lights && o.view == 0) pg_decl_define(out, "PG_REFERENCE_CULL");
    uint32_t n = pg_lights_of(in);
    const bool lit = p->sh.has_lights;
    uint32_t chunk = ref_chunk(lpd, in->output_width, in->output_height);
    uint32_t nd = ref_dispatches(n, chunk);
    if (lit && nd > 1) {
        pg_decl_define(out, "PG_REFERENCE_ACCUM");
        pg_decl_explain(out, "%u lights in %u dispatches of <= %u lights (%s), running sums kept between them", n, nd,
                        chunk, lpd ? "lights_per_dispatch" : "auto: <= 2^34 light evaluations and 32768 lights each");
        if (model == PG_SHADING_LAMBERT) pg_decl_mark_unused(out, p->accum[1], "lambert: no specular sum");
        if (model == PG_SHADING_PBR) pg_decl_mark_unused(out, p->accum[1], "pbr: one running sum (accum_diffuse)");
    } else {
        char why[160];
        if (!lit) snprintf(why, sizeof why, "%s", n == 0 ? "0 lights" : "debug view reads no lights");
        else snprintf(why, sizeof why, "%u lights fit one dispatch (<= %u lights, %s)", n, chunk,
                      lpd ? "lights_per_dispatch" : "auto: <= 2^34 light evaluations and 32768 lights");
        pg_decl_mark_unused(out, p->accum[0], why);
        pg_decl_mark_unused(out, p->accum[1], why);
    }
    if ((r = ref_env_declare(in, out, p, err))) return r;
    return ref_check_sizes(in, out, p, emissive, err);
}

static pg_result ref_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    reference_lighting *p = self;
    pg_gpu *gpu = ctx->gpu;
    const ref_params *pa = PG_PARAMS(ctx, ref_params);
    pg_result r;
    p->lights_per_dispatch = pa->lights_per_dispatch;
    p->ambient = pa->sh.ambient;
    p->has_lights = pa->sh.has_lights;
    p->light_slot = pa->sh.lights;
    p->hdr = pa->hdr;
    p->accum[0] = pa->accum[0];
    p->accum[1] = pa->accum[1];
    p->has_emissive = pg_slot_ok(pa->emissive) && !pg_ctx_unused(ctx, pa->emissive);
    p->has_accum = !pg_ctx_unused(ctx, pa->accum[0]);
    p->n_accum = !p->has_accum ? 0 : pg_ctx_unused(ctx, pa->accum[1]) ? 1 : 2;
    const pg_phys_resource *hdr = pg_ctx_res(ctx, pa->hdr); /* rgba16f or rgba32f (declare) */
    /* the images sized like hdr have its extent (declare) */
    if ((r = pg_sampler_create(gpu, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, &p->sampler, err))) return r;
    pg_set_binding b[10];
    uint32_t n = 0;
    for (uint32_t t = 0; t < 3; t++)
        b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pg_ctx_res(ctx, pa->surface[t]), p->sampler, 0};
    b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, hdr, VK_NULL_HANDLE, 0};
    for (uint32_t k = 0; k < p->n_accum; k++)
        b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, pg_ctx_res(ctx, pa->accum[k]), VK_NULL_HANDLE, 0};
    if (p->has_emissive) /* EMISSIVE_BINDING in the shader */
        b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pg_ctx_res(ctx, pa->emissive), p->sampler, 0};
    const pg_scene_gpu *sg = PG_SCENE_OF(ctx);
    p->has_env = pa->env;
    if (p->has_env && (!sg || !sg->environment.buffer))
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: the scene has an environment but no uploaded texels",
                       ctx->pass->name);
    const uint32_t env_binding = n;
    pg_phys_resource env_src = {.kind = PG_RES_BUFFER}, env_cdf = {.kind = PG_RES_BUFFER};
    if (p->has_env) { /* the last bindings: the scene's environment texels (level 0 first), its tables */
        env_src.buffer = sg->environment.buffer;
        env_src.size = sg->environment.size;
        b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &env_src, VK_NULL_HANDLE, 0};
        if (sg->env_cdf.buffer) {
            env_cdf.buffer = sg->env_cdf.buffer;
            env_cdf.size = sg->env_cdf.size;
            b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &env_cdf, VK_NULL_HANDLE, 0};
        }
    }
    char name[PG_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s.surface", ctx->pass->name);
    if ((r = pg_pass_set_create(gpu, n, b, name, &p->surface, err))) return r;
    if ((r = pg_light_set_create(ctx, &pa->sh, &p->lights, err))) return r;
    VkDescriptorSetLayout sets[3] = {ctx->frame_layout, p->surface.layout, p->lights.layout};
    if ((r = pg_pipeline_layout_create(gpu, p->lights.layout ? 3 : 2, sets, 4 * sizeof(uint32_t), &p->layout, err)))
        return r;
    const char *defs[PG_MAX_DEFINES + 5];
    uint32_t nd = pg_decl_define_list(&ctx->pass->decl, defs, PG_MAX_DEFINES);
    char fmt_def[48], env_defs[3][48];
    defs[nd++] = pg_hdr_format_define(hdr, fmt_def, sizeof fmt_def);
    if (p->has_env) {
        snprintf(env_defs[0], sizeof env_defs[0], "PG_REFERENCE_ENV_BINDING=%u", env_binding);
        snprintf(env_defs[1], sizeof env_defs[1], "PG_ENV_SRC_W=%u", sg->env_width);
        snprintf(env_defs[2], sizeof env_defs[2], "PG_ENV_SRC_H=%u", sg->env_height);
        for (int k = 0; k < 3; k++) defs[nd++] = env_defs[k];
        if (sg->env_cdf.buffer) defs[nd++] = "PG_REFERENCE_ENV_IS";
    }
    VkShaderModule cs;
    if ((r = pg_shader_module(gpu, "reference_lighting.comp", VK_SHADER_STAGE_COMPUTE_BIT, defs, nd, &cs, err)))
        return r;
    r = pg_compute_pipeline_create(gpu, p->layout, cs, ctx->pass->name, &p->pipeline, err);
    vkDestroyShaderModule(gpu->device, cs, NULL);
    return r;
}

static void ref_record(void *self, const pg_pass_record_ctx *ctx)
{
    reference_lighting *p = self;
    const pg_phys_resource *hdr = pg_ctx_res(ctx, p->hdr);
    VkCommandBuffer cmd = ctx->cmd;
    VkDescriptorSet sets[3] = {ctx->frame_set, p->surface.set, p->lights.set};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, p->lights.set ? 3 : 2, sets, 0, NULL);
    uint32_t gx = (hdr->width + REF_TILE_X - 1) / REF_TILE_X, gy = (hdr->height + REF_TILE_Y - 1) / REF_TILE_Y;
    uint32_t n = 0;
    if (p->has_lights) {
        uint64_t cap = pg_ctx_res(ctx, p->light_slot)->size / 32; /* never read past the light buffer */
        n = PG_FRAME_OF(ctx)->counts[0] < cap ? PG_FRAME_OF(ctx)->counts[0] : (uint32_t)cap;
    }
    uint32_t chunk = ref_chunk(p->lights_per_dispatch, ctx->width, ctx->height);
    /* Without the sum images (the graph was compiled for fewer lights than this frame has) the
     * whole loop runs in one dispatch: slower, never wrong. */
    if (n <= chunk || !p->has_accum) {
        uint32_t pc[4] = {0, n, 0, 0};
        memcpy(&pc[3], &p->ambient, sizeof(float));
        vkCmdPushConstants(cmd, p->layout, PG_PUSH_STAGES,
                           0, sizeof pc, pc);
        vkCmdDispatch(cmd, gx, gy, 1);
        return;
    }
    /* this dispatch's sums -> the next one (read and written again) */
    VkImageMemoryBarrier2 b[2];
    uint32_t nb = p->n_accum;
    for (uint32_t k = 0; k < nb; k++)
        b[k] = pg_image_barrier(pg_ctx_res(ctx, p->accum[k])->image, VK_IMAGE_ASPECT_COLOR_BIT,
                                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL);
    for (uint32_t first = 0; first < n; first += chunk) {
        uint32_t end = n - first > chunk ? first + chunk : n;
        uint32_t mode = (first > 0 ? REF_MODE_LOAD : 0u) | (end < n ? REF_MODE_STORE : 0u);
        uint32_t pc[4] = {first, end, mode, 0};
        memcpy(&pc[3], &p->ambient, sizeof(float));
        vkCmdPushConstants(cmd, p->layout, PG_PUSH_STAGES,
                           0, sizeof pc, pc);
        vkCmdDispatch(cmd, gx, gy, 1);
        if (end < n) pg_cmd_barriers(cmd, nb, b, 0, NULL);
    }
}

static pg_result ref_update(void *self, const void *params, pg_error *err)
{
    (void)err;
    reference_lighting *p = self;
    p->ambient = ((const ref_params *)params)->sh.ambient;
    return PG_OK;
}

static void ref_destroy(void *self, pg_gpu *gpu)
{
    reference_lighting *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    pg_pass_set_destroy(gpu, &p->surface);
    pg_pass_set_destroy(gpu, &p->lights);
    if (p->sampler) vkDestroySampler(gpu->device, p->sampler, NULL);
}

const pg_pass_type pg_pass_reference_lighting = {
    .name = "reference_lighting",
    .summary = "compute: shade every pixel of a float G-buffer with every light in index order, tiled through shared "
               "memory and split over dispatches (exact reference, bit-identical to forward_naive)",
    .instance_size = sizeof(reference_lighting),
    .params_size = sizeof(ref_params),
    .declare = ref_declare,
    .create = ref_create,
    .record = ref_record,
    .destroy = ref_destroy,
    .runtime_options = pg_shading_runtime_options,
    .update = ref_update,
};
