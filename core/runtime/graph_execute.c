/* graph_execute.c - physical resources, pass instances, recording and submission of a plan. */
#include "graph_execute.h"
#include "vk_pipeline.h"

#include "alias_pack.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cjson/cJSON.h>

typedef struct gpu_times {
    uint64_t frame;
    bool valid;
    double total_ms, pass_ms[PG_MAX_PASSES];
    double pass_start_ms[PG_MAX_PASSES]; /* from the frame's first timestamp (both queues) */
} gpu_times;

struct pg_runtime {
    pg_gpu *gpu;
    const pg_graph_plan *plan;
    const pg_pipeline *pipeline;
    const pg_scene_gpu *scene;
    uint32_t width, height;
    uint32_t frame_size;             /* bytes of the caller's per-frame block */
    uint64_t mem_sig, pipe_sig, val_sig; /* see memory_signature, pipeline_signature, value_signature */
    bool built;
    pg_phys_resource res[PG_MAX_RESOURCES];
    bool persistent_initialized[PG_MAX_RESOURCES];
    VkDeviceMemory block_memory[PG_MAX_RESOURCES];
    VkDeviceSize block_memory_size[PG_MAX_RESOURCES];
    int block_memory_of[PG_MAX_RESOURCES];   /* the plan block each block_memory belongs to */
    bool block_split[PG_MAX_RESOURCES];      /* plan block split at run time (blocks_fallback) */
    void *pass_state[PG_MAX_PASSES]; /* indexed like plan->passes */
    /* frame constants */
    VkDescriptorSetLayout frame_layout;
    VkDescriptorPool frame_pool;
    /* frames in flight: everything the host writes or reads per frame has one copy per slot;
     * frame k uses slot k % n_in_flight and waits only for the fence of frame k - n_in_flight */
    struct {
        VkDescriptorSet frame_set;
        pg_buffer frame_ubo;
        void *frame;               /* CPU copy of the frame block (frame_size bytes) */
        /* one command buffer per plan batch, from the pool of its queue's family (cmd_pool[b]) */
        VkCommandBuffer cmds[PG_MAX_BATCHES];
        VkCommandPool cmd_pool[PG_MAX_BATCHES];
        VkFence fence;
        bool pending;              /* submitted, results not collected yet */
        uint64_t frame_no;
        /* timestamps: per queue a pool of 2 per executed pass (begin before its barriers, end
         * after it), reset by the queue's first batch; the last batch of each queue copies its
         * pool to timestamps (graphics first, then compute) */
        VkQueryPool queries, cqueries;
        pg_buffer timestamps;      /* the query results, copied at the end of the frame */
        pg_buffer readback[2];
    } slot[PG_MAX_FRAMES_IN_FLIGHT];
    bool test_no_frame_barrier;    /* pg_runtime_test_drop_frame_barrier */
    uint32_t n_in_flight, cur;     /* cur: the slot of the last submitted frame */
    /* async compute: one timeline semaphore per queue (graphics, compute), the last value each
     * signalled, and the values the last frame's batches signalled (for the next frame's
     * prev_frame_wait; prev_gen: the plan they belong to) */
    VkSemaphore timeline[PG_QUEUE_COUNT];
    uint64_t tl_value[PG_QUEUE_COUNT];
    uint64_t prev_batch_value[PG_MAX_BATCHES];
    uint64_t prev_gen;
    bool compute_stamps;           /* the compute family has timestamps */
    uint32_t qslot[PG_MAX_PASSES]; /* executed pass -> its index among its queue's passes */
    uint32_t n_on_queue[PG_QUEUE_COUNT];
    uint64_t frame_no;
    uint32_t n_queries;
    bool readback_valid[2];
    /* GPU times of the last frame whose fence was seen signalled */
    double gpu_pass_ms[PG_MAX_PASSES], gpu_total_ms;
    double gpu_pass_start_ms[PG_MAX_PASSES];
    bool gpu_valid;
    uint64_t gpu_frame;
    gpu_times gpu_hist[4]; /* the GPU times of the last frames collected, by frame number % 4 */
    /* frames since the pass reports were last read; report_due: read them after the next frame
     * even if that means waiting (a new plan, a grown buffer) */
    uint32_t frames_unreported;
    bool report_due;
    pg_runtime_stats stats;
    const pg_param_override *settings; /* borrowed, see pg_runtime_set_settings */
    uint32_t n_settings;
    /* "grow" buffers: the size each one reached, by name, kept across plans so a new plan (a
     * new light count, a pipeline switch) starts from it instead of growing again; limit: a
     * size the device refused (later requests stay below it) */
    struct {
        char name[PG_NAME_MAX];
        uint64_t bytes, limit;
    } capacity[PG_MAX_RESOURCES];
    uint32_t n_capacity;
    char grow_note[160];               /* last refused growth, repeated in every frame's stats */
};

static uint32_t capacity_slot(pg_runtime *rt, const char *name, bool add)
{
    for (uint32_t i = 0; i < rt->n_capacity; i++)
        if (!strcmp(rt->capacity[i].name, name)) return i;
    if (!add || rt->n_capacity >= PG_MAX_RESOURCES) return UINT32_MAX;
    uint32_t i = rt->n_capacity++;
    pg_strlcpy(rt->capacity[i].name, name, sizeof rt->capacity[i].name);
    rt->capacity[i].bytes = 0;
    rt->capacity[i].limit = UINT64_MAX;
    return i;
}

static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const uint8_t *p = data;
    for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static bool is_runtime_option(const pg_pass_type *t, const char *key)
{
    for (uint32_t i = 0; t->runtime_options && t->runtime_options[i]; i++)
        if (key && !strcmp(t->runtime_options[i], key)) return true;
    return false;
}

/* A pass's options, key by key, as printed JSON; runtime: only (true) or all but (false) the
 * options its type lists in pg_pass_type.runtime_options. */
static uint64_t hash_options(uint64_t s, const pg_pass_type *t, const cJSON *options, bool runtime)
{
    const cJSON *it;
    cJSON_ArrayForEach(it, options)
    {
        if (is_runtime_option(t, it->string) != runtime) continue;
        char *txt = cJSON_PrintUnformatted(it);
        s = fnv(s, it->string ? it->string : "", it->string ? strlen(it->string) + 1 : 1);
        if (txt) {
            s = fnv(s, txt, strlen(txt) + 1);
            cJSON_free(txt);
        }
    }
    return s;
}

/* One resource's part of the memory signature: its size, format, usage, lifetime, memory block
 * and what places it there (first and last pass, may_inherit). */
static uint64_t resource_signature(uint64_t s, const pg_plan_resource *r)
{
    s = fnv(s, r->name, strlen(r->name) + 1);
    s = fnv(s, &r->kind, sizeof r->kind);
    s = fnv(s, &r->format, sizeof r->format);
    s = fnv(s, &r->width, sizeof r->width);
    s = fnv(s, &r->height, sizeof r->height);
    s = fnv(s, &r->size_bytes, sizeof r->size_bytes);
    s = fnv(s, &r->usage, sizeof r->usage);
    s = fnv(s, &r->culled, sizeof r->culled);
    s = fnv(s, &r->growable, sizeof r->growable);
    s = fnv(s, &r->block, sizeof r->block);
    s = fnv(s, &r->lifetime, sizeof r->lifetime);
    s = fnv(s, &r->first_pass, sizeof r->first_pass);
    s = fnv(s, &r->last_pass, sizeof r->last_pass);
    s = fnv(s, &r->may_inherit, sizeof r->may_inherit);
    return s;
}

/* (a) What needs new physical resources: the output size, every resource's part
 * (resource_signature), and which resources are the outputs (the readback buffers). */
static uint64_t memory_signature(const pg_graph_plan *plan, uint32_t w, uint32_t h)
{
    uint64_t s = 1469598103934665603ull;
    s = fnv(s, &w, sizeof w);
    s = fnv(s, &h, sizeof h);
    s = fnv(s, &plan->n_resources, sizeof plan->n_resources);
    s = fnv(s, &plan->n_blocks, sizeof plan->n_blocks);
    s = fnv(s, &plan->output, sizeof plan->output);
    s = fnv(s, &plan->hdr_output, sizeof plan->hdr_output);
    for (uint32_t i = 0; i < plan->n_resources; i++) s = resource_signature(s, &plan->resources[i]);
    return s;
}

static bool same_members(const pg_plan_block *a, const pg_plan_block *b)
{
    return a->n_members == b->n_members && !memcmp(a->members, b->members, sizeof(int) * a->n_members);
}

/* Which resources of the new plan differ from the built plan's (changed[i]) and which memory
 * blocks hold one (dirty[b]), when the rest can be kept: same size, outputs, number of resources
 * and blocks, each changed resource keeps its name, kind and block, a dirty block keeps its
 * members (all of them are then re-created and the block packed again). E.g. the light buffer
 * after a new light count. false: nothing changed, or a full memory rebuild is needed. */
static bool resources_changed(const pg_runtime *rt, const pg_graph_plan *plan, uint32_t w, uint32_t h,
                              bool *changed, bool *dirty)
{
    const pg_graph_plan *old = rt->plan;
    if (!rt->built || !old || w != rt->width || h != rt->height || plan->n_resources != old->n_resources ||
        plan->n_blocks != old->n_blocks || plan->output != old->output || plan->hdr_output != old->hdr_output)
        return false;
    uint32_t n = 0;
    memset(dirty, 0, sizeof(bool) * PG_MAX_RESOURCES);
    for (uint32_t i = 0; i < plan->n_resources; i++) {
        const pg_plan_resource *a = &old->resources[i], *b = &plan->resources[i];
        changed[i] = resource_signature(0, a) != resource_signature(0, b);
        if (!changed[i]) continue;
        if (a->block != b->block || (int)i == plan->output || (int)i == plan->hdr_output || strcmp(a->name, b->name) ||
            a->kind != b->kind)
            return false;
        if (b->block >= 0) {
            if (!same_members(&old->blocks[b->block], &plan->blocks[b->block])) return false;
            dirty[b->block] = true;
        }
        n++;
    }
    for (uint32_t b = 0; b < plan->n_blocks; b++)
        for (uint32_t m = 0; dirty[b] && m < plan->blocks[b].n_members; m++) changed[plan->blocks[b].members[m]] = true;
    return n > 0;
}

/* (b) What needs new pass instances: the scene, the settings, the executed passes in order with
 * their types, shader variants (defines), bound resources and the options that are not run-time
 * values (pg_pass_type.runtime_options). */
static uint64_t pipeline_signature(const pg_runtime *rt, const pg_graph_plan *plan, const pg_pipeline *pl,
                                   const pg_scene_gpu *scene)
{
    uint64_t s = 1469598103934665603ull;
    s = fnv(s, &scene, sizeof scene);
    for (uint32_t i = 0; i < rt->n_settings; i++) {
        const char *k = rt->settings[i].key ? rt->settings[i].key : "";
        const char *v = rt->settings[i].value ? rt->settings[i].value : "";
        s = fnv(s, k, strlen(k) + 1);
        s = fnv(s, v, strlen(v) + 1);
    }
    s = fnv(s, &plan->n_order, sizeof plan->n_order);
    for (uint32_t i = 0; i < plan->n_order; i++) {
        const pg_plan_pass *p = &plan->passes[plan->order[i]];
        s = fnv(s, &plan->order[i], sizeof plan->order[i]);
        s = fnv(s, p->name, strlen(p->name) + 1);
        s = fnv(s, p->type->name, strlen(p->type->name) + 1);
        for (uint32_t d = 0; d < p->decl.n_defines; d++)
            s = fnv(s, p->decl.defines[d], strlen(p->decl.defines[d]) + 1);
        s = hash_options(s, p->type, pl->passes[p->desc_index].options, false);
        s = fnv(s, &p->n_slots, sizeof p->n_slots);
        for (uint32_t k = 0; k < p->n_slots; k++) {
            s = fnv(s, &p->slots[k].resource, sizeof(int));
            s = fnv(s, &p->slots[k].decl.unused, sizeof(bool));
        }
        s = fnv(s, &p->queue, sizeof p->queue); /* pass-owned objects are used on one queue */
    }
    return s;
}

/* (c) The run-time values: the options the pass types list as such (pass.update() gets them). */
static uint64_t value_signature(const pg_graph_plan *plan, const pg_pipeline *pl)
{
    uint64_t s = 1469598103934665603ull;
    for (uint32_t i = 0; i < plan->n_order; i++) {
        const pg_plan_pass *p = &plan->passes[plan->order[i]];
        s = hash_options(s, p->type, pl->passes[p->desc_index].options, true);
    }
    return s;
}

/* The state a persistent resource is assumed to start each frame in (its frame-wrap barriers):
 * kept contents are only valid for a new plan that assumes the same. */
static uint64_t wrap_signature(const pg_graph_plan *plan, int ri)
{
    uint64_t s = 1469598103934665603ull;
    for (uint32_t o = 0; o < plan->n_order; o++) {
        const pg_plan_pass *p = &plan->passes[plan->order[o]];
        for (uint32_t b = 0; b < p->n_barriers; b++) {
            const pg_barrier *br = &p->barriers[b];
            if (br->resource != ri || !br->wrap) continue;
            s = fnv(s, &o, sizeof o);
            s = fnv(s, &br->old_layout, sizeof br->old_layout);
            s = fnv(s, &br->src_stages, sizeof br->src_stages);
            s = fnv(s, &br->src_access, sizeof br->src_access);
        }
    }
    for (uint32_t o = 0; o < plan->n_order; o++) { /* and the layout of every access */
        const pg_plan_pass *p = &plan->passes[plan->order[o]];
        for (uint32_t k = 0; k < p->n_slots; k++)
            if (p->slots[k].resource == ri) s = fnv(s, &p->slots[k].sync.layout, sizeof(uint32_t));
    }
    for (uint32_t b = 0; b < plan->n_final_barriers; b++)
        if (plan->final_barriers[b].resource == ri) s = fnv(s, &plan->final_barriers[b].new_layout, sizeof(uint32_t));
    return s;
}

/* With frames in flight, the most frames between two readings of the pass reports. */
#define PG_REPORT_EVERY 8

/* The pass instances and the per-plan query pools (the device must be idle). */
static void destroy_passes(pg_runtime *rt)
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

static void destroy_built(pg_runtime *rt)
{
    pg_gpu *gpu = rt->gpu;
    if (!rt->built && !rt->plan) return;
    vkDeviceWaitIdle(gpu->device);
    destroy_passes(rt);
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
    destroy_built(rt);
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

static pg_result create_unbound(pg_runtime *rt, int i, pg_error *err)
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
            uint32_t c = capacity_slot(rt, pr->name, false);
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

static VkMemoryRequirements requirements(pg_runtime *rt, int i)
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
    uint32_t type = pg_gpu_memory_type(rt->gpu, bits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type == UINT32_MAX) type = pg_gpu_memory_type(rt->gpu, bits, 0);
    if (type == UINT32_MAX) return pg_fail(err, PG_ERR_VULKAN, "%s: no memory type fits", name);
    VkMemoryAllocateInfo mai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                .allocationSize = size, .memoryTypeIndex = type};
    VkResult vr = pg_gpu_alloc_memory(rt->gpu, &mai, out);
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
        .scene = rt->scene,
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

/* Packs plan block b again with the real memory requirements of its members (created unbound),
 * allocates its memory (one VkDeviceMemory per sub-block, in free block_memory slots) and binds
 * them; bound[m] is set for each member bound. */
static pg_result build_block(pg_runtime *rt, uint32_t b, bool *bound, pg_error *err)
{
    const pg_graph_plan *plan = rt->plan;
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
static pg_result build_own(pg_runtime *rt, int i, pg_error *err)
{
    const pg_plan_resource *pr = &rt->plan->resources[i];
    VkMemoryRequirements req = requirements(rt, i);
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
static pg_result build_memory(pg_runtime *rt, pg_error *err)
{
    const pg_graph_plan *plan = rt->plan;
    pg_gpu *gpu = rt->gpu;
    pg_result r;
    rt->stats.resource_creations++;
    rt->stats.memory_bytes_transient = 0;
    rt->stats.memory_bytes_unaliased = 0;
    for (uint32_t i = 0; i < plan->n_resources; i++) {
        if (plan->resources[i].culled) continue;
        if ((r = create_unbound(rt, (int)i, err))) return r;
    }
    /* shared blocks: each plan block is packed again with the real memory requirements
     * (core/graph/alias_pack.c), only among its own members, so two resources share bytes at run time
     * only if the plan's alias barriers order them; members without a common memory type end up
     * in separate allocations */
    bool bound[PG_MAX_RESOURCES] = {0};
    for (uint32_t b = 0; b < plan->n_blocks; b++)
        if ((r = build_block(rt, b, bound, err))) return r;
    for (uint32_t i = 0; i < plan->n_resources; i++) {
        if (plan->resources[i].culled || bound[i]) continue;
        if ((r = build_own(rt, (int)i, err))) return r;
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
static pg_result build_passes(pg_runtime *rt, pg_error *err)
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
static pg_result grow_buffer(pg_runtime *rt, int ri, uint64_t needed, uint64_t max, pg_frame_stats *st,
                             pg_error *err)
{
    pg_gpu *gpu = rt->gpu;
    pg_phys_resource *r = &rt->res[ri];
    const pg_plan_resource *pr = &rt->plan->resources[ri];
    uint32_t c = capacity_slot(rt, pr->name, true);
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
        uint32_t type = pg_gpu_memory_type(gpu, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        if (type == UINT32_MAX) type = pg_gpu_memory_type(gpu, req.memoryTypeBits, 0);
        VkMemoryAllocateInfo mai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                    .allocationSize = req.size, .memoryTypeIndex = type};
        vr = type == UINT32_MAX ? VK_ERROR_OUT_OF_DEVICE_MEMORY : pg_gpu_alloc_memory(gpu, &mai, &nm);
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
            destroy_built(rt);
            return res;
        }
    }
    return PG_OK;
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

/* Re-creates the changed resources of the (new) plan and packs the dirty blocks again (the
 * passes are destroyed, the device idle); the other resources and blocks are untouched. */
static pg_result recreate_resources(pg_runtime *rt, const bool *changed, const bool *dirty, pg_error *err)
{
    pg_gpu *gpu = rt->gpu;
    const pg_graph_plan *plan = rt->plan;
    pg_result r;
    for (uint32_t i = 0; i < plan->n_resources; i++) {
        if (!changed[i]) continue;
        pg_phys_resource *p = &rt->res[i];
        /* what build_memory counted for it: block members' requirements, transient own allocations */
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
        rt->persistent_initialized[i] = false;
    }
    for (uint32_t k = 0; k < PG_MAX_RESOURCES; k++) {
        if (!rt->block_memory[k] || !dirty[rt->block_memory_of[k]]) continue;
        pg_gpu_free_memory(gpu, rt->block_memory[k]);
        rt->stats.memory_bytes_transient -= rt->block_memory_size[k];
        rt->block_memory[k] = VK_NULL_HANDLE;
        rt->block_memory_size[k] = 0;
    }
    for (uint32_t b = 0; b < plan->n_blocks; b++)
        if (dirty[b] && rt->block_split[b]) rt->stats.blocks_fallback--;
    for (uint32_t i = 0; i < plan->n_resources; i++)
        if (changed[i] && !plan->resources[i].culled && (r = create_unbound(rt, (int)i, err))) return r;
    bool bound[PG_MAX_RESOURCES] = {0};
    for (uint32_t b = 0; b < plan->n_blocks; b++)
        if (dirty[b] && (r = build_block(rt, b, bound, err))) return r;
    for (uint32_t i = 0; i < plan->n_resources; i++)
        if (changed[i] && !plan->resources[i].culled && !bound[i] && (r = build_own(rt, (int)i, err))) return r;
    return PG_OK;
}

/* Only the run-time values changed: every kept pass instance re-reads its options. */
static pg_result update_values(pg_runtime *rt, pg_error *err)
{
    for (uint32_t o = 0; o < rt->plan->n_order; o++) {
        int pi = rt->plan->order[o];
        const pg_plan_pass *pass = &rt->plan->passes[pi];
        if (!pass->type->update || !rt->pass_state[pi]) continue;
        pg_result r = pass->type->update(rt->pass_state[pi], &rt->pipeline->passes[pass->desc_index], err);
        if (r) return pg_error_prefix(err, "pass '%s' (%s)", pass->name, pass->type->name);
    }
    return PG_OK;
}

pg_result pg_runtime_set_plan(pg_runtime *rt, const pg_graph_plan *plan, const pg_pipeline *pipeline,
                              const pg_scene_gpu *scene, uint32_t width, uint32_t height, pg_error *err)
{
    const pg_gpu *g = rt->gpu;
    if (plan->async && (!g->compute_queue || !rt->timeline[0]))
        return pg_fail(err, PG_ERR_INVALID_ARG, "the plan uses the compute queue but the device has none (%s)",
                       g->single_queue_why[0] ? g->single_queue_why : "no timeline semaphores");
    if (plan->async && plan->qfot != (g->compute_family != g->queue_family))
        return pg_fail(err, PG_ERR_INVALID_ARG,
                       "the plan was compiled for queues of %s family, the device's are of %s: compile with "
                       "pg_runtime_queue_caps()", plan->qfot ? "different" : "one", plan->qfot ? "one" : "different");
    const uint64_t msig = memory_signature(plan, width, height);
    const uint64_t psig = pipeline_signature(rt, plan, pipeline, scene);
    const uint64_t vsig = value_signature(plan, pipeline);
    rt->report_due = true; /* a new light count may need a buffer to grow: read the next report */
    pg_result r;
    if (rt->built && msig == rt->mem_sig && psig == rt->pipe_sig) {
        /* same resources and pass instances: keep every object, adopt the new plan; only the
         * run-time values may differ */
        rt->plan = plan;
        rt->pipeline = pipeline;
        rt->scene = scene;
        if (vsig == rt->val_sig) {
            rt->stats.last_rebuild = PG_REBUILD_NONE;
            return PG_OK;
        }
        rt->stats.value_updates++;
        rt->stats.last_rebuild = PG_REBUILD_VALUES;
        /* a frame in flight may still read the old values only through its command buffer
         * (push constants are recorded), so no wait is needed */
        r = update_values(rt, err);
        rt->val_sig = r ? 0 : vsig; /* failed: the next plan updates again */
        return r;
    }
    bool changed[PG_MAX_RESOURCES], dirty[PG_MAX_RESOURCES];
    const bool some = msig != rt->mem_sig && resources_changed(rt, plan, width, height, changed, dirty);
    if (rt->built && (msig == rt->mem_sig || some)) {
        /* same resources: keep them (and what persistent ones hold when the new plan assumes
         * the same state at frame start), re-create the pass instances only */
        vkDeviceWaitIdle(rt->gpu->device);
        destroy_passes(rt);
        for (uint32_t i = 0; i < plan->n_resources; i++)
            if (wrap_signature(plan, (int)i) != wrap_signature(rt->plan, (int)i)) rt->persistent_initialized[i] = false;
        rt->plan = plan;
        rt->pipeline = pipeline;
        rt->scene = scene;
        rt->pipe_sig = psig;
        rt->val_sig = vsig;
        if (some) { /* ... but the resources that changed (with their blocks): re-create them */
            rt->mem_sig = msig;
            rt->stats.resource_rebuilds++;
            rt->stats.last_rebuild = PG_REBUILD_RESOURCES;
            r = recreate_resources(rt, changed, dirty, err);
        } else {
            rt->stats.pipeline_rebuilds++;
            rt->stats.last_rebuild = PG_REBUILD_PIPELINES;
            r = PG_OK;
        }
        if (!r) r = build_passes(rt, err);
    } else {
        destroy_built(rt);
        rt->plan = plan;
        rt->pipeline = pipeline;
        rt->scene = scene;
        rt->width = width;
        rt->height = height;
        rt->mem_sig = msig;
        rt->pipe_sig = psig;
        rt->val_sig = vsig;
        rt->stats.memory_rebuilds++;
        rt->stats.last_rebuild = PG_REBUILD_MEMORY;
        r = build_memory(rt, err);
        if (!r) r = build_passes(rt, err);
    }
    if (r) {
        destroy_built(rt);
        rt->plan = NULL;
        return r;
    }
    rt->built = true;
    return PG_OK;
}

/* A global memory barrier before every pass of an immediate-mode plan (pg_graph_plan.immediate):
 * orders everything, the passes' own resources included. */
static void emit_full_barrier(VkCommandBuffer cmd)
{
    VkMemoryBarrier2 mb = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
        .srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
        .srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT,
        .dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
        .dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
    };
    VkDependencyInfo di = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1,
                           .pMemoryBarriers = &mb};
    vkCmdPipelineBarrier2(cmd, &di);
}

static void emit_barriers(pg_runtime *rt, VkCommandBuffer cmd, uint32_t n, const pg_barrier *bars)
{
    VkImageMemoryBarrier2 ib[PG_MAX_RESOURCES];
    VkBufferMemoryBarrier2 bb[PG_MAX_RESOURCES];
    uint32_t ni = 0, nb = 0;
    for (uint32_t i = 0; i < n && i < PG_MAX_RESOURCES; i++) {
        const pg_barrier *b = &bars[i];
        const pg_phys_resource *r = &rt->res[b->resource];
        uint64_t src_stages = b->src_stages, src_access = b->src_access;
        uint32_t old_layout = b->old_layout;
        if (b->wrap && !rt->persistent_initialized[b->resource]) {
            /* very first frame: nothing to wait for, contents undefined */
            src_stages = VK_PIPELINE_STAGE_2_NONE;
            src_access = 0;
            old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
        }
        /* With frames in flight a barrier that waits for nothing (a transient's first use) would
         * not chain to the frame-start barrier: its layout transition could overwrite memory the
         * previous frame still reads (synchronization validation at queue submit reports it).
         * Its own stages make the chain. */
        if (!src_stages && rt->n_in_flight > 1) src_stages = b->dst_stages;
        if (b->is_image) {
            ib[ni++] = pg_image_barrier(r->image, pg_vk_aspect(r->format), src_stages, src_access, b->dst_stages,
                                        b->dst_access, (VkImageLayout)old_layout, (VkImageLayout)b->new_layout);
        } else {
            bb[nb++] = (VkBufferMemoryBarrier2){
                .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
                .srcStageMask = src_stages,
                .srcAccessMask = src_access,
                .dstStageMask = b->dst_stages,
                .dstAccessMask = b->dst_access,
                .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                .buffer = r->buffer,
                .size = VK_WHOLE_SIZE,
            };
        }
    }
    pg_cmd_barriers(cmd, ni, ib, nb, bb);
}

static uint32_t queue_family(const pg_runtime *rt, pg_queue q)
{
    return q == PG_QUEUE_COMPUTE ? rt->gpu->compute_family : rt->gpu->queue_family;
}

/* The release (at the end of batch b) or acquire (at its start) halves of the plan's ownership
 * transfers: same layouts in both; the release's destination and the acquire's source access
 * are empty (the semaphore between the batches orders them; the acquire's source stages are its
 * destination stages, which the batch's semaphore wait covers, so the chain holds). */
static void emit_qfots(pg_runtime *rt, VkCommandBuffer cmd, uint32_t b, bool release)
{
    const pg_graph_plan *plan = rt->plan;
    VkImageMemoryBarrier2 ib[PG_MAX_RESOURCES];
    VkBufferMemoryBarrier2 bb[PG_MAX_RESOURCES];
    uint32_t ni = 0, nb = 0;
    for (uint32_t i = 0; i < plan->n_qfots; i++) {
        const pg_qfot *t = &plan->qfots[i];
        if ((release ? t->release_batch : t->acquire_batch) != (int)b) continue;
        const pg_phys_resource *r = &rt->res[t->resource];
        const uint64_t ss = release ? t->src_stages : t->dst_stages, sa = release ? t->src_access : 0;
        const uint64_t ds = release ? VK_PIPELINE_STAGE_2_NONE : t->dst_stages, da = release ? 0 : t->dst_access;
        const uint32_t sf = queue_family(rt, t->src_queue), df = queue_family(rt, t->dst_queue);
        if (t->is_image && ni < PG_MAX_RESOURCES) {
            VkImageMemoryBarrier2 x = pg_image_barrier(r->image, pg_vk_aspect(r->format), ss, sa, ds, da,
                                                       (VkImageLayout)t->old_layout, (VkImageLayout)t->new_layout);
            x.srcQueueFamilyIndex = sf;
            x.dstQueueFamilyIndex = df;
            ib[ni++] = x;
        } else if (!t->is_image && nb < PG_MAX_RESOURCES) {
            bb[nb++] = (VkBufferMemoryBarrier2){
                .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
                .srcStageMask = ss, .srcAccessMask = sa, .dstStageMask = ds, .dstAccessMask = da,
                .srcQueueFamilyIndex = sf, .dstQueueFamilyIndex = df,
                .buffer = r->buffer, .size = VK_WHOLE_SIZE,
            };
        }
    }
    if (ni || nb) pg_cmd_barriers(cmd, ni, ib, nb, bb);
}

static void check_load_op(const pg_pass_record_ctx *ctx, uint32_t slot, bool clears)
{
    if (!ctx->record_error || ctx->record_error->msg[0] || !ctx->pass || slot >= ctx->pass->n_slots) return;
    const pg_slot_decl *d = &ctx->pass->slots[slot].decl;
    const bool full = d->access == PG_ACCESS_COLOR_WRITE || d->access == PG_ACCESS_DEPTH_WRITE;
    const bool loads = d->access == PG_ACCESS_COLOR_RMW || d->access == PG_ACCESS_DEPTH_RMW ||
                       d->access == PG_ACCESS_DEPTH_READ;
    if (!full && !loads)
        pg_fail(ctx->record_error, PG_ERR_INVALID_ARG,
                "pass '%s': slot '%s' is declared %s, not an attachment, but rendering begins on it", ctx->pass->name,
                d->name, pg_access_name(d->access));
    else if (full && !clears)
        pg_fail(ctx->record_error, PG_ERR_INVALID_ARG,
                "pass '%s': slot '%s' is declared %s (a full write) but rendering begins with LOAD_OP_LOAD: "
                "clear it, or declare a read-modify-write",
                ctx->pass->name, d->name, pg_access_name(d->access));
    else if (loads && clears)
        pg_fail(ctx->record_error, PG_ERR_INVALID_ARG,
                "pass '%s': slot '%s' is declared %s (it loads the contents) but rendering begins with "
                "LOAD_OP_CLEAR: load it, or declare a full write",
                ctx->pass->name, d->name, pg_access_name(d->access));
}

void pg_pass_begin_rendering(const pg_pass_record_ctx *ctx, uint32_t n_color, const uint32_t *color_slots,
                             const VkClearColorValue *clears, int depth_slot, bool clear_depth, float depth_clear)
{
    VkImageView views[8];
    uint32_t w = 0, h = 0;
    if (n_color > 8) n_color = 8;
    for (uint32_t i = 0; i < n_color; i++) {
        const pg_phys_resource *r = ctx->slots[color_slots[i]];
        views[i] = r->view;
        if (!i) w = r->width, h = r->height;
        check_load_op(ctx, color_slots[i], clears != NULL);
    }
    VkImageView dv = VK_NULL_HANDLE;
    if (depth_slot >= 0) {
        const pg_phys_resource *r = ctx->slots[depth_slot];
        dv = r->view;
        if (!n_color) w = r->width, h = r->height;
        check_load_op(ctx, (uint32_t)depth_slot, clear_depth);
    }
    pg_cmd_begin_rendering(ctx->cmd, w, h, n_color, views, clears, dv, clear_depth, depth_clear);
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* Reads the timestamps of slot f (its fence has signalled) into rt->gpu_*. */
static void collect_timestamps(pg_runtime *rt, uint32_t f)
{
    pg_gpu *gpu = rt->gpu;
    const pg_graph_plan *plan = rt->plan;
    rt->slot[f].pending = false;
    if (!rt->slot[f].queries) return;
    /* the frame copied its query results to a host-visible buffer (vkGetQueryPoolResults on
     * lavapipe blocks until the frame submitted after this one is done too) */
    if (!rt->slot[f].timestamps.mapped) return;
    uint64_t ts[2 * (2 * PG_MAX_PASSES + 1)];
    memcpy(ts, rt->slot[f].timestamps.mapped, 2 * sizeof(uint64_t) * rt->n_queries);
    const uint32_t bits[PG_QUEUE_COUNT] = {gpu->timestamp_valid_bits, gpu->compute_timestamp_valid_bits};
    /* the two queues' timestamps are taken as one timebase (checked on the GPU, README) */
    uint64_t t_min = UINT64_MAX, t_max = 0;
    for (uint32_t o = 0; o < plan->n_order; o++) {
        const pg_queue q = plan->passes[plan->order[o]].queue;
        if (q == PG_QUEUE_COMPUTE && !rt->compute_stamps) {
            rt->gpu_pass_ms[o] = 0;
            continue;
        }
        const uint64_t mask = bits[q] >= 64 ? ~0ull : ((1ull << bits[q]) - 1);
        const uint64_t b0 = ts[q * rt->n_queries + 2 * rt->qslot[o]] & mask;
        const uint64_t b1 = ts[q * rt->n_queries + 2 * rt->qslot[o] + 1] & mask;
        rt->gpu_pass_ms[o] = ((b1 - b0) & mask) * (double)gpu->timestamp_period_ns * 1e-6;
        if (b0 < t_min) t_min = b0;
        if (b1 > t_max) t_max = b1;
    }
    rt->gpu_total_ms = t_max > t_min ? (t_max - t_min) * (double)gpu->timestamp_period_ns * 1e-6 : 0;
    for (uint32_t o = 0; o < plan->n_order; o++) {
        const pg_queue q = plan->passes[plan->order[o]].queue;
        const uint64_t mask = bits[q] >= 64 ? ~0ull : ((1ull << bits[q]) - 1);
        const uint64_t b0 = ts[q * rt->n_queries + 2 * rt->qslot[o]] & mask;
        rt->gpu_pass_start_ms[o] = (q == PG_QUEUE_COMPUTE && !rt->compute_stamps) || b0 < t_min
                                       ? 0 : (b0 - t_min) * (double)gpu->timestamp_period_ns * 1e-6;
    }
    rt->gpu_valid = true;
    rt->gpu_frame = rt->slot[f].frame_no;
    gpu_times *h = &rt->gpu_hist[rt->gpu_frame % 4];
    h->frame = rt->gpu_frame;
    h->valid = true;
    h->total_ms = rt->gpu_total_ms;
    memcpy(h->pass_ms, rt->gpu_pass_ms, sizeof(double) * plan->n_order);
    memcpy(h->pass_start_ms, rt->gpu_pass_start_ms, sizeof(double) * plan->n_order);
}

/* Waits for slot f's frame if it is pending; counts a wait that found the fence unsignalled. */
static pg_result wait_slot(pg_runtime *rt, uint32_t f, double *wait_ms, pg_error *err)
{
    if (!rt->slot[f].pending) return PG_OK;
    VkDevice dev = rt->gpu->device;
    VkResult st = vkGetFenceStatus(dev, rt->slot[f].fence);
    if (st == VK_NOT_READY) {
        rt->stats.fence_waits++;
        double tw = now_ms();
        PG_VK_TRY(err, vkWaitForFences(dev, 1, &rt->slot[f].fence, VK_TRUE, UINT64_MAX));
        *wait_ms += now_ms() - tw;
    } else if (st != VK_SUCCESS) {
        return pg_fail(err, PG_ERR_VULKAN, "frame fence: %s", pg_vk_result_name(st));
    }
    collect_timestamps(rt, f);
    return PG_OK;
}

void pg_runtime_test_drop_frame_barrier(pg_runtime *rt, bool drop)
{
    rt->test_no_frame_barrier = drop;
}

pg_result pg_runtime_set_frames_in_flight(pg_runtime *rt, uint32_t n, pg_error *err)
{
    if (n < 1 || n > PG_MAX_FRAMES_IN_FLIGHT)
        return pg_fail(err, PG_ERR_INVALID_ARG, "frames in flight: %u (1..%d)", n, PG_MAX_FRAMES_IN_FLIGHT);
    pg_result r = pg_runtime_wait_idle(rt, err);
    if (r) return r;
    rt->n_in_flight = n;
    return PG_OK;
}

bool pg_runtime_gpu_times(const pg_runtime *rt, uint64_t frame, double *total_ms, double *pass_ms)
{
    const gpu_times *h = &rt->gpu_hist[frame % 4];
    if (!h->valid || h->frame != frame || !rt->plan) return false;
    if (total_ms) *total_ms = h->total_ms;
    if (pass_ms) memcpy(pass_ms, h->pass_ms, sizeof(double) * rt->plan->n_order);
    return true;
}

pg_result pg_runtime_wait_idle(pg_runtime *rt, pg_error *err)
{
    double w = 0;
    for (uint32_t k = 1; k <= PG_MAX_FRAMES_IN_FLIGHT; k++) { /* oldest first: the freshest times win */
        pg_result r = wait_slot(rt, (rt->cur + k) % PG_MAX_FRAMES_IN_FLIGHT, &w, err);
        if (r) return r;
    }
    return PG_OK;
}

pg_result pg_runtime_render(pg_runtime *rt, const void *frame_block, bool readback, pg_frame_stats *stats,
                            pg_error *err)
{
    if (!rt->built) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_runtime_render: no plan set");
    pg_gpu *gpu = rt->gpu;
    const pg_graph_plan *plan = rt->plan;
    double t0 = now_ms(), wait_ms = 0;
    const uint32_t n_fif = rt->n_in_flight;
    const uint32_t f = (uint32_t)(rt->frame_no % n_fif);
    pg_result wr = wait_slot(rt, f, &wait_ms, err); /* the frame that used this slot n_fif frames ago */
    if (wr) return wr;
    memcpy(rt->slot[f].frame, frame_block, rt->frame_size);
    memcpy(rt->slot[f].frame_ubo.mapped, rt->slot[f].frame, rt->frame_size);
    VkQueryPool qpool[PG_QUEUE_COUNT] = {rt->slot[f].queries, rt->slot[f].cqueries};
    /* the first and last batch of each queue (timestamp reset / copy, frames-in-flight barrier) */
    int first_of[PG_QUEUE_COUNT] = {-1, -1}, last_of[PG_QUEUE_COUNT] = {-1, -1};
    for (uint32_t b = 0; b < plan->n_batches; b++) {
        const int q = plan->batches[b].queue;
        if (first_of[q] < 0) first_of[q] = (int)b;
        last_of[q] = (int)b;
    }
    pg_error record_error = {0};
    for (uint32_t b = 0; b < plan->n_batches; b++) {
        const pg_plan_batch *bt = &plan->batches[b];
        const int q = bt->queue;
        VkCommandPool pool = q == PG_QUEUE_COMPUTE ? gpu->compute_cmd_pool : gpu->cmd_pool;
        if (rt->slot[f].cmds[b] && rt->slot[f].cmd_pool[b] != pool) {
            vkFreeCommandBuffers(gpu->device, rt->slot[f].cmd_pool[b], 1, &rt->slot[f].cmds[b]);
            rt->slot[f].cmds[b] = VK_NULL_HANDLE;
        }
        if (!rt->slot[f].cmds[b]) {
            VkCommandBufferAllocateInfo cai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                               .commandPool = pool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                               .commandBufferCount = 1};
            PG_VK_TRY(err, vkAllocateCommandBuffers(gpu->device, &cai, &rt->slot[f].cmds[b]));
            rt->slot[f].cmd_pool[b] = pool;
            pg_gpu_name(gpu, VK_OBJECT_TYPE_COMMAND_BUFFER, (uint64_t)(uintptr_t)rt->slot[f].cmds[b],
                        "frame%u.batch%u.%s", f, b, pg_queue_name((pg_queue)q));
        }
        VkCommandBuffer cmd = rt->slot[f].cmds[b];
        PG_VK_TRY(err, vkResetCommandBuffer(cmd, 0));
        VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
        PG_VK_TRY(err, vkBeginCommandBuffer(cmd, &bi));
        if (first_of[q] == (int)b) {
            /* With frames in flight the previous frame may still run: the frames share the
             * graph's resources (persistent and transient bytes), so this frame's work on this
             * queue starts after all earlier work on it (one full barrier; submission order
             * makes it cover earlier submits). The compute queue's first batch also waits for
             * the previous frame's graphics work (prev_frame_wait). */
            if (n_fif > 1 && !rt->test_no_frame_barrier) emit_full_barrier(cmd);
            if (qpool[q]) vkCmdResetQueryPool(cmd, qpool[q], 0, rt->n_queries);
        }
        emit_qfots(rt, cmd, b, false); /* acquires */
        for (uint32_t o = bt->first; o < bt->first + bt->count; o++) {
            int pi = plan->order[o];
            const pg_plan_pass *pass = &plan->passes[pi];
            if (qpool[q]) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, qpool[q], 2 * rt->qslot[o]);
            if (gpu->cmd_begin_label) {
                VkDebugUtilsLabelEXT label = {.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT, .pLabelName = pass->name};
                gpu->cmd_begin_label(cmd, &label);
            }
            if (plan->immediate) emit_full_barrier(cmd);
            emit_barriers(rt, cmd, pass->n_barriers, pass->barriers);
            pg_pass_record_ctx ctx = {
                .gpu = gpu,
                .cmd = cmd,
                .pass = pass,
                .scene = rt->scene,
                .frame_set = rt->slot[f].frame_set,
                .frame = rt->slot[f].frame,
                .frame_size = rt->frame_size,
                .width = rt->width,
                .height = rt->height,
                .record_error = &record_error,
            };
            for (uint32_t s = 0; s < pass->n_slots; s++) ctx.slots[s] = &rt->res[pass->slots[s].resource];
            pass->type->record(rt->pass_state[pi], &ctx);
            if (gpu->cmd_end_label) gpu->cmd_end_label(cmd);
            if (qpool[q]) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, qpool[q], 2 * rt->qslot[o] + 1);
        }
        if (bt->last) {
            if (plan->immediate) emit_full_barrier(cmd);
            emit_barriers(rt, cmd, plan->n_final_barriers, plan->final_barriers);
        }
        emit_qfots(rt, cmd, b, true); /* releases */
        if (qpool[q] && last_of[q] == (int)b && rt->n_on_queue[q]) {
            vkCmdCopyQueryPoolResults(cmd, qpool[q], 0, 2 * rt->n_on_queue[q], rt->slot[f].timestamps.buffer,
                                      (VkDeviceSize)q * rt->n_queries * sizeof(uint64_t), sizeof(uint64_t),
                                      VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
            VkBufferMemoryBarrier2 tb = pg_buffer_barrier(rt->slot[f].timestamps.buffer, VK_PIPELINE_STAGE_2_COPY_BIT,
                                                          VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                                                          VK_ACCESS_2_HOST_READ_BIT);
            pg_cmd_barriers(cmd, 0, NULL, 1, &tb);
        }
        if (bt->last) {
            int outs[2] = {plan->output, plan->hdr_output};
            for (int k = 0; k < 2; k++) {
                rt->readback_valid[k] = false;
                if (!readback || outs[k] < 0 || !rt->slot[f].readback[k].buffer) continue;
                const pg_phys_resource *r = &rt->res[outs[k]];
                VkBufferImageCopy c = {.imageSubresource = {pg_vk_aspect(r->format), 0, 0, 1},
                                       .imageExtent = {r->width, r->height, 1}};
                vkCmdCopyImageToBuffer(cmd, r->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                       rt->slot[f].readback[k].buffer, 1, &c);
                VkBufferMemoryBarrier2 hb =
                    pg_buffer_barrier(rt->slot[f].readback[k].buffer, VK_PIPELINE_STAGE_2_COPY_BIT,
                                      VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
                pg_cmd_barriers(cmd, 0, NULL, 1, &hb);
                rt->readback_valid[k] = true;
            }
        }
        PG_VK_TRY(err, vkEndCommandBuffer(cmd));
    }
    if (record_error.msg[0]) { /* a pass broke its declaration: not submitted */
        rt->readback_valid[0] = rt->readback_valid[1] = false;
        return pg_fail(err, record_error.code, "%s", record_error.msg);
    }
    /* submit the batches in plan order: each signals its queue's timeline semaphore; a batch
     * waits for the newest other-queue batch it depends on (and the first compute batch for the
     * previous frame's graphics work); the last (graphics) batch signals the fence */
    PG_VK_TRY(err, vkResetFences(gpu->device, 1, &rt->slot[f].fence));
    uint64_t value[PG_MAX_BATCHES] = {0};
    const uint64_t gfx_before = rt->tl_value[PG_QUEUE_GRAPHICS];
    for (uint32_t b = 0; b < plan->n_batches; b++) {
        const pg_plan_batch *bt = &plan->batches[b];
        const int q = bt->queue, other = 1 - q;
        uint64_t wv = 0, wst = 0;
        for (uint32_t w = 0; w < bt->n_waits; w++) {
            if (value[bt->waits[w].batch] > wv) wv = value[bt->waits[w].batch];
            wst |= bt->waits[w].stages;
        }
        if (bt->prev_frame_wait >= 0 && other == PG_QUEUE_GRAPHICS && gfx_before) {
            uint64_t v = rt->prev_gen == plan->generation ? rt->prev_batch_value[bt->prev_frame_wait] : gfx_before;
            if (v > wv) wv = v;
            wst |= VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        }
        VkSemaphoreSubmitInfo wsi = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = rt->timeline[other],
                                     .value = wv, .stageMask = wst};
        VkSemaphoreSubmitInfo ssi = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = rt->timeline[q],
                                     .value = 0, .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
        const bool sem = plan->async && rt->timeline[q];
        if (sem) value[b] = ssi.value = ++rt->tl_value[q];
        VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO,
                                         .commandBuffer = rt->slot[f].cmds[b]};
        VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2,
                            .waitSemaphoreInfoCount = sem && wv ? 1 : 0, .pWaitSemaphoreInfos = &wsi,
                            .commandBufferInfoCount = 1, .pCommandBufferInfos = &cbi,
                            .signalSemaphoreInfoCount = sem ? 1 : 0, .pSignalSemaphoreInfos = &ssi};
        VkQueue queue = q == PG_QUEUE_COMPUTE ? gpu->compute_queue : gpu->queue;
        VkResult sr = pg_vk_fault_next("vkQueueSubmit2(batch)") ? VK_ERROR_DEVICE_LOST
                                                                 : vkQueueSubmit2(queue, 1, &si, bt->last ? rt->slot[f].fence : VK_NULL_HANDLE);
        if (sr != VK_SUCCESS) {
            if (sem) rt->tl_value[q]--; /* never signalled: no later wait may name it */
            return pg_fail(err, PG_ERR_VULKAN, "vkQueueSubmit2(batch %u of %u, %s queue) failed: %s", b, plan->n_batches,
                           pg_queue_name((pg_queue)q), pg_vk_result_name(sr));
        }
    }
    memcpy(rt->prev_batch_value, value, sizeof value);
    rt->prev_gen = plan->generation;
    rt->slot[f].pending = true;
    rt->slot[f].frame_no = rt->frame_no++;
    rt->cur = f;
    rt->stats.frames_submitted++;
    /* one frame in flight, or a read-back: wait for this frame (its staging is read after its fence) */
    if (n_fif == 1 || readback) {
        rt->stats.sync_waits++;
        double tw = now_ms();
        PG_VK_TRY(err, vkWaitForFences(gpu->device, 1, &rt->slot[f].fence, VK_TRUE, UINT64_MAX));
        wait_ms += now_ms() - tw;
        collect_timestamps(rt, f);
    }
    for (uint32_t i = 0; i < plan->n_resources; i++)
        if (!plan->resources[i].culled && plan->resources[i].lifetime != PG_LIFETIME_TRANSIENT)
            rt->persistent_initialized[i] = true;
    /* pass reports read what the passes' host-visible buffers hold: only when no frame is in
     * flight (checked, never waited for), else the passes may be writing them */
    bool idle = true;
    for (uint32_t k = 1; k <= n_fif; k++) {
        uint32_t g = (f + k) % n_fif; /* oldest first */
        if (!rt->slot[g].pending) continue;
        VkResult fs = vkGetFenceStatus(gpu->device, rt->slot[g].fence);
        if (fs == VK_SUCCESS) collect_timestamps(rt, g);
        else idle = false;
    }
    /* Pass reports (overflow counters, growth requests) must still arrive: after a new plan or a
     * growth, and at least every PG_REPORT_EVERY frames, wait for the frames in flight. */
    if (!idle && (rt->report_due || rt->frames_unreported + 1 >= PG_REPORT_EVERY)) {
        double tw = now_ms();
        pg_result ir = pg_runtime_wait_idle(rt, err);
        if (ir) return ir;
        wait_ms += now_ms() - tw;
        rt->stats.report_waits++;
        idle = true;
    }
    rt->report_due = false;
    rt->frames_unreported = idle ? 0 : rt->frames_unreported + 1;

    pg_frame_stats local_stats;
    if (!stats) stats = &local_stats;
    {
        memset(stats, 0, sizeof *stats);
        stats->n_passes = plan->n_order;
        for (uint32_t o = 0; o < plan->n_order; o++) {
            pg_strlcpy(stats->pass_names[o], plan->passes[plan->order[o]].name, PG_NAME_MAX);
            stats->pass_queue[o] = (uint8_t)plan->passes[plan->order[o]].queue;
        }
        stats->n_batches = plan->n_batches;
        stats->frame = rt->slot[f].frame_no;
        stats->in_flight = n_fif;
        stats->wait_ms = wait_ms;
        if (rt->gpu_valid) {
            memcpy(stats->pass_ms, rt->gpu_pass_ms, sizeof(double) * plan->n_order);
            memcpy(stats->pass_start_ms, rt->gpu_pass_start_ms, sizeof(double) * plan->n_order);
            stats->gpu_total_ms = rt->gpu_total_ms;
            stats->gpu_frame = rt->gpu_frame;
            stats->timestamps_valid = true;
        }
        stats->reports_valid = idle;
        if (!idle) rt->stats.reports_skipped++;
        for (uint32_t o = 0; o < plan->n_order && idle; o++) {
            const pg_plan_pass *pass = &plan->passes[plan->order[o]];
            if (!pass->type->report) continue;
            pg_pass_report rep = {0};
            pass->type->report(rt->pass_state[plan->order[o]], &rep);
            for (uint32_t k = 0; k < rep.n && stats->n_counters < 32; k++) {
                pg_strlcpy(stats->counters[stats->n_counters].pass, pass->name, PG_NAME_MAX);
                pg_strlcpy(stats->counters[stats->n_counters].name, rep.counters[k].name, 32);
                stats->counters[stats->n_counters].value = rep.counters[k].value;
                stats->n_counters++;
            }
            for (uint32_t k = 0; k < rep.n_notes && stats->n_notes < 4; k++)
                pg_strlcpy(stats->notes[stats->n_notes++], rep.notes[k], sizeof stats->notes[0]);
            for (uint32_t k = 0; k < rep.n_grow; k++) {
                if (rep.grow[k].slot >= pass->n_slots) continue;
                int ri = pass->slots[rep.grow[k].slot].resource;
                if (ri < 0 || !plan->resources[ri].growable) continue;
                rt->report_due = true; /* the frame after a growth shows whether it sufficed */
                pg_result gr = grow_buffer(rt, ri, rep.grow[k].needed, rep.grow[k].max, stats, err);
                if (gr) return gr;
                if (!rt->built) return pg_fail(err, PG_ERR_VULKAN, "runtime lost its plan while growing a buffer");
            }
        }
        if (rt->grow_note[0] && stats->n_notes < 4)
            pg_strlcpy(stats->notes[stats->n_notes++], rt->grow_note, sizeof stats->notes[0]);
        stats->cpu_ms = now_ms() - t0 - wait_ms;
    }
    return PG_OK;
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
