/* fuzz_pipeline_json.c - libFuzzer target for the pipeline JSON loader (core/graph/pipeline_json*.c) and,
 * when a pipeline loads, the pure graph compiler (core/graph/graph_compile.c with every built-in pass
 * type's declare()) and the text/dot/svg reports of the plan.
 *
 * Each input is tried three ways:
 *   A. as a top-level pipeline, "$DIR/input.json" (DIR is a private temporary directory holding a
 *      copy of pipelines/fragments/ as fragments/ and tests/corpus/pipelines/good/fragments/ as
 *      good_fragments/, plus fixed_frag.json), without overrides;
 *   B. the same with --set overrides: when A loaded, one for each of the first parameters (an
 *      enum's last value, a bool flipped, an int's max, a float's min), else two fixed ones that
 *      the shipped pipelines declare (hdr_format=rgba32f, shading=blinn_phong);
 *   C. as an included fragment: written to $DIR/frag_input.json and included, after the fixed
 *      fragment fixed_frag.json, by a fixed top-level file, with --set fz_mode=b.
 * A pipeline that loads is compiled for two fixed sets of scene features. DIR also holds the GLSL of
 * every example under pipelines/examples/ (flat: their names differ), so the seeds made from the
 * examples (run.sh: their includes pointed at fragments/) reach the `shader` pass type's declare:
 * its options, the shader's compilation and the reflection checks.
 *
 * Invariants checked (abort = a finding): a result code in range; out set iff PG_OK; on failure
 * err.code equals the result and err.msg is a non-empty terminated string; a loaded pipeline is
 * within its limits and every pass has an options object; a compiled plan's order and output
 * indices are in range. ASan/UBSan/LSan catch the rest. */
#include "scene_vars.h"
#include "graph.h"
#include "graph_dump.h"
#include "pass_list.h"
#include "pipeline.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdint.h>

#include "fuzz_common.h"

#ifndef PG_SOURCE_DIR
#define PG_SOURCE_DIR "."
#endif

static pg_pass_registry g_reg;
static FILE *g_null;
static char g_top_path[512], g_frag_path[512], g_fixed_top_path[512];

/* Declares fz_mode (enum), fz_gain (float), a lights buffer, an HDR target and the passes that
 * fill them, so an input fragment can refer to fz_* names. */
static const char k_fixed_frag[] =
    "{\n"
    "  \"description\": \"fixed fragment of the fuzz target\",\n"
    "  \"parameters\": {\n"
    "    \"fz_mode\": {\"type\": \"enum\", \"values\": [\"a\", \"b\"], \"default\": \"a\"},\n"
    "    \"fz_gain\": {\"type\": \"float\", \"default\": 1.0, \"min\": 0, \"max\": 8}\n"
    "  },\n"
    "  \"resources\": [\n"
    "    {\"name\": \"fz_lights\", \"type\": \"buffer\", \"stride\": 32, \"count\": [\"lights\"],\n"
    "     \"lifetime\": \"persistent\"},\n"
    "    {\"name\": \"fz_hdr\", \"type\": \"image\", \"format\": \"rgba16f\"},\n"
    "    {\"name\": \"fz_depth\", \"type\": \"image\", \"format\": \"d32f\", \"when\": \"$fz_mode == b\"}\n"
    "  ],\n"
    "  \"passes\": [\n"
    "    {\"name\": \"fz_animate\", \"type\": \"light_animate\", \"writes\": [\"fz_lights\"],\n"
    "     \"side_effects\": true},\n"
    "    {\"name\": \"fz_shade\", \"type\": \"forward_naive\", \"reads\": [\"fz_lights\"],\n"
    "     \"writes\": [\"fz_hdr\", \"fz_depth\"], \"when\": \"$fz_mode == b\"}\n"
    "  ]\n"
    "}\n";

static const char k_fixed_top[] =
    "{\n"
    "  \"name\": \"fuzz_top\",\n"
    "  \"include\": [\"fixed_frag.json\", \"frag_input.json\"],\n"
    "  \"resources\": [{\"name\": \"fz_ldr\", \"type\": \"image\", \"format\": \"rgba8\"}],\n"
    "  \"passes\": [{\"name\": \"fz_display\", \"type\": \"display_tonemap\", \"reads\": [\"fz_hdr\"],\n"
    "              \"writes\": [\"fz_ldr\"], \"options\": {\"exposure\": \"$fz_gain\"}}],\n"
    "  \"output\": \"fz_ldr\",\n"
    "  \"hdr_output\": \"fz_hdr\"\n"
    "}\n";

static int keep_json(const char *name) { return fuzz_ends_with(name, ".json"); }

static int keep_glsl(const char *name)
{
    return fuzz_ends_with(name, ".comp") || fuzz_ends_with(name, ".frag") || fuzz_ends_with(name, ".glsl");
}

/* the examples' shaders, flat into dir */
static void copy_example_shaders(const char *dir)
{
    DIR *d = opendir(PG_SOURCE_DIR "/pipelines/examples");
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.') continue;
        char src[1024];
        snprintf(src, sizeof src, "%s/pipelines/examples/%s", PG_SOURCE_DIR, e->d_name);
        fuzz_copy_dir(src, dir, keep_glsl);
    }
    closedir(d);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *dir = fuzz_dir("pipeline");
    char sub[600];
    snprintf(sub, sizeof sub, "%s/fragments", dir);
    mkdir(sub, 0700);
    fuzz_copy_dir(PG_SOURCE_DIR "/pipelines/fragments", sub, keep_json);
    snprintf(sub, sizeof sub, "%s/good_fragments", dir);
    mkdir(sub, 0700);
    fuzz_copy_dir(PG_SOURCE_DIR "/tests/corpus/pipelines/good/fragments", sub, keep_json);
    copy_example_shaders(dir);
    snprintf(sub, sizeof sub, "%s/fixed_frag.json", dir);
    fuzz_write(sub, k_fixed_frag, strlen(k_fixed_frag));
    snprintf(g_top_path, sizeof g_top_path, "%s/input.json", dir);
    snprintf(g_frag_path, sizeof g_frag_path, "%s/frag_input.json", dir);
    snprintf(g_fixed_top_path, sizeof g_fixed_top_path, "%s/fixed_top.json", dir);
    pg_register_builtin_passes(&g_reg);
    g_null = fopen("/dev/null", "w");
    if (!g_null) fuzz_die("cannot open /dev/null");
    return 0;
}

static void check_error(pg_result r, const pg_error *err, const char *what)
{
    if ((int)r < 0 || r >= PG_ERR_COUNT) fuzz_die("%s: result %d out of range", what, (int)r);
    if (r == PG_OK) return;
    if (!memchr(err->msg, 0, sizeof err->msg)) fuzz_die("%s: message not terminated", what);
    if (err->code != r)
        fuzz_die("%s: returned %s but err.code is %s: %s", what, pg_result_name(r),
                 pg_result_name(err->code), err->msg);
    if (!err->msg[0]) fuzz_die("%s: %s with an empty message", what, pg_result_name(r));
}

static void check_pipeline(const pg_pipeline *p)
{
    if (p->n_passes > PG_MAX_PASSES || p->n_resources > PG_MAX_RESOURCES ||
        p->n_params > PG_MAX_PARAMS || p->n_omitted > PG_MAX_PASSES + PG_MAX_RESOURCES)
        fuzz_die("pipeline counts out of range: %u passes, %u resources, %u params, %u omitted",
                 p->n_passes, p->n_resources, p->n_params, p->n_omitted);
    if (!p->output[0] || !pg_pipeline_find_resource(p, p->output))
        fuzz_die("loaded pipeline without a valid output '%s'", p->output);
    for (uint32_t i = 0; i < p->n_passes; i++) {
        const pg_pass_desc *d = &p->passes[i];
        if (!cJSON_IsObject(d->options)) fuzz_die("pass %u without an options object", i);
        if (d->n_reads > PG_MAX_SLOTS || d->n_writes > PG_MAX_SLOTS || d->n_after > PG_MAX_AFTER)
            fuzz_die("pass %u slot counts out of range", i);
        for (uint32_t k = 0; k < d->n_reads; k++)
            if (!pg_pipeline_find_resource(p, d->reads[k]))
                fuzz_die("pass '%s' reads unknown '%s'", d->name, d->reads[k]);
        for (uint32_t k = 0; k < d->n_writes; k++)
            if (!pg_pipeline_find_resource(p, d->writes[k]))
                fuzz_die("pass '%s' writes unknown '%s'", d->name, d->writes[k]);
    }
}

static void compile_one(const pg_pipeline *p, pg_scene_features feat, uint32_t lights, uint32_t w, uint32_t h,
                        bool no_alias)
{
    pg_compile_desc cd = {.pipeline = p, .registry = &g_reg,
                          .output_width = w, .output_height = h, .disable_aliasing = no_alias};
    pg_scene_vars_set(&cd.vars, &feat, lights, NULL);
    pg_graph_plan *plan = NULL;
    pg_error err = {0};
    pg_result r = pg_graph_compile(&cd, &plan, &err);
    check_error(r, &err, "pg_graph_compile");
    if ((r == PG_OK) != (plan != NULL)) fuzz_die("compile: result %s, plan %p", pg_result_name(r), (void *)plan);
    if (plan) {
        if (plan->n_passes != p->n_passes || plan->n_order > plan->n_passes ||
            plan->n_resources != p->n_resources || plan->n_blocks > PG_MAX_RESOURCES ||
            plan->n_explain > PG_MAX_EXPLAIN)
            fuzz_die("plan counts out of range");
        for (uint32_t i = 0; i < plan->n_order; i++)
            if (plan->order[i] < 0 || (uint32_t)plan->order[i] >= plan->n_passes)
                fuzz_die("plan order[%u] = %d", i, plan->order[i]);
        if (plan->output < 0 || (uint32_t)plan->output >= plan->n_resources)
            fuzz_die("plan output %d", plan->output);
        pg_graph_plan_print(plan, p, g_null);
        pg_dump_dot(plan, p, g_null);
        pg_dump_timeline_svg(plan, p, g_null);
    }
    pg_graph_plan_free(plan);
}

/* Loads, checks, compiles, frees. Returns the pipeline (caller frees) when keep is set. */
static pg_pipeline *load_one(const char *text, const char *vpath, const pg_param_override *ov,
                             uint32_t n_ov, bool keep)
{
    pg_pipeline *p = (pg_pipeline *)&g_reg; /* any non-NULL value: must be reset */
    pg_error err = {0};
    pg_result r = pg_pipeline_load_string(text, vpath, ov, n_ov, &p, &err);
    check_error(r, &err, "pg_pipeline_load_string");
    if ((r == PG_OK) != (p != NULL)) fuzz_die("load: result %s, out %p", pg_result_name(r), (void *)p);
    if (!p) return NULL;
    check_pipeline(p);
    pg_scene_features rich = {.has_textures = true, .has_normal_maps = true, .has_alpha_mask = true};
    pg_scene_features bare = {0};
    compile_one(p, rich, 1000, 64, 36, false);
    compile_one(p, bare, 0, 7, 3, true);
    if (keep) return p;
    pg_pipeline_free(p);
    return NULL;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = 0;

    /* A */
    pg_pipeline *p = load_one(text, g_top_path, NULL, 0, true);

    /* B */
    char values[3][PG_NAME_MAX + 32];
    pg_param_override ov[3];
    uint32_t n_ov = 0;
    if (p) {
        for (uint32_t i = 0; i < p->n_params && n_ov < 3; i++) {
            const pg_param *prm = &p->params[i];
            char *v = values[n_ov];
            switch (prm->type) {
            case PG_PARAM_ENUM: snprintf(v, sizeof values[0], "%s", prm->values[prm->n_values - 1]); break;
            case PG_PARAM_BOOL: snprintf(v, sizeof values[0], "%s", prm->boolean ? "false" : "true"); break;
            case PG_PARAM_INT:
                snprintf(v, sizeof values[0], "%.0f", isinf(prm->max) ? prm->number + 1 : prm->max);
                break;
            case PG_PARAM_FLOAT:
                snprintf(v, sizeof values[0], "%.17g", isinf(prm->min) ? prm->number * 0.5 : prm->min);
                break;
            }
            ov[n_ov].key = prm->name;
            ov[n_ov].value = v;
            n_ov++;
        }
        if (n_ov) pg_pipeline_free(load_one(text, g_top_path, ov, n_ov, false));
        pg_pipeline_free(p);
    } else {
        static const pg_param_override fixed[] = {{"hdr_format", "rgba32f"}, {"shading", "blinn_phong"}};
        load_one(text, g_top_path, fixed, 2, false);
    }

    /* C */
    fuzz_write(g_frag_path, data, strlen(text));
    static const pg_param_override frag_ov[] = {{"fz_mode", "b"}};
    load_one(k_fixed_top, g_fixed_top_path, frag_ov, 1, false);

    free(text);
    return 0;
}
