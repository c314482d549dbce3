/* graph_execute.c - physical resources, pass instances, recording and submission of a plan.
 * This file: create/destroy, settings and the lookup API; graph_execute_internal.h lists the
 * others. */
#include "graph_execute_internal.h"

#include <stdlib.h>
#include <string.h>

/* The pass instances and the per-plan query pools (the device must be idle). */
void pg_rt_destroy_passes(pg_runtime *rt)
{
    pg_gpu *gpu = rt->gpu;
    if (rt->plan) {
        for (uint32_t i = 0; i < rt->plan->n_passes; i++) {
            if (rt->pass_state[i]) {
                rt->plan->passes[i].type->destroy(rt->pass_state[i], gpu);
                free(rt->pass_state[i]);
                rt->pass_state[i] = NULL;
            }
        }
    }
    for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++) {
        if (rt->slot[f].queries) vkDestroyQueryPool(gpu->device, rt->slot[f].queries, NULL);
        if (rt->slot[f].cqueries) vkDestroyQueryPool(gpu->device, rt->slot[f].cqueries, NULL);
        pg_buffer_destroy(gpu, &rt->slot[f].timestamps);
        rt->slot[f].queries = rt->slot[f].cqueries = VK_NULL_HANDLE;
        rt->slot[f].pending = false; /* the device is idle: every fence has signalled */
    }
    rt->gpu_valid = false;
    memset(rt->gpu_hist, 0, sizeof rt->gpu_hist);
    rt->prev_gen = 0;
}

void pg_rt_destroy_built(pg_runtime *rt)
{
    pg_gpu *gpu = rt->gpu;
    if (!rt->built && !rt->plan) return;
    vkDeviceWaitIdle(gpu->device);
    pg_rt_destroy_passes(rt);
    for (uint32_t i = 0; i < PG_MAX_RESOURCES; i++) {
        pg_phys_resource *r = &rt->res[i];
        if (r->view) vkDestroyImageView(gpu->device, r->view, NULL);
        if (r->image) vkDestroyImage(gpu->device, r->image, NULL);
        if (r->buffer) vkDestroyBuffer(gpu->device, r->buffer, NULL);
        if (r->own_memory) pg_gpu_free_memory(gpu, r->own_memory);
        memset(r, 0, sizeof *r);
        if (rt->block_memory[i]) pg_gpu_free_memory(gpu, rt->block_memory[i]);
        rt->block_memory[i] = VK_NULL_HANDLE;
        rt->block_memory_size[i] = 0;
        rt->block_split[i] = false;
        rt->persistent_initialized[i] = false;
    }
    for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++)
        for (int i = 0; i < 2; i++) pg_buffer_destroy(gpu, &rt->slot[f].readback[i]);
    rt->readback_valid[0] = rt->readback_valid[1] = false;
    rt->built = false;
}

pg_result pg_runtime_create(pg_gpu *gpu, uint32_t frame_block_size, pg_runtime **out, pg_error *err)
{
    *out = NULL;
    if (!frame_block_size || frame_block_size > 65536)
        return pg_fail(err, PG_ERR_INVALID_ARG, "pg_runtime_create: frame block of %u bytes (1..65536)",
                       frame_block_size);
    pg_runtime *rt = calloc(1, sizeof *rt);
    if (!rt) return pg_fail(err, PG_ERR_OOM, "out of memory");
    rt->gpu = gpu;
    rt->frame_size = frame_block_size;
    rt->n_in_flight = 1;
    pg_result r;
    VkDescriptorSetLayoutBinding b = {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
                                      VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT |
                                          VK_SHADER_STAGE_COMPUTE_BIT,
                                      NULL};
    VkDescriptorSetLayoutCreateInfo lci = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                           .bindingCount = 1, .pBindings = &b};
    VkResult vr = vkCreateDescriptorSetLayout(gpu->device, &lci, NULL, &rt->frame_layout);
    if (vr) goto vkfail;
    VkDescriptorPoolSize ps = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, PG_MAX_FRAMES_IN_FLIGHT};
    VkDescriptorPoolCreateInfo pci = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                      .maxSets = PG_MAX_FRAMES_IN_FLIGHT, .poolSizeCount = 1, .pPoolSizes = &ps};
    vr = vkCreateDescriptorPool(gpu->device, &pci, NULL, &rt->frame_pool);
    if (vr) goto vkfail;
    for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++) {
        char nm[32];
        snprintf(nm, sizeof nm, "frame%u.uniforms", f);
        if (!(rt->slot[f].frame = calloc(1, frame_block_size))) {
            pg_runtime_destroy(rt);
            return pg_fail(err, PG_ERR_OOM, "out of memory");
        }
        if ((r = pg_buffer_create(gpu, frame_block_size, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true, nm,
                                  &rt->slot[f].frame_ubo, err)))
            goto fail;
        VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                          .descriptorPool = rt->frame_pool, .descriptorSetCount = 1,
                                          .pSetLayouts = &rt->frame_layout};
        vr = vkAllocateDescriptorSets(gpu->device, &ai, &rt->slot[f].frame_set);
        if (vr) goto vkfail;
        VkDescriptorBufferInfo bi = {rt->slot[f].frame_ubo.buffer, 0, VK_WHOLE_SIZE};
        VkWriteDescriptorSet w = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = rt->slot[f].frame_set,
                                  .dstBinding = 0, .descriptorCount = 1,
                                  .descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, .pBufferInfo = &bi};
        vkUpdateDescriptorSets(gpu->device, 1, &w, 0, NULL);
        VkFenceCreateInfo fci = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        vr = vkCreateFence(gpu->device, &fci, NULL, &rt->slot[f].fence);
        if (vr) goto vkfail;
        pg_gpu_name(gpu, VK_OBJECT_TYPE_FENCE, (uint64_t)rt->slot[f].fence, "frame%u.fence", f);
    }
    pg_gpu_name(gpu, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, (uint64_t)rt->frame_layout, "frame.layout");
    if (gpu->timeline_semaphores)
        for (int q = 0; q < PG_QUEUE_COUNT; q++) {
            VkSemaphoreTypeCreateInfo tci = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO,
                                             .semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE};
            VkSemaphoreCreateInfo sci = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, .pNext = &tci};
            vr = vkCreateSemaphore(gpu->device, &sci, NULL, &rt->timeline[q]);
            if (vr) goto vkfail;
            pg_gpu_name(gpu, VK_OBJECT_TYPE_SEMAPHORE, (uint64_t)rt->timeline[q], "timeline.%s",
                        pg_queue_name((pg_queue)q));
        }
    *out = rt;
    return PG_OK;
vkfail:
    r = pg_fail(err, PG_ERR_VULKAN, "runtime set-up failed: %s", pg_vk_result_name(vr));
fail:
    pg_runtime_destroy(rt);
    return r;
}

void pg_runtime_destroy(pg_runtime *rt)
{
    if (!rt) return;
    pg_gpu *gpu = rt->gpu;
    pg_rt_destroy_built(rt);
    for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++) {
        if (rt->slot[f].fence) vkDestroyFence(gpu->device, rt->slot[f].fence, NULL);
        for (uint32_t b = 0; b < PG_MAX_BATCHES; b++)
            if (rt->slot[f].cmds[b]) vkFreeCommandBuffers(gpu->device, rt->slot[f].cmd_pool[b], 1, &rt->slot[f].cmds[b]);
        pg_buffer_destroy(gpu, &rt->slot[f].frame_ubo);
        free(rt->slot[f].frame);
    }
    for (int q = 0; q < PG_QUEUE_COUNT; q++)
        if (rt->timeline[q]) vkDestroySemaphore(gpu->device, rt->timeline[q], NULL);
    if (rt->frame_pool) vkDestroyDescriptorPool(gpu->device, rt->frame_pool, NULL);
    if (rt->frame_layout) vkDestroyDescriptorSetLayout(gpu->device, rt->frame_layout, NULL);
    free(rt);
}

void pg_runtime_set_settings(pg_runtime *rt, const pg_param_override *settings, uint32_t n_settings)
{
    rt->settings = n_settings ? settings : NULL;
    rt->n_settings = settings ? n_settings : 0;
}

uint64_t pg_frame_counter_sum(const pg_frame_stats *st, const char *name)
{
    uint64_t sum = 0;
    for (uint32_t i = 0; st && name && i < st->n_counters; i++)
        if (!strcmp(st->counters[i].name, name)) sum += st->counters[i].value;
    return sum;
}

const char *pg_ctx_setting(const pg_pass_create_ctx *ctx, const char *key)
{
    const char *found = NULL;
    for (uint32_t i = 0; ctx && key && i < ctx->n_settings; i++)
        if (ctx->settings[i].key && !strcmp(ctx->settings[i].key, key)) found = ctx->settings[i].value;
    return found;
}

const void *pg_runtime_output(const pg_runtime *rt, int which, uint32_t *w, uint32_t *h, pg_format *fmt)
{
    if (which < 0 || which > 1 || !rt->plan || !rt->readback_valid[which]) return NULL;
    int idx = which ? rt->plan->hdr_output : rt->plan->output;
    if (idx < 0) return NULL;
    const pg_plan_resource *pr = &rt->plan->resources[idx];
    if (w) *w = pr->width;
    if (h) *h = pr->height;
    if (fmt) *fmt = pr->format;
    return rt->slot[rt->cur].readback[which].mapped;
}

const char *pg_rebuild_kind_name(pg_rebuild_kind k)
{
    static const char *const names[] = {"none", "values", "pipelines", "resources", "memory"};
    return (unsigned)k < 5 ? names[k] : "?";
}

pg_runtime_stats pg_runtime_get_stats(const pg_runtime *rt)
{
    pg_runtime_stats st = rt->stats;
    st.grow_bytes = 0;
    for (uint32_t i = 0; rt->plan && i < rt->plan->n_resources; i++)
        if (rt->plan->resources[i].growable && !rt->plan->resources[i].culled) st.grow_bytes += rt->res[i].size;
    return st;
}

const pg_phys_resource *pg_runtime_output_image(const pg_runtime *rt, int which)
{
    if (!rt->plan || which < 0 || which > 1) return NULL;
    int idx = which ? rt->plan->hdr_output : rt->plan->output;
    return idx >= 0 ? &rt->res[idx] : NULL;
}

pg_result pg_runtime_resource(const pg_runtime *rt, pg_res_handle h, const pg_phys_resource **out, pg_error *err)
{
    if (out) *out = NULL;
    if (!rt || !rt->built) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_runtime_resource: no plan set");
    pg_result r = pg_plan_resource_get(rt->plan, h, NULL, err);
    if (!r && out) *out = &rt->res[h.index];
    return r;
}

/* by name, through a handle of the current plan */
static int buffer_index(const pg_runtime *rt, const char *name)
{
    pg_res_handle h;
    const pg_plan_resource *pr;
    if (!rt->plan || !name || pg_plan_find_resource(rt->plan, name, &h, NULL) ||
        pg_plan_resource_get(rt->plan, h, &pr, NULL))
        return -1;
    return pr->kind == PG_RES_BUFFER && !pr->culled && rt->res[h.index].buffer ? (int)h.index : -1;
}

uint64_t pg_runtime_buffer_size(const pg_runtime *rt, const char *name)
{
    int i = buffer_index(rt, name);
    return i < 0 ? 0 : rt->res[i].size;
}

pg_result pg_runtime_read_buffer(pg_runtime *rt, const char *name, uint64_t offset, uint64_t size, void *dst,
                                 pg_error *err)
{
    int i = buffer_index(rt, name);
    if (i < 0) return pg_fail(err, PG_ERR_INVALID_ARG, "read_buffer: no buffer resource '%s' in the plan", name ? name : "");
    const pg_phys_resource *r = &rt->res[i];
    if (offset > r->size || size > r->size - offset)
        return pg_fail(err, PG_ERR_INVALID_ARG, "read_buffer: '%s': bytes %llu..%llu past its %llu bytes", name,
                       (unsigned long long)offset, (unsigned long long)(offset + size), (unsigned long long)r->size);
    if (!size) return PG_OK;
    pg_buffer staging;
    pg_result res = pg_buffer_create(rt->gpu, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, "readback.buffer",
                                     &staging, err);
    if (res) return res;
    VkCommandBuffer cmd;
    if ((res = pg_gpu_begin_once(rt->gpu, &cmd, err))) {
        pg_buffer_destroy(rt->gpu, &staging);
        return res;
    }
    VkMemoryBarrier2 mb = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
        .srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
        .srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT,
        .dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT,
        .dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT,
    };
    VkDependencyInfo di = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1, .pMemoryBarriers = &mb};
    vkCmdPipelineBarrier2(cmd, &di);
    VkBufferCopy c = {offset, 0, size};
    vkCmdCopyBuffer(cmd, r->buffer, staging.buffer, 1, &c);
    VkBufferMemoryBarrier2 hb = pg_buffer_barrier(staging.buffer, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                                  VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    pg_cmd_barriers(cmd, 0, NULL, 1, &hb);
    res = pg_gpu_end_once(rt->gpu, cmd, err);
    if (!res) memcpy(dst, staging.mapped, size);
    pg_buffer_destroy(rt->gpu, &staging);
    return res;
}

pg_queue_caps pg_runtime_queue_caps(const pg_runtime *rt, bool async_off)
{
    pg_queue_caps c;
    memset(&c, 0, sizeof c);
    const pg_gpu *g = rt->gpu;
    c.async_off = async_off;
    if (g->compute_queue && rt->timeline[0]) {
        c.n_queues = 2;
        c.separate_family = g->compute_family != g->queue_family;
    } else {
        c.n_queues = 1;
        snprintf(c.why_single, sizeof c.why_single, "%s",
                 g->single_queue_why[0] ? g->single_queue_why : "the device lacks timelineSemaphore");
    }
    return c;
}

const pg_phys_resource *pg_runtime_resource_at(const pg_runtime *rt, int index)
{
    if (!rt || !rt->plan || index < 0 || (uint32_t)index >= rt->plan->n_resources) return NULL;
    return &rt->res[index];
}
