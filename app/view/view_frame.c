/* view_frame.c - `passgraph view`: the difference-to-reference view and one frame: the graph
 * renders offscreen, then one command buffer blits its output into the swapchain image, draws
 * the UI, optionally copies the window for a screenshot, and presents. */
#include "view.h"

/* ---------------------------------------------------------------- difference view */

/* FLIP mode: the LDR-FLIP map of the two display outputs (w x h) in diff_rgba, its mean and cost
 * (said once on stdout after the mode is chosen) */
static pg_result update_flip(viewer *v, uint32_t w, uint32_t h, pg_error *err)
{
    uint32_t lw, lh, rw, rh;
    pg_format fa, fb;
    const uint8_t *a = pg_runtime_output(v->session->runtime, 0, &lw, &lh, &fa);
    const uint8_t *b = pg_runtime_output(v->naive->runtime, 0, &rw, &rh, &fb);
    if (!a || !b || lw != w || lh != h || rw != w || rh != h || (fa != PG_FMT_RGBA8_UNORM && fa != PG_FMT_RGBA8_SRGB) ||
        (fb != PG_FMT_RGBA8_UNORM && fb != PG_FMT_RGBA8_SRGB))
        return pg_fail(err, PG_ERR_INVALID_ARG, "FLIP view needs both pipelines' 8-bit display outputs at %ux%u", w, h);
    float *map = realloc(v->flip_map, (size_t)w * h * sizeof *map);
    if (!map) return pg_fail(err, PG_ERR_OOM, "out of memory");
    v->flip_map = map;
    const double t0 = pg_time_s();
    pg_result r = pg_flip_ldr(a, b, w, h, NULL, map, &v->flip_mean, err);
    if (r) return pg_error_prefix(err, "FLIP view");
    v->flip_ms = (pg_time_s() - t0) * 1e3;
    pg_flip_map_rgba(map, w, h, v->diff_rgba);
    if (!v->flip_said)
        printf("view: FLIP against the reference: mean %.6g (%ux%u, %.1f ms CPU)\n", v->flip_mean, w, h, v->flip_ms);
    v->flip_said = true;
    return PG_OK;
}

static pg_result update_diff(viewer *v, pg_error *err)
{
    uint32_t w, h, rw, rh;
    pg_format fa, fb;
    const void *a = pg_runtime_output(v->session->runtime, 1, &w, &h, &fa);
    const void *b = v->naive ? pg_runtime_output(v->naive->runtime, 1, &rw, &rh, &fb) : NULL;
    if (!a || !b || w != rw || h != rh)
        return pg_fail(err, PG_ERR_INVALID_ARG, "difference view needs both pipelines to declare an hdr_output");
    size_t px = (size_t)w * h;
    if (!v->diff_image.image || v->diff_image.width != w || v->diff_image.height != h) {
        vkDeviceWaitIdle(v->app.gpu->device);
        pg_image_destroy(v->app.gpu, &v->diff_image);
        pg_buffer_destroy(v->app.gpu, &v->diff_staging);
        free(v->diff_rgba);
        free(v->hdr_a);
        free(v->hdr_b);
        v->diff_rgba = malloc(px * 4);
        v->hdr_a = malloc(px * 16);
        v->hdr_b = malloc(px * 16);
        if (!v->diff_rgba || !v->hdr_a || !v->hdr_b) return pg_fail(err, PG_ERR_OOM, "out of memory");
        pg_result r;
        if ((r = pg_image_create(v->app.gpu, VK_FORMAT_R8G8B8A8_SRGB, w, h, 1,
                                 VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                 "view.diff",
                                 &v->diff_image, err)))
            return r;
        if ((r = pg_buffer_create(v->app.gpu, px * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true, "view.diff.staging",
                                  &v->diff_staging, err)))
            return r;
    }
    pg_result r;
    if ((r = pg_hdr_to_float(a, fa, w, h, v->hdr_a, err)) || (r = pg_hdr_to_float(b, fb, w, h, v->hdr_b, err))) return r;
    if (v->diff_flip) {
        if ((r = update_flip(v, w, h, err))) return r;
    } else {
        v->diff_scale = pg_error_quantile(v->hdr_a, v->hdr_b, w, h, 0.99);
        pg_error_heatmap(v->hdr_a, v->hdr_b, w, h, v->diff_scale, v->diff_rgba);
    }
    double se = 0;
    for (size_t i = 0; i < px * 4; i++)
        if (i % 4 != 3) se += (double)(v->hdr_a[i] - v->hdr_b[i]) * (v->hdr_a[i] - v->hdr_b[i]);
    v->diff_rmse = sqrt(se / (double)(px * 3));
    memcpy(v->diff_staging.mapped, v->diff_rgba, px * 4);
    return PG_OK;
}

/* ---------------------------------------------------------------- one frame */

static bool srgb_format(VkFormat f)
{
    return f == VK_FORMAT_R8G8B8A8_SRGB || f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_A8B8G8R8_SRGB_PACK32;
}

/* The image to blit into the swapchain. The graph's 8-bit output holds display-encoded bytes
 * whether it is rgba8 (the OCIO display pass encoded them) or rgba8_srgb (encoded on write); a
 * blit between a UNORM and an sRGB format would decode or encode them once more, so when the
 * output's kind differs from the swapchain's the bytes are first copied (vkCmdCopyImage: no
 * conversion) into an image of the swapchain's kind. */
static pg_result present_source(viewer *v, VkCommandBuffer cmd, const pg_phys_resource *out, VkImage *src,
                                pg_error *err)
{
    *src = out->image;
    VkFormat other;
    if (out->format == VK_FORMAT_R8G8B8A8_UNORM) other = VK_FORMAT_R8G8B8A8_SRGB;
    else if (out->format == VK_FORMAT_R8G8B8A8_SRGB) other = VK_FORMAT_R8G8B8A8_UNORM;
    else return PG_OK; /* float outputs: the blit converts values, which is right for them */
    if (srgb_format(out->format) == srgb_format(v->win.format)) return PG_OK;
    pg_image *pc = &v->present_copy;
    if (!pc->image || pc->format != other || pc->width != out->width || pc->height != out->height) {
        vkDeviceWaitIdle(v->app.gpu->device);
        pg_image_destroy(v->app.gpu, pc);
        pg_result r = pg_image_create(v->app.gpu, other, out->width, out->height, 1,
                                      VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                          VK_IMAGE_USAGE_SAMPLED_BIT, /* pg_image_create makes a view */
                                      "view.present_copy", pc, err);
        if (r) return r;
    }
    VkImageMemoryBarrier2 b = pg_image_barrier(pc->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT, 0,
                                               VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                               VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    pg_cmd_barriers(cmd, 1, &b, 0, NULL);
    VkImageCopy c = {.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                     .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                     .extent = {out->width, out->height, 1}};
    vkCmdCopyImage(cmd, out->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, pc->image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &c);
    b = pg_image_barrier(pc->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                         VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    pg_cmd_barriers(cmd, 1, &b, 0, NULL);
    *src = pc->image;
    return PG_OK;
}

/* the frame the viewer's settings describe, at the window's size */
static pg_frame_info viewer_frame_info(const viewer *v)
{
    pg_frame_info fi = pg_app_frame(&v->app);
    fi.camera = v->camera;
    fi.lights.count = (uint32_t)v->light_count;
    fi.lights.radius = v->radius;
    fi.lights.intensity = v->intensity;
    fi.lights.ambient = v->ambient;
    fi.lights.env_intensity = v->env_intensity;
    fi.lights.env_rotation = v->env_rotation_deg * (float)(3.14159265358979 / 180.0);
    fi.lights.speed = v->speed;
    fi.lights.seed = (uint32_t)v->seed;
    fi.time = v->time;
    fi.width = v->win.extent.width;
    fi.height = v->win.extent.height;
    return fi;
}

/* the displayed graph's frame; growth and light overflow said on stdout */
static pg_result render_graph(viewer *v, const pg_frame_info *fi, pg_error *err)
{
    pg_result r = pg_session_render(v->session, fi, v->diff, &v->stats, err);
    if (r) return r;
    for (uint32_t k = 0; k < v->stats.n_grown; k++) {
        v->growths++;
        snprintf(v->last_growth, sizeof v->last_growth, "%s grew %.2f -> %.2f MiB at %d lights", v->stats.grown[k].resource,
                 v->stats.grown[k].old_bytes / 1048576.0, v->stats.grown[k].new_bytes / 1048576.0, v->light_count);
        printf("view: %s\n", v->last_growth);
    }
    if (pg_frame_counter_sum(&v->stats, "overflow_dropped") && v->stats.n_notes) printf("view: %s\n", v->stats.notes[0]);
    return PG_OK;
}

/* with the difference view on: the reference pipeline's frame and the heatmap in diff_staging */
static pg_result render_diff(viewer *v, const pg_frame_info *fi, pg_error *err)
{
    pg_result r;
    if (!v->naive) {
        char naive[PG_PATH_MAX];
        pg_data_path(naive, sizeof naive, "pipelines/reference.json"); /* exact, fast at any count */
        if ((r = open_session(v, naive, false, &v->naive, err))) return r;
    }
    pg_frame_stats ns;
    if ((r = pg_session_render(v->naive, fi, true, &ns, err))) return r;
    /* the diff staging is written by the host: no viewer frame may still read it */
    PG_VK_TRY(err, vkWaitForFences(v->app.gpu->device, PG_VIEW_FRAMES, v->win.fence, VK_TRUE, UINT64_MAX));
    return update_diff(v, err);
}

/* statistics history */
static void record_history(viewer *v)
{
    v->hist_total[v->hist_pos] = (float)v->stats.gpu_total_ms;
    for (uint32_t p = 0; p < v->stats.n_passes && p < PG_MAX_PASSES; p++) v->hist_pass[p][v->hist_pos] = (float)v->stats.pass_ms[p];
    v->hist_pos = (v->hist_pos + 1) % HIST;
    v->hist_n++;
}

/* the image blitted to the swapchain: the heatmap (uploaded from diff_staging) or the graph's
 * display output; *src ready as a transfer source of sw x sh */
static pg_result blit_source(viewer *v, VkCommandBuffer cmd, bool show_diff, VkImage *src, uint32_t *sw,
                             uint32_t *sh, pg_error *err)
{
    if (!v->session) { /* nothing to show: blit_to_swapchain clears */
        *src = VK_NULL_HANDLE;
        return PG_OK;
    }
    if (!show_diff) {
        const pg_phys_resource *out = pg_runtime_output_image(v->session->runtime, 0);
        pg_result r = present_source(v, cmd, out, src, err);
        if (r) return r;
        *sw = out->width;
        *sh = out->height;
        return PG_OK;
    }
    VkImageMemoryBarrier2 b = pg_image_barrier(v->diff_image.image, VK_IMAGE_ASPECT_COLOR_BIT,
                                               VK_PIPELINE_STAGE_2_BLIT_BIT, 0, VK_PIPELINE_STAGE_2_COPY_BIT,
                                               VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    pg_cmd_barriers(cmd, 1, &b, 0, NULL);
    VkBufferImageCopy c = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                           .imageExtent = {v->diff_image.width, v->diff_image.height, 1}};
    vkCmdCopyBufferToImage(cmd, v->diff_staging.buffer, v->diff_image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &c);
    b = pg_image_barrier(v->diff_image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                         VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    pg_cmd_barriers(cmd, 1, &b, 0, NULL);
    *src = v->diff_image.image;
    *sw = v->diff_image.width;
    *sh = v->diff_image.height;
    return PG_OK;
}

/* src (sw x sh) scaled onto swapchain image `index`; the acquire semaphore is waited at the blit
 * stage, the transition chains after it */
static void blit_to_swapchain(VkCommandBuffer cmd, const pg_view_window *w, uint32_t index, VkImage src, uint32_t sw,
                              uint32_t sh)
{
    VkImageMemoryBarrier2 to_dst = pg_image_barrier(w->images[index], VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                                                    0, VK_PIPELINE_STAGE_2_BLIT_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT,
                                                    VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    pg_cmd_barriers(cmd, 1, &to_dst, 0, NULL);
    if (!src) { /* no graph to show (the pipeline did not load after a scene change): a grey frame
                 * under the panel that says why */
        const VkClearColorValue grey = {.float32 = {0.08f, 0.08f, 0.08f, 1.0f}};
        const VkImageSubresourceRange all = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, w->images[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &grey, 1, &all);
        return;
    }
    VkImageBlit blit = {
        .srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .srcOffsets = {{0, 0, 0}, {(int32_t)sw, (int32_t)sh, 1}},
        .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .dstOffsets = {{0, 0, 0}, {(int32_t)w->extent.width, (int32_t)w->extent.height, 1}},
    };
    vkCmdBlitImage(cmd, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, w->images[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                   &blit, VK_FILTER_NEAREST);
}

/* swapchain image `index` copied to the screenshot buffer (grown as needed), then to present */
static pg_result record_screenshot(viewer *v, VkCommandBuffer cmd, uint32_t index, pg_error *err)
{
    pg_gpu *gpu = v->app.gpu;
    const pg_view_window *w = &v->win;
    VkDeviceSize bytes = (VkDeviceSize)w->extent.width * w->extent.height * 4;
    if (v->shot.size < bytes) {
        pg_buffer_destroy(gpu, &v->shot);
        pg_result r = pg_buffer_create(gpu, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, "view.screenshot", &v->shot, err);
        if (r) return r;
    }
    VkBufferImageCopy c = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                           .imageExtent = {w->extent.width, w->extent.height, 1}};
    vkCmdCopyImageToBuffer(cmd, w->images[index], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, v->shot.buffer, 1, &c);
    VkImageMemoryBarrier2 to_present = pg_image_barrier(
        w->images[index], VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, 0, VK_PIPELINE_STAGE_2_NONE, 0,
        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    VkBufferMemoryBarrier2 host = pg_buffer_barrier(v->shot.buffer, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                                    VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    pg_cmd_barriers(cmd, 1, &to_present, 1, &host);
    return PG_OK;
}

/* cmd waits for the acquired image (blit stage), signals render_done[index], fences slot fs */
static pg_result submit_frame(pg_gpu *gpu, pg_view_window *w, VkCommandBuffer cmd, uint32_t fs, uint32_t index,
                              pg_error *err)
{
    VkSemaphoreSubmitInfo wait = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO,
                                  .semaphore = w->image_ready[fs],
                                  .stageMask = VK_PIPELINE_STAGE_2_BLIT_BIT};
    VkSemaphoreSubmitInfo signal = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO,
                                    .semaphore = w->render_done[index],
                                    .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
    VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, .commandBuffer = cmd};
    VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2,
                        .waitSemaphoreInfoCount = 1,
                        .pWaitSemaphoreInfos = &wait,
                        .commandBufferInfoCount = 1,
                        .pCommandBufferInfos = &cbi,
                        .signalSemaphoreInfoCount = 1,
                        .pSignalSemaphoreInfos = &signal};
    PG_VK_TRY(err, vkResetFences(gpu->device, 1, &w->fence[fs]));
    PG_VK_TRY(err, vkQueueSubmit2(gpu->queue, 1, &si, w->fence[fs]));
    return PG_OK;
}

/* the screenshot, read after its own frame (slot fs): swapchain pixels -> RGBA for the PNG */
static pg_result save_screenshot(viewer *v, uint32_t fs, pg_error *err)
{
    pg_view_window *w = &v->win;
    PG_VK_TRY(err, vkWaitForFences(v->app.gpu->device, 1, &w->fence[fs], VK_TRUE, UINT64_MAX));
    uint32_t n = w->extent.width * w->extent.height;
    uint8_t *px = malloc((size_t)n * 4);
    if (!px) return PG_OK;
    memcpy(px, v->shot.mapped, (size_t)n * 4);
    if (w->format == VK_FORMAT_B8G8R8A8_SRGB || w->format == VK_FORMAT_B8G8R8A8_UNORM)
        for (uint32_t i = 0; i < n; i++) {
            uint8_t t = px[i * 4];
            px[i * 4] = px[i * 4 + 2];
            px[i * 4 + 2] = t;
        }
    for (uint32_t i = 0; i < n; i++) px[i * 4 + 3] = 255;
    pg_result r = pg_write_image(v->shot_file, px, w->extent.width, w->extent.height, err);
    free(px);
    if (r) return r;
    printf("view: screenshot %s (%ux%u)\n", v->shot_file, w->extent.width, w->extent.height);
    return PG_OK;
}

/* One viewer frame: the graph (and the reference for the difference view), the history, acquire,
 * one command buffer (source, blit, UI, screenshot copy), submit, present, the screenshot. */
pg_result draw_frame(viewer *v, bool capture, pg_error *err)
{
    pg_gpu *gpu = v->app.gpu;
    pg_view_window *w = &v->win;
    double t0 = pg_time_s();
    pg_frame_info fi = viewer_frame_info(v);
    pg_result r;
    if (v->session && (r = render_graph(v, &fi, err))) {
        /* a device loss ends the run; a frame the graph cannot make at these settings (a light
         * buffer past what one binding spans) drops the graph and says why: a new light count, a
         * switch or an edit loads it again (the run ended) */
        if (r == PG_ERR_VULKAN || r == PG_ERR_NO_DEVICE) return r;
        snprintf(v->error, sizeof v->error, "%s", err->msg);
        fprintf(stderr, "passgraph view: %s\n", err->msg);
        vkDeviceWaitIdle(gpu->device);
        pg_session_destroy(v->session);
        pg_session_destroy(v->naive);
        v->session = v->naive = NULL;
        v->failed_lights = v->light_count;
        memset(err, 0, sizeof *err);
    }
    bool show_diff = false;
    if (v->diff && v->session) {
        /* the reference failing (its file broken on disk) turns the difference view off and says
         * why; the graph goes on */
        if (render_diff(v, &fi, err)) {
            snprintf(v->error, sizeof v->error, "difference view off: %s", err->msg);
            fprintf(stderr, "passgraph view: %s\n", v->error);
            v->diff = false;
            pg_session_destroy(v->naive);
            v->naive = NULL;
            memset(err, 0, sizeof *err);
        } else {
            show_diff = true;
        }
    }
    if (v->session) record_history(v);

    /* this slot's previous frame (two frames ago) must be done with its command buffer and semaphore */
    const uint32_t fs = w->slot;
    PG_VK_TRY(err, vkWaitForFences(gpu->device, 1, &w->fence[fs], VK_TRUE, UINT64_MAX));
    uint32_t index;
    VkResult vr = vkAcquireNextImageKHR(gpu->device, w->swapchain, UINT64_MAX, w->image_ready[fs], VK_NULL_HANDLE, &index);
    if (vr == VK_ERROR_OUT_OF_DATE_KHR) { /* the semaphore was not signalled: rebuild, next frame */
        bool minimised;
        return pg_view_window_resize(w, &minimised, err);
    }
    if (vr != VK_SUCCESS && vr != VK_SUBOPTIMAL_KHR)
        return pg_fail(err, PG_ERR_VULKAN, "vkAcquireNextImageKHR failed: %s", pg_vk_result_name(vr));

    build_ui(v);

    VkCommandBuffer cmd = w->cmd[fs];
    PG_VK_TRY(err, vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    PG_VK_TRY(err, vkBeginCommandBuffer(cmd, &bi));
    VkImage src = VK_NULL_HANDLE;
    uint32_t sw = 0, sh = 0;
    if ((r = blit_source(v, cmd, show_diff, &src, &sw, &sh, err))) return r;
    blit_to_swapchain(cmd, w, index, src, sw, sh);
    bool shot = capture && w->usage_transfer_src;
    VkRenderPassBeginInfo rp = {
        .sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
        .renderPass = shot ? w->pass_capture : w->pass_present,
        .framebuffer = w->framebuffers[index],
        .renderArea = {{0, 0}, w->extent},
    };
    vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
    pg_ui_render(cmd);
    vkCmdEndRenderPass(cmd);
    if (shot && (r = record_screenshot(v, cmd, index, err))) return r;
    PG_VK_TRY(err, vkEndCommandBuffer(cmd));
    if ((r = submit_frame(gpu, w, cmd, fs, index, err))) return r;
    w->slot = (fs + 1) % PG_VIEW_FRAMES;
    VkPresentInfoKHR pi = {.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR,
                           .waitSemaphoreCount = 1,
                           .pWaitSemaphores = &w->render_done[index],
                           .swapchainCount = 1,
                           .pSwapchains = &w->swapchain,
                           .pImageIndices = &index};
    vr = vkQueuePresentKHR(gpu->queue, &pi);
    if (shot) {
        if ((r = save_screenshot(v, fs, err))) {
            /* --screenshot's (the run's result) fails the run; the button's or an --at one's is
             * shown and the viewer goes on */
            if (v->screenshot_path && !strcmp(v->shot_file, v->screenshot_path)) return r;
            snprintf(v->error, sizeof v->error, "screenshot not written: %s", err->msg);
            fprintf(stderr, "passgraph view: %s\n", v->error);
            memset(err, 0, sizeof *err);
        }
    } else if (capture) {
        fprintf(stderr, "passgraph view: this surface cannot be read back; screenshot skipped\n");
    }
    if (vr == VK_ERROR_OUT_OF_DATE_KHR || vr == VK_SUBOPTIMAL_KHR) {
        bool minimised;
        if ((r = pg_view_window_resize(w, &minimised, err))) return r;
    } else if (vr != VK_SUCCESS) {
        return pg_fail(err, PG_ERR_VULKAN, "vkQueuePresentKHR failed: %s", pg_vk_result_name(vr));
    }
    v->cpu_frame_ms = (pg_time_s() - t0) * 1e3;
    if (v->n_frame_ms < 512) v->frame_ms[v->n_frame_ms++] = v->cpu_frame_ms;
    return PG_OK;
}
