/* cmd_dump.c - `passgraph dump`: the compiled graph as text, JSON, Graphviz DOT (or an image
 * Graphviz renders from it) or a memory-timeline SVG, without a GPU and without rendering. */
#include "pg_file.h"
#include "scene_vars.h"
#include "size_note.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "sides.h"
#include "commands.h"
#include "graph.h"
#include "graph_dump.h"

static const char *const dump_help =
    "usage: passgraph dump [options] [--format text|json|dot|timeline] [--out FILE]\n"
    "Compiles a pipeline for a scene, lights and output size, and prints what the graph does,\n"
    "without a GPU and without rendering: the passes in execution order with their reads, writes\n"
    "and the barriers placed before them (stages, accesses, old/new layout), the culled passes and\n"
    "resources and the left-out items and shader features, each with its reason, every resource\n"
    "with format, size, lifetime (first..last pass) and the memory block and offset it aliases\n"
    "into, a memory timeline, and totals (passes, barriers, transient bytes before/after aliasing).\n"
    "The formats are documented in docs/dump-format.md.\n"
    "\n"
    "dump options:\n"
    "  --format FORMAT      text (default): the readable report with a text memory timeline\n"
    "                       json: stable, versioned (\"format_version\": 1), for tools and diffs\n"
    "                       dot: a Graphviz graph (passes, resources, barriers on the edges,\n"
    "                            culled and omitted items dashed grey)\n"
    "                       timeline (or svg-timeline): an SVG chart of the transient resources\n"
    "                            over the executed passes, one row per memory block\n"
    "  --out FILE           where to write (default: standard output; '-' too). With --format dot,\n"
    "                       a name ending in .svg, .png or .pdf is rendered by Graphviz's 'dot'\n"
    "                       (package graphviz; run directly, not through a shell); any other name\n"
    "                       gets the DOT text. --format timeline writes SVG only.\n"
    "\n"
    "options that change the compiled graph:\n"
    "  --pipeline FILE      pipeline JSON (default: pipelines/naive.json in the data folder)\n"
    "  --scene FILE|default the scene whose features matter: alpha-mask materials, normal maps,\n"
    "                       textures (loaded on the CPU only; default: the built-in atrium)\n"
    "  --scenario FILE      JSON set-up; its light count and scene are used\n"
    "  --lights N           number of lights: sizes the light buffers; 0 culls light animation\n"
    "                       and cluster assignment (default 256)\n"
    "  --size WxH           output size, 1..16384 each (default 1920x1080)\n"
    "  --set KEY=VALUE      override a pipeline parameter (repeatable)\n"
    "  --view NAME          debug view (the pipeline's 'view' parameter); an OCIO view name is\n"
    "                       accepted and changes nothing here (colour is applied at render time)\n"
    "  --debug-view NAME    the same, never an OCIO view\n"
    "  --gltf-scene N       the glTF scene (scenes[N]) whose features matter\n"
    "  --variant N|NAME     the glTF material variant (KHR_materials_variants)\n"
    "  --animation A        the glTF animation (N, NAME, all or none): whether skinning and\n"
    "                       morphing passes run\n"
    "  --environment E      FILE.hdr|FILE.exr|default|none: whether the environment passes run\n"
    "  --include-dir DIR    a folder the pipeline's includes may come from (repeatable)\n"
    "  --plugin FILE.so     load pass types from a plug-in (repeatable; docs/plugins.md)\n"
    "  --no-aliasing        give every transient its own memory block\n"
    "  --immediate          the debugging mode: passes in declaration order, no aliasing,\n"
    "                       full barriers (ALL_COMMANDS -> ALL_COMMANDS) before every pass\n"
    "  --async-compute MODE plan for a graphics and a compute queue: on (of different queue\n"
    "                       families, as on NVIDIA: ownership transfers), emulate (one family:\n"
    "                       semaphores only), off (one queue; the default here plans for one)\n"
    "\n"
    "accepted so that a 'passgraph render' command line can be reused, without effect here:\n"
    "  --time, --seed, --radius, --intensity, --ambient, --environment-intensity,\n"
    "  --environment-rotation, --frames, --device, --validation, --explain, --quiet,\n"
    "  --camera (checked: an unknown glTF camera is refused, as by render),\n"
    "  --ocio-config, --display, --ocio-view (checked against the OCIO config)\n"
    "\n"
    "examples:\n"
    "  passgraph dump --pipeline pipelines/deferred.json --lights 1000\n"
    "  passgraph dump --pipeline pipelines/deferred.json --format json --out deferred.json\n"
    "  passgraph dump --pipeline pipelines/deferred.json --format dot --out deferred.svg\n"
    "  passgraph dump --pipeline pipelines/deferred.json --format timeline --out memory.svg\n";

typedef enum dump_format { DUMP_TEXT, DUMP_JSON, DUMP_DOT, DUMP_TIMELINE } dump_format;

static int parse_format(const char *v, dump_format *out)
{
    if (!strcmp(v, "text")) *out = DUMP_TEXT;
    else if (!strcmp(v, "json")) *out = DUMP_JSON;
    else if (!strcmp(v, "dot")) *out = DUMP_DOT;
    else if (!strcmp(v, "timeline") || !strcmp(v, "svg-timeline")) *out = DUMP_TIMELINE;
    else return -1;
    return 0;
}

static bool to_stdout(const char *out)
{
    return !out || !strcmp(out, "-");
}

/* Opens the output (stdout for none or "-"); the message names the file. */
static FILE *open_out(const char *out, pg_error *err)
{
    if (to_stdout(out)) return stdout;
    FILE *f = fopen(out, "wb");
    if (!f) pg_fail(err, PG_ERR_IO, "cannot write '%s': %s", out, strerror(errno));
    return f;
}

static pg_result close_out(FILE *f, const char *out, pg_error *err)
{
    const bool bad = ferror(f) != 0;
    const int rc = f == stdout ? fflush(f) : fclose(f);
    if (bad || rc != 0)
        return pg_fail(err, PG_ERR_IO, "cannot write '%s'", to_stdout(out) ? "(standard output)" : out);
    return PG_OK;
}

/* Renders the DOT text of the plan through Graphviz into out (its extension picks the format). */
static pg_result write_graphviz(const pg_graph_plan *plan, const pg_pipeline *pl, const char *out,
                                const char *gv_format, pg_error *err)
{
    /* check the destination first so its error reads like every other 'cannot write' */
    FILE *probe = fopen(out, "wb");
    if (!probe) return pg_fail(err, PG_ERR_IO, "cannot write '%s': %s", out, strerror(errno));
    fclose(probe);
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    if (!mem) return pg_fail(err, PG_ERR_OOM, "out of memory");
    pg_dump_dot(plan, pl, mem);
    const bool bad = ferror(mem) != 0;
    fclose(mem);
    if (bad || !text) {
        free(text);
        return pg_fail(err, PG_ERR_OOM, "out of memory");
    }
    pg_result r = pg_dump_run_graphviz(text, gv_format, out, err);
    free(text);
    if (r) remove(out);
    return r;
}

/* No device here: --async-compute says which queues to plan for. */
static pg_queue_caps queues_for(const pg_cli_common *opt)
{
    pg_queue_caps q = {0};
    if (opt->async_compute == PG_ASYNC_ON || opt->async_compute == PG_ASYNC_EMULATE) {
        q.n_queues = 2;
        q.separate_family = opt->async_compute == PG_ASYNC_ON;
    } else if (opt->async_compute == PG_ASYNC_OFF) {
        q.n_queues = 2;
        q.async_off = true;
    }
    return q;
}

/* The command line into opt and format, checked before any work (the output writable, --set and
 * --debug-view against the pipeline): -1 to go on, else the exit status. */
static int dump_setup(int argc, char **argv, pg_cli_common *opt, dump_format *format_out, const char **gv_out)
{
    pg_cli_defaults(opt);
    opt->width = 1920;
    opt->height = 1080;
    opt->quiet = true;
    dump_format format = DUMP_TEXT;
    pg_error err = {0};
    for (int i = 0; i < argc; i++) {
        bool used;
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(dump_help, stdout);
            return 0;
        }
        if (!strcmp(argv[i], "--format")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "passgraph dump: --format: missing value (text, json, dot or timeline)\n");
                return 2;
            }
            if (parse_format(argv[++i], &format)) {
                fprintf(stderr, "passgraph dump: --format %s: expected text, json, dot or timeline\n", argv[i]);
                return 2;
            }
            continue;
        }
        if (pg_cli_parse_common(opt, argc, argv, &i, &used, &err)) {
            fprintf(stderr, "passgraph dump: %s\n", err.msg);
            return 2;
        }
        if (!used) {
            fprintf(stderr, "passgraph dump: unknown option '%s' (see passgraph dump --help)\n", argv[i]);
            return 2;
        }
    }
    const char *gv_format = NULL;
    if (format == DUMP_DOT && !to_stdout(opt->out)) gv_format = pg_dump_graphviz_format_for(opt->out);
    if (format == DUMP_TIMELINE && !to_stdout(opt->out)) {
        const char *ext = pg_dump_graphviz_format_for(opt->out);
        if (ext && strcmp(ext, "svg")) {
            fprintf(stderr,
                    "passgraph dump: --out %s: --format timeline writes SVG; give a .svg name (convert it with "
                    "e.g. rsvg-convert)\n",
                    opt->out);
            return 2;
        }
    }

    /* the output can be written: checked before any work, with the OS reason */
    if (!to_stdout(opt->out) && pg_file_check_writable(opt->out, "--out", &err)) {
        fprintf(stderr, "passgraph dump: %s\n", err.msg);
        return 2;
    }
    if (pg_sides_check_common(opt, &err)) { /* --set, --debug-view: bad options (exit 2), as render's */
        fprintf(stderr, "passgraph dump: %s\n", err.msg);
        return 2;
    }
    *format_out = format;
    *gv_out = gv_format;
    return -1;
}

int pg_cmd_dump(int argc, char **argv)
{
    pg_cli_common opt;
    dump_format format = DUMP_TEXT;
    const char *gv_format = NULL;
    pg_error err = {0};
    const int setup_rc = dump_setup(argc, argv, &opt, &format, &gv_format);
    if (setup_rc >= 0) return setup_rc;
    pg_app app;
    if (pg_app_open(&app, &opt, false /* no GPU */, &err)) {
        fprintf(stderr, "passgraph dump: %s\n", err.msg);
        return 1;
    }
    int rc = 1;
    pg_pipeline *pl = NULL;
    pg_graph_plan *plan = NULL;
    char *json = NULL;
    FILE *f = NULL;
    if (pg_pipeline_load(app.pipeline_path, opt.sets, opt.n_sets, &pl, &err)) goto done;
    pg_compile_desc cd = {
        .pipeline = pl,
        .registry = &app.registry,
        .output_width = opt.width,
        .output_height = opt.height,
        .disable_aliasing = opt.no_aliasing,
        .immediate = opt.immediate,
    };
    cd.queues = queues_for(&opt);
    if (pg_scene_vars_set(&cd.vars, app.scene ? &app.scene->features : NULL, app.lights.count, &err) ||
        pg_graph_compile(&cd, &plan, &err))
        goto done;
    pg_size_note_print(stderr, "dump", opt.width, opt.height, plan);

    if (gv_format) {
        if (write_graphviz(plan, pl, opt.out, gv_format, &err)) goto done;
    } else {
        if (format == DUMP_JSON && !(json = pg_dump_json(plan, pl))) {
            pg_fail(&err, PG_ERR_OOM, "out of memory building the JSON dump");
            goto done;
        }
        if (!(f = open_out(opt.out, &err))) goto done;
        switch (format) {
        case DUMP_TEXT: pg_dump_text(plan, pl, f); break;
        case DUMP_JSON: fprintf(f, "%s\n", json); break;
        case DUMP_DOT: pg_dump_dot(plan, pl, f); break;
        case DUMP_TIMELINE: pg_dump_timeline_svg(plan, pl, f); break;
        }
        pg_result r = close_out(f, opt.out, &err);
        f = NULL;
        if (r) goto done;
    }
    if (!to_stdout(opt.out)) {
        uint32_t barriers = 0;
        for (uint32_t i = 0; i < plan->n_passes; i++) barriers += plan->passes[i].n_barriers;
        printf("dump: %s %ux%u lights=%u: %u passes run, %u culled; %u barriers (+%u after the last pass); "
               "transient %llu B -> %llu B aliased -> %s\n",
               pl->name, opt.width, opt.height, app.lights.count, plan->n_order, plan->n_passes - plan->n_order,
               barriers, plan->n_final_barriers, (unsigned long long)plan->transient_bytes_unaliased,
               (unsigned long long)plan->transient_bytes_aliased, opt.out);
    }
    rc = 0;
done:
    if (rc && err.code) fprintf(stderr, "passgraph dump: %s\n", err.msg);
    free(json);
    pg_graph_plan_free(plan);
    pg_pipeline_free(pl);
    pg_app_close(&app);
    return rc;
}
