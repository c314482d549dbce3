/* luminance_histogram.c - compute pass: counts the pixels of an HDR image per bin of log2
 * luminance (shaders/luminance_histogram.comp). Luminance is Rec.709's (0.2126 R + 0.7152 G +
 * 0.0722 B); bin = floor((log2 L - min_ev) / (max_ev - min_ev) * bins), clamped to [0, bins - 1],
 * so values outside the range (and L <= 0) land in the end bins.
 * Slots: reads [hdr] (sampled, float class); writes [histogram] (storage buffer of `bins` uint32
 * counts, cleared by the pass itself: storage_rw marked initializes).
 * Options: bins (8..256, default 64; a shader variant), min_ev, max_ev (defaults -8 and 8;
 * run-time values, push constants). The pass has side effects: its buffer is for the host. */
#include <string.h>

#include "graph_execute.h"
#include "pass_api.h"
#include "pass_set.h"
#include "shader.h"
#include "vk_pipeline.h"

typedef struct lh_params { /* filled once by declare, read by create/update */
    uint32_t bins;
    float min_ev, max_ev;
    pg_slot hdr, histogram;
} lh_params;

typedef struct luminance_histogram { /* the instance create builds */
    float range[2];      /* min_ev, max_ev (run-time values): push constants */
    pg_slot hdr;
    VkSampler sampler;
    pg_pass_set set;
    VkPipelineLayout layout;
    VkPipeline pipeline;
} luminance_histogram;

static const char *const k_runtime[] = {"min_ev", "max_ev", NULL};

/* the bytes of a buffer resource for this compile (count terms resolved as the compiler does) */
static uint64_t lh_buffer_bytes(const pg_declare_in *in, const pg_resource_desc *rd)
{
    uint64_t n = rd->stride;
    for (uint32_t i = 0; i < rd->n_count_terms; i++) {
        const pg_count_term *t = &rd->count[i];
        n *= t->kind == PG_COUNT_VAR      ? (uint64_t)pg_var(in, t->var)
             : t->kind == PG_COUNT_PIXELS ? (uint64_t)in->output_width * in->output_height
                                          : (uint64_t)t->value;
    }
    return n;
}

static pg_result lh_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {"bins", "min_ev", "max_ev", NULL};
    const pg_pass_desc *d = in->desc;
    pg_result r;
    int64_t bins;
    double min_ev, max_ev;
    if ((r = pg_opt_check_known(d, known, err))) return r;
    if ((r = pg_opt_int(d, "bins", 64, 8, 256, &bins, err))) return r;
    if ((r = pg_opt_float(d, "min_ev", -8.0, -64.0, 64.0, &min_ev, err))) return r;
    if ((r = pg_opt_float(d, "max_ev", 8.0, -64.0, 64.0, &max_ev, err))) return r;
    if (!(min_ev < max_ev))
        return pg_fail(err, PG_ERR_SCHEMA, "%s: %s.options.max_ev: must be greater than min_ev (%g), got %g", d->file,
                       d->json_path, min_ev, max_ev);
    lh_params *p = pg_decl_params(out, sizeof *p);
    p->bins = (uint32_t)bins;
    p->min_ev = (float)min_ev;
    p->max_ev = (float)max_ev;
    pg_decl_runtime_param(out, &p->min_ev, sizeof p->min_ev);
    pg_decl_runtime_param(out, &p->max_ev, sizeof p->max_ev);
    p->hdr = pg_decl_read(out, "hdr", PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_COMPUTE, PG_FMTCLASS_FLOAT);
    /* the first dispatch clears every bin, the second adds to them: read and written, but
     * initialized by the pass itself */
    p->histogram = pg_decl_write(out, "histogram", PG_RES_BUFFER, PG_ACCESS_STORAGE_RW, PG_STAGE_COMPUTE, 0);
    pg_decl_mark_initializes(out, p->histogram);
    out->side_effects = true; /* nothing in the graph reads the counts: the host does */
    pg_decl_define_int(out, "HIST_BINS", bins);
    /* the buffer must hold the bins: known from the plan, so refused here (dump refuses it too) */
    const pg_resource_desc *rd = d->n_writes == 1 ? pg_pipeline_find_resource(in->pipeline, d->writes[0]) : NULL;
    if (rd && rd->kind == PG_RES_BUFFER && lh_buffer_bytes(in, rd) < (uint64_t)bins * 4)
        return pg_fail(err, PG_ERR_SCHEMA,
                       "%s: %s.writes[0]: buffer '%s' has %llu bytes, the histogram needs %lld (bins x 4)", d->file,
                       d->json_path, rd->name, (unsigned long long)lh_buffer_bytes(in, rd), (long long)bins * 4);
    return PG_OK;
}

static pg_result lh_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    luminance_histogram *p = self;
    pg_gpu *gpu = ctx->gpu;
    const lh_params *pa = PG_PARAMS(ctx, lh_params);
    pg_result r;
    p->range[0] = pa->min_ev;
    p->range[1] = pa->max_ev;
    p->hdr = pa->hdr;
    if ((r = pg_sampler_create(gpu, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, &p->sampler, err)))
        return r;
    pg_set_binding b[2] = {
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pg_ctx_res(ctx, pa->hdr), p->sampler, 0},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pg_ctx_res(ctx, pa->histogram), VK_NULL_HANDLE, 0},
    };
    if ((r = pg_pass_set_create(gpu, 2, b, ctx->pass->name, &p->set, err))) return r;
    VkDescriptorSetLayout sets[2] = {ctx->frame_layout, p->set.layout};
    if ((r = pg_pipeline_layout_create(gpu, 2, sets, 16, &p->layout, err))) return r;
    const char *defs[PG_MAX_DEFINES];
    uint32_t nd = pg_decl_define_list(&ctx->pass->decl, defs, PG_MAX_DEFINES);
    VkShaderModule cs;
    if ((r = pg_shader_module(gpu, "luminance_histogram.comp", VK_SHADER_STAGE_COMPUTE_BIT, defs, nd, &cs, err)))
        return r;
    r = pg_compute_pipeline_create(gpu, p->layout, cs, ctx->pass->name, &p->pipeline, err);
    vkDestroyShaderModule(gpu->device, cs, NULL);
    return r;
}

static void lh_record(void *self, const pg_pass_record_ctx *ctx)
{
    luminance_histogram *p = self;
    const pg_phys_resource *hdr = pg_ctx_res(ctx, p->hdr);
    VkDescriptorSet sets[2] = {ctx->frame_set, p->set.set};
    vkCmdBindPipeline(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 2, sets, 0, NULL);
    uint32_t pc[4] = {0, 0, 0, 0}; /* min_ev, max_ev, mode (0 clear, 1 count) */
    memcpy(&pc[0], p->range, sizeof p->range);
    vkCmdPushConstants(ctx->cmd, p->layout, PG_PUSH_STAGES, 0, sizeof pc, pc);
    vkCmdDispatch(ctx->cmd, 1, 1, 1);
    /* the clear -> the counting dispatch, within the pass: the pass's own barrier */
    pg_cmd_memory_barrier(ctx->cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    pc[2] = 1;
    vkCmdPushConstants(ctx->cmd, p->layout, PG_PUSH_STAGES, 0, sizeof pc, pc);
    vkCmdDispatch(ctx->cmd, (hdr->width + 15) / 16, (hdr->height + 15) / 16, 1);
}

static pg_result lh_update(void *self, const void *params, pg_error *err)
{
    (void)err;
    luminance_histogram *p = self;
    const lh_params *pa = params;
    p->range[0] = pa->min_ev;
    p->range[1] = pa->max_ev;
    return PG_OK;
}

static void lh_destroy(void *self, pg_gpu *gpu)
{
    luminance_histogram *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    pg_pass_set_destroy(gpu, &p->set);
    if (p->sampler) vkDestroySampler(gpu->device, p->sampler, NULL);
}

const pg_pass_type pg_pass_luminance_histogram = {
    .name = "luminance_histogram",
    .summary = "compute: count an HDR image's pixels per bin of log2 luminance into a buffer",
    .instance_size = sizeof(luminance_histogram),
    .params_size = sizeof(lh_params),
    .declare = lh_declare,
    .create = lh_create,
    .record = lh_record,
    .destroy = lh_destroy,
    .runtime_options = k_runtime,
    .update = lh_update,
};
