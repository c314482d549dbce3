/* passgraph_embed.c - passgraph as a library: the API of include/passgraph/passgraph.h
 * (docs/embedding.md) over the renderer's session (renderer/render_session.h): a device, the
 * uploaded scene, the pipeline's session, the frame set-up the tools use (pg_scene_default_view),
 * images read back into memory or blitted into the caller's VkImage, per-pass GPU times, and the
 * image error against a second session on a reference pipeline. */
#include "passgraph.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "default_view.h"
#include "frame.h"
#include "image_compare.h"
#include "image_util.h"
#include "pass_list.h"
#include "plugins.h"
#include "render_session.h"
#include "scene_gpu.h"

#define MAX_PARAMS 64

struct passgraph {
    pg_gpu *gpu;
    pg_scene *scene;
    pg_scene_gpu *sg;
    pg_pass_registry reg;
    pg_plugins plugins;    /* the pipeline file's "plugins" */
    pg_session *session, *reference;
    char pipeline[PG_PATH_MAX], reference_path[PG_PATH_MAX];
    char keys[MAX_PARAMS][PG_NAME_MAX], values[MAX_PARAMS][PG_NAME_MAX];
    pg_param_override params[MAX_PARAMS];
    uint32_t n_params;
    pg_frame_info fi;
    pg_frame_stats stats;
    bool have_frame;       /* a frame was read back (passgraph_read_*, passgraph_error_against) */
};

uint32_t passgraph_embed_version(void)
{
    return PASSGRAPH_EMBED_VERSION;
}

static pg_result add_param(passgraph *p, const char *key, const char *value, pg_error *err)
{
    uint32_t i = 0;
    while (i < p->n_params && strcmp(p->keys[i], key)) i++;
    if (i == MAX_PARAMS) return pg_fail(err, PG_ERR_LIMIT, "more than %d parameter overrides", MAX_PARAMS);
    if (!pg_strlcpy(p->keys[i], key, PG_NAME_MAX) || !pg_strlcpy(p->values[i], value, PG_NAME_MAX))
        return pg_fail(err, PG_ERR_INVALID_ARG, "parameter '%s': key or value longer than %d bytes", key, PG_NAME_MAX - 1);
    if (i == p->n_params) p->n_params++;
    for (uint32_t k = 0; k < p->n_params; k++) p->params[k] = (pg_param_override){p->keys[k], p->values[k]};
    return PG_OK;
}

/* A session on path with the overrides; declared_only: only those the pipeline declares (the
 * reference: a parameter of the pipeline under test need not exist there, as in `compare`). */
static pg_result open_session(passgraph *p, const char *path, bool declared_only, pg_session **out, pg_error *err)
{
    pg_param_override ov[MAX_PARAMS];
    uint32_t n = 0;
    pg_pipeline *probe = NULL;
    if (declared_only) {
        pg_result r = pg_pipeline_load(path, NULL, 0, &probe, err);
        if (r) return r;
    }
    for (uint32_t i = 0; i < p->n_params; i++)
        if (!probe || pg_pipeline_find_param(probe, p->keys[i])) ov[n++] = p->params[i];
    pg_pipeline_free(probe);
    pg_session_desc sd = {.pipeline_path = path, .registry = &p->reg, .overrides = ov, .n_overrides = n};
    return pg_session_create(p->gpu, p->sg, &sd, out, err);
}

static pg_result open_parts(passgraph *p, const passgraph_desc *d, pg_error *err)
{
    for (uint32_t i = 0; i < d->n_params; i++) {
        const char *eq = d->params[i] ? strchr(d->params[i], '=') : NULL;
        char key[PG_NAME_MAX];
        if (!eq || eq == d->params[i] || (size_t)(eq - d->params[i]) >= sizeof key)
            return pg_fail(err, PG_ERR_INVALID_ARG, "params[%u]: expected KEY=VALUE", i);
        snprintf(key, sizeof key, "%.*s", (int)(eq - d->params[i]), d->params[i]);
        pg_result r = add_param(p, key, eq + 1, err);
        if (r) return r;
    }
    if (d->pipeline) {
        if (!d->pipeline[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_open: pipeline \"\": an empty path");
        if (!pg_strlcpy(p->pipeline, d->pipeline, sizeof p->pipeline))
            return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_open: pipeline path longer than %d bytes", PG_PATH_MAX - 1);
    } else {
        pg_data_path(p->pipeline, sizeof p->pipeline, "pipelines/forward_plus.json");
    }
    if (!d->width != !d->height)
        return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_open: size %ux%u: give both sides, or 0x0 for 1280x720",
                       d->width, d->height);
    pg_gpu_desc gd = {.validation = d->validation, .device_index = d->device, .quiet = true};
    pg_result r = pg_gpu_create(&gd, &p->gpu, err);
    if (!r) r = pg_scene_load(d->scene ? d->scene : "default", &p->scene, err);
    if (!r) r = pg_scene_gpu_create(p->gpu, p->scene, &p->sg, err);
    if (r) return r;
    pg_register_builtin_passes(&p->reg);
    /* the pass types the pipeline file lists (a file that does not load is reported by the session) */
    if ((r = pg_plugins_load_listed(&p->reg, p->pipeline, &p->plugins, err))) return r;
    p->fi.width = d->width ? d->width : 1280;
    p->fi.height = d->height ? d->height : 720;
    if (p->fi.width > 16384 || p->fi.height > 16384)
        return pg_fail(err, PG_ERR_INVALID_ARG, "size %ux%u: at most 16384 a side", p->fi.width, p->fi.height);
    r = pg_scene_default_view(p->scene, NULL, (float)p->fi.width / (float)p->fi.height, 256, 7, &p->fi.camera,
                              &p->fi.lights, NULL, 0, NULL, 0, err);
    if (r) return r;
    r = passgraph_set_lights(p, 256, 7, 0.0f, err);
    if (!r) r = open_session(p, p->pipeline, false, &p->session, err);
    /* compiled now, as the header says: a pipeline the passes refuse fails here, not at the first frame */
    if (!r) r = pg_session_compile(p->session, p->fi.lights.count, p->fi.width, p->fi.height, err);
    return r;
}

pg_result passgraph_open(const passgraph_desc *desc, passgraph **out, pg_error *err)
{
    if (!out) return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_open: no output");
    *out = NULL;
    if (!desc) return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_open: no description");
    if (desc->n_params && !desc->params)
        return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_open: n_params %u but no params", desc->n_params);
    passgraph *p = calloc(1, sizeof *p);
    if (!p) return pg_fail(err, PG_ERR_OOM, "out of memory");
    pg_result r = open_parts(p, desc, err);
    if (r) {
        passgraph_close(p);
        return r;
    }
    *out = p;
    return PG_OK;
}

void passgraph_close(passgraph *p)
{
    if (!p) return;
    pg_session_destroy(p->reference);
    pg_session_destroy(p->session);
    if (p->sg) pg_scene_gpu_destroy(p->gpu, p->sg);
    pg_scene_free(p->scene);
    if (p->gpu) pg_gpu_destroy(p->gpu);
    pg_plugins_close(&p->plugins); /* after every session that used their types */
    free(p);
}

static bool finite3(const float v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

pg_result passgraph_set_camera(passgraph *p, const float eye[3], const float target[3], const float up[3],
                               float fov_y_deg, float near_z, float far_z, pg_error *err)
{
    if (!p || !eye || !target || !up)
        return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_set_camera: no session, eye, target or up");
    if (!finite3(eye) || !finite3(target) || !finite3(up))
        return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_set_camera: eye, target and up must be finite");
    if (eye[0] == target[0] && eye[1] == target[1] && eye[2] == target[2])
        return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_set_camera: eye and target are the same point");
    if (!(fov_y_deg > 0 && fov_y_deg < 180))
        return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_set_camera: fov %g: expected 0 < fov < 180 degrees", fov_y_deg);
    const float n = near_z > 0 ? near_z : p->fi.camera.near_z, f = far_z > 0 ? far_z : p->fi.camera.far_z;
    if (!(n > 0 && f > n && isfinite(f)))
        return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_set_camera: near %g, far %g: expected 0 < near < far", n, f);
    pg_camera *c = &p->fi.camera;
    memcpy(c->position, eye, sizeof c->position);
    memcpy(c->target, target, sizeof c->target);
    memcpy(c->up, up, sizeof c->up);
    c->fov_y_deg = fov_y_deg;
    c->near_z = n;
    c->far_z = f;
    c->ortho_height = 0;
    return PG_OK;
}

pg_result passgraph_set_lights(passgraph *p, uint32_t count, uint32_t seed, float time, pg_error *err)
{
    if (!p) return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_set_lights: no session");
    if (count > (1u << 24)) return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_set_lights: %u lights: at most 2^24", count);
    if (!(fabsf(time) <= PG_MAX_TIME_S))
        return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_set_lights: time %g: a finite number of seconds within +-%g "
                       "(a float holds under a frame's precision past it)", (double)time, PG_MAX_TIME_S);
    /* as the tools: the file's own lights first, then the generated ones; around an object their
     * intensity follows their count (pg_light_setup_object) */
    p->fi.lights.file_count = p->scene->n_lights;
    p->fi.lights.count = p->scene->n_lights + count;
    p->fi.lights.seed = seed;
    if (strcmp(p->scene->path, "default") != 0) p->fi.lights.intensity = pg_light_setup_object(p->scene, count, seed).intensity;
    p->fi.time = time;
    return PG_OK;
}

pg_result passgraph_set_param(passgraph *p, const char *key, const char *value, pg_error *err)
{
    if (!p || !key || !value) return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_set_param: no session, key or value");
    /* a refused key or value is taken back: later calls see the overrides as they were */
    const uint32_t n0 = p->n_params;
    uint32_t i = 0;
    while (i < n0 && strcmp(p->keys[i], key)) i++;
    char old[PG_NAME_MAX] = "";
    if (i < n0) pg_strlcpy(old, p->values[i], sizeof old);
    pg_result r = add_param(p, key, value, err);
    if (!r) r = pg_session_reload(p->session, p->pipeline, p->params, p->n_params, err);
    if (r) {
        if (i < n0) pg_strlcpy(p->values[i], old, PG_NAME_MAX);
        p->n_params = n0;
    }
    /* the reference session (passgraph_error_against) is opened again with the new overrides */
    pg_session_destroy(p->reference);
    p->reference = NULL;
    return r;
}

pg_result passgraph_render(passgraph *p, pg_error *err)
{
    if (!p) return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_render: no session");
    p->have_frame = false;
    pg_result r = pg_session_render(p->session, &p->fi, true, &p->stats, err);
    p->have_frame = r == PG_OK;
    return r;
}

static pg_result read_output(const passgraph *p, pg_session *s, int which, void *dst, size_t dst_bytes, pg_error *err)
{
    if (!p || !dst) return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_read_%s: no session or no destination buffer",
                                   which ? "hdr" : "rgba8");
    if (!p->have_frame) return pg_fail(err, PG_ERR_INVALID_ARG, "no frame read back yet: call passgraph_render first");
    uint32_t w, h;
    pg_format fmt;
    const void *px = pg_runtime_output(s->runtime, which, &w, &h, &fmt);
    if (!px) return pg_fail(err, PG_ERR_INVALID_ARG, "the pipeline has no %s", which ? "hdr_output" : "output");
    const size_t need = (size_t)w * h * (which ? 4 * sizeof(float) : 4);
    if (dst_bytes < need)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%zu bytes given; %ux%u %s needs %zu", dst_bytes, w, h,
                       which ? "RGBA32F" : "RGBA8", need);
    if (which) return pg_hdr_to_float(px, fmt, w, h, dst, err);
    if (fmt != PG_FMT_RGBA8_UNORM && fmt != PG_FMT_RGBA8_SRGB)
        return pg_fail(err, PG_ERR_FORMAT, "the output is %s, not an 8-bit RGBA image", pg_format_get(fmt)->name);
    memcpy(dst, px, need);
    return PG_OK;
}

pg_result passgraph_read_rgba8(const passgraph *p, uint8_t *dst, size_t dst_bytes, pg_error *err)
{
    return read_output(p, p ? p->session : NULL, 0, dst, dst_bytes, err);
}

pg_result passgraph_read_hdr(const passgraph *p, float *dst, size_t dst_bytes, pg_error *err)
{
    return read_output(p, p ? p->session : NULL, 1, dst, dst_bytes, err);
}

void passgraph_get_vulkan(const passgraph *p, passgraph_vulkan *out)
{
    if (!out) return;
    if (!p) {
        *out = (passgraph_vulkan){0};
        return;
    }
    *out = (passgraph_vulkan){p->gpu->instance, p->gpu->phys, p->gpu->device, p->gpu->queue, p->gpu->queue_family};
}

/* One image barrier over every stage (the copy is a one-off, not a frame's hot path). */
static void image_barrier(VkCommandBuffer cmd, VkImage img, VkImageLayout from, VkImageLayout to, VkAccessFlags2 src_access,
                          VkAccessFlags2 dst_access)
{
    const VkImageMemoryBarrier2 b =
        pg_image_barrier(img, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, src_access,
                         VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, dst_access, from, to);
    pg_cmd_barriers(cmd, 1, &b, 0, NULL);
}

pg_result passgraph_render_to_image(passgraph *p, VkImage dst, VkFormat format, VkImageLayout old_layout,
                                    VkImageLayout new_layout, pg_error *err)
{
    if (!p || !dst) return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_render_to_image: no session or no image");
    if (!pg_vk_format_blits_from_unorm(format))
        return pg_fail(err, PG_ERR_FORMAT,
                       "passgraph_render_to_image: VkFormat %d is an integer, depth/stencil or compressed format: a blit "
                       "from the RGBA8 output cannot write it",
                       (int)format);
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(p->gpu->phys, format, &fp);
    if (!(fp.linearTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT) &&
        !(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT))
        return pg_fail(err, PG_ERR_FORMAT, "passgraph_render_to_image: VkFormat %d cannot be a blit destination on this device",
                       (int)format);
    p->have_frame = false;
    pg_result r = pg_session_render(p->session, &p->fi, false, &p->stats, err);
    if (!r) r = pg_runtime_wait_idle(p->session->runtime, err);
    const pg_phys_resource *src = r ? NULL : pg_runtime_output_image(p->session->runtime, 0);
    if (!r && !src) r = pg_fail(err, PG_ERR_INVALID_ARG, "the pipeline's output is not an image");
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    if (!r) r = pg_gpu_begin_once(p->gpu, &cmd, err);
    if (r) return r;
    /* the output stays in TRANSFER_SRC_OPTIMAL, where every frame leaves it (graph_execute.h) */
    image_barrier(cmd, src->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_ACCESS_2_MEMORY_WRITE_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    image_barrier(cmd, dst, old_layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageBlit region = {
        .srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .srcOffsets = {{0, 0, 0}, {(int32_t)src->width, (int32_t)src->height, 1}},
        .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .dstOffsets = {{0, 0, 0}, {(int32_t)src->width, (int32_t)src->height, 1}},
    };
    vkCmdBlitImage(cmd, src->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                   &region, VK_FILTER_NEAREST);
    image_barrier(cmd, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, new_layout, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    return pg_gpu_end_once(p->gpu, cmd, err);
}

uint32_t passgraph_pass_count(const passgraph *p)
{
    return p ? p->stats.n_passes : 0;
}

const char *passgraph_pass_name(const passgraph *p, uint32_t i)
{
    return p && i < p->stats.n_passes ? p->stats.pass_names[i] : NULL;
}

double passgraph_pass_ms(const passgraph *p, uint32_t i)
{
    return p && i < p->stats.n_passes && p->stats.timestamps_valid ? p->stats.pass_ms[i] : NAN;
}

double passgraph_gpu_ms(const passgraph *p)
{
    return p && p->stats.timestamps_valid ? p->stats.gpu_total_ms : NAN;
}

uint32_t passgraph_validation_messages(const passgraph *p)
{
    return p ? p->gpu->validation_messages : 0;
}

const char *passgraph_data_dir(void)
{
    return pg_data_dir();
}

void passgraph_size(const passgraph *p, uint32_t *width, uint32_t *height)
{
    if (width) *width = p ? p->fi.width : 0;
    if (height) *height = p ? p->fi.height : 0;
}

/* RGBA32F and RGBA8 copies of a session's last read-back frame (malloc'd) */
static pg_result frame_copy(passgraph *p, pg_session *s, float **hdr, uint8_t **ldr, pg_error *err)
{
    const size_t n = (size_t)p->fi.width * p->fi.height;
    *hdr = malloc(n * 4 * sizeof(float));
    *ldr = malloc(n * 4);
    if (!*hdr || !*ldr) return pg_fail(err, PG_ERR_OOM, "out of memory");
    pg_result r = read_output(p, s, 1, *hdr, n * 4 * sizeof(float), err);
    if (!r) r = read_output(p, s, 0, *ldr, n * 4, err);
    return r;
}

pg_result passgraph_error_against(passgraph *p, const char *reference, passgraph_error_stats *out, pg_error *err)
{
    if (!p || !out) return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_error_against: no session or no output");
    char path[PG_PATH_MAX];
    if (reference && !reference[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_error_against: reference \"\": an empty path");
    if (reference && !pg_strlcpy(path, reference, sizeof path))
        return pg_fail(err, PG_ERR_INVALID_ARG, "passgraph_error_against: reference path longer than %d bytes", PG_PATH_MAX - 1);
    if (!reference) pg_data_path(path, sizeof path, "pipelines/reference.json");
    if (!p->have_frame) return pg_fail(err, PG_ERR_INVALID_ARG, "no frame read back yet: call passgraph_render first");
    pg_result r = PG_OK;
    if (!p->reference || strcmp(path, p->reference_path)) {
        pg_session_destroy(p->reference);
        p->reference = NULL;
        if ((r = pg_plugins_load_listed(&p->reg, path, &p->plugins, err))) return r;
        if ((r = open_session(p, path, true, &p->reference, err))) return r;
        pg_strlcpy(p->reference_path, path, sizeof p->reference_path);
    }
    pg_frame_stats rs;
    float *ha = NULL, *hb = NULL;
    uint8_t *la = NULL, *lb = NULL;
    r = frame_copy(p, p->session, &ha, &la, err);
    if (!r) r = pg_session_render(p->reference, &p->fi, true, &rs, err);
    if (!r) r = frame_copy(p, p->reference, &hb, &lb, err);
    pg_image_error e;
    if (!r) r = pg_image_error_compute(ha, hb, la, lb, p->fi.width, p->fi.height, 1.0, &e, err);
    if (!r) *out = (passgraph_error_stats){e.rmse_linear, e.psnr_linear, e.max_abs_linear, e.share_over_threshold};
    free(ha);
    free(hb);
    free(la);
    free(lb);
    return r;
}
