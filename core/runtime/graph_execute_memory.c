/* graph_execute_memory.c - physical resources, memory blocks, pass instances, growable buffers
 * (owns pg_runtime.mem, graph_execute_internal.h). Calls graph_execute_frames.c (readback
 * buffers, waits) and graph_execute_timing.c (query pools) only. */
#include "graph_execute_internal.h"

#include "alias_pack.h"
#include "pg_file.h"

#include <stdlib.h>
#include <string.h>

/* The capacity entry of the "grow" buffer `name` (added when add is set); UINT32_MAX if none. */
static uint32_t capacity_slot(pg_runtime *rt, const char *name, bool add)
{
    pg_rt_memory *m = &rt->mem;
    for (uint32_t i = 0; i < m->n_capacity; i++)
        if (!strcmp(m->capacity[i].name, name)) return i;
    if (!add || m->n_capacity >= PG_MAX_RESOURCES) return UINT32_MAX;
    uint32_t i = m->n_capacity++;
    pg_strlcpy(m->capacity[i].name, name, sizeof m->capacity[i].name);
    m->capacity[i].bytes = 0;
    m->capacity[i].limit = UINT64_MAX;
    return i;
}

static pg_result create_unbound(pg_runtime *rt, int i, pg_error *err)
{
    pg_gpu *gpu = rt->cfg.gpu;
    const pg_plan_resource *pr = &rt->cur.plan->resources[i];
    pg_phys_resource *r = &rt->mem.res[i];
    r->kind = pr->kind;
    r->content_tag = 0; /* new contents: no pass wrote them */
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
            uint32_t c = capacity_slot(rt, pr->name, false);
            if (c != UINT32_MAX && rt->mem.capacity[c].bytes > r->size) r->size = rt->mem.capacity[c].bytes;
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

/* create_unbound, its failure naming the resource ("resource 'b' (buffer, 256.0 GiB): vkCreateBuffer
 * ... failed: VK_ERROR_OUT_OF_DEVICE_MEMORY"): the device's own message names no object */
static pg_result create_named(pg_runtime *rt, int i, pg_error *err)
{
    pg_result r = create_unbound(rt, i, err);
    if (r) {
        const pg_plan_resource *pr = &rt->cur.plan->resources[i];
        char size[32];
        pg_file_fmt_size(pr->size_bytes, size, sizeof size);
        if (pr->kind == PG_RES_IMAGE)
            pg_error_prefix(err, "resource '%s' (image %ux%u %s, about %s)", pr->name, pr->width, pr->height,
                            pg_format_get(pr->format)->name, size);
        else
            pg_error_prefix(err, "resource '%s' (buffer, %s)", pr->name, size);
    }
    return r;
}

static VkMemoryRequirements requirements(pg_runtime *rt, int i)
{
    VkMemoryRequirements req = {0};
    if (rt->mem.res[i].image) vkGetImageMemoryRequirements(rt->cfg.gpu->device, rt->mem.res[i].image, &req);
    else vkGetBufferMemoryRequirements(rt->cfg.gpu->device, rt->mem.res[i].buffer, &req);
    return req;
}

static pg_result bind(pg_runtime *rt, int i, VkDeviceMemory mem, VkDeviceSize offset, pg_error *err)
{
    pg_phys_resource *r = &rt->mem.res[i];
    if (r->image) {
        PG_VK_TRY(err, vkBindImageMemory(rt->cfg.gpu->device, r->image, mem, offset));
        VkImageViewCreateInfo vci = {
            .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
            .image = r->image,
            .viewType = VK_IMAGE_VIEW_TYPE_2D,
            .format = r->format,
            .subresourceRange = {pg_vk_aspect(r->format), 0, 1, 0, 1},
        };
        PG_VK_TRY(err, vkCreateImageView(rt->cfg.gpu->device, &vci, NULL, &r->view));
        pg_gpu_name(rt->cfg.gpu, VK_OBJECT_TYPE_IMAGE_VIEW, (uint64_t)r->view, "%s.view",
                    rt->cur.plan->resources[i].name);
    } else {
        PG_VK_TRY(err, vkBindBufferMemory(rt->cfg.gpu->device, r->buffer, mem, offset));
    }
    return PG_OK;
}

static pg_result alloc(pg_runtime *rt, VkDeviceSize size, uint32_t bits, const char *name, VkDeviceMemory *out,
                       pg_error *err)
{
    VkResult vr = pg_gpu_alloc_device_memory(rt->cfg.gpu, size, bits, out);
    if (vr != VK_SUCCESS)
        return pg_fail(err, PG_ERR_VULKAN, "%s: vkAllocateMemory(%llu bytes) failed: %s", name,
                       (unsigned long long)size, pg_vk_result_name(vr));
    pg_gpu_name(rt->cfg.gpu, VK_OBJECT_TYPE_DEVICE_MEMORY, (uint64_t)*out, "%s", name);
    return PG_OK;
}

static pg_result create_pass(pg_runtime *rt, int pi, pg_error *err)
{
    const pg_graph_plan *plan = rt->cur.plan;
    const pg_plan_pass *pass = &plan->passes[pi];
    pg_pass_create_ctx ctx = {
        .gpu = rt->cfg.gpu,
        .plan = plan,
        .pass = pass,
        .desc = &rt->cur.pipeline->passes[pass->desc_index],
        .pipeline = rt->cur.pipeline,
        .user = rt->cur.user.data,
        .frame_layout = rt->frames.frame_layout,
        .width = rt->cur.width,
        .height = rt->cur.height,
        .settings = rt->cfg.settings,
        .n_settings = rt->cfg.n_settings,
    };
    for (uint32_t s = 0; s < pass->n_slots; s++) ctx.slots[s] = &rt->mem.res[pass->slots[s].resource];
    const pg_pass_type *t = pass->type;
    if (!t->create || !t->record || !t->destroy) /* a type registered for the compiler alone */
        return pg_fail(err, PG_ERR_INVALID_ARG, "pass '%s': its type '%s' has no %s function: it cannot run", pass->name,
                       t->name, !t->create ? "create" : !t->record ? "record" : "destroy");
    rt->mem.pass_state[pi] = calloc(1, pass->type->instance_size ? pass->type->instance_size : 1);
    if (!rt->mem.pass_state[pi])
        return pg_fail(err, PG_ERR_OOM, "pass '%s' (%s): out of memory for its state of %zu bytes", pass->name,
                       t->name, t->instance_size);
    pg_result r = pass->type->create(rt->mem.pass_state[pi], &ctx, err);
    if (r) return pg_error_prefix(err, "pass '%s' (%s)", pass->name, pass->type->name);
    return PG_OK;
}

/* Packs plan block b again with the real memory requirements of its members (created unbound),
 * allocates its memory (one VkDeviceMemory per sub-block, in free block_memory slots) and binds
 * them; bound[m] is set for each member bound. */
static pg_result build_block(pg_runtime *rt, uint32_t b, bool *bound, pg_error *err)
{
    const pg_graph_plan *plan = rt->cur.plan;
    const pg_plan_block *blk = &plan->blocks[b];
    pg_result r;
    pg_pack_item items[PG_MAX_RESOURCES];
    pg_pack_place place[PG_MAX_RESOURCES];
    pg_pack_block sub[PG_MAX_RESOURCES];
    for (uint32_t m = 0; m < blk->n_members; m++) {
        const pg_plan_resource *pr = &plan->resources[blk->members[m]];
        VkMemoryRequirements req = requirements(rt, blk->members[m]);
        items[m] = (pg_pack_item){.size = req.size, .alignment = req.alignment,
                                  .type_bits = req.memoryTypeBits, .klass = 0,
                                  .first = pr->first_pass, .last = pr->last_pass,
                                  .may_inherit = pr->may_inherit};
        rt->stats.memory_bytes_unaliased += req.size;
    }
    const int n_sub = pg_alias_pack(items, blk->n_members, true, place, sub);
    if (n_sub < 0) return pg_fail(err, PG_ERR_LIMIT, "block%u: too many members", b);
    rt->mem.block_split[b] = n_sub > 1;
    if (n_sub > 1) rt->stats.blocks_fallback++;
    for (int sb = 0; sb < n_sub; sb++) {
        if (sub[sb].type_bits == 0) continue; /* a member no memory type fits: fails below */
        uint32_t slot = 0;
        while (slot < PG_MAX_RESOURCES && rt->mem.block_memory[slot]) slot++;
        if (slot >= PG_MAX_RESOURCES) return pg_fail(err, PG_ERR_LIMIT, "too many memory blocks");
        char name[64];
        snprintf(name, sizeof name, n_sub > 1 ? "block%u.%d" : "block%u", b, sb);
        if ((r = alloc(rt, sub[sb].size, sub[sb].type_bits, name, &rt->mem.block_memory[slot], err))) return r;
        rt->mem.block_memory_size[slot] = sub[sb].size;
        rt->mem.block_memory_of[slot] = (int)b;
        rt->stats.memory_bytes_transient += sub[sb].size;
        for (uint32_t m = 0; m < blk->n_members; m++) {
            if (place[m].block != sb) continue;
            rt->mem.res[blk->members[m]].memory = rt->mem.block_memory[slot];
            rt->mem.res[blk->members[m]].memory_offset = place[m].offset;
            rt->mem.res[blk->members[m]].memory_size = items[m].size;
            if ((r = bind(rt, blk->members[m], rt->mem.block_memory[slot], place[m].offset, err))) return r;
            bound[blk->members[m]] = true;
        }
    }
    return PG_OK;
}

/* An own allocation for resource i (not in a block, or its block could not hold it). */
static pg_result build_own(pg_runtime *rt, int i, pg_error *err)
{
    const pg_plan_resource *pr = &rt->cur.plan->resources[i];
    VkMemoryRequirements req = requirements(rt, i);
    pg_result r = alloc(rt, req.size, req.memoryTypeBits, pr->name, &rt->mem.res[i].own_memory, err);
    if (r) return r;
    if (pr->lifetime == PG_LIFETIME_TRANSIENT) {
        rt->stats.memory_bytes_transient += req.size;
        rt->stats.memory_bytes_unaliased += req.size; /* e.g. "grow" buffers: never aliased */
    }
    rt->mem.res[i].memory = rt->mem.res[i].own_memory;
    rt->mem.res[i].memory_size = req.size;
    return bind(rt, i, rt->mem.res[i].own_memory, 0, err);
}

static bool carriable(const pg_plan_resource *r)
{
    return !r->culled && r->kind == PG_RES_BUFFER && r->lifetime == PG_LIFETIME_PERSISTENT && !r->growable &&
           r->block < 0;
}

void pg_rt_carry_persistent(pg_runtime *rt, const pg_graph_plan *next)
{
    const pg_graph_plan *old = rt->cur.plan;
    pg_rt_memory *m = &rt->mem;
    memset(m->carried_set, 0, sizeof m->carried_set);
    if (!m->built || !old) return;
    for (uint32_t j = 0; j < next->n_resources; j++) {
        const pg_plan_resource *b = &next->resources[j];
        for (uint32_t i = 0; carriable(b) && i < old->n_resources; i++) {
            const pg_plan_resource *a = &old->resources[i];
            if (!carriable(a) || strcmp(a->name, b->name) || a->size_bytes != b->size_bytes || a->usage != b->usage ||
                !m->res[i].own_memory)
                continue;
            m->carried[j] = m->res[i];
            m->carried_set[j] = true;
            m->carried_init[j] = m->persistent_initialized[i];
            memset(&m->res[i], 0, sizeof m->res[i]); /* not freed by pg_rt_destroy_built */
            break;
        }
    }
}

/* The physical resources (memory blocks, own allocations, the carried persistent buffers) and the
 * readback buffers (graph_execute_frames.c). */
pg_result pg_rt_build_memory(pg_runtime *rt, pg_error *err)
{
    const pg_graph_plan *plan = rt->cur.plan;
    pg_result r;
    rt->stats.resource_creations++;
    rt->stats.memory_bytes_transient = 0;
    rt->stats.memory_bytes_unaliased = 0;
    bool bound[PG_MAX_RESOURCES] = {0};
    for (uint32_t i = 0; i < plan->n_resources; i++) { /* first, so a failure below frees them too */
        if (!rt->mem.carried_set[i]) continue;
        rt->mem.res[i] = rt->mem.carried[i];
        rt->mem.persistent_initialized[i] = rt->mem.carried_init[i];
        rt->mem.carried_set[i] = false;
        bound[i] = true;
    }
    for (uint32_t i = 0; i < plan->n_resources; i++) {
        if (plan->resources[i].culled || bound[i]) continue;
        if ((r = create_named(rt, (int)i, err))) return r;
    }
    /* shared blocks: each plan block is packed again with the real memory requirements
     * (core/graph/alias_pack.c), only among its own members, so two resources share bytes at run time
     * only if the plan's alias barriers order them; members without a common memory type end up
     * in separate allocations */
    for (uint32_t b = 0; b < plan->n_blocks; b++)
        if ((r = build_block(rt, b, bound, err))) return r;
    for (uint32_t i = 0; i < plan->n_resources; i++) {
        if (plan->resources[i].culled || bound[i]) continue;
        if ((r = build_own(rt, (int)i, err))) return r;
    }
    return pg_rt_frames_build_readback(rt, err);
}

/* The per-plan query pools (graph_execute_timing.c) and the pass instances, on the physical
 * resources built; then the runtime is built. */
pg_result pg_rt_build_passes(pg_runtime *rt, pg_error *err)
{
    const pg_graph_plan *plan = rt->cur.plan;
    pg_result r;
    if ((r = pg_rt_timing_build(rt, err))) return r;
    /* pass instances (those kept from the previous plan are there already: graph_execute_plan.c) */
    rt->stats.last_passes_created = 0;
    for (uint32_t o = 0; o < plan->n_order; o++) {
        if (rt->mem.pass_state[plan->order[o]]) continue;
        if ((r = create_pass(rt, plan->order[o], err))) return r;
        rt->stats.last_passes_created++;
    }
    rt->mem.built = true;
    return PG_OK;
}


/* The pass instances, the per-plan query pools and what the frame slots know of the plan (the
 * device must be idle). */
void pg_rt_destroy_passes(pg_runtime *rt)
{
    pg_gpu *gpu = rt->cfg.gpu;
    const pg_graph_plan *plan = rt->cur.plan;
    for (uint32_t i = 0; plan && i < plan->n_passes; i++) {
        if (rt->mem.pass_state[i]) {
            plan->passes[i].type->destroy(rt->mem.pass_state[i], gpu);
            free(rt->mem.pass_state[i]);
            rt->mem.pass_state[i] = NULL;
        }
    }
    pg_rt_timing_destroy(rt);
    pg_rt_frames_forget(rt);
}

/* Everything built for the plan: pass instances, resources, memory blocks, readback buffers. */
void pg_rt_destroy_built(pg_runtime *rt)
{
    pg_gpu *gpu = rt->cfg.gpu;
    pg_rt_memory *m = &rt->mem;
    if (!m->built && !rt->cur.plan) return;
    vkDeviceWaitIdle(gpu->device);
    pg_rt_destroy_passes(rt);
    for (uint32_t i = 0; i < PG_MAX_RESOURCES; i++) {
        pg_phys_resource *r = &m->res[i];
        if (r->view) vkDestroyImageView(gpu->device, r->view, NULL);
        if (r->image) vkDestroyImage(gpu->device, r->image, NULL);
        if (r->buffer) vkDestroyBuffer(gpu->device, r->buffer, NULL);
        if (r->own_memory) pg_gpu_free_memory(gpu, r->own_memory);
        memset(r, 0, sizeof *r);
        if (m->block_memory[i]) pg_gpu_free_memory(gpu, m->block_memory[i]);
        m->block_memory[i] = VK_NULL_HANDLE;
        m->block_memory_size[i] = 0;
        m->block_split[i] = false;
        m->persistent_initialized[i] = false;
    }
    pg_rt_frames_destroy_readback(rt);
    m->n_pending = 0;
    m->built = false;
}

/* Re-creates the changed resources of the (new) plan and packs the dirty blocks again (the
 * passes are destroyed, the device idle); the other resources and blocks are untouched. */
pg_result pg_rt_recreate_resources(pg_runtime *rt, const bool *changed, const bool *dirty, pg_error *err)
{
    pg_gpu *gpu = rt->cfg.gpu;
    const pg_graph_plan *plan = rt->cur.plan;
    pg_result r;
    for (uint32_t i = 0; i < plan->n_resources; i++) {
        if (!changed[i]) continue;
        pg_phys_resource *p = &rt->mem.res[i];
        /* what pg_rt_build_memory counted for it: block members' requirements, transient own allocations */
        if (plan->resources[i].block >= 0) rt->stats.memory_bytes_unaliased -= p->memory_size;
        else if (p->own_memory && plan->resources[i].lifetime == PG_LIFETIME_TRANSIENT) {
            rt->stats.memory_bytes_transient -= p->memory_size;
            rt->stats.memory_bytes_unaliased -= p->memory_size;
        }
        if (p->view) vkDestroyImageView(gpu->device, p->view, NULL);
        if (p->image) vkDestroyImage(gpu->device, p->image, NULL);
        if (p->buffer) vkDestroyBuffer(gpu->device, p->buffer, NULL);
        if (p->own_memory) pg_gpu_free_memory(gpu, p->own_memory);
        memset(p, 0, sizeof *p);
        rt->mem.persistent_initialized[i] = false;
    }
    for (uint32_t k = 0; k < PG_MAX_RESOURCES; k++) {
        if (!rt->mem.block_memory[k] || !dirty[rt->mem.block_memory_of[k]]) continue;
        pg_gpu_free_memory(gpu, rt->mem.block_memory[k]);
        rt->stats.memory_bytes_transient -= rt->mem.block_memory_size[k];
        rt->mem.block_memory[k] = VK_NULL_HANDLE;
        rt->mem.block_memory_size[k] = 0;
    }
    for (uint32_t b = 0; b < plan->n_blocks; b++)
        if (dirty[b] && rt->mem.block_split[b]) rt->stats.blocks_fallback--;
    for (uint32_t i = 0; i < plan->n_resources; i++)
        if (changed[i] && !plan->resources[i].culled && (r = create_named(rt, (int)i, err))) return r;
    bool bound[PG_MAX_RESOURCES] = {0};
    for (uint32_t b = 0; b < plan->n_blocks; b++)
        if (dirty[b] && (r = build_block(rt, b, bound, err))) return r;
    for (uint32_t i = 0; i < plan->n_resources; i++)
        if (changed[i] && !plan->resources[i].culled && !bound[i] && (r = build_own(rt, (int)i, err))) return r;
    return PG_OK;
}

/* Only the run-time values changed: every kept pass instance takes them from its new params. */
pg_result pg_rt_update_values(pg_runtime *rt, pg_error *err)
{
    for (uint32_t o = 0; o < rt->cur.plan->n_order; o++) {
        int pi = rt->cur.plan->order[o];
        const pg_plan_pass *pass = &rt->cur.plan->passes[pi];
        if (!pass->type->update || !rt->mem.pass_state[pi]) continue;
        pg_result r = pass->type->update(rt->mem.pass_state[pi], pass->decl.params, err);
        if (r) return pg_error_prefix(err, "pass '%s' (%s)", pass->name, pass->type->name);
    }
    return PG_OK;
}

/* A new plan assumes another state of the persistent resource at frame start: its contents
 * are not kept. */
void pg_rt_forget_contents(pg_runtime *rt, int resource)
{
    rt->mem.persistent_initialized[resource] = false;
}

/* After a frame: every persistent resource it used holds contents (its next frame-wrap
 * barriers wait for them). */
void pg_rt_mark_persistent_written(pg_runtime *rt)
{
    const pg_graph_plan *plan = rt->cur.plan;
    for (uint32_t i = 0; i < plan->n_resources; i++)
        if (!plan->resources[i].culled && plan->resources[i].lifetime != PG_LIFETIME_TRANSIENT)
            rt->mem.persistent_initialized[i] = true;
}

/* ---- "grow" buffers: requested while a frame's pass reports are read, applied between frames */

void pg_rt_clear_growth(pg_runtime *rt)
{
    rt->mem.n_pending = 0;
}

void pg_rt_request_growth(pg_runtime *rt, int resource, uint64_t needed, uint64_t max)
{
    pg_rt_memory *m = &rt->mem;
    if (m->n_pending >= PG_RT_MAX_GROW_REQUESTS) return;
    m->pending[m->n_pending++] = (pg_rt_grow_request){.resource = resource, .needed = needed, .max = max};
}

bool pg_runtime_growth_pending(const pg_runtime *rt)
{
    return rt->mem.n_pending > 0;
}

/* vkCreateBuffer, or VK_ERROR_OUT_OF_DEVICE_MEMORY without creating when fault injection picks
 * this call (pg_vk_fault_next, PASSGRAPH_FAULT_AT: tests/cli/fault_test.sh). */
static VkResult create_buffer_or_fault(VkDevice dev, const VkBufferCreateInfo *bci, VkBuffer *out)
{
    if (pg_vk_fault_next("vkCreateBuffer(grow)")) return VK_ERROR_OUT_OF_DEVICE_MEMORY;
    return vkCreateBuffer(dev, bci, NULL, out);
}

/* A new buffer for resource pr with its own memory, trying the sizes tries[] in turn (0 or not
 * above `above`: skipped); *got: the size made (0: none, *vr says why). */
static void new_grow_buffer(pg_runtime *rt, const pg_plan_resource *pr, const uint64_t tries[2], uint64_t above,
                            VkBuffer *nb, VkDeviceMemory *nm, uint64_t *got, VkResult *vr)
{
    pg_gpu *gpu = rt->cfg.gpu;
    *nb = VK_NULL_HANDLE;
    *nm = VK_NULL_HANDLE;
    *got = 0;
    *vr = VK_SUCCESS;
    for (int t = 0; t < 2 && !*got; t++) {
        if (tries[t] <= above) continue;
        VkBufferCreateInfo bci = {
            .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
            .size = tries[t],
            .usage = (pr->usage ? pr->usage : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
            .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
        };
        *vr = create_buffer_or_fault(gpu->device, &bci, nb);
        if (*vr != VK_SUCCESS) {
            *nb = VK_NULL_HANDLE;
            continue;
        }
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(gpu->device, *nb, &req);
        *vr = pg_gpu_alloc_device_memory(gpu, req.size, req.memoryTypeBits, nm);
        if (*vr == VK_SUCCESS) *vr = vkBindBufferMemory(gpu->device, *nb, *nm, 0);
        if (*vr != VK_SUCCESS) {
            if (*nm) pg_gpu_free_memory(gpu, *nm);
            vkDestroyBuffer(gpu->device, *nb, NULL);
            *nb = VK_NULL_HANDLE;
            *nm = VK_NULL_HANDLE;
            continue;
        }
        *got = tries[t];
    }
}

/* Destroys the pass instances bound to resource ri (they hold descriptors of it). */
static void destroy_passes_using(pg_runtime *rt, int ri)
{
    const pg_graph_plan *plan = rt->cur.plan;
    for (uint32_t o = 0; o < plan->n_order; o++) {
        int pi = plan->order[o];
        const pg_plan_pass *pass = &plan->passes[pi];
        bool uses = false;
        for (uint32_t k = 0; k < pass->n_slots; k++) uses |= pass->slots[k].resource == ri;
        if (uses && rt->mem.pass_state[pi]) {
            pass->type->destroy(rt->mem.pass_state[pi], rt->cfg.gpu);
            free(rt->mem.pass_state[pi]);
            rt->mem.pass_state[pi] = NULL;
        }
    }
}

/* Re-creates the growable buffer ri with at least `needed` bytes: `needed` plus 1/8 of headroom
 * (PG_GROW_HEADROOM_DIV; so a buffer holds at most 1.125x what its last growth needed, after any
 * number of growths), at most `max` (and below any size the device refused before). The new
 * buffer is made before the old one goes, so a refused allocation keeps the old one (and a note
 * says so); then every pass bound to the buffer is re-created (its descriptors point at it). */
#define PG_GROW_HEADROOM_DIV 8

static pg_result grow_buffer(pg_runtime *rt, int ri, uint64_t needed, uint64_t max, pg_frame_stats *st,
                             pg_error *err)
{
    pg_gpu *gpu = rt->cfg.gpu;
    pg_phys_resource *r = &rt->mem.res[ri];
    const pg_plan_resource *pr = &rt->cur.plan->resources[ri];
    uint32_t c = capacity_slot(rt, pr->name, true);
    if (c == UINT32_MAX) return PG_OK;
    uint64_t limit = max < rt->mem.capacity[c].limit ? max : rt->mem.capacity[c].limit;
    if (needed <= r->size || limit <= r->size) return PG_OK; /* at its limit: the pass counts the rest */
    uint64_t headroom = needed / PG_GROW_HEADROOM_DIV;
    uint64_t want = needed > UINT64_MAX - headroom ? UINT64_MAX : needed + headroom;
    if (want < UINT64_MAX - 255) want = (want + 255) & ~(uint64_t)255;
    if (want > limit) want = limit;
    uint64_t exact = needed < limit ? needed : limit;
    const uint64_t tries[2] = {want, exact < want ? exact : 0};
    VkBuffer nb;
    VkDeviceMemory nm;
    VkResult vr;
    uint64_t got;
    new_grow_buffer(rt, pr, tries, r->size, &nb, &nm, &got, &vr);
    if (!got) {
        rt->mem.capacity[c].limit = r->size;
        snprintf(rt->mem.grow_note, sizeof rt->mem.grow_note,
                 "buffer '%s' could not grow from %llu to %llu bytes (%s): kept; what does not fit is dropped "
                 "and counted",
                 pr->name, (unsigned long long)r->size, (unsigned long long)exact, pg_vk_result_name(vr));
        return PG_OK;
    }
    destroy_passes_using(rt, ri);
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
    rt->mem.capacity[c].bytes = got;
    rt->stats.grow_events++;
    rt->stats.memory_bytes_transient += got - old;
    rt->stats.memory_bytes_unaliased += got - old;
    if (st && st->n_grown < 4) {
        pg_strlcpy(st->grown[st->n_grown].resource, pr->name, PG_NAME_MAX);
        st->grown[st->n_grown].old_bytes = old;
        st->grown[st->n_grown].new_bytes = got;
        st->n_grown++;
    }
    for (uint32_t o = 0; o < rt->cur.plan->n_order; o++) {
        int pi = rt->cur.plan->order[o];
        if (rt->mem.pass_state[pi]) continue;
        pg_result res = create_pass(rt, pi, err);
        if (res) { /* as a failed set_plan: no plan (it kept one whose resources were destroyed) */
            pg_rt_destroy_built(rt);
            rt->cur.plan = NULL;
            return res;
        }
    }
    return PG_OK;
}

/* The runtime's growth note (a refused growth) changed from `before` while growing: the frame's
 * stats end with it, as pg_runtime_render would have put it there. */
static void update_grow_note(const pg_runtime *rt, const char *before, pg_frame_stats *st)
{
    const char *note = rt->mem.grow_note;
    if (!st || !strcmp(before, note)) return;
    if (before[0] && st->n_notes && !strcmp(st->notes[st->n_notes - 1], before))
        pg_strlcpy(st->notes[st->n_notes - 1], note, sizeof st->notes[0]);
    else if (st->n_notes < 4)
        pg_strlcpy(st->notes[st->n_notes++], note, sizeof st->notes[0]);
}

pg_result pg_runtime_apply_growth(pg_runtime *rt, pg_frame_stats *stats, pg_error *err)
{
    pg_rt_memory *m = &rt->mem;
    if (!m->n_pending) return PG_OK;
    if (!m->built) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_runtime_apply_growth: no plan set");
    /* the requests were read when no frame was in flight; wait anyway in case one was since */
    pg_result r = pg_runtime_wait_idle(rt, err);
    if (r) return r;
    pg_rt_grow_request req[PG_RT_MAX_GROW_REQUESTS];
    const uint32_t n = m->n_pending;
    memcpy(req, m->pending, sizeof req[0] * n);
    m->n_pending = 0;
    char before[sizeof m->grow_note];
    pg_strlcpy(before, m->grow_note, sizeof before);
    for (uint32_t i = 0; i < n; i++) {
        if ((r = grow_buffer(rt, req[i].resource, req[i].needed, req[i].max, stats, err))) return r;
        if (!m->built) return pg_fail(err, PG_ERR_VULKAN, "runtime lost its plan while growing a buffer");
    }
    update_grow_note(rt, before, stats);
    return PG_OK;
}
