/* graph_execute_frames.c - frames in flight: the frame slots (frame block, fence, command
 * buffers, readback staging), the timeline semaphores and the submission of a frame's batches
 * (owns pg_runtime.frames, graph_execute_internal.h). Calls graph_execute_timing.c only. */
#include "graph_execute_internal.h"

#include <stdlib.h>
#include <string.h>

/* Set-up calls are not counted by fault injection (pg_vk_fault_next): no PG_VK_TRY here. */
static pg_result setup_failed(VkResult vr, pg_error *err)
{
    return pg_fail(err, PG_ERR_VULKAN, "runtime set-up failed: %s", pg_vk_result_name(vr));
}

static pg_result create_slot(pg_runtime *rt, uint32_t f, pg_error *err)
{
    pg_gpu *gpu = rt->cfg.gpu;
    pg_rt_frames *fr = &rt->frames;
    char nm[32];
    snprintf(nm, sizeof nm, "frame%u.uniforms", f);
    if (!(fr->slot[f].frame = calloc(1, rt->cfg.frame_size))) return pg_fail(err, PG_ERR_OOM, "out of memory");
    pg_result r = pg_buffer_create(gpu, rt->cfg.frame_size, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true, nm,
                                   &fr->slot[f].frame_ubo, err);
    if (r) return r;
    VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                      .descriptorPool = fr->frame_pool, .descriptorSetCount = 1,
                                      .pSetLayouts = &fr->frame_layout};
    VkResult vr = vkAllocateDescriptorSets(gpu->device, &ai, &fr->slot[f].frame_set);
    if (vr) return setup_failed(vr, err);
    VkDescriptorBufferInfo bi = {fr->slot[f].frame_ubo.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = fr->slot[f].frame_set,
                              .dstBinding = 0, .descriptorCount = 1,
                              .descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, .pBufferInfo = &bi};
    vkUpdateDescriptorSets(gpu->device, 1, &w, 0, NULL);
    VkFenceCreateInfo fci = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    if ((vr = vkCreateFence(gpu->device, &fci, NULL, &fr->slot[f].fence))) return setup_failed(vr, err);
    pg_gpu_name(gpu, VK_OBJECT_TYPE_FENCE, (uint64_t)fr->slot[f].fence, "frame%u.fence", f);
    return PG_OK;
}

/* The frame block's layout and pool, every slot's frame block, uniform buffer, descriptor set
 * and fence, and the timeline semaphores (one frame in flight to begin with). On failure the
 * caller destroys (pg_rt_frames_destroy). */
pg_result pg_rt_frames_create(pg_runtime *rt, pg_error *err)
{
    pg_gpu *gpu = rt->cfg.gpu;
    pg_rt_frames *fr = &rt->frames;
    pg_result r;
    fr->n_in_flight = 1;
    VkDescriptorSetLayoutBinding b = {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
                                      VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT |
                                          VK_SHADER_STAGE_COMPUTE_BIT,
                                      NULL};
    VkDescriptorSetLayoutCreateInfo lci = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                           .bindingCount = 1, .pBindings = &b};
    VkResult vr = vkCreateDescriptorSetLayout(gpu->device, &lci, NULL, &fr->frame_layout);
    if (vr) return setup_failed(vr, err);
    VkDescriptorPoolSize ps = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, PG_MAX_FRAMES_IN_FLIGHT};
    VkDescriptorPoolCreateInfo pci = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                      .maxSets = PG_MAX_FRAMES_IN_FLIGHT, .poolSizeCount = 1, .pPoolSizes = &ps};
    if ((vr = vkCreateDescriptorPool(gpu->device, &pci, NULL, &fr->frame_pool))) return setup_failed(vr, err);
    for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++)
        if ((r = create_slot(rt, f, err))) return r;
    pg_gpu_name(gpu, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, (uint64_t)fr->frame_layout, "frame.layout");
    if (!gpu->timeline_semaphores) return PG_OK;
    for (int q = 0; q < PG_QUEUE_COUNT; q++) {
        VkSemaphoreTypeCreateInfo tci = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO,
                                         .semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE};
        VkSemaphoreCreateInfo sci = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, .pNext = &tci};
        if ((vr = vkCreateSemaphore(gpu->device, &sci, NULL, &fr->timeline[q]))) return setup_failed(vr, err);
        pg_gpu_name(gpu, VK_OBJECT_TYPE_SEMAPHORE, (uint64_t)fr->timeline[q], "timeline.%s", pg_queue_name((pg_queue)q));
    }
    return PG_OK;
}

void pg_rt_frames_destroy(pg_runtime *rt)
{
    pg_gpu *gpu = rt->cfg.gpu;
    pg_rt_frames *fr = &rt->frames;
    for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++) {
        if (fr->slot[f].fence) vkDestroyFence(gpu->device, fr->slot[f].fence, NULL);
        for (uint32_t b = 0; b < PG_MAX_BATCHES; b++)
            if (fr->slot[f].cmds[b]) vkFreeCommandBuffers(gpu->device, fr->slot[f].cmd_pool[b], 1, &fr->slot[f].cmds[b]);
        pg_buffer_destroy(gpu, &fr->slot[f].frame_ubo);
        free(fr->slot[f].frame);
    }
    for (int q = 0; q < PG_QUEUE_COUNT; q++)
        if (fr->timeline[q]) vkDestroySemaphore(gpu->device, fr->timeline[q], NULL);
    if (fr->frame_pool) vkDestroyDescriptorPool(gpu->device, fr->frame_pool, NULL);
    if (fr->frame_layout) vkDestroyDescriptorSetLayout(gpu->device, fr->frame_layout, NULL);
}

/* Every slot's staging buffers for the plan's output and hdr_output. */
pg_result pg_rt_frames_build_readback(pg_runtime *rt, pg_error *err)
{
    const pg_graph_plan *plan = rt->cur.plan;
    int outs[2] = {plan->output, plan->hdr_output};
    for (int k = 0; k < 2; k++) {
        if (outs[k] < 0) continue;
        const pg_plan_resource *pr = &plan->resources[outs[k]];
        VkDeviceSize bytes = (VkDeviceSize)pr->width * pr->height * pg_format_get(pr->format)->bytes_per_pixel;
        for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++) {
            char nm[40];
            snprintf(nm, sizeof nm, "frame%u.readback.%s", f, k ? "hdr" : "output");
            pg_result r = pg_buffer_create(rt->cfg.gpu, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, nm,
                                           &rt->frames.slot[f].readback[k], err);
            if (r) return r;
        }
    }
    return PG_OK;
}

void pg_rt_frames_destroy_readback(pg_runtime *rt)
{
    for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++)
        for (int i = 0; i < 2; i++) pg_buffer_destroy(rt->cfg.gpu, &rt->frames.slot[f].readback[i]);
    rt->frames.readback_valid[0] = rt->frames.readback_valid[1] = false;
}

/* The device is idle and the plan's pass instances go: no frame is pending, and the next
 * frame's compute queue does not wait for batches of this plan. */
void pg_rt_frames_forget(pg_runtime *rt)
{
    for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++) rt->frames.slot[f].pending = false;
    rt->frames.prev_gen = 0;
}

/* Waits for slot f's frame if it is pending (counts a wait that found the fence unsignalled)
 * and collects its timestamps. */
static pg_result wait_slot(pg_runtime *rt, uint32_t f, double *wait_ms, pg_error *err)
{
    pg_rt_frames *fr = &rt->frames;
    if (!fr->slot[f].pending) return PG_OK;
    VkDevice dev = rt->cfg.gpu->device;
    VkResult st = vkGetFenceStatus(dev, fr->slot[f].fence);
    if (st == VK_NOT_READY) {
        rt->stats.fence_waits++;
        double tw = pg_rt_now_ms();
        PG_VK_TRY(err, vkWaitForFences(dev, 1, &fr->slot[f].fence, VK_TRUE, UINT64_MAX));
        *wait_ms += pg_rt_now_ms() - tw;
    } else if (st != VK_SUCCESS) {
        return pg_fail(err, PG_ERR_VULKAN, "frame fence: %s", pg_vk_result_name(st));
    }
    fr->slot[f].pending = false;
    pg_rt_timing_collect(rt, f, fr->slot[f].frame_no);
    return PG_OK;
}

void pg_runtime_test_drop_frame_barrier(pg_runtime *rt, bool drop)
{
    rt->frames.test_no_frame_barrier = drop;
}

pg_result pg_runtime_set_frames_in_flight(pg_runtime *rt, uint32_t n, pg_error *err)
{
    if (n < 1 || n > PG_MAX_FRAMES_IN_FLIGHT)
        return pg_fail(err, PG_ERR_INVALID_ARG, "frames in flight: %u (1..%d)", n, PG_MAX_FRAMES_IN_FLIGHT);
    pg_result r = pg_runtime_wait_idle(rt, err);
    if (r) return r;
    rt->frames.n_in_flight = n;
    return PG_OK;
}

pg_result pg_runtime_wait_idle(pg_runtime *rt, pg_error *err)
{
    double w = 0;
    for (uint32_t k = 1; k <= PG_MAX_FRAMES_IN_FLIGHT; k++) { /* oldest first: the freshest times win */
        pg_result r = wait_slot(rt, (rt->frames.cur + k) % PG_MAX_FRAMES_IN_FLIGHT, &w, err);
        if (r) return r;
    }
    return PG_OK;
}

/* Step 1 of a frame: its slot (*slot), after waiting for the frame that used it n_in_flight
 * frames ago, with the caller's frame block copied in and uploaded. */
pg_result pg_rt_frame_begin(pg_runtime *rt, const void *frame_block, uint32_t *slot, double *wait_ms,
                            pg_error *err)
{
    pg_rt_frames *fr = &rt->frames;
    const uint32_t f = (uint32_t)(fr->frame_no % fr->n_in_flight);
    *slot = f;
    pg_result r = wait_slot(rt, f, wait_ms, err);
    if (r) return r;
    memcpy(fr->slot[f].frame, frame_block, rt->cfg.frame_size);
    memcpy(fr->slot[f].frame_ubo.mapped, fr->slot[f].frame, rt->cfg.frame_size);
    return PG_OK;
}

/* Step 2: slot f's command buffer for batch b, allocated on first use from its queue's pool
 * (again when the batch moved to the other queue), reset and begun. */
pg_result pg_rt_frame_cmd(pg_runtime *rt, uint32_t f, uint32_t b, VkCommandBuffer *out, pg_error *err)
{
    pg_gpu *gpu = rt->cfg.gpu;
    pg_rt_frames *fr = &rt->frames;
    const int q = rt->cur.plan->batches[b].queue;
    VkCommandPool pool = q == PG_QUEUE_COMPUTE ? gpu->compute_cmd_pool : gpu->cmd_pool;
    if (fr->slot[f].cmds[b] && fr->slot[f].cmd_pool[b] != pool) {
        vkFreeCommandBuffers(gpu->device, fr->slot[f].cmd_pool[b], 1, &fr->slot[f].cmds[b]);
        fr->slot[f].cmds[b] = VK_NULL_HANDLE;
    }
    if (!fr->slot[f].cmds[b]) {
        VkCommandBufferAllocateInfo cai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                           .commandPool = pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                           .commandBufferCount = 1};
        PG_VK_TRY(err, vkAllocateCommandBuffers(gpu->device, &cai, &fr->slot[f].cmds[b]));
        fr->slot[f].cmd_pool[b] = pool;
        pg_gpu_name(gpu, VK_OBJECT_TYPE_COMMAND_BUFFER, (uint64_t)(uintptr_t)fr->slot[f].cmds[b], "frame%u.batch%u.%s",
                    f, b, pg_queue_name((pg_queue)q));
    }
    VkCommandBuffer cmd = fr->slot[f].cmds[b];
    PG_VK_TRY(err, vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    PG_VK_TRY(err, vkBeginCommandBuffer(cmd, &bi));
    *out = cmd;
    return PG_OK;
}

/* In the frame's last batch: copies the outputs to slot f's staging buffers when readback is
 * set (they become pg_runtime_output's pixels once the frame's fence signals). */
void pg_rt_frame_record_readback(pg_runtime *rt, VkCommandBuffer cmd, uint32_t f, bool readback)
{
    pg_rt_frames *fr = &rt->frames;
    const int outs[2] = {rt->cur.plan->output, rt->cur.plan->hdr_output};
    for (int k = 0; k < 2; k++) {
        fr->readback_valid[k] = false;
        if (!readback || outs[k] < 0 || !fr->slot[f].readback[k].buffer) continue;
        const pg_phys_resource *r = &rt->mem.res[outs[k]];
        VkBufferImageCopy c = {.imageSubresource = {pg_vk_aspect(r->format), 0, 0, 1},
                               .imageExtent = {r->width, r->height, 1}};
        vkCmdCopyImageToBuffer(cmd, r->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, fr->slot[f].readback[k].buffer, 1,
                               &c);
        VkBufferMemoryBarrier2 hb =
            pg_buffer_barrier(fr->slot[f].readback[k].buffer, VK_PIPELINE_STAGE_2_COPY_BIT,
                              VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        pg_cmd_barriers(cmd, 0, NULL, 1, &hb);
        fr->readback_valid[k] = true;
    }
}

/* A frame recorded but not submitted: no output to read back. */
void pg_rt_frame_drop_readback(pg_runtime *rt)
{
    rt->frames.readback_valid[0] = rt->frames.readback_valid[1] = false;
}

/* vkQueueSubmit2, or VK_ERROR_DEVICE_LOST without submitting when fault injection picks this
 * call (pg_vk_fault_next, PASSGRAPH_FAULT_AT: tests/cli/fault_test.sh). */
static VkResult submit_or_fault(VkQueue queue, const VkSubmitInfo2 *si, VkFence fence)
{
    if (pg_vk_fault_next("vkQueueSubmit2(batch)")) return VK_ERROR_DEVICE_LOST;
    return vkQueueSubmit2(queue, 1, si, fence);
}

/* Step 3: submits slot f's batches in plan order. Each signals its queue's timeline semaphore;
 * a batch waits for the newest other-queue batch it depends on (and the first compute batch for
 * the previous frame's graphics work); the last (graphics) batch signals the slot's fence. The
 * slot is then pending and the frame counted. */
pg_result pg_rt_frame_submit(pg_runtime *rt, uint32_t f, pg_error *err)
{
    pg_gpu *gpu = rt->cfg.gpu;
    pg_rt_frames *fr = &rt->frames;
    const pg_graph_plan *plan = rt->cur.plan;
    PG_VK_TRY(err, vkResetFences(gpu->device, 1, &fr->slot[f].fence));
    uint64_t value[PG_MAX_BATCHES] = {0};
    const uint64_t gfx_before = fr->tl_value[PG_QUEUE_GRAPHICS];
    for (uint32_t b = 0; b < plan->n_batches; b++) {
        const pg_plan_batch *bt = &plan->batches[b];
        const int q = bt->queue, other = 1 - q;
        uint64_t wv = 0, wst = 0;
        for (uint32_t w = 0; w < bt->n_waits; w++) {
            if (value[bt->waits[w].batch] > wv) wv = value[bt->waits[w].batch];
            wst |= bt->waits[w].stages;
        }
        if (bt->prev_frame_wait >= 0 && other == PG_QUEUE_GRAPHICS && gfx_before) {
            uint64_t v = fr->prev_gen == plan->generation ? fr->prev_batch_value[bt->prev_frame_wait] : gfx_before;
            if (v > wv) wv = v;
            wst |= VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        }
        VkSemaphoreSubmitInfo wsi = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = fr->timeline[other],
                                     .value = wv, .stageMask = wst};
        VkSemaphoreSubmitInfo ssi = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = fr->timeline[q],
                                     .value = 0, .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
        const bool sem = plan->async && fr->timeline[q];
        if (sem) value[b] = ssi.value = ++fr->tl_value[q];
        VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO,
                                         .commandBuffer = fr->slot[f].cmds[b]};
        VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2,
                            .waitSemaphoreInfoCount = sem && wv ? 1 : 0, .pWaitSemaphoreInfos = &wsi,
                            .commandBufferInfoCount = 1, .pCommandBufferInfos = &cbi,
                            .signalSemaphoreInfoCount = sem ? 1 : 0, .pSignalSemaphoreInfos = &ssi};
        VkQueue queue = q == PG_QUEUE_COMPUTE ? gpu->compute_queue : gpu->queue;
        VkResult sr = submit_or_fault(queue, &si, bt->last ? fr->slot[f].fence : VK_NULL_HANDLE);
        if (sr != VK_SUCCESS) {
            if (sem) fr->tl_value[q]--; /* never signalled: no later wait may name it */
            /* batches 0..b-1 run: the next frame would reuse this slot's command buffers, uniform
             * block and queries while they may still be read (the slot is not marked pending; its
             * fence comes with the last batch), so they are waited for first */
            if (b > 0) vkDeviceWaitIdle(gpu->device);
            return pg_fail(err, PG_ERR_VULKAN, "vkQueueSubmit2(batch %u of %u, %s queue) failed: %s", b, plan->n_batches,
                           pg_queue_name((pg_queue)q), pg_vk_result_name(sr));
        }
    }
    memcpy(fr->prev_batch_value, value, sizeof value);
    fr->prev_gen = plan->generation;
    fr->slot[f].pending = true;
    fr->slot[f].frame_no = fr->frame_no++;
    fr->cur = f;
    rt->stats.frames_submitted++;
    return PG_OK;
}

/* Step 4: after slot f's submission. With one frame in flight, or a read-back, waits for it (its
 * staging is read after its fence); then collects every other frame found finished, oldest
 * first, without waiting. *idle: no frame is in flight any more. */
pg_result pg_rt_frame_settle(pg_runtime *rt, uint32_t f, bool readback, double *wait_ms, bool *idle,
                             pg_error *err)
{
    pg_rt_frames *fr = &rt->frames;
    VkDevice dev = rt->cfg.gpu->device;
    const uint32_t n_fif = fr->n_in_flight;
    if (n_fif == 1 || readback) {
        rt->stats.sync_waits++;
        double tw = pg_rt_now_ms();
        PG_VK_TRY(err, vkWaitForFences(dev, 1, &fr->slot[f].fence, VK_TRUE, UINT64_MAX));
        *wait_ms += pg_rt_now_ms() - tw;
        fr->slot[f].pending = false;
        pg_rt_timing_collect(rt, f, fr->slot[f].frame_no);
    }
    *idle = true;
    for (uint32_t k = 1; k <= n_fif; k++) {
        uint32_t g = (f + k) % n_fif; /* oldest first */
        if (!fr->slot[g].pending) continue;
        if (vkGetFenceStatus(dev, fr->slot[g].fence) == VK_SUCCESS) {
            fr->slot[g].pending = false;
            pg_rt_timing_collect(rt, g, fr->slot[g].frame_no);
        } else {
            *idle = false;
        }
    }
    return PG_OK;
}
