/* graph_sync.c - the one table that turns a pass's declared access into synchronization2 stage
 * and access masks, an image layout and usage flags. Barrier inference uses nothing else. */
#include "graph.h"

#include <string.h>
#include <vulkan/vulkan_core.h>

static uint64_t shader_stages(uint32_t stages)
{
    uint64_t s = 0;
    if (stages & PG_STAGE_VERTEX) s |= VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
    if (stages & PG_STAGE_FRAGMENT) s |= VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    if (stages & PG_STAGE_COMPUTE) s |= VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    if (!s) s = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    return s;
}

pg_sync_info pg_access_sync(pg_access access, uint32_t stages, pg_res_kind kind, pg_format format)
{
    pg_sync_info s;
    memset(&s, 0, sizeof s); /* padding too: plans are compared bytewise */
    const bool img = kind == PG_RES_IMAGE;
    const bool depth = pg_format_get(format)->fmt_class == PG_FMTCLASS_DEPTH;
    (void)depth;
    switch (access) {
    case PG_ACCESS_COLOR_WRITE:
    case PG_ACCESS_COLOR_RMW:
        s.stages = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
        s.access = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
        if (access == PG_ACCESS_COLOR_RMW) s.access |= VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT;
        s.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        s.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
        s.writes = true;
        s.reads = access == PG_ACCESS_COLOR_RMW;
        s.full_write = access == PG_ACCESS_COLOR_WRITE;
        break;
    case PG_ACCESS_DEPTH_WRITE:
    case PG_ACCESS_DEPTH_RMW:
        s.stages = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                   VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
        s.access = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                   VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
        s.layout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        s.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
        s.writes = true;
        s.reads = access == PG_ACCESS_DEPTH_RMW;
        s.full_write = access == PG_ACCESS_DEPTH_WRITE; /* cleared */
        break;
    case PG_ACCESS_DEPTH_READ:
        s.stages = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                   VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
        s.access = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
        s.layout = VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
        s.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
        s.reads = true;
        break;
    case PG_ACCESS_SAMPLED:
        s.stages = shader_stages(stages);
        s.access = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
        s.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        s.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
        s.reads = true;
        break;
    case PG_ACCESS_STORAGE_READ:
    case PG_ACCESS_STORAGE_WRITE:
    case PG_ACCESS_STORAGE_RW:
        s.stages = shader_stages(stages);
        s.access = 0;
        if (access != PG_ACCESS_STORAGE_WRITE) s.access |= VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
        if (access != PG_ACCESS_STORAGE_READ) s.access |= VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
        s.layout = VK_IMAGE_LAYOUT_GENERAL;
        s.usage = img ? VK_IMAGE_USAGE_STORAGE_BIT : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        s.reads = access != PG_ACCESS_STORAGE_WRITE;
        s.writes = access != PG_ACCESS_STORAGE_READ;
        s.full_write = access == PG_ACCESS_STORAGE_WRITE;
        break;
    case PG_ACCESS_UNIFORM:
        s.stages = shader_stages(stages);
        s.access = VK_ACCESS_2_UNIFORM_READ_BIT;
        s.usage = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
        s.reads = true;
        break;
    case PG_ACCESS_TRANSFER_SRC:
        s.stages = VK_PIPELINE_STAGE_2_COPY_BIT;
        s.access = VK_ACCESS_2_TRANSFER_READ_BIT;
        s.layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        s.usage = img ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
        s.reads = true;
        break;
    case PG_ACCESS_TRANSFER_DST:
        s.stages = VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT;
        s.access = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        s.layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        s.usage = img ? VK_IMAGE_USAGE_TRANSFER_DST_BIT : VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        s.writes = true;
        s.full_write = true;
        break;
    case PG_ACCESS_VERTEX_INPUT:
        s.stages = VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT;
        s.access = VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT;
        s.usage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
        s.reads = true;
        break;
    case PG_ACCESS_INDIRECT:
        s.stages = VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT;
        s.access = VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT;
        s.usage = VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
        s.reads = true;
        break;
    default:
        break;
    }
    if (!img) s.layout = VK_IMAGE_LAYOUT_UNDEFINED;
    return s;
}

const char *pg_access_name(pg_access a)
{
    static const char *n[PG_ACCESS_COUNT] = {
        "color_write", "color_rmw", "depth_write", "depth_rmw", "depth_read", "sampled",
        "storage_read", "storage_write", "storage_rw", "uniform", "transfer_src",
        "transfer_dst", "indirect", "vertex_input",
    };
    return (unsigned)a < PG_ACCESS_COUNT ? n[a] : "?";
}
