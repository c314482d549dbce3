/* test_pipeline_stats.c - the driver statistics' text (core/vk/pipeline_stats.c): each statistic
 * format as "name=value", a line cut short never overflows, and PASSGRAPH_PIPELINE_STATS's values.
 * No GPU (lavapipe has no VK_KHR_pipeline_executable_properties: cli_test.sh checks that a render
 * asking for statistics there says so in one line and renders the same image). */
#include <stdlib.h>
#include <string.h>

#include "pipeline_stats.h"
#include "test_util.h"

static VkPipelineExecutableStatisticKHR stat(const char *name, VkPipelineExecutableStatisticFormatKHR f)
{
    VkPipelineExecutableStatisticKHR s = {.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR, .format = f};
    strncpy(s.name, name, sizeof s.name - 1);
    return s;
}

int main(void)
{
    char buf[64];
    VkPipelineExecutableStatisticKHR s = stat("Register Count", VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR);
    s.value.u64 = 72;
    CHECK(pg_pipeline_stat_format(&s, buf, sizeof buf) == strlen("Register Count=72"));
    CHECK(strcmp(buf, "Register Count=72") == 0);
    s = stat("Delta", VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR);
    s.value.i64 = -5;
    pg_pipeline_stat_format(&s, buf, sizeof buf);
    CHECK(strcmp(buf, "Delta=-5") == 0);
    s = stat("Spills", VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR);
    s.value.b32 = VK_TRUE;
    pg_pipeline_stat_format(&s, buf, sizeof buf);
    CHECK(strcmp(buf, "Spills=true") == 0);
    s = stat("Occupancy", VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR);
    s.value.f64 = 0.75;
    pg_pipeline_stat_format(&s, buf, sizeof buf);
    CHECK(strcmp(buf, "Occupancy=0.75") == 0);
    s = stat("Odd", (VkPipelineExecutableStatisticFormatKHR)99);
    pg_pipeline_stat_format(&s, buf, sizeof buf);
    CHECK(strcmp(buf, "Odd=?") == 0);
    /* cut short: the length written, terminated, nothing past cap */
    s = stat("Register Count", VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR);
    s.value.u64 = 123456789;
    char small[9];
    memset(small, 'x', sizeof small);
    size_t n = pg_pipeline_stat_format(&s, small, 8);
    CHECK(n == 7 && strcmp(small, "Registe") == 0 && small[8] == 'x');
    CHECK(pg_pipeline_stat_format(&s, small, 0) == 0 && small[8] == 'x');

    unsetenv("PASSGRAPH_PIPELINE_STATS");
    CHECK(!pg_pipeline_stats_wanted());
    setenv("PASSGRAPH_PIPELINE_STATS", "0", 1);
    CHECK(!pg_pipeline_stats_wanted());
    setenv("PASSGRAPH_PIPELINE_STATS", "", 1);
    CHECK(!pg_pipeline_stats_wanted());
    setenv("PASSGRAPH_PIPELINE_STATS", "1", 1);
    CHECK(pg_pipeline_stats_wanted());
    return pg_test_finish("test_pipeline_stats");
}
