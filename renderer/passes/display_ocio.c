/* display_ocio.c - scene-linear HDR -> display image through OpenColorIO (the default display
 * pass; display_tonemap is the simple alternative).
 *
 * create() opens the OCIO config, builds the processor scene_linear -> (display, view), lets OCIO
 * generate its GLSL (core/color/ocio.h rewrites it for Vulkan: LUT samplers at set 1, bindings 1..N),
 * compiles shaders/display_ocio.frag with that code included, and uploads OCIO's LUT textures
 * once (staging buffer, one-shot command buffer with its own barriers, waited for). record()
 * draws one full-screen triangle: exposure (a multiply in scene-linear, push constant), then the
 * OCIO function. The result is display-encoded, so the target is rgba8 (UNORM) or a float
 * format; rgba8_srgb is refused (it would encode a second time).
 *
 * Option stage "compute" (default): a compute pass instead of the full-screen triangle
 * (shaders/display_ocio.comp: the same function, written with imageStore; the ldr image must then
 * be a storage format: rgba8 or a float one), for GPUs whose raster hardware is a small part of
 * the chip; "fragment": the full-screen triangle.
 *
 * Slots: reads [hdr] (sampled, fragment or compute); writes [ldr] (colour attachment, or storage
 * image with stage compute).
 * Options: exposure (> 0, default 1), display, view (strings; "" = the config's defaults), stage.
 * Application settings (pg_ctx_setting) win over the options: "ocio.config" (file; absent: $OCIO,
 * else assets/ocio/config.ocio), "ocio.display", "ocio.view".
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "display_common.h"
#include "exr.h"
#include "graph_execute.h"
#include "ocio.h"
#include "pass_api.h"
#include "shader.h"
#include "pass_set.h"
#include "vk_pipeline.h"

#define DO_MAX_LUTS 15 /* + the hdr binding = pg_pass_set_create's 16 */

typedef struct do_lut {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
    pg_phys_resource res; /* only .view is read (pg_pass_set_create) */
} do_lut;

/* The display and view option strings kept in the params block (the block holds at most
 * PG_MAX_PASS_PARAMS bytes: two names of DO_OPT_NAME_MAX - 1 characters). */
#define DO_OPT_NAME_MAX 128
typedef struct do_params { /* filled once by declare, read by create/update */
    float exposure;        /* a run-time value: push constant */
    bool compute;          /* stage "compute" */
    pg_slot hdr, ldr;
    char display[DO_OPT_NAME_MAX], view[DO_OPT_NAME_MAX]; /* options ("" unless set) */
} do_params;

typedef struct display_ocio {
    bool compute;           /* option stage "compute" */
    uint32_t width, height; /* the ldr image (compute) */
    pg_pass_set set;
    VkSampler nearest, linear;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    uint32_t n_luts;
    do_lut luts[DO_MAX_LUTS];
    float exposure;
    uint32_t ldr_slot; /* plan slot of ldr (stage fragment: pg_pass_begin_rendering) */
} display_ocio;

static const char *const k_known[] = {"exposure", "display", "view", "stage", NULL};
static const char *const k_stages[] = {"compute", "fragment", NULL};

static pg_result do_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    do_params *p = pg_decl_params(out, sizeof *p);
    pg_result r;
    double exposure;
    if ((r = pg_opt_check_known(in->desc, k_known, err))) return r;
    if ((r = pg_opt_float(in->desc, "exposure", 1.0, 1e-6, 1e6, &exposure, err))) return r;
    p->exposure = (float)exposure;
    pg_decl_runtime_param(out, &p->exposure, sizeof p->exposure);
    if ((r = pg_opt_string(in->desc, "display", "", p->display, sizeof p->display, err))) return r;
    if ((r = pg_opt_string(in->desc, "view", "", p->view, sizeof p->view, err))) return r;
    if (in->desc->n_writes >= 1 && in->pipeline) {
        const pg_resource_desc *ldr = pg_pipeline_find_resource(in->pipeline, in->desc->writes[0]);
        if (ldr && ldr->kind == PG_RES_IMAGE && pg_format_get(ldr->format)->srgb)
            return pg_fail(err, PG_ERR_FORMAT,
                           "%s: %s.writes[0]: resource '%s' is %s, but display_ocio writes display-encoded values "
                           "(the OCIO view encodes for the display): use rgba8 (UNORM) or a float format",
                           in->desc->file, in->desc->json_path, ldr->name, pg_format_get(ldr->format)->name);
    }
    int stage;
    if ((r = pg_opt_enum(in->desc, "stage", k_stages, 0, &stage, err))) return r;
    p->compute = stage == 0;
    if (stage == 0) {
        p->hdr = pg_decl_read(out, "hdr", PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_COMPUTE, PG_FMTCLASS_FLOAT);
        p->ldr = pg_decl_write(out, "ldr", PG_RES_IMAGE, PG_ACCESS_STORAGE_WRITE, PG_STAGE_COMPUTE, PG_FMTCLASS_FLOAT);
        char where[32];
        const pg_resource_desc *ldr = pg_decl_slot_resource(in, p->ldr, PG_RES_IMAGE, where, sizeof where);
        if (ldr && !pg_format_get(ldr->format)->storage_ok)
            return pg_fail(err, PG_ERR_FORMAT,
                           "%s: %s.%s: pass '%s' slot ldr: stage \"compute\" writes the display image as a storage "
                           "image, and %s (resource '%s') is not a storage format: use rgba8 or a float format, or "
                           "stage \"fragment\"",
                           in->desc->file, in->desc->json_path, where, in->desc->name,
                           pg_format_get(ldr->format)->name, ldr->name);
    } else {
        p->hdr = pg_decl_read(out, "hdr", PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
        p->ldr = pg_decl_write(out, "ldr", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    }
    return PG_OK;
}

static bool linear_filter_ok(pg_gpu *gpu, VkFormat f)
{
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(gpu->phys, f, &fp);
    return (fp.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
}

/* One LUT image (1D/2D/3D, one mip level) with its memory and view. Vulkan calls are checked
 * with PG_VK_TRY (fault injection included); do_destroy frees whatever was made. */
static pg_result create_lut_image(pg_gpu *gpu, do_lut *l, const pg_ocio_texture *t, VkFormat format,
                                  const char *pass_name, pg_error *err)
{
    VkImageType type = t->dim == PG_OCIO_TEX_1D ? VK_IMAGE_TYPE_1D
                       : t->dim == PG_OCIO_TEX_2D ? VK_IMAGE_TYPE_2D : VK_IMAGE_TYPE_3D;
    VkImageViewType vtype = t->dim == PG_OCIO_TEX_1D ? VK_IMAGE_VIEW_TYPE_1D
                            : t->dim == PG_OCIO_TEX_2D ? VK_IMAGE_VIEW_TYPE_2D : VK_IMAGE_VIEW_TYPE_3D;
    uint32_t limit = t->dim == PG_OCIO_TEX_1D ? gpu->props.limits.maxImageDimension1D
                     : t->dim == PG_OCIO_TEX_2D ? gpu->props.limits.maxImageDimension2D
                                                : gpu->props.limits.maxImageDimension3D;
    if (t->width > limit || t->height > limit || t->depth > limit)
        return pg_fail(err, PG_ERR_LIMIT, "OCIO LUT '%s' (%ux%ux%u) exceeds the device limit %u", t->sampler, t->width,
                       t->height, t->depth, limit);
    VkImageCreateInfo ici = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
        .imageType = type,
        .format = format,
        .extent = {t->width, t->height, t->depth},
        .mipLevels = 1,
        .arrayLayers = 1,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .tiling = VK_IMAGE_TILING_OPTIMAL,
        .usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
        .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
    };
    PG_VK_TRY(err, vkCreateImage(gpu->device, &ici, NULL, &l->image));
    pg_gpu_name(gpu, VK_OBJECT_TYPE_IMAGE, (uint64_t)l->image, "%s.%s", pass_name, t->sampler);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(gpu->device, l->image, &req);
    PG_VK_TRY(err, pg_gpu_alloc_device_memory(gpu, req.size, req.memoryTypeBits, &l->memory));
    PG_VK_TRY(err, vkBindImageMemory(gpu->device, l->image, l->memory, 0));
    VkImageViewCreateInfo vci = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                                 .image = l->image,
                                 .viewType = vtype,
                                 .format = format,
                                 .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    PG_VK_TRY(err, vkCreateImageView(gpu->device, &vci, NULL, &l->view));
    l->res.kind = PG_RES_IMAGE;
    l->res.image = l->image;
    l->res.view = l->view;
    l->res.format = format;
    l->res.width = t->width;
    l->res.height = t->height;
    return PG_OK;
}

/* OCIO's R or RGB floats -> R / RGBA texels, 32- or 16-bit. */
static void fill_texels(uint8_t *dst, const pg_ocio_texture *t, VkFormat format)
{
    size_t n = (size_t)t->width * t->height * t->depth;
    bool one = t->channels == 1;
    bool f32 = format == VK_FORMAT_R32_SFLOAT || format == VK_FORMAT_R32G32B32A32_SFLOAT;
    uint32_t nc = one ? 1 : 4;
    for (size_t k = 0; k < n; k++) {
        float v[4] = {t->values[k * t->channels], 0, 0, 1};
        if (!one) {
            v[1] = t->values[k * 3 + 1];
            v[2] = t->values[k * 3 + 2];
        }
        for (uint32_t c = 0; c < nc; c++) {
            if (f32) {
                memcpy(dst + (k * nc + c) * 4, &v[c], 4);
            } else {
                uint16_t h = pg_float_to_half(v[c]);
                memcpy(dst + (k * nc + c) * 2, &h, 2);
            }
        }
    }
}

/* Creates the LUT images, uploads every texture's values through one staging buffer and a
 * one-shot command buffer (waited for), and leaves them SHADER_READ_ONLY for the shader. */
static pg_result upload_luts(display_ocio *p, pg_gpu *gpu, const pg_ocio_shader *sh, const char *pass_name,
                             pg_error *err)
{
    if (!sh->n_textures) return PG_OK;
    if (sh->n_textures > DO_MAX_LUTS)
        return pg_fail(err, PG_ERR_LIMIT, "the OCIO processor needs %u LUT textures (at most %d)", sh->n_textures,
                       DO_MAX_LUTS);
    /* float32 texels when the device filters them (or nothing is filtered), else half floats */
    bool f32_rgba = linear_filter_ok(gpu, VK_FORMAT_R32G32B32A32_SFLOAT);
    bool f32_r = linear_filter_ok(gpu, VK_FORMAT_R32_SFLOAT);
    VkFormat formats[DO_MAX_LUTS];
    VkDeviceSize offsets[DO_MAX_LUTS], total = 0;
    for (uint32_t i = 0; i < sh->n_textures; i++) {
        const pg_ocio_texture *t = &sh->textures[i];
        bool one = t->channels == 1;
        bool f32 = (one ? f32_r : f32_rgba) || !t->linear;
        formats[i] = one ? (f32 ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_R16_SFLOAT)
                         : (f32 ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT);
        VkDeviceSize texel = (one ? 1 : 4) * (f32 ? 4 : 2);
        offsets[i] = total;
        total += ((VkDeviceSize)t->width * t->height * t->depth * texel + 15) & ~(VkDeviceSize)15;
    }
    pg_buffer staging = {0};
    pg_result r = pg_buffer_create(gpu, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true, "display_ocio.staging",
                                   &staging, err);
    for (uint32_t i = 0; i < sh->n_textures && !r; i++) {
        p->n_luts = i + 1;
        r = create_lut_image(gpu, &p->luts[i], &sh->textures[i], formats[i], pass_name, err);
        if (!r) fill_texels((uint8_t *)staging.mapped + offsets[i], &sh->textures[i], formats[i]);
    }
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    if (!r) r = pg_gpu_begin_once(gpu, &cmd, err);
    if (!r) {
        VkImageMemoryBarrier2 b[DO_MAX_LUTS];
        for (uint32_t i = 0; i < sh->n_textures; i++)
            b[i] = pg_image_barrier(p->luts[i].image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_NONE, 0,
                                    VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                    VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        pg_cmd_barriers(cmd, sh->n_textures, b, 0, NULL);
        for (uint32_t i = 0; i < sh->n_textures; i++) {
            const pg_ocio_texture *t = &sh->textures[i];
            VkBufferImageCopy c = {.bufferOffset = offsets[i],
                                   .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                   .imageExtent = {t->width, t->height, t->depth}};
            vkCmdCopyBufferToImage(cmd, staging.buffer, p->luts[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &c);
        }
        for (uint32_t i = 0; i < sh->n_textures; i++)
            b[i] = pg_image_barrier(p->luts[i].image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                                    VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        pg_cmd_barriers(cmd, sh->n_textures, b, 0, NULL);
        r = pg_gpu_end_once(gpu, cmd, err);
    }
    pg_buffer_destroy(gpu, &staging);
    return r;
}

static pg_result create_samplers(display_ocio *p, pg_gpu *gpu, pg_error *err)
{
    pg_result r = pg_sampler_create(gpu, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, &p->nearest, err);
    if (r) return r;
    return pg_sampler_create(gpu, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, &p->linear, err);
}

static pg_result do_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    display_ocio *p = self;
    pg_gpu *gpu = ctx->gpu;
    const do_params *pa = PG_PARAMS(ctx, do_params);
    pg_result r;
    const char *opt_display = pa->display, *opt_view = pa->view;
    p->exposure = pa->exposure;
    p->compute = pa->compute;
    const pg_phys_resource *ldr = pg_ctx_res(ctx, pa->ldr);
    p->ldr_slot = pg_plan_slot_of(ctx->pass, pa->ldr);
    p->width = ldr->width;
    p->height = ldr->height;
    const char *ldr_fmt = pg_format_get(ldr->pg_fmt)->name;
    const char *display = pg_ctx_setting(ctx, "ocio.display");
    const char *view = pg_ctx_setting(ctx, "ocio.view");
    if (!display || !display[0]) display = opt_display;
    if (!view || !view[0]) view = opt_view;
    char path[PG_PATH_MAX];
    pg_ocio_resolve_path(pg_ctx_setting(ctx, "ocio.config"), path, sizeof path);

    pg_ocio_config *cfg = NULL;
    pg_ocio_shader *sh = NULL;
    VkShaderModule vs = VK_NULL_HANDLE, fs = VK_NULL_HANDLE;
    if ((r = pg_ocio_open(path, &cfg, err))) goto out;
    pg_ocio_shader_desc sd = {.display = display, .view = view, .function_name = "ocio_display",
                              .set = 1, .first_binding = 1};
    if ((r = pg_ocio_shader_create(cfg, &sd, &sh, err))) goto out;
    if ((r = upload_luts(p, gpu, sh, ctx->pass->name, err))) goto out;

    if ((r = create_samplers(p, gpu, err))) goto out;
    pg_set_binding b[2 + DO_MAX_LUTS];
    b[0] = (pg_set_binding){VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pg_ctx_res(ctx, pa->hdr), p->nearest, 0};
    for (uint32_t i = 0; i < p->n_luts; i++)
        b[1 + i] = (pg_set_binding){VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, &p->luts[i].res,
                                    sh->textures[i].linear ? p->linear : p->nearest, 0};
    uint32_t nb = 1 + p->n_luts;
    if (p->compute) b[nb++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, ldr, VK_NULL_HANDLE, 0};
    if ((r = pg_pass_set_create(gpu, nb, b, ctx->pass->name, &p->set, err))) goto out;
    VkDescriptorSetLayout sets[2] = {ctx->frame_layout, p->set.layout};
    if ((r = pg_pipeline_layout_create(gpu, 2, sets, sizeof(float), &p->layout, err))) goto out;
    pg_shader_source gen = {"ocio_display.glsl", sh->glsl};
    if (p->compute) {
        char bind_def[40], fmt_def[48];
        snprintf(bind_def, sizeof bind_def, "PG_LDR_BINDING=%u", 1 + p->n_luts);
        snprintf(fmt_def, sizeof fmt_def, "PG_LDR_FORMAT=%s", ldr_fmt);
        const char *defs[2] = {bind_def, fmt_def};
        VkShaderModule cs = VK_NULL_HANDLE;
        if ((r = pg_shader_module_ex(gpu, "display_ocio.comp", VK_SHADER_STAGE_COMPUTE_BIT, defs, 2, &gen, 1, &cs,
                                     err))) {
            pg_error_prefix(err, "%s: display '%s', view '%s'", path, sh->display, sh->view);
            goto out;
        }
        pg_compute_pipeline_desc cd = {.layout = p->layout, .cs = cs};
        r = pg_compute_pipeline_create_ex(gpu, &cd, ctx->pass->name, &p->pipeline, err);
        vkDestroyShaderModule(gpu->device, cs, NULL);
        goto out;
    }
    if ((r = pg_shader_module(gpu, "fullscreen.vert", VK_SHADER_STAGE_VERTEX_BIT, NULL, 0, &vs, err))) goto out;
    if ((r = pg_shader_module_ex(gpu, "display_ocio.frag", VK_SHADER_STAGE_FRAGMENT_BIT, NULL, 0, &gen, 1, &fs,
                                 err))) {
        pg_error_prefix(err, "%s: display '%s', view '%s'", path, sh->display, sh->view);
        goto out;
    }
    pg_gfx_pipeline_desc d = {
        .layout = p->layout,
        .vs = vs,
        .fs = fs,
        .n_color = 1,
        .color_formats = {ldr->format},
    };
    r = pg_gfx_pipeline_create(gpu, &d, ctx->pass->name, &p->pipeline, err);
out:
    if (vs) vkDestroyShaderModule(gpu->device, vs, NULL);
    if (fs) vkDestroyShaderModule(gpu->device, fs, NULL);
    pg_ocio_shader_free(sh);
    pg_ocio_close(cfg);
    return r;
}

static void do_record(void *self, const pg_pass_record_ctx *ctx)
{
    display_ocio *p = self;
    if (!p->compute) {
        pg_display_record_fullscreen(ctx, p->ldr_slot, p->pipeline, p->layout, p->set.set, p->exposure);
        return;
    }
    VkDescriptorSet sets[2] = {ctx->frame_set, p->set.set};
    vkCmdBindPipeline(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 2, sets, 0, NULL);
    vkCmdPushConstants(ctx->cmd, p->layout, PG_PUSH_STAGES, 0, sizeof(float), &p->exposure);
    vkCmdDispatch(ctx->cmd, (p->width + 7) / 8, (p->height + 7) / 8, 1);
}

static void do_destroy(void *self, pg_gpu *gpu)
{
    display_ocio *p = self;
    if (p->pipeline) vkDestroyPipeline(gpu->device, p->pipeline, NULL);
    if (p->layout) vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
    pg_pass_set_destroy(gpu, &p->set);
    if (p->nearest) vkDestroySampler(gpu->device, p->nearest, NULL);
    if (p->linear) vkDestroySampler(gpu->device, p->linear, NULL);
    for (uint32_t i = 0; i < p->n_luts; i++) {
        do_lut *l = &p->luts[i];
        if (l->view) vkDestroyImageView(gpu->device, l->view, NULL);
        if (l->image) vkDestroyImage(gpu->device, l->image, NULL);
        pg_gpu_free_memory(gpu, l->memory);
    }
    memset(p, 0, sizeof *p);
}

/* exposure is a push constant: a new value re-creates nothing (runtime_options) */
static const char *const k_runtime[] = {"exposure", NULL};

static pg_result do_update(void *self, const void *params, pg_error *err)
{
    (void)err;
    display_ocio *p = self;
    p->exposure = ((const do_params *)params)->exposure;
    return PG_OK;
}

const pg_pass_type pg_pass_display_ocio = {
    .name = "display_ocio",
    .summary = "compute (or graphics): HDR -> display image through an OpenColorIO display/view transform "
               "(exposure first)",
    .instance_size = sizeof(display_ocio),
    .params_size = sizeof(do_params),
    .declare = do_declare,
    .create = do_create,
    .record = do_record,
    .destroy = do_destroy,
    .runtime_options = k_runtime,
    .update = do_update,
};
