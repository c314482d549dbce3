/* passgraph.c - the one executable: `passgraph SUBCOMMAND [options]`. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "vk_context.h"

static void usage(FILE *f)
{
    fprintf(f,
            "usage: passgraph <command> [options]\n"
            "\n"
            "passgraph renders scenes lit by many point lights with render pipelines described in JSON\n"
            "(pipelines/*.json): the graph orders passes, culls what the output does not need, aliases\n"
            "transient memory and places every Vulkan barrier itself.\n"
            "\n"
            "commands:\n"
            "  render    render one frame headless to a PNG and print GPU timings per pass\n"
            "  view      open a window: fly through the scene, switch and edit pipelines live\n"
            "  compare   render one frame with a pipeline and a reference pipeline; print the image\n"
            "            error (RMSE, PSNR, max abs; linear HDR and 8-bit display) and GPU timings\n"
            "  bench     render every pipeline over light counts, sizes and parameter sweeps; record GPU\n"
            "            time per pass, memory, overflow and image error against a reference pipeline\n"
            "            (default pipelines/reference.json) to CSV, JSON and SVG charts; --shard K/N runs\n"
            "            every N-th configuration\n"
            "  bench-merge  join the outputs of 'bench --shard K/N' runs into one sweep's CSV, JSON, charts\n"
            "  dump      print the compiled graph without rendering (no GPU): passes, barriers,\n"
            "            culls and reasons, resources, memory blocks; as text, JSON, Graphviz DOT/SVG\n"
            "            or a memory-timeline SVG\n"
            "  devices   list the Vulkan devices (for --device)\n"
            "  lights-table  write a glTF with N generated point lights stored in it (a binary\n"
            "            PASSGRAPH_lights_table, or KHR_lights_punctual JSON)\n"
            "\n"
            "'passgraph <command> --help' lists a command's options.\n");
}

int pg_cmd_devices(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    pg_error err = {0};
    if (pg_gpu_list_devices(stdout, &err)) {
        fprintf(stderr, "passgraph devices: %s\n", err.msg);
        return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(cmd, "render")) return pg_cmd_render(argc - 2, argv + 2);
    if (!strcmp(cmd, "view")) return pg_cmd_view(argc - 2, argv + 2);
    if (!strcmp(cmd, "compare")) return pg_cmd_compare(argc - 2, argv + 2);
    if (!strcmp(cmd, "dump")) return pg_cmd_dump(argc - 2, argv + 2);
    if (!strcmp(cmd, "bench")) return pg_cmd_bench(argc - 2, argv + 2);
    if (!strcmp(cmd, "bench-merge")) return pg_cmd_bench_merge(argc - 2, argv + 2);
    if (!strcmp(cmd, "devices")) return pg_cmd_devices(argc - 2, argv + 2);
    if (!strcmp(cmd, "lights-table")) return pg_cmd_lights_table(argc - 2, argv + 2);
    fprintf(stderr, "passgraph: unknown command '%s'\n", cmd);
    usage(stderr);
    return 2;
}
