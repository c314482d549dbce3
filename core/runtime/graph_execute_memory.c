/* graph_execute_memory.c - physical resources, memory blocks, pass instances, growable buffers. */
#include "graph_execute_internal.h"

#include "alias_pack.h"

#include <stdlib.h>

pg_result pg_rt_create_unbound(pg_runtime *rt, int i, pg_error *err)
{
    pg_gpu *gpu = rt->gpu;
    const pg_plan_resource *pr = &rt->plan->resources[i];
    pg_phys_resource *r = &rt->res[i];
    r->kind = pr->kind;
    if (pr->kind == PG_RES_IMAGE) {
        const pg_format_info *fi = pg_format_get(pr->format);
        r->format = (VkFormat)fi->vk_format;
        r->pg_fmt = pr->format;
        r->width = pr->width;
        r->height = pr->height;
        VkImageCreateInfo ici = {
            .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
            .imageType = VK_IMAGE_TYPE_2D,
            .format = r->format,
            .extent = {pr->width, pr->height, 1},
            .mipLevels = 1,
            .arrayLayers = 1,
            .samples = VK_SAMPLE_COUNT_1_BIT,
            .tiling = VK_IMAGE_TILING_OPTIMAL,
            .usage = pr->usage ? pr->usage : VK_IMAGE_USAGE_SAMPLED_BIT,
            .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
        };
        VkImageFormatProperties ifp;
        VkResult fr = vkGetPhysicalDeviceImageFormatProperties(gpu->phys, ici.format, ici.imageType, ici.tiling,
                                                               ici.usage, 0, &ifp);
        if (fr != VK_SUCCESS)
            return pg_fail(err, PG_ERR_FORMAT, "resource '%s': format %s does not support its usage (0x%x) on %s",
                           pr->name, fi->name, ici.usage, gpu->props.deviceName);
        if (pr->width > ifp.maxExtent.width || pr->height > ifp.maxExtent.height)
            return pg_fail(err, PG_ERR_LIMIT, "resource '%s': %ux%u exceeds the device limit %ux%u", pr->name,
                           pr->width, pr->height, ifp.maxExtent.width, ifp.maxExtent.height);
        PG_VK_TRY(err, vkCreateImage(gpu->device, &ici, NULL, &r->image));
        pg_gpu_name(gpu, VK_OBJECT_TYPE_IMAGE, (uint64_t)r->image, "%s", pr->name);
    } else {
        r->size = pr->size_bytes;
        if (pr->growable) {
            uint32_t c = pg_rt_capacity_slot(rt, pr->name, false);
            if (c != UINT32_MAX && rt->capacity[c].bytes > r->size) r->size = rt->capacity[c].bytes;
        }
        VkBufferCreateInfo bci = {
            .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
            .size = r->size,
            /* + TRANSFER_SRC: pg_runtime_read_buffer can copy any buffer out */
            .usage = (pr->usage ? pr->usage : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
            .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
        };
        PG_VK_TRY(err, vkCreateBuffer(gpu->device, &bci, NULL, &r->buffer));
        pg_gpu_name(gpu, VK_OBJECT_TYPE_BUFFER, (uint64_t)r->buffer, "%s", pr->name);
    }
    return PG_OK;
}

VkMemoryRequirements pg_rt_requirements(pg_runtime *rt, int i)
{
    VkMemoryRequirements req = {0};
    if (rt->res[i].image) vkGetImageMemoryRequirements(rt->gpu->device, rt->res[i].image, &req);
    else vkGetBufferMemoryRequirements(rt->gpu->device, rt->res[i].buffer, &req);
    return req;
}

static pg_result bind(pg_runtime *rt, int i, VkDeviceMemory mem, VkDeviceSize offset, pg_error *err)
{
    pg_phys_resource *r = &rt->res[i];
    if (r->image) {
        PG_VK_TRY(err, vkBindImageMemory(rt->gpu->device, r->image, mem, offset));
        VkImageViewCreateInfo vci = {
            .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
            .image = r->image,
            .viewType = VK_IMAGE_VIEW_TYPE_2D,
            .format = r->format,
            .subresourceRange = {pg_vk_aspect(r->format), 0, 1, 0, 1},
        };
        PG_VK_TRY(err, vkCreateImageView(rt->gpu->device, &vci, NULL, &r->view));
        pg_gpu_name(rt->gpu, VK_OBJECT_TYPE_IMAGE_VIEW, (uint64_t)r->view, "%s.view",
                    rt->plan->resources[i].name);
    } else {
        PG_VK_TRY(err, vkBindBufferMemory(rt->gpu->device, r->buffer, mem, offset));
    }
    return PG_OK;
}

static pg_result alloc(pg_runtime *rt, VkDeviceSize size, uint32_t bits, const char *name, VkDeviceMemory *out,
                       pg_error *err)
{
    VkResult vr = pg_gpu_alloc_device_memory(rt->gpu, size, bits, out);
    if (vr != VK_SUCCESS)
        return pg_fail(err, PG_ERR_VULKAN, "%s: vkAllocateMemory(%llu bytes) failed: %s", name,
                       (unsigned long long)size, pg_vk_result_name(vr));
    pg_gpu_name(rt->gpu, VK_OBJECT_TYPE_DEVICE_MEMORY, (uint64_t)*out, "%s", name);
    return PG_OK;
}

static pg_result create_pass(pg_runtime *rt, int pi, pg_error *err)
{
    const pg_graph_plan *plan = rt->plan;
    const pg_plan_pass *pass = &plan->passes[pi];
    pg_pass_create_ctx ctx = {
        .gpu = rt->gpu,
        .plan = plan,
        .pass = pass,
        .desc = &rt->pipeline->passes[pass->desc_index],
        .pipeline = rt->pipeline,
        .user = rt->user.data,
        .frame_layout = rt->frame_layout,
        .width = rt->width,
        .height = rt->height,
        .settings = rt->settings,
        .n_settings = rt->n_settings,
    };
    for (uint32_t s = 0; s < pass->n_slots; s++) ctx.slots[s] = &rt->res[pass->slots[s].resource];
    rt->pass_state[pi] = calloc(1, pass->type->instance_size ? pass->type->instance_size : 1);
    if (!rt->pass_state[pi]) return pg_fail(err, PG_ERR_OOM, "out of memory");
    pg_result r = pass->type->create(rt->pass_state[pi], &ctx, err);
    if (r) return pg_error_prefix(err, "pass '%s' (%s)", pass->name, pass->type->name);
    return PG_OK;
}

/* Packs plan block b again with the real memory pg_rt_requirements of its members (created unbound),
 * allocates its memory (one VkDeviceMemory per sub-block, in free block_memory slots) and binds
 * them; bound[m] is set for each member bound. */
pg_result pg_rt_build_block(pg_runtime *rt, uint32_t b, bool *bound, pg_error *err)
{
    const pg_graph_plan *plan = rt->plan;
    const pg_plan_block *blk = &plan->blocks[b];
    pg_result r;
    pg_pack_item items[PG_MAX_RESOURCES];
    pg_pack_place place[PG_MAX_RESOURCES];
    pg_pack_block sub[PG_MAX_RESOURCES];
    for (uint32_t m = 0; m < blk->n_members; m++) {
        const pg_plan_resource *pr = &plan->resources[blk->members[m]];
        VkMemoryRequirements req = pg_rt_requirements(rt, blk->members[m]);
        items[m] = (pg_pack_item){.size = req.size, .alignment = req.alignment,
                                  .type_bits = req.memoryTypeBits, .klass = 0,
                                  .first = pr->first_pass, .last = pr->last_pass,
                                  .may_inherit = pr->may_inherit};
        rt->stats.memory_bytes_unaliased += req.size;
    }
    const int n_sub = pg_alias_pack(items, blk->n_members, true, place, sub);
    if (n_sub < 0) return pg_fail(err, PG_ERR_LIMIT, "block%u: too many members", b);
    rt->block_split[b] = n_sub > 1;
    if (n_sub > 1) rt->stats.blocks_fallback++;
    for (int sb = 0; sb < n_sub; sb++) {
        if (sub[sb].type_bits == 0) continue; /* a member no memory type fits: fails below */
        uint32_t slot = 0;
        while (slot < PG_MAX_RESOURCES && rt->block_memory[slot]) slot++;
        if (slot >= PG_MAX_RESOURCES) return pg_fail(err, PG_ERR_LIMIT, "too many memory blocks");
        char name[64];
        snprintf(name, sizeof name, n_sub > 1 ? "block%u.%d" : "block%u", b, sb);
        if ((r = alloc(rt, sub[sb].size, sub[sb].type_bits, name, &rt->block_memory[slot], err))) return r;
        rt->block_memory_size[slot] = sub[sb].size;
        rt->block_memory_of[slot] = (int)b;
        rt->stats.memory_bytes_transient += sub[sb].size;
        for (uint32_t m = 0; m < blk->n_members; m++) {
            if (place[m].block != sb) continue;
            rt->res[blk->members[m]].memory = rt->block_memory[slot];
            rt->res[blk->members[m]].memory_offset = place[m].offset;
            rt->res[blk->members[m]].memory_size = items[m].size;
            if ((r = bind(rt, blk->members[m], rt->block_memory[slot], place[m].offset, err))) return r;
            bound[blk->members[m]] = true;
        }
    }
    return PG_OK;
}

/* An own allocation for resource i (not in a block, or its block could not hold it). */
pg_result pg_rt_build_own(pg_runtime *rt, int i, pg_error *err)
{
    const pg_plan_resource *pr = &rt->plan->resources[i];
    VkMemoryRequirements req = pg_rt_requirements(rt, i);
    pg_result r = alloc(rt, req.size, req.memoryTypeBits, pr->name, &rt->res[i].own_memory, err);
    if (r) return r;
    if (pr->lifetime == PG_LIFETIME_TRANSIENT) {
        rt->stats.memory_bytes_transient += req.size;
        rt->stats.memory_bytes_unaliased += req.size; /* e.g. "grow" buffers: never aliased */
    }
    rt->res[i].memory = rt->res[i].own_memory;
    rt->res[i].memory_size = req.size;
    return bind(rt, i, rt->res[i].own_memory, 0, err);
}

/* The physical resources (memory blocks, own allocations) and the readback buffers. */
pg_result pg_rt_build_memory(pg_runtime *rt, pg_error *err)
{
    const pg_graph_plan *plan = rt->plan;
    pg_gpu *gpu = rt->gpu;
    pg_result r;
    rt->stats.resource_creations++;
    rt->stats.memory_bytes_transient = 0;
    rt->stats.memory_bytes_unaliased = 0;
    for (uint32_t i = 0; i < plan->n_resources; i++) {
        if (plan->resources[i].culled) continue;
        if ((r = pg_rt_create_unbound(rt, (int)i, err))) return r;
    }
    /* shared blocks: each plan block is packed again with the real memory pg_rt_requirements
     * (core/graph/alias_pack.c), only among its own members, so two resources share bytes at run time
     * only if the plan's alias barriers order them; members without a common memory type end up
     * in separate allocations */
    bool bound[PG_MAX_RESOURCES] = {0};
    for (uint32_t b = 0; b < plan->n_blocks; b++)
        if ((r = pg_rt_build_block(rt, b, bound, err))) return r;
    for (uint32_t i = 0; i < plan->n_resources; i++) {
        if (plan->resources[i].culled || bound[i]) continue;
        if ((r = pg_rt_build_own(rt, (int)i, err))) return r;
    }
    /* readback buffers */
    int outs[2] = {plan->output, plan->hdr_output};
    for (int k = 0; k < 2; k++) {
        if (outs[k] < 0) continue;
        const pg_plan_resource *pr = &plan->resources[outs[k]];
        VkDeviceSize bytes = (VkDeviceSize)pr->width * pr->height * pg_format_get(pr->format)->bytes_per_pixel;
        for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++) {
            char nm[40];
            snprintf(nm, sizeof nm, "frame%u.readback.%s", f, k ? "hdr" : "output");
            if ((r = pg_buffer_create(gpu, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, nm,
                                      &rt->slot[f].readback[k], err)))
                return r;
        }
    }
    return PG_OK;
}

/* The per-plan query pools and the pass instances, on the physical resources built. */
pg_result pg_rt_build_passes(pg_runtime *rt, pg_error *err)
{
    const pg_graph_plan *plan = rt->plan;
    pg_gpu *gpu = rt->gpu;
    pg_result r;
    rt->n_queries = 2 * plan->n_order + 1; /* per queue pool; the +1 keeps it non-empty */
    rt->compute_stamps = plan->async && gpu->compute_timestamp_valid_bits > 0;
    rt->n_on_queue[0] = rt->n_on_queue[1] = 0;
    for (uint32_t o = 0; o < plan->n_order; o++) rt->qslot[o] = rt->n_on_queue[plan->passes[plan->order[o]].queue]++;
    if (gpu->timestamp_valid_bits) {
        VkQueryPoolCreateInfo qci = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                     .queryType = VK_QUERY_TYPE_TIMESTAMP, .queryCount = rt->n_queries};
        for (uint32_t f = 0; f < PG_MAX_FRAMES_IN_FLIGHT; f++) {
            PG_VK_TRY(err, vkCreateQueryPool(gpu->device, &qci, NULL, &rt->slot[f].queries));
            pg_gpu_name(gpu, VK_OBJECT_TYPE_QUERY_POOL, (uint64_t)rt->slot[f].queries, "frame%u.timestamps", f);
            if (rt->compute_stamps) {
                PG_VK_TRY(err, vkCreateQueryPool(gpu->device, &qci, NULL, &rt->slot[f].cqueries));
                pg_gpu_name(gpu, VK_OBJECT_TYPE_QUERY_POOL, (uint64_t)rt->slot[f].cqueries, "frame%u.timestamps.compute", f);
            }
            char nm[40];
            snprintf(nm, sizeof nm, "frame%u.timestamp_results", f);
            if ((r = pg_buffer_create(gpu, 2 * sizeof(uint64_t) * rt->n_queries, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, nm,
                                      &rt->slot[f].timestamps, err)))
                return r;
        }
    }
    /* pass instances */
    for (uint32_t o = 0; o < plan->n_order; o++)
        if ((r = create_pass(rt, plan->order[o], err))) return r;
    return PG_OK;
}

/* Re-creates the growable buffer ri with at least `needed` bytes: twice its size or `needed`,
 * whichever is larger, at most `max` (and below any size the device refused before). The new
 * buffer is made before the old one goes, so a refused allocation keeps the old one (and a note
 * says so); then every pass bound to the buffer is re-created (its descriptors point at it). */
pg_result pg_rt_grow_buffer(pg_runtime *rt, int ri, uint64_t needed, uint64_t max, pg_frame_stats *st,
                            pg_error *err)
{
    pg_gpu *gpu = rt->gpu;
    pg_phys_resource *r = &rt->res[ri];
    const pg_plan_resource *pr = &rt->plan->resources[ri];
    uint32_t c = pg_rt_capacity_slot(rt, pr->name, true);
    if (c == UINT32_MAX) return PG_OK;
    uint64_t limit = max < rt->capacity[c].limit ? max : rt->capacity[c].limit;
    if (needed <= r->size || limit <= r->size) return PG_OK; /* at its limit: the pass counts the rest */
    uint64_t want = r->size > UINT64_MAX / 2 ? UINT64_MAX : r->size * 2;
    if (want < needed) want = needed;
    if (want > limit) want = limit;
    uint64_t exact = needed < limit ? needed : limit;
    uint64_t tries[2] = {want, exact < want ? exact : 0};
    VkBuffer nb = VK_NULL_HANDLE;
    VkDeviceMemory nm = VK_NULL_HANDLE;
    VkResult vr = VK_SUCCESS;
    uint64_t got = 0;
    for (int t = 0; t < 2 && !got; t++) {
        if (tries[t] <= r->size) continue;
        VkBufferCreateInfo bci = {
            .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
            .size = tries[t],
            .usage = (pr->usage ? pr->usage : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
            .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
        };
        vr = pg_vk_fault_next("vkCreateBuffer(grow)") ? VK_ERROR_OUT_OF_DEVICE_MEMORY
                                                       : vkCreateBuffer(gpu->device, &bci, NULL, &nb);
        if (vr != VK_SUCCESS) {
            nb = VK_NULL_HANDLE;
            continue;
        }
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(gpu->device, nb, &req);
        vr = pg_gpu_alloc_device_memory(gpu, req.size, req.memoryTypeBits, &nm);
        if (vr == VK_SUCCESS) vr = vkBindBufferMemory(gpu->device, nb, nm, 0);
        if (vr != VK_SUCCESS) {
            if (nm) pg_gpu_free_memory(gpu, nm);
            vkDestroyBuffer(gpu->device, nb, NULL);
            nb = VK_NULL_HANDLE;
            nm = VK_NULL_HANDLE;
            continue;
        }
        got = tries[t];
    }
    if (!got) {
        rt->capacity[c].limit = r->size;
        snprintf(rt->grow_note, sizeof rt->grow_note,
                 "buffer '%s' could not grow from %llu to %llu bytes (%s): kept; what does not fit is dropped "
                 "and counted",
                 pr->name, (unsigned long long)r->size, (unsigned long long)exact, pg_vk_result_name(vr));
        return PG_OK;
    }
    /* the passes bound to the buffer hold descriptors of it: destroy them first */
    for (uint32_t o = 0; o < rt->plan->n_order; o++) {
        int pi = rt->plan->order[o];
        const pg_plan_pass *pass = &rt->plan->passes[pi];
        bool uses = false;
        for (uint32_t k = 0; k < pass->n_slots; k++) uses |= pass->slots[k].resource == ri;
        if (uses && rt->pass_state[pi]) {
            pass->type->destroy(rt->pass_state[pi], gpu);
            free(rt->pass_state[pi]);
            rt->pass_state[pi] = NULL;
        }
    }
    uint64_t old = r->size;
    vkDestroyBuffer(gpu->device, r->buffer, NULL);
    if (r->own_memory) pg_gpu_free_memory(gpu, r->own_memory);
    r->buffer = nb;
    r->own_memory = nm;
    r->memory = nm;
    r->memory_offset = 0;
    r->memory_size = got;
    r->size = got;
    pg_gpu_name(gpu, VK_OBJECT_TYPE_BUFFER, (uint64_t)nb, "%s", pr->name);
    pg_gpu_name(gpu, VK_OBJECT_TYPE_DEVICE_MEMORY, (uint64_t)nm, "%s", pr->name);
    rt->capacity[c].bytes = got;
    rt->stats.grow_events++;
    rt->stats.memory_bytes_transient += got - old;
    rt->stats.memory_bytes_unaliased += got - old;
    if (st && st->n_grown < 4) {
        pg_strlcpy(st->grown[st->n_grown].resource, pr->name, PG_NAME_MAX);
        st->grown[st->n_grown].old_bytes = old;
        st->grown[st->n_grown].new_bytes = got;
        st->n_grown++;
    }
    for (uint32_t o = 0; o < rt->plan->n_order; o++) {
        int pi = rt->plan->order[o];
        if (rt->pass_state[pi]) continue;
        pg_result res = create_pass(rt, pi, err);
        if (res) {
            pg_rt_destroy_built(rt);
            return res;
        }
    }
    return PG_OK;
}
