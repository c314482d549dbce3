/* deferred_lighting.c - compute pass: for every pixel, rebuild position, normal and material
 * from the G-buffer of one packing variant and shade it with the lights of its cluster
 * (shaders/deferred_lighting.comp; same light model and summation order as forward).
 * Slots: reads [lights, cluster_counts, cluster_lights, depth, G-buffer targets of the variant,
 *               emissive (optional: the gbuffer pass's emissive target, added once per pixel as
 *               forward adds it; unused - not allocated - without emissive materials; not bound:
 *               no emission drawn, explain line), environment (optional, after the emissive slot: the
 *               filtered environment, shading_common.h)]
 *        writes [hdr] (storage image, every pixel written).
 * packing "visibility": the one "target" is the visibility pass's triangle id (r32ui); the surface
 * is rebuilt from the triangle, its vertex streams and its material here (visibility_common.h,
 * shaders/visibility_surface.glsl; the scene's set is bound as set 3), with the material variant
 * the scene needs; no emissive slot (the material's emission is evaluated here).
 * Options: packing (as gbuffer, or visibility), shading, ambient, view, tile_size (8 or 16, default
 * 8: the workgroup is tile_size x tile_size pixels), tile_lights (default true: each tile culls its clusters' lists against the bounding box of its pixels and shares the
 * kept lights through shared memory; bit-identical to false, with far fewer light evaluations),
 * tile_backface (default true: the tile also drops the lights behind all its pixels' surfaces;
 * bit-identical, fewer evaluations),
 * ris_candidates (0, the default: every light of the list, exact; M > 0: the approximation knob of
 * shaders/shading.glsl pg_ris_estimate, M candidates a sample, resampled importance sampling of
 * the list; no tiling), ris_samples (1..64, default 1: independent RIS samples averaged a pixel),
 * lights ("clusters", the default, or "tree": reads [light_tree, depth, ...] and shades a lightcut
 * a pixel, shaders/shading.glsl pg_lightcut), lightcut_error (0.02: its per-pixel relative bound),
 * lightcut_bucket (a power of two, 1 to 256, default PG_LIGHTCUT_BUCKET_DEFAULT: a node the walk refines
 * whose subtree holds at most that many leaves has them all summed exactly instead of walked; 1: the
 * plain walk),
 * stochastic_threshold (0 = off; > 0: the lights were culled by a stochastic_lights pass with that
 * threshold, and each kept light counts 1/p times, lighting.glsl PG_STOCHASTIC_CULL). */
#include <stdio.h>
#include <string.h>

#include "frame.h"
#include "gbuffer_layout.h"
#include "scene_draw.h"
#include "scene_vars.h"
#include "shader.h"
#include "shading_common.h"
#include "visibility_common.h"

/* lightcut_bucket's default (docs/performance.md, the lightcut's walk) */
#define PG_LIGHTCUT_BUCKET_DEFAULT 32

typedef struct dl_params { /* filled once by declare, read by create/update/record */
    pg_shading_params sh;       /* options, lights and cluster slots */
    pg_scene_draw_features draw;/* packing visibility: the material variant */
    int packing;
    uint32_t tile;              /* option tile_size: workgroup edge in pixels (8 or 16) */
    bool tiled;                 /* PG_TILE_LIGHTS declared */
    pg_slot depth, targets[4], emissive_slot, hdr;
} dl_params;

typedef struct deferred_lighting {
    float ambient;          /* option "ambient" (a run-time value): push constant */
    int packing;
    double far_over_near;
    pg_buffer evals;        /* host-visible 64-bit count of light evaluations (PG_COUNT_EVALS) */
    bool counted;   /* the last recorded frame's (oct16: its depth precision, dl_report) */
    pg_slot hdr;
    uint32_t tile;          /* workgroup edge in pixels (8 or 16) */
    VkSampler sampler;
    pg_pass_set gbuf, lights;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    pg_vis_geometry vis;            /* packing visibility */
    VkDescriptorSetLayout empty;    /* packing visibility without lights: set 2 */
    VkDescriptorSet scene_set;      /* packing visibility: set 3 */
} deferred_lighting;

static const char *const k_extra[] = {"packing",        "tile_lights", "tile_size",      "tile_backface",
                                     "ris_candidates", "ris_samples", "lights",         "lightcut_error",
                                     "lightcut_bucket", "stochastic_threshold", NULL};
static const char *const k_light_sources[] = {"clusters", "tree", NULL};

static pg_result dl_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    dl_params *p = pg_decl_params(out, sizeof *p);
    int packing, source;
    pg_result r;
    if ((r = pg_opt_enum(in->desc, "lights", k_light_sources, 0, &source, err))) return r;
    if ((r = pg_shading_opts_read(in->desc, source == 0, k_extra, &p->sh, err))) return r;
    if ((r = pg_opt_enum(in->desc, "packing", pg_gbuffer_packings, 0, &packing, err))) return r;
    p->packing = packing;
    if (source == 1) { /* lightcut: reads [light_tree, depth, targets...] */
        p->sh.lights = pg_decl_read(out, "light_tree", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_COMPUTE, 0);
        p->sh.cluster_counts = p->sh.cluster_lists = PG_SLOT_NONE;
    } else {
        p->sh.lights = pg_decl_read(out, "lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_COMPUTE, 0);
        p->sh.cluster_counts =
            pg_decl_read(out, "cluster_counts", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_COMPUTE, 0);
        p->sh.cluster_lists =
            pg_decl_read(out, "cluster_lights", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, PG_STAGE_COMPUTE, 0);
        if ((r = pg_shading_grid_declare(&p->sh, in, err))) return r;
    }
    p->depth = pg_decl_read(out, "depth", PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_COMPUTE, PG_FMTCLASS_DEPTH);
    for (uint32_t t = 0; t < pg_gbuffer_targets[packing]; t++)
        p->targets[t] = pg_decl_read(out, pg_gbuffer_slot_names[packing][t], PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_COMPUTE,
                     packing >= PG_GBUFFER_PACKED ? PG_FMTCLASS_UINT : PG_FMTCLASS_FLOAT);
    bool emissive = false;
    const uint32_t light_reads = source == 1 ? 1 : 3;
    if (packing == PG_GBUFFER_VISIBILITY) {
        const uint32_t extra = light_reads + 2; /* the optional environment and geometry slots may follow */
        const pg_resource_desc *rd =
            in->desc->n_reads > extra ? pg_pipeline_find_resource(in->pipeline, in->desc->reads[extra]) : NULL;
        if (in->desc->n_reads > extra + 2 || (rd && rd->kind == PG_RES_IMAGE))
            return pg_fail(err, PG_ERR_SCHEMA,
                           "%s: %s.reads[%u]: packing \"visibility\" takes no emissive target (the material's "
                           "emission is evaluated in this pass)",
                           in->desc->file, in->desc->json_path, light_reads + 2);
        pg_scene_draw_declare_features(in, out, &p->draw);
    } else if ((r = pg_emissive_slot_declare(in, out, false, false, &p->emissive_slot, &emissive, err))) {
        return r;
    }
    p->hdr = pg_decl_write(out, "hdr", PG_RES_IMAGE, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, PG_FMTCLASS_FLOAT);
    if ((r = pg_hdr_storage_check(in, p->hdr, "deferred lighting", err))) return r;
    pg_decl_define(out, pg_gbuffer_defines[packing]);
    if (emissive) pg_decl_define(out, "PG_DEFERRED_EMISSIVE");
    pg_shading_declare(&p->sh, in, out);
    pg_environment_slot_declare(in, out, &p->sh, PG_STAGE_COMPUTE, true);
    if (packing == PG_GBUFFER_VISIBILITY) pg_geometry_slot_declare(in, out, &p->draw, true);
    bool tiled;
    int64_t tile;
    if ((r = pg_opt_bool(in->desc, "tile_lights", true, &tiled, err))) return r;
    if ((r = pg_opt_int(in->desc, "tile_size", 8, 8, 16, &tile, err))) return r;
    if (tile != 8 && tile != 16)
        return pg_fail(err, PG_ERR_SCHEMA, "%s: %s.options.tile_size: expected 8 or 16, got %lld", in->desc->file,
                       in->desc->json_path, (long long)tile);
    p->tile = (uint32_t)tile;
    pg_decl_define_int(out, "PG_TILE", tile);
    bool backface;
    if ((r = pg_opt_bool(in->desc, "tile_backface", true, &backface, err))) return r;
    int64_t ris_m, ris_s;
    if ((r = pg_opt_int(in->desc, "ris_candidates", 0, 0, 4096, &ris_m, err))) return r;
    if ((r = pg_opt_int(in->desc, "ris_samples", 1, 1, 64, &ris_s, err))) return r;
    if (ris_m > 0 && source == 1)
        return pg_fail(err, PG_ERR_SCHEMA, "%s: %s.options.ris_candidates: resampling draws from cluster lists: it "
                       "needs lights \"clusters\", not \"tree\"", in->desc->file, in->desc->json_path);
    bool ris = ris_m > 0 && p->sh.o.view == 0 && pg_lights_of(in) > 0;
    if (ris) {
        pg_decl_define(out, "PG_RIS");
        pg_decl_define_int(out, "PG_RIS_M", ris_m);
        pg_decl_define_int(out, "PG_RIS_S", ris_s);
        pg_decl_explain(out, "ris_candidates %lld, ris_samples %lld: an approximation (unbiased): %lld light "
                        "evaluations a pixel instead of its whole cluster list", (long long)ris_m, (long long)ris_s,
                        (long long)(ris_m * ris_s));
    }
    double sc_tau;
    if ((r = pg_opt_float(in->desc, "stochastic_threshold", 0.0, 0.0, 1e6, &sc_tau, err))) return r;
    if (sc_tau > 0 && source == 0 && pg_lights_of(in) > 0) {
        pg_decl_define(out, "PG_STOCHASTIC_CULL");
        pg_decl_define_float(out, "PG_SC_TAU_MICRO", (double)(int64_t)(sc_tau * 1e6 + 0.5));
        pg_decl_explain(out, "stochastic_threshold %g: the lights (culled by a stochastic_lights pass with the same "
                        "threshold) count 1/p times: unbiased, noisy", sc_tau);
    }
    double lc_eps;
    int64_t lc_bucket;
    if ((r = pg_opt_float(in->desc, "lightcut_error", 0.02, 1e-6, 1.0, &lc_eps, err))) return r;
    if ((r = pg_opt_int(in->desc, "lightcut_bucket", PG_LIGHTCUT_BUCKET_DEFAULT, 1, 256, &lc_bucket, err))) return r;
    if ((lc_bucket & (lc_bucket - 1)) != 0)
        return pg_fail(err, PG_ERR_SCHEMA, "%s: %s.options.lightcut_bucket: expected a power of two (1 to 256), got %lld",
                       in->desc->file, in->desc->json_path, (long long)lc_bucket);
    if (source == 1 && pg_lights_of(in) > 0 && p->sh.o.view == 0) {
        pg_decl_define(out, "PG_LIGHTCUT");
        pg_decl_define_int(out, "PG_LC_EPS_PPM", (int64_t)(lc_eps * 1e6 + 0.5));
        pg_decl_define_int(out, "PG_LC_BUCKET", lc_bucket);
        pg_decl_explain(out, "lights tree: a lightcut a pixel, every pixel within %g of its exact value (relative, "
                        "per channel); a refined subtree of up to %lld lights summed exactly", lc_eps,
                        (long long)lc_bucket);
    }
    if (p->sh.has_lights && p->sh.o.view == 0) { /* light evaluations counted (counter light_evals) */
        pg_decl_define(out, "PG_COUNT_EVALS");
        pg_decl_define_int(out, "PG_EVALS_BINDING", source == 0 ? 3 : 1);
    }
    p->tiled = tiled && !ris && source == 0 && p->sh.o.view == 0 && pg_lights_of(in) > 0;
    if (p->tiled) {
        pg_decl_define(out, "PG_TILE_LIGHTS");
        if (backface) pg_decl_define(out, "PG_TILE_BACKFACE");
    }
    return PG_OK;
}

static pg_result dl_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    deferred_lighting *p = self;
    pg_gpu *gpu = ctx->gpu;
    const dl_params *pa = PG_PARAMS(ctx, dl_params);
    pg_result r;
    p->ambient = pa->sh.ambient;
    p->packing = pa->packing;
    uint32_t n_targets = pg_gbuffer_targets[pa->packing];
    p->hdr = pa->hdr;
    bool vis = pa->packing == PG_GBUFFER_VISIBILITY;
    bool emissive = !vis && pg_slot_ok(pa->emissive_slot) && !pg_ctx_unused(ctx, pa->emissive_slot);
    if (vis && (r = pg_vis_geometry_create(ctx, &pa->draw, 3, &p->vis, err))) return r;
    const pg_phys_resource *hdr = pg_ctx_res(ctx, pa->hdr); /* rgba16f or rgba32f (declare) */
    /* one invocation a pixel of hdr reads the G-buffer at that pixel: another size showed a
     * magnified corner (float) or nearly black (packed) */
    const pg_phys_resource *gsize = pg_ctx_res(ctx, pa->depth);
    if (gsize->width != hdr->width || gsize->height != hdr->height)
        return pg_fail(err, PG_ERR_FORMAT, "%s: %s: its output (%ux%u) and its G-buffer depth (%ux%u) differ in size: "
                                           "the lighting pass reads the G-buffer pixel for pixel",
                       ctx->desc->file, ctx->desc->json_path, hdr->width, hdr->height, gsize->width, gsize->height);
    if ((r = pg_sampler_create(gpu, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, &p->sampler, err))) return r;
    pg_set_binding b[12];
    uint32_t n = 0;
    b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pg_ctx_res(ctx, pa->depth), p->sampler, 0};
    for (uint32_t t = 0; t < n_targets; t++)
        b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pg_ctx_res(ctx, pa->targets[t]), p->sampler, 0};
    b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, hdr, VK_NULL_HANDLE, 0};
    if (emissive) /* binding HDR_BINDING + 1 */
        b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pg_ctx_res(ctx, pa->emissive_slot), p->sampler,
                                  0};
    if (vis) n = pg_vis_geometry_bindings(&p->vis, PG_SCENE_OF(ctx), b, n); /* binding 3 on */
    char name[PG_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s.gbuffer", ctx->pass->name);
    if ((r = pg_pass_set_create(gpu, n, b, name, &p->gbuf, err))) return r;
    p->counted = pa->sh.has_lights && pa->sh.o.view == 0;
    pg_phys_resource ev = {0};
    if (p->counted) {
        snprintf(name, sizeof name, "%s.evals", ctx->pass->name);
        if ((r = pg_buffer_create(gpu, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true,
                                  name, &p->evals, err)))
            return r;
        memset(p->evals.mapped, 0, 16);
        ev = (pg_phys_resource){.kind = PG_RES_BUFFER, .buffer = p->evals.buffer, .size = p->evals.size};
    }
    if ((r = pg_light_set_create_ex(ctx, &pa->sh, p->counted ? &ev : NULL, &p->lights, err))) return r;
    VkDescriptorSetLayout sets[4] = {ctx->frame_layout, p->gbuf.layout, p->lights.layout, VK_NULL_HANDLE};
    uint32_t n_sets = p->lights.layout ? 3 : 2;
    if (vis) { /* set 3: the scene's materials and textures (set 2 stays empty without lights) */
        if (!p->lights.layout) {
            VkDescriptorSetLayoutCreateInfo eci = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
            PG_VK_TRY(err, vkCreateDescriptorSetLayout(gpu->device, &eci, NULL, &p->empty));
            sets[2] = p->empty;
        }
        sets[3] = PG_SCENE_OF(ctx)->set_layout;
        p->scene_set = PG_SCENE_OF(ctx)->set;
        n_sets = 4;
    }
    if ((r = pg_pipeline_layout_create(gpu, n_sets, sets, sizeof(float), &p->layout, err))) return r;
    const char *defs[PG_MAX_DEFINES + 16];
    uint32_t nd = 0;
    if (vis) nd = pg_vis_geometry_define_list(&p->vis, defs);
    else nd = pg_decl_define_list(&ctx->pass->decl, defs, PG_MAX_DEFINES);
    char fmt_def[48], wbuf[2][40];
    defs[nd++] = pg_hdr_format_define(hdr, fmt_def, sizeof fmt_def);
    nd += pg_light_set_defines(ctx, &pa->sh, wbuf, defs + nd);
    const bool tiled = pa->tiled;
    p->tile = pa->tile;
    /* the tiled path orders lights within a subgroup by ballots when every subgroup is full */
    uint32_t tile_n = p->tile * p->tile;
    bool subgroups = tiled && gpu->exact_subgroups && gpu->subgroup_size <= tile_n && tile_n % gpu->subgroup_size == 0;
    if (subgroups) defs[nd++] = "PG_TILE_SUBGROUPS";
    VkShaderModule cs;
    if ((r = pg_shader_module(gpu, "deferred_lighting.comp", VK_SHADER_STAGE_COMPUTE_BIT, defs, nd, &cs, err)))
        return r;
    pg_compute_pipeline_desc pd = {.layout = p->layout, .cs = cs, .subgroup_size = subgroups ? gpu->subgroup_size : 0};
    r = pg_compute_pipeline_create_ex(gpu, &pd, ctx->pass->name, &p->pipeline, err);
    vkDestroyShaderModule(gpu->device, cs, NULL);
    return r;
}

static void dl_record(void *self, const pg_pass_record_ctx *ctx)
{
    deferred_lighting *p = self;
    const pg_phys_resource *hdr = pg_ctx_res(ctx, p->hdr);
    pg_vis_geometry_record(&p->vis, ctx); /* packing visibility: the draws the pose mirrors */
    if (p->counted) { /* the count is the pass's own: zeroed, then written by the dispatch */
        vkCmdFillBuffer(ctx->cmd, p->evals.buffer, 0, VK_WHOLE_SIZE, 0);
        VkBufferMemoryBarrier2 bb = pg_buffer_barrier(p->evals.buffer, VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                                                      VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        pg_cmd_barriers(ctx->cmd, 0, NULL, 1, &bb);
    }
    VkDescriptorSet sets[3] = {ctx->frame_set, p->gbuf.set, p->lights.set};
    vkCmdBindPipeline(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, p->lights.set ? 3 : 2, sets, 0,
                            NULL);
    if (p->scene_set)
        vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 3, 1, &p->scene_set, 0, NULL);
    vkCmdPushConstants(ctx->cmd, p->layout, PG_PUSH_STAGES, 0, sizeof(float), &p->ambient);
    const pg_frame_uniforms *fu = PG_FRAME_OF(ctx);
    p->far_over_near = fu->clip[0] > 0 ? (double)fu->clip[1] / fu->clip[0] : 0;
    vkCmdDispatch(ctx->cmd, (hdr->width + p->tile - 1) / p->tile, (hdr->height + p->tile - 1) / p->tile, 1);
    if (p->counted) {
        VkBufferMemoryBarrier2 bb = pg_buffer_barrier(p->evals.buffer, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                                      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                                                      VK_ACCESS_2_HOST_READ_BIT);
        pg_cmd_barriers(ctx->cmd, 0, NULL, 1, &bb);
    }
}

/* oct16 rebuilds positions from the D32 depth, whose relative view-depth error near the far plane
 * is about 2^-25 far/near (docs/accuracy.md, "Position from depth"): past far/near = 1e5 the
 * documented display bound no longer holds (test_gpu_framing check_near_plane), and the frame says so */
#define PG_OCT16_MAX_DEPTH_RATIO 1e5

static void dl_report(void *self, pg_pass_report *out)
{
    deferred_lighting *p = self;
    if (p->counted) {
        const uint32_t *c = p->evals.mapped;
        pg_report_add(out, "light_evals", ((uint64_t)c[1] << 32) | c[0]);
    }
    if (p->packing == PG_GBUFFER_OCT16 && p->far_over_near > PG_OCT16_MAX_DEPTH_RATIO * 1.001)
        pg_report_note(out, "gbuffer oct16 rebuilds positions from D32 depth: far/near = %.3g (past %.0e) gives "
                       "view depths off by up to %.2g%% near the far plane, beyond the documented oct16 bounds; "
                       "gbuffer=packed stores the view depth", p->far_over_near, PG_OCT16_MAX_DEPTH_RATIO,
                       100.0 * p->far_over_near / 33554432.0);
}

static pg_result dl_update(void *self, const void *params, pg_error *err)
{
    (void)err;
    deferred_lighting *p = self;
    p->ambient = ((const dl_params *)params)->sh.ambient;
    return PG_OK;
}

static void dl_destroy(void *self, pg_gpu *gpu)
{
    deferred_lighting *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    pg_pass_set_destroy(gpu, &p->gbuf);
    pg_pass_set_destroy(gpu, &p->lights);
    pg_vis_geometry_destroy(gpu, &p->vis);
    if (p->empty) vkDestroyDescriptorSetLayout(gpu->device, p->empty, NULL);
    if (p->sampler) vkDestroySampler(gpu->device, p->sampler, NULL);
    pg_buffer_destroy(gpu, &p->evals);
}

const pg_pass_type pg_pass_deferred_lighting = {
    .name = "deferred_lighting",
    .summary = "compute: shade every pixel from the G-buffer with the lights of its cluster",
    .instance_size = sizeof(deferred_lighting),
    .params_size = sizeof(dl_params),
    .declare = dl_declare,
    .create = dl_create,
    .record = dl_record,
    .destroy = dl_destroy,
    .report = dl_report,
    .runtime_options = pg_shading_runtime_options,
    .update = dl_update,
};
