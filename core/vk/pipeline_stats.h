/* pipeline_stats.h - what the driver says each pipeline costs (VK_KHR_pipeline_executable_properties):
 * with PASSGRAPH_PIPELINE_STATS=1 in the environment and a device that has the extension, every
 * pipeline passgraph creates is created with VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR and one
 * line a shader executable goes to stderr:
 *   passgraph: pipeline-stats: <pipeline name> <executable name>: <statistic>=<value>, ...
 * (whatever statistics the driver names, e.g. register counts; not yet seen on a GPU). A device without the
 * extension gets one line saying so and nothing else changes. docs/cli.md ("Environment"). */
#ifndef PG_PIPELINE_STATS_H
#define PG_PIPELINE_STATS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <vulkan/vulkan.h>

typedef struct pg_gpu pg_gpu;

/* PASSGRAPH_PIPELINE_STATS is set (and not "0") */
bool pg_pipeline_stats_wanted(void);

/* the flags a pipeline is created with (VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR when on) */
VkPipelineCreateFlags pg_pipeline_stats_flags(const pg_gpu *gpu);

/* one line a shader executable of p (named name) to stderr, when on */
void pg_pipeline_stats_report(const pg_gpu *gpu, VkPipeline p, const char *name);

/* one statistic as text: "name=value" (bool, integers, floats as %g) into buf; its length */
size_t pg_pipeline_stat_format(const VkPipelineExecutableStatisticKHR *s, char *buf, size_t cap);

#endif
