/* graph_names.c - the short names of plan values that reports, dumps and messages share:
 * Vulkan stage/access/layout values, resource kinds, lifetimes and queues, and byte sizes
 * (graph.h). A leaf: it
 * calls no other file of the compiler.
 */
#include "graph.h"
#include "graph_report.h"

#include <inttypes.h>
#include <stdio.h>
#include <string.h>
#include <vulkan/vulkan_core.h>

typedef struct bit_name {
    uint64_t bit;
    const char *name;
} bit_name;

/* Vulkan's *_2 flag bits are 'static const' variables, not constant expressions, so the tables
 * are built on the stack. */
static void bit_names(const bit_name *table, size_t n, uint64_t bits, char *buf, size_t size)
{
    if (!buf || !size) return;
    buf[0] = 0;
    if (bits == 0) {
        pg_strlcpy(buf, "none", size);
        return;
    }
    size_t len = 0;
    uint64_t left = bits;
    for (size_t i = 0; i < n && len < size; i++) {
        if (!(left & table[i].bit)) continue;
        int w = snprintf(buf + len, size - len, "%s%s", len ? "|" : "", table[i].name);
        if (w < 0) break;
        len += (size_t)w;
        left &= ~table[i].bit;
    }
    if (left && len < size)
        snprintf(buf + len, size - len, "%s0x%" PRIx64, len ? "|" : "", left);
}

void pg_stage_names(uint64_t stages, char *buf, size_t buf_size)
{
    const bit_name t[] = {
        {VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, "top"},
        {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, "draw_indirect"},
        {VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT, "vertex_input"},
        {VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, "vertex_shader"},
        {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, "fragment_shader"},
        {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT, "early_tests"},
        {VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, "late_tests"},
        {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, "color_output"},
        {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, "compute_shader"},
        {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, "all_transfer"},
        {VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, "bottom"},
        {VK_PIPELINE_STAGE_2_HOST_BIT, "host"},
        {VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT, "all_graphics"},
        {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, "all_commands"},
        {VK_PIPELINE_STAGE_2_COPY_BIT, "copy"},
        {VK_PIPELINE_STAGE_2_RESOLVE_BIT, "resolve"},
        {VK_PIPELINE_STAGE_2_BLIT_BIT, "blit"},
        {VK_PIPELINE_STAGE_2_CLEAR_BIT, "clear"},
        {VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, "index_input"},
        {VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT, "vertex_attribute_input"},
        {VK_PIPELINE_STAGE_2_PRE_RASTERIZATION_SHADERS_BIT, "pre_rasterization"},
    };
    bit_names(t, sizeof t / sizeof t[0], stages, buf, buf_size);
}

/* The access bits' names in report order (a function: Vulkan's *_2 bits are not constants). */
static size_t access_table(bit_name *t)
{
    const bit_name table[] = {
        {VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, "indirect_read"},
        {VK_ACCESS_2_INDEX_READ_BIT, "index_read"},
        {VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT, "vertex_attribute_read"},
        {VK_ACCESS_2_UNIFORM_READ_BIT, "uniform_read"},
        {VK_ACCESS_2_INPUT_ATTACHMENT_READ_BIT, "input_attachment_read"},
        {VK_ACCESS_2_SHADER_READ_BIT, "shader_read"},
        {VK_ACCESS_2_SHADER_WRITE_BIT, "shader_write"},
        {VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, "color_read"},
        {VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, "color_write"},
        {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, "depth_read"},
        {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, "depth_write"},
        {VK_ACCESS_2_TRANSFER_READ_BIT, "transfer_read"},
        {VK_ACCESS_2_TRANSFER_WRITE_BIT, "transfer_write"},
        {VK_ACCESS_2_HOST_READ_BIT, "host_read"},
        {VK_ACCESS_2_HOST_WRITE_BIT, "host_write"},
        {VK_ACCESS_2_MEMORY_READ_BIT, "memory_read"},
        {VK_ACCESS_2_MEMORY_WRITE_BIT, "memory_write"},
        {VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, "sampled_read"},
        {VK_ACCESS_2_SHADER_STORAGE_READ_BIT, "storage_read"},
        {VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, "storage_write"},
    };
    memcpy(t, table, sizeof table);
    return sizeof table / sizeof table[0];
}

void pg_access_mask_names(uint64_t access, char *buf, size_t buf_size)
{
    bit_name t[32];
    bit_names(t, access_table(t), access, buf, buf_size);
}

uint32_t pg_access_bit_names(uint64_t access, const char **names, uint32_t max, uint64_t *unnamed)
{
    bit_name t[32];
    const size_t n = access_table(t);
    uint32_t count = 0;
    for (size_t i = 0; i < n; i++) {
        if (!(access & t[i].bit)) continue;
        if (count < max) names[count++] = t[i].name;
        access &= ~t[i].bit;
    }
    if (unnamed) *unnamed = access;
    return count;
}

const char *pg_layout_name(uint32_t layout)
{
    switch (layout) {
    case VK_IMAGE_LAYOUT_UNDEFINED: return "undefined";
    case VK_IMAGE_LAYOUT_GENERAL: return "general";
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: return "color_attachment";
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL: return "depth_stencil_attachment";
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL: return "depth_stencil_read_only";
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return "shader_read_only";
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return "transfer_src";
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return "transfer_dst";
    case VK_IMAGE_LAYOUT_PREINITIALIZED: return "preinitialized";
    case VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL: return "depth_attachment";
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL: return "depth_read_only";
    case VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL: return "read_only";
    case VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL: return "attachment";
    case VK_IMAGE_LAYOUT_PRESENT_SRC_KHR: return "present_src";
    default: return "?";
    }
}

const char *pg_res_kind_name(pg_res_kind kind)
{
    return kind == PG_RES_IMAGE ? "image" : kind == PG_RES_BUFFER ? "buffer" : "?";
}

const char *pg_lifetime_name(pg_lifetime_kind lifetime)
{
    switch (lifetime) {
    case PG_LIFETIME_TRANSIENT: return "transient";
    case PG_LIFETIME_PERSISTENT: return "persistent";
    case PG_LIFETIME_IMPORTED: return "imported";
    default: return "?";
    }
}

const char *pg_queue_name(pg_queue q)
{
    return q == PG_QUEUE_COMPUTE ? "compute" : "graphics";
}

void pg_fmt_bytes(uint64_t b, char *buf, size_t size)
{
    if (b >= (1ull << 30))
        snprintf(buf, size, "%.2f GiB", (double)b / (double)(1ull << 30));
    else if (b >= (1ull << 20))
        snprintf(buf, size, "%.2f MiB", (double)b / (double)(1ull << 20));
    else if (b >= 1024)
        snprintf(buf, size, "%.1f KiB", (double)b / 1024.0);
    else
        snprintf(buf, size, "%" PRIu64 " B", b);
}
