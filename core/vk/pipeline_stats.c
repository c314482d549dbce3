/* pipeline_stats.c - the driver's statistics of every pipeline (pipeline_stats.h) */
#include "pipeline_stats.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vk_context.h"

bool pg_pipeline_stats_wanted(void)
{
    const char *e = getenv("PASSGRAPH_PIPELINE_STATS");
    return e && e[0] && strcmp(e, "0") != 0;
}

VkPipelineCreateFlags pg_pipeline_stats_flags(const pg_gpu *gpu)
{
    return gpu->exec_stats ? VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR : 0;
}

size_t pg_pipeline_stat_format(const VkPipelineExecutableStatisticKHR *s, char *buf, size_t cap)
{
    int n;
    switch (s->format) {
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR:
        n = snprintf(buf, cap, "%s=%s", s->name, s->value.b32 ? "true" : "false");
        break;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
        n = snprintf(buf, cap, "%s=%" PRId64, s->name, s->value.i64);
        break;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
        n = snprintf(buf, cap, "%s=%" PRIu64, s->name, s->value.u64);
        break;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR:
        n = snprintf(buf, cap, "%s=%g", s->name, s->value.f64);
        break;
    default:
        n = snprintf(buf, cap, "%s=?", s->name);
        break;
    }
    if (n < 0) n = 0;
    return (size_t)n < cap ? (size_t)n : (cap ? cap - 1 : 0);
}

/* the statistics of executable e of p, "a=1, b=2", into line */
static void stats_line(const pg_gpu *gpu, VkPipeline p, uint32_t e, char *line, size_t cap)
{
    VkPipelineExecutableInfoKHR info = {.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR,
                                        .pipeline = p, .executableIndex = e};
    uint32_t n = 0;
    line[0] = '\0';
    if (gpu->exec_stats(gpu->device, &info, &n, NULL) != VK_SUCCESS || n == 0) return;
    VkPipelineExecutableStatisticKHR *st = calloc(n, sizeof *st);
    if (!st) return;
    for (uint32_t i = 0; i < n; i++) st[i].sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR;
    if (gpu->exec_stats(gpu->device, &info, &n, st) >= 0) {
        size_t len = 0;
        for (uint32_t i = 0; i < n && len + 1 < cap; i++) {
            if (i) len += (size_t)snprintf(line + len, cap - len, ", ");
            if (len + 1 < cap) len += pg_pipeline_stat_format(&st[i], line + len, cap - len);
        }
    }
    free(st);
}

void pg_pipeline_stats_report(const pg_gpu *gpu, VkPipeline p, const char *name)
{
    if (!gpu->exec_stats || !gpu->exec_props || p == VK_NULL_HANDLE) return;
    VkPipelineInfoKHR pi = {.sType = VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR, .pipeline = p};
    uint32_t n = 0;
    if (gpu->exec_props(gpu->device, &pi, &n, NULL) != VK_SUCCESS || n == 0) return;
    VkPipelineExecutablePropertiesKHR *pr = calloc(n, sizeof *pr);
    if (!pr) return;
    for (uint32_t i = 0; i < n; i++) pr[i].sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR;
    if (gpu->exec_props(gpu->device, &pi, &n, pr) >= 0) {
        for (uint32_t e = 0; e < n; e++) {
            char line[1024];
            stats_line(gpu, p, e, line, sizeof line);
            fprintf(stderr, "passgraph: pipeline-stats: %s %s: %s\n", name, pr[e].name, line);
        }
    }
    free(pr);
}
