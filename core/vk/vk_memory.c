/* vk_memory.c - allocation helpers: memory types and allocations, buffers, images, one-time
 * command buffers, barriers, the process RSS. */
#include "vk_context.h"

#include <string.h>

uint32_t pg_gpu_memory_type(const pg_gpu *gpu, uint32_t bits, VkMemoryPropertyFlags want)
{
    for (uint32_t i = 0; i < gpu->mem_props.memoryTypeCount; i++)
        if ((bits & (1u << i)) && (gpu->mem_props.memoryTypes[i].propertyFlags & want) == want)
            return i;
    return UINT32_MAX;
}

uint64_t pg_gpu_device_local_bytes(const pg_gpu *gpu)
{
    uint64_t best = 0;
    for (uint32_t i = 0; i < gpu->mem_props.memoryHeapCount; i++)
        if ((gpu->mem_props.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) &&
            gpu->mem_props.memoryHeaps[i].size > best)
            best = gpu->mem_props.memoryHeaps[i].size;
    return best;
}

VkResult pg_gpu_alloc_device_memory(pg_gpu *gpu, VkDeviceSize size, uint32_t type_bits, VkDeviceMemory *out)
{
    uint32_t type = pg_gpu_memory_type(gpu, type_bits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type == UINT32_MAX) type = pg_gpu_memory_type(gpu, type_bits, 0);
    if (type == UINT32_MAX) return VK_ERROR_OUT_OF_DEVICE_MEMORY;
    VkMemoryAllocateInfo mai = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = size,
        .memoryTypeIndex = type,
    };
    return pg_gpu_alloc_memory(gpu, &mai, out);
}

pg_result pg_buffer_create(pg_gpu *gpu, VkDeviceSize size, VkBufferUsageFlags usage,
                           bool host_visible, const char *name, pg_buffer *out, pg_error *err)
{
    return pg_buffer_create_ex(gpu, size, usage, host_visible, host_visible, name, out, err);
}

pg_result pg_buffer_create_ex(pg_gpu *gpu, VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible,
                              bool both_queues, const char *name, pg_buffer *out, pg_error *err)
{
    memset(out, 0, sizeof *out);
    if (size == 0) size = 16;
    VkBufferCreateInfo bci = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = size,
        .usage = usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    /* host-written/read buffers (frame uniforms, staging, timestamps) and the static scene data
     * may be used on both queues of different families: concurrent sharing, no ownership transfers */
    const uint32_t fams[2] = {gpu->queue_family, gpu->compute_family};
    if (both_queues && gpu->compute_queue && gpu->compute_family != gpu->queue_family) {
        bci.sharingMode = VK_SHARING_MODE_CONCURRENT;
        bci.queueFamilyIndexCount = 2;
        bci.pQueueFamilyIndices = fams;
    }
    PG_VK_TRY(err, vkCreateBuffer(gpu->device, &bci, NULL, &out->buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(gpu->device, out->buffer, &req);
    VkMemoryPropertyFlags want = host_visible
                                     ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                     : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    uint32_t type = pg_gpu_memory_type(gpu, req.memoryTypeBits, want);
    if (type == UINT32_MAX) {
        pg_buffer_destroy(gpu, out);
        return pg_fail(err, PG_ERR_VULKAN, "buffer '%s': no suitable memory type", name);
    }
    VkMemoryAllocateInfo mai = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = req.size,
        .memoryTypeIndex = type,
    };
    VkResult r = pg_gpu_alloc_memory(gpu, &mai, &out->memory);
    if (r != VK_SUCCESS) {
        pg_buffer_destroy(gpu, out);
        return pg_fail(err, PG_ERR_VULKAN, "buffer '%s': vkAllocateMemory(%llu bytes) failed: %s",
                       name, (unsigned long long)req.size, pg_vk_result_name(r));
    }
    /* failing past the allocation: both destroyed (callers holding the buffer in a local leaked them) */
    PG_VK_TRY_OR(err, vkBindBufferMemory(gpu->device, out->buffer, out->memory, 0), pg_buffer_destroy(gpu, out));
    if (host_visible)
        PG_VK_TRY_OR(err, vkMapMemory(gpu->device, out->memory, 0, VK_WHOLE_SIZE, 0, &out->mapped),
                     pg_buffer_destroy(gpu, out));
    out->size = size;
    pg_gpu_name(gpu, VK_OBJECT_TYPE_BUFFER, (uint64_t)out->buffer, "%s", name);
    pg_gpu_name(gpu, VK_OBJECT_TYPE_DEVICE_MEMORY, (uint64_t)out->memory, "%s.memory", name);
    return PG_OK;
}

void pg_buffer_destroy(pg_gpu *gpu, pg_buffer *b)
{
    if (b->buffer) vkDestroyBuffer(gpu->device, b->buffer, NULL);
    if (b->memory) pg_gpu_free_memory(gpu, b->memory);
    memset(b, 0, sizeof *b);
}

VkImageAspectFlags pg_vk_aspect(VkFormat f)
{
    switch (f) {
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D16_UNORM:
        return VK_IMAGE_ASPECT_DEPTH_BIT;
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
        return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    default:
        return VK_IMAGE_ASPECT_COLOR_BIT;
    }
}

/* Whether a blit from an RGBA8 UNORM image may write f: not an integer format (a blit keeps to one
 * numeric class) and not a depth/stencil one (a blit keeps to one aspect). Whether the device can
 * blit into f at all is its format features' question (VK_FORMAT_FEATURE_BLIT_DST_BIT). */
bool pg_vk_format_blits_from_unorm(VkFormat f)
{
    switch (f) {
    case VK_FORMAT_R8_UINT: case VK_FORMAT_R8_SINT: case VK_FORMAT_R8G8_UINT: case VK_FORMAT_R8G8_SINT:
    case VK_FORMAT_R8G8B8_UINT: case VK_FORMAT_R8G8B8_SINT: case VK_FORMAT_B8G8R8_UINT:
    case VK_FORMAT_B8G8R8_SINT: case VK_FORMAT_R8G8B8A8_UINT: case VK_FORMAT_R8G8B8A8_SINT:
    case VK_FORMAT_B8G8R8A8_UINT: case VK_FORMAT_B8G8R8A8_SINT: case VK_FORMAT_A8B8G8R8_UINT_PACK32:
    case VK_FORMAT_A8B8G8R8_SINT_PACK32: case VK_FORMAT_A2R10G10B10_UINT_PACK32:
    case VK_FORMAT_A2R10G10B10_SINT_PACK32: case VK_FORMAT_A2B10G10R10_UINT_PACK32:
    case VK_FORMAT_A2B10G10R10_SINT_PACK32: case VK_FORMAT_R16_UINT: case VK_FORMAT_R16_SINT:
    case VK_FORMAT_R16G16_UINT: case VK_FORMAT_R16G16_SINT: case VK_FORMAT_R16G16B16_UINT:
    case VK_FORMAT_R16G16B16_SINT: case VK_FORMAT_R16G16B16A16_UINT: case VK_FORMAT_R16G16B16A16_SINT:
    case VK_FORMAT_R32_UINT: case VK_FORMAT_R32_SINT: case VK_FORMAT_R32G32_UINT: case VK_FORMAT_R32G32_SINT:
    case VK_FORMAT_R32G32B32_UINT: case VK_FORMAT_R32G32B32_SINT: case VK_FORMAT_R32G32B32A32_UINT:
    case VK_FORMAT_R32G32B32A32_SINT: case VK_FORMAT_R64_UINT: case VK_FORMAT_R64_SINT:
    case VK_FORMAT_R64G64_UINT: case VK_FORMAT_R64G64_SINT: case VK_FORMAT_R64G64B64_UINT:
    case VK_FORMAT_R64G64B64_SINT: case VK_FORMAT_R64G64B64A64_UINT: case VK_FORMAT_R64G64B64A64_SINT:
    case VK_FORMAT_D16_UNORM: case VK_FORMAT_X8_D24_UNORM_PACK32: case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_S8_UINT: case VK_FORMAT_D16_UNORM_S8_UINT: case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
        return false;
    default:
        return f != VK_FORMAT_UNDEFINED;
    }
}

pg_result pg_image_create(pg_gpu *gpu, VkFormat format, uint32_t w, uint32_t h, uint32_t mips,
                          VkImageUsageFlags usage, const char *name, pg_image *out, pg_error *err)
{
    memset(out, 0, sizeof *out);
    VkImageCreateInfo ici = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
        .imageType = VK_IMAGE_TYPE_2D,
        .format = format,
        .extent = {w, h, 1},
        .mipLevels = mips,
        .arrayLayers = 1,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .tiling = VK_IMAGE_TILING_OPTIMAL,
        .usage = usage,
        .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
    };
    PG_VK_TRY(err, vkCreateImage(gpu->device, &ici, NULL, &out->image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(gpu->device, out->image, &req);
    VkResult r = pg_gpu_alloc_device_memory(gpu, req.size, req.memoryTypeBits, &out->memory);
    if (r != VK_SUCCESS) {
        pg_image_destroy(gpu, out);
        return pg_fail(err, PG_ERR_VULKAN, "image '%s' %ux%u: vkAllocateMemory failed: %s", name,
                       w, h, pg_vk_result_name(r));
    }
    PG_VK_TRY_OR(err, vkBindImageMemory(gpu->device, out->image, out->memory, 0), pg_image_destroy(gpu, out));
    VkImageViewCreateInfo vci = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
        .image = out->image,
        .viewType = VK_IMAGE_VIEW_TYPE_2D,
        .format = format,
        .subresourceRange = {pg_vk_aspect(format), 0, mips, 0, 1},
    };
    PG_VK_TRY_OR(err, vkCreateImageView(gpu->device, &vci, NULL, &out->view), pg_image_destroy(gpu, out));
    out->format = format;
    out->width = w;
    out->height = h;
    out->mips = mips;
    pg_gpu_name(gpu, VK_OBJECT_TYPE_IMAGE, (uint64_t)out->image, "%s", name);
    pg_gpu_name(gpu, VK_OBJECT_TYPE_IMAGE_VIEW, (uint64_t)out->view, "%s.view", name);
    pg_gpu_name(gpu, VK_OBJECT_TYPE_DEVICE_MEMORY, (uint64_t)out->memory, "%s.memory", name);
    return PG_OK;
}

void pg_image_destroy(pg_gpu *gpu, pg_image *img)
{
    if (img->view) vkDestroyImageView(gpu->device, img->view, NULL);
    if (img->image) vkDestroyImage(gpu->device, img->image, NULL);
    if (img->memory) pg_gpu_free_memory(gpu, img->memory);
    memset(img, 0, sizeof *img);
}

pg_result pg_gpu_begin_once(pg_gpu *gpu, VkCommandBuffer *out, pg_error *err)
{
    VkCommandBufferAllocateInfo ai = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = gpu->cmd_pool,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    PG_VK_TRY(err, vkAllocateCommandBuffers(gpu->device, &ai, out));
    VkCommandBufferBeginInfo bi = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    VkResult r = vkBeginCommandBuffer(*out, &bi);
    if (r != VK_SUCCESS) {
        vkFreeCommandBuffers(gpu->device, gpu->cmd_pool, 1, out);
        return pg_fail(err, PG_ERR_VULKAN, "vkBeginCommandBuffer failed: %s", pg_vk_result_name(r));
    }
    return PG_OK;
}

pg_result pg_gpu_end_once(pg_gpu *gpu, VkCommandBuffer cmd, pg_error *err)
{
    pg_result res = PG_OK;
    VkResult r = vkEndCommandBuffer(cmd);
    if (r == VK_SUCCESS) {
        VkCommandBufferSubmitInfo cbi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO,
                                         .commandBuffer = cmd};
        VkSubmitInfo2 si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2,
                            .commandBufferInfoCount = 1,
                            .pCommandBufferInfos = &cbi};
        r = pg_vk_fault_next("vkQueueSubmit2(one-shot)") ? VK_ERROR_DEVICE_LOST
                                                          : vkQueueSubmit2(gpu->queue, 1, &si, VK_NULL_HANDLE);
        if (r == VK_SUCCESS) r = vkQueueWaitIdle(gpu->queue);
    }
    if (r != VK_SUCCESS)
        res = pg_fail(err, PG_ERR_VULKAN, "one-shot submit failed: %s", pg_vk_result_name(r));
    vkFreeCommandBuffers(gpu->device, gpu->cmd_pool, 1, &cmd);
    return res;
}

VkBufferMemoryBarrier2 pg_buffer_barrier(VkBuffer buffer, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                                         VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access)
{
    return (VkBufferMemoryBarrier2){
        .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
        .srcStageMask = src_stage,
        .srcAccessMask = src_access,
        .dstStageMask = dst_stage,
        .dstAccessMask = dst_access,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .buffer = buffer,
        .size = VK_WHOLE_SIZE,
    };
}

VkImageMemoryBarrier2 pg_image_barrier(VkImage image, VkImageAspectFlags aspect,
                                       VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                                       VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access,
                                       VkImageLayout old_layout, VkImageLayout new_layout)
{
    VkImageMemoryBarrier2 b = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2,
        .srcStageMask = src_stage,
        .srcAccessMask = src_access,
        .dstStageMask = dst_stage,
        .dstAccessMask = dst_access,
        .oldLayout = old_layout,
        .newLayout = new_layout,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = image,
        .subresourceRange = {aspect, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS},
    };
    return b;
}

static void cmd_dependency(VkCommandBuffer cmd, const VkMemoryBarrier2 *memory, uint32_t n_images,
                           const VkImageMemoryBarrier2 *images, uint32_t n_buffers,
                           const VkBufferMemoryBarrier2 *buffers)
{
    VkDependencyInfo dep = {
        .sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
        .memoryBarrierCount = memory ? 1 : 0,
        .pMemoryBarriers = memory,
        .bufferMemoryBarrierCount = n_buffers,
        .pBufferMemoryBarriers = buffers,
        .imageMemoryBarrierCount = n_images,
        .pImageMemoryBarriers = images,
    };
    vkCmdPipelineBarrier2(cmd, &dep);
}

void pg_cmd_barriers(VkCommandBuffer cmd, uint32_t n_images, const VkImageMemoryBarrier2 *images,
                     uint32_t n_buffers, const VkBufferMemoryBarrier2 *buffers)
{
    if (!n_images && !n_buffers) return;
    cmd_dependency(cmd, NULL, n_images, images, n_buffers, buffers);
}

void pg_cmd_memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                           VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access)
{
    VkMemoryBarrier2 mb = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
        .srcStageMask = src_stage,
        .srcAccessMask = src_access,
        .dstStageMask = dst_stage,
        .dstAccessMask = dst_access,
    };
    cmd_dependency(cmd, &mb, 0, NULL, 0, NULL);
}

VkResult pg_gpu_alloc_memory(pg_gpu *gpu, const VkMemoryAllocateInfo *info, VkDeviceMemory *out)
{
    VkResult r = vkAllocateMemory(gpu->device, info, NULL, out);
    if (r == VK_SUCCESS) gpu->live_memory_objects++;
    return r;
}

void pg_gpu_free_memory(pg_gpu *gpu, VkDeviceMemory mem)
{
    if (!mem) return;
    vkFreeMemory(gpu->device, mem, NULL);
    gpu->live_memory_objects--;
}

uint64_t pg_process_rss(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    if (!f) return 0;
    unsigned long size = 0, resident = 0;
    int n = fscanf(f, "%lu %lu", &size, &resident);
    fclose(f);
    return n == 2 ? (uint64_t)resident * 4096u : 0;
}
