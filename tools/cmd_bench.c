/* cmd_bench.c - `passgraph bench`: error against run time for every pipeline, swept over light
 * counts, output sizes and pipeline parameters.
 *
 * For each scene x size x light count x pipeline x variant it renders --warmup + --frames timed
 * frames (frame k at --time + k * --time-step: the lights move as in an animation, reproducibly)
 * and then one frame at exactly --time with read-back, whose images are compared with the
 * reference pipeline's frame at the same time (pg_image_error_compute; the reference takes the
 * overrides sides.h describes, so one block may render it once per swept value it declares).
 * Results go to DIR/results.csv, DIR/results.json and three SVG charts written by core/svg_plot.c.
 * SIGINT stops after the current frame and writes what was measured (exit 130). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <dirent.h>
#include <time.h>
#include <unistd.h>

#include <cjson/cJSON.h>

#include "app.h"
#include "bench_stats.h"
#include "commands.h"
#include "image_compare.h"
#include "image_util.h"
#include "shader.h"
#include "sides.h"
#include "svg_plot.h"

static const char *const bench_help =
    "usage: passgraph bench [--pipelines LIST|all] [--lights N,N,...] [--size WxH,WxH,...] --out DIR [options]\n"
    "Renders every pipeline (x every --sweep variant) at every light count and output size and records,\n"
    "per configuration: GPU ms per pass and in total from timestamps (median, mean, min, max, p95 over\n"
    "--frames timed frames after --warmup), CPU time (cpu_ms: record + submit, host; wait_ms: host\n"
    "time blocked on fences; --frames-in-flight, default 2), transient memory\n"
    "before/after aliasing (the plan's numbers and the device memory allocated), light overflow of\n"
    "clustered pipelines, and the image error against the reference pipeline at --time (RMSE, PSNR,\n"
    "max abs; linear HDR and 8-bit display). Writes DIR/results.csv, DIR/results.json and the charts\n"
    "DIR/gpu_time_vs_lights.svg, DIR/passes_stacked.svg, DIR/error_vs_time.svg (docs/performance.md\n"
    "documents every column). Timed frame k (warm-up frames included) renders at --time + k *\n"
    "--time-step, so the lights move; the error frame is rendered at exactly --time, after them.\n"
    "Progress and ETA go to stderr; Ctrl-C finishes the current frame, writes what was measured and\n"
    "exits 130. Exit 0 when every configuration ran, 1 when one failed (its rows say why in 'status'\n"
    "and 'message'; the others still run) or validation reported a message, 2 on bad options.\n\n"
    "What each side takes: --set KEY=VALUE goes to every pipeline that declares KEY and to the reference\n"
    "when it declares KEY; --pipeline-set KEY=VALUE to the pipelines only, --reference-set KEY=VALUE to\n"
    "the reference only (each wins over --set on its side); a --sweep value goes to the pipeline and,\n"
    "when the reference declares KEY, to the reference too, so --sweep shading=lambert,blinn_phong\n"
    "compares each light model with the same one (--reference-set shading=lambert pins it instead);\n"
    "--debug-view is the pipelines' only. The 'bench: sides:' lines at the start, the 'sets' and\n"
    "'reference_sets' columns and results.json's meta say what each side used.\n\n";

/* a second string: C11 compilers need only support 4095 characters in one literal */
static const char *const bench_help_options =
    "bench options:\n"
    "  --pipelines LIST|all pipeline JSON files, comma-separated; a bare name (forward_plus) means\n"
    "                       pipelines/NAME.json of the data folder; 'all' (default): every top-level\n"
    "                       JSON file in the data folder's pipelines/ (also --pipeline FILE)\n"
    "  --lights N,N,...     light counts (default 100,1000,5000); sorted, duplicates dropped\n"
    "  --size WxH,WxH,...   output sizes (default 640x360)\n"
    "  --scene FILE,...     one or more scenes (default: the built-in atrium); --scenario applies to each\n"
    "  --warmup N           untimed frames before the timed ones (default 2)\n"
    "  --frames-in-flight N 1 or 2 (default 2): with 2 the host waits only for the frame two back\n"
    "  --frames N           timed frames per configuration (default 10)\n"
    "  --time T             the error frame's animation time, and the first timed frame's (default 0)\n"
    "  --time-step S        animation time added per frame (default 0.0166667 = 1/60 s; 0: every frame\n"
    "                       at --time)\n"
    "  --sweep KEY=V1,V2,.. run each pipeline that declares parameter KEY once per value (repeatable;\n"
    "                       several sweeps give every combination); the 'variant' column says which.\n"
    "                       The reference takes each value too when it declares KEY\n"
    "  --set KEY=VALUE      applied to every pipeline that declares KEY, and to the reference if it\n"
    "                       declares KEY (a key none of them declares is refused)\n"
    "  --pipeline-set KEY=VALUE  applied to every pipeline that declares KEY, never to the reference\n"
    "  --reference-set KEY=VALUE applied to the reference only; wins over --set and --sweep there\n"
    "  --reference FILE     the exact pipeline errors are measured against (default\n"
    "                       pipelines/reference.json: a compute pass shading every pixel with every light)\n"
    "  --reference-max-lights N  above N lights the reference is not rendered (error columns empty,\n"
    "                       'error_note' says why) and the reference pipeline's own rows are skipped.\n"
    "                       Default: 1000000 on a GPU; on a CPU device (lavapipe) what keeps a reference\n"
    "                       frame under 1.152e9 light x pixel evaluations (about 10 s there): 20000\n"
    "                       lights at 320x180, 5000 at 640x360, 555 at 1920x1080\n"
    "  --naive-max-lights N deprecated name of --reference-max-lights (prints a warning)\n"
    "  --out DIR            output folder (created if missing)\n"
    "  --quiet              no progress bar\n\n"
    "common options (--lights, --size, --pipeline, --frames as above):\n";

#define MAX_LIST 64
#define MAX_SWEEPS 8
#define MAX_SWEEP_VALUES 32
#define MAX_VARIANTS 1024
/* Reference frames on a CPU device (lavapipe) cost about 1e8 light x pixel evaluations a second
 * on two cores; without --reference-max-lights the reference is rendered up to this many per
 * frame (20,000 lights at 320x180, 5,000 at 640x360: about ten seconds a reference frame). */
#define CPU_REFERENCE_BUDGET (20000.0 * 320.0 * 180.0)
#define GPU_REFERENCE_MAX_LIGHTS 1000000u

static volatile sig_atomic_t g_interrupted;

static void on_sigint(int sig)
{
    (void)sig;
    g_interrupted = 1;
}

typedef struct sweep {
    const char *key;
    uint32_t n;
    const char *values[MAX_SWEEP_VALUES];
} sweep;

typedef struct variant {
    char label[256];                  /* "gbuffer=oct16;max_lights=256"; "" without sweeps */
    char sets_label[256];             /* its overrides besides the swept values (--set, --pipeline-set) */
    pg_ov_list ov;                    /* what the pipeline gets: --set, swept values, --pipeline-set */
    uint32_t ref;                     /* index into bench.refs: what the reference gets for this variant */
    bool ok;                          /* loads with these overrides */
    char msg[PG_ERROR_MSG_MAX];
    uint32_t series;                  /* global index: colour / marker in the charts */
} variant;

typedef struct pipe_entry {
    char path[PG_PATH_MAX];
    char name[PG_NAME_MAX];
    bool is_reference;
    bool loaded;
    char msg[PG_ERROR_MSG_MAX];
    uint32_t n_variants;
    variant *variants;
} pipe_entry;

typedef enum row_status { ROW_OK = 0, ROW_ERROR, ROW_SKIPPED, ROW_INTERRUPTED } row_status;
static const char *const status_names[] = {"ok", "error", "skipped", "interrupted"};

typedef struct pass_stat {
    char name[PG_NAME_MAX];
    pg_sample_stats st;
} pass_stat;

typedef struct bench_row {
    uint32_t scene, pipe, variant, lights, width, height;
    row_status status;
    char message[PG_ERROR_MSG_MAX];
    uint32_t frames;                  /* timed frames measured */
    pg_sample_stats gpu, cpu, wait;
    uint32_t n_passes;
    pass_stat passes[PG_MAX_PASSES];
    bool has_memory;
    uint64_t plan_unaliased, plan_aliased, dev_unaliased, dev_aliased;
    bool has_overflow;
    uint64_t ov_clusters, ov_dropped, ov_clusters_max;
    /* light lists of clustered pipelines: references stored, bytes of the list buffers, and how
     * often a "grow" buffer was enlarged over the row's frames (each such frame rendered again) */
    uint64_t light_refs, list_bytes;
    uint32_t grow_events;
    bool has_error;
    pg_image_error e;
    bool has_nonfinite;
    uint64_t nonfinite;
    char error_note[256];
} bench_row;

typedef struct reference {
    bool tried, ok;
    char msg[PG_ERROR_MSG_MAX];
    float *hdr;
    uint8_t *ldr;
    uint32_t w, h;
} reference;

typedef struct ref_variant {
    pg_ov_list ov;                    /* the reference's overrides */
    char label[256];                  /* "k=v;k=v" as in the results' reference_sets column */
    uint32_t last_use;                /* last (pipeline, variant) in run order that needs it */
} ref_variant;

typedef struct bench {
    pg_cli_common opt;
    /* lists */
    uint32_t n_lights, n_sizes, n_scenes, n_sweeps, n_pipes;
    uint32_t lights[MAX_LIST];
    uint32_t widths[MAX_LIST], heights[MAX_LIST];
    const char *scenes[MAX_LIST];
    char scene_names[MAX_LIST][PG_PATH_MAX];
    sweep sweeps[MAX_SWEEPS];
    pipe_entry *pipes;
    uint32_t n_series;
    char ref_path[PG_PATH_MAX];
    char ref_name[PG_NAME_MAX];
    pg_side_sets sides;               /* --set, --pipeline-set, --reference-set, the debug view */
    uint32_t n_refs;                  /* distinct reference override sets (one per swept value the
                                       * reference declares), each rendered once per block */
    ref_variant *refs;
    char ref_sweeps[256];             /* the swept keys the reference declares, ","-separated */
    bool has_ref_max_lights;          /* --reference-max-lights (or --naive-max-lights) given */
    uint32_t ref_max_lights;
    bool device_known, device_cpu;    /* VK_PHYSICAL_DEVICE_TYPE_CPU: the default limit is a budget */
    uint32_t warmup;
    uint32_t frames_in_flight;
    double time_step;
    const char *out_dir;
    /* results */
    bench_row *rows;
    uint32_t n_rows, cap_rows, n_failed;
    char device[256];
    uint32_t validation_messages;
    bool interrupted;
    /* progress */
    bool progress, tty;
    double total_work, done_work;
    double t_start, t_last_draw;
    uint32_t rows_total, rows_done;
} bench;

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* ---------------------------------------------------------------- options */

/* Splits s in place at sep; at most max parts. Returns the count, or -1 if there are too many. */
static int split_list(char *s, char sep, char **parts, int max)
{
    int n = 0;
    for (;;) {
        if (n >= max) return -1;
        parts[n++] = s;
        char *c = strchr(s, sep);
        if (!c) break;
        *c = 0;
        s = c + 1;
    }
    return n;
}

/* One list element through the common parser, so values are checked exactly like render's. */
static pg_result parse_one_common(const char *opt, char *value, pg_cli_common *scratch, pg_error *err)
{
    char *av[2] = {(char *)opt, value};
    int i = 0;
    bool used;
    return pg_cli_parse_common(scratch, 2, av, &i, &used, err);
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

static pg_result parse_lights(bench *B, char *v, pg_error *err)
{
    char *parts[MAX_LIST];
    int n = split_list(v, ',', parts, MAX_LIST);
    if (n < 0) return pg_fail(err, PG_ERR_INVALID_ARG, "--lights: at most %d values", MAX_LIST);
    uint32_t tmp[MAX_LIST];
    for (int i = 0; i < n; i++) {
        pg_cli_common c;
        pg_cli_defaults(&c);
        if (!parts[i][0]) return pg_fail(err, PG_ERR_INVALID_ARG, "--lights: empty value in the list");
        pg_result r = parse_one_common("--lights", parts[i], &c, err);
        if (r) return r;
        tmp[i] = c.lights;
    }
    qsort(tmp, (size_t)n, sizeof *tmp, cmp_u32);
    B->n_lights = 0;
    for (int i = 0; i < n; i++)
        if (!B->n_lights || B->lights[B->n_lights - 1] != tmp[i]) B->lights[B->n_lights++] = tmp[i];
    return PG_OK;
}

static pg_result parse_sizes(bench *B, char *v, pg_error *err)
{
    char *parts[MAX_LIST];
    int n = split_list(v, ',', parts, MAX_LIST);
    if (n < 0) return pg_fail(err, PG_ERR_INVALID_ARG, "--size: at most %d values", MAX_LIST);
    B->n_sizes = 0;
    for (int i = 0; i < n; i++) {
        pg_cli_common c;
        pg_cli_defaults(&c);
        if (!parts[i][0]) return pg_fail(err, PG_ERR_INVALID_ARG, "--size: empty value in the list");
        pg_result r = parse_one_common("--size", parts[i], &c, err);
        if (r) return r;
        bool dup = false;
        for (uint32_t k = 0; k < B->n_sizes; k++) dup |= B->widths[k] == c.width && B->heights[k] == c.height;
        if (dup) continue;
        B->widths[B->n_sizes] = c.width;
        B->heights[B->n_sizes] = c.height;
        B->n_sizes++;
    }
    return PG_OK;
}

static pg_result parse_sweep(bench *B, char *v, pg_error *err)
{
    if (B->n_sweeps >= MAX_SWEEPS) return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep: at most %d", MAX_SWEEPS);
    char *eq = strchr(v, '=');
    if (!eq || eq == v || !eq[1])
        return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: expected KEY=VALUE1,VALUE2,...", v);
    *eq = 0;
    sweep *s = &B->sweeps[B->n_sweeps];
    s->key = v;
    for (uint32_t k = 0; k < B->n_sweeps; k++)
        if (!strcmp(B->sweeps[k].key, v)) return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: key given twice", v);
    char *parts[MAX_SWEEP_VALUES];
    int n = split_list(eq + 1, ',', parts, MAX_SWEEP_VALUES);
    if (n < 0) return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: at most %d values", v, MAX_SWEEP_VALUES);
    s->n = 0;
    for (int i = 0; i < n; i++) {
        if (!parts[i][0]) return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: empty value in the list", v);
        for (uint32_t k = 0; k < s->n; k++)
            if (!strcmp(s->values[k], parts[i]))
                return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: value '%s' given twice", v, parts[i]);
        s->values[s->n++] = parts[i];
    }
    B->n_sweeps++;
    return PG_OK;
}

static pg_result parse_u32_opt(const char *opt, const char *v, uint32_t max, uint32_t *out, pg_error *err)
{
    if (!v || !*v) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: missing value", opt);
    if (*v < '0' || *v > '9')
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s: expected a whole number in [0, %u]", opt, v, max);
    errno = 0;
    char *end;
    unsigned long long u = strtoull(v, &end, 10);
    if (errno || *end || u > max)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s: expected a whole number in [0, %u]", opt, v, max);
    *out = (uint32_t)u;
    return PG_OK;
}

/* ---------------------------------------------------------------- pipelines and variants */

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

static bool is_file(const char *p)
{
    struct stat st;
    return !stat(p, &st) && S_ISREG(st.st_mode);
}

static void file_stem(const char *path, char *buf, size_t size)
{
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    pg_strlcpy(buf, b, size);
    char *dot = strrchr(buf, '.');
    if (dot && dot != buf) *dot = 0;
}

static pg_result add_pipe(bench *B, const char *path, pg_error *err)
{
    pipe_entry *p = realloc(B->pipes, (B->n_pipes + 1) * sizeof *p);
    if (!p) return pg_fail(err, PG_ERR_OOM, "out of memory");
    B->pipes = p;
    pipe_entry *e = &p[B->n_pipes++];
    memset(e, 0, sizeof *e);
    pg_strlcpy(e->path, path, sizeof e->path);
    file_stem(path, e->name, sizeof e->name);
    return PG_OK;
}

/* Every top-level *.json of the data folder's pipelines/, sorted by name. */
static pg_result list_all_pipelines(bench *B, pg_error *err)
{
    char dir[PG_PATH_MAX];
    pg_data_path(dir, sizeof dir, "pipelines");
    DIR *d = opendir(dir);
    if (!d) return pg_fail(err, PG_ERR_IO, "--pipelines all: cannot list %s: %s", dir, strerror(errno));
    char *names[256];
    uint32_t n = 0;
    pg_result r = PG_OK;
    struct dirent *de;
    while ((de = readdir(d))) {
        size_t l = strlen(de->d_name);
        if (l < 6 || strcmp(de->d_name + l - 5, ".json") || de->d_name[0] == '.') continue;
        char full[PG_PATH_MAX];
        snprintf(full, sizeof full, "%s/%s", dir, de->d_name);
        if (!is_file(full)) continue;
        if (n >= 256) {
            r = pg_fail(err, PG_ERR_LIMIT, "--pipelines all: more than 256 files in %s", dir);
            break;
        }
        names[n] = malloc(strlen(full) + 1);
        if (!names[n]) {
            r = pg_fail(err, PG_ERR_OOM, "out of memory");
            break;
        }
        memcpy(names[n], full, strlen(full) + 1);
        n++;
    }
    closedir(d);
    if (!r) {
        qsort(names, n, sizeof *names, cmp_str);
        if (!n) r = pg_fail(err, PG_ERR_IO, "--pipelines all: no .json file in %s", dir);
    }
    for (uint32_t i = 0; i < n; i++) {
        if (!r) r = add_pipe(B, names[i], err);
        free(names[i]);
    }
    return r;
}

static pg_result resolve_pipelines(bench *B, char *list, pg_error *err)
{
    if (!list || !strcmp(list, "all")) return list_all_pipelines(B, err);
    char *parts[MAX_LIST];
    int n = split_list(list, ',', parts, MAX_LIST);
    if (n < 0) return pg_fail(err, PG_ERR_INVALID_ARG, "--pipelines: at most %d entries", MAX_LIST);
    for (int i = 0; i < n; i++) {
        const char *t = parts[i];
        if (!t[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "--pipelines: empty entry in the list");
        if (!strcmp(t, "all")) return pg_fail(err, PG_ERR_INVALID_ARG, "--pipelines: 'all' cannot be combined with names");
        char path[PG_PATH_MAX];
        pg_strlcpy(path, t, sizeof path);
        if (!is_file(t) && !strchr(t, '/')) {
            char rel[PG_PATH_MAX], cand[PG_PATH_MAX];
            size_t l = strlen(t);
            snprintf(rel, sizeof rel, "pipelines/%s%s", t, l > 5 && !strcmp(t + l - 5, ".json") ? "" : ".json");
            pg_data_path(cand, sizeof cand, rel);
            if (is_file(cand)) pg_strlcpy(path, cand, sizeof path);
        }
        pg_result r = add_pipe(B, path, err);
        if (r) return r;
    }
    return PG_OK;
}

static bool same_file(const char *a, const char *b)
{
    char ra[PATH_MAX], rb[PATH_MAX];
    if (!realpath(a, ra) || !realpath(b, rb)) return !strcmp(a, b);
    return !strcmp(ra, rb);
}

static bool same_ov(const pg_ov_list *a, const pg_ov_list *b)
{
    if (a->n != b->n) return false;
    for (uint32_t k = 0; k < a->n; k++)
        if (strcmp(a->ov[k].key, b->ov[k].key) || strcmp(a->ov[k].value, b->ov[k].value)) return false;
    return true;
}

/* The index of the reference set ov in B->refs, added if new (lists are built in one key order). */
static uint32_t find_or_add_ref(bench *B, const pg_ov_list *ov, pg_error *err, bool *oom)
{
    for (uint32_t k = 0; k < B->n_refs; k++)
        if (same_ov(&B->refs[k].ov, ov)) return k;
    ref_variant *r = realloc(B->refs, (B->n_refs + 1) * sizeof *r);
    if (!r) {
        *oom = true;
        pg_fail(err, PG_ERR_OOM, "out of memory");
        return 0;
    }
    B->refs = r;
    ref_variant *e = &r[B->n_refs];
    memset(e, 0, sizeof *e);
    e->ov = *ov;
    pg_ov_list_format(ov, e->label, sizeof e->label);
    return B->n_refs++;
}

/* Loads every pipeline once (names, declared parameters), checks that each --set / --pipeline-set /
 * --sweep key is declared somewhere and each --reference-set key by the reference, builds the
 * variants with what each side gets (sides.h) and checks that each loads. Bad keys, and values
 * the reference refuses, are option errors (exit 2, returned as PG_ERR_INVALID_ARG); a pipeline
 * that does not load is recorded in its rows, a reference that does not load in every row's note. */
static pg_result plan_variants(bench *B, pg_error *err)
{
    const pg_side_sets *ss = &B->sides;
    bool set_used[PG_SIDES_MAX_OV] = {0}, pset_used[PG_SIDES_MAX_OV] = {0}, sweep_used[MAX_SWEEPS] = {0};
    bool any_loaded = false;
    pg_result r = PG_OK;
    for (uint32_t k = 0; k < B->n_sweeps; k++) {
        if (pg_ov_list_get(&ss->set, B->sweeps[k].key))
            return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: the same key is given with --set", B->sweeps[k].key);
        for (uint32_t s = 0; s < ss->pipeline.n; s++)
            if (!strcmp(ss->pipeline.ov[s].key, B->sweeps[k].key))
                return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: the same key is given with %s", B->sweeps[k].key,
                               ss->pipeline.from[s]);
    }
    /* the reference: its declared parameters decide which --set and swept values it takes */
    pg_pipeline *ref = NULL;
    pg_error re = {0};
    if (!pg_pipeline_load(B->ref_path, NULL, 0, &ref, &re)) {
        pg_strlcpy(B->ref_name, ref->name, sizeof B->ref_name);
        if ((r = pg_sides_check_keys(&ss->reference, ref, "reference", err))) goto done;
        for (uint32_t s = 0; s < ss->set.n; s++) set_used[s] |= pg_pipeline_find_param(ref, ss->set.ov[s].key) != NULL;
        size_t l = 0;
        for (uint32_t k = 0; k < B->n_sweeps; k++)
            if (pg_pipeline_find_param(ref, B->sweeps[k].key) && !pg_ov_list_get(&ss->reference, B->sweeps[k].key)) {
                l += (size_t)snprintf(B->ref_sweeps + l, l < sizeof B->ref_sweeps ? sizeof B->ref_sweeps - l : 0, "%s%s",
                                      l ? "," : "", B->sweeps[k].key);
                if (l >= sizeof B->ref_sweeps) l = sizeof B->ref_sweeps - 1;
            }
    } else {
        ref = NULL;
        file_stem(B->ref_path, B->ref_name, sizeof B->ref_name);
    }
    uint32_t series = 0;
    for (uint32_t pi = 0; pi < B->n_pipes; pi++) {
        pipe_entry *pe = &B->pipes[pi];
        pe->is_reference = same_file(pe->path, B->ref_path);
        pg_pipeline *pl = NULL;
        pg_error le = {0};
        uint32_t n_var = 1;
        bool declares[MAX_SWEEPS] = {0};
        pg_ov_list fixed; /* this pipeline's overrides without the swept values */
        memset(&fixed, 0, sizeof fixed);
        if (pg_pipeline_load(pe->path, NULL, 0, &pl, &le)) {
            pg_strlcpy(pe->msg, le.msg, sizeof pe->msg);
        } else {
            pe->loaded = any_loaded = true;
            pg_strlcpy(pe->name, pl->name, sizeof pe->name);
            for (uint32_t s = 0; s < ss->set.n; s++) set_used[s] |= pg_pipeline_find_param(pl, ss->set.ov[s].key) != NULL;
            for (uint32_t s = 0; s < ss->pipeline.n; s++)
                pset_used[s] |= pg_pipeline_find_param(pl, ss->pipeline.ov[s].key) != NULL;
            pg_sides_pipeline(ss, pl, NULL, 0, &fixed);
            for (uint32_t k = 0; k < B->n_sweeps; k++)
                if (pg_pipeline_find_param(pl, B->sweeps[k].key)) {
                    declares[k] = sweep_used[k] = true;
                    n_var *= B->sweeps[k].n;
                    if (n_var > MAX_VARIANTS) {
                        pg_pipeline_free(pl);
                        r = pg_fail(err, PG_ERR_INVALID_ARG, "--sweep: more than %d variants of %s", MAX_VARIANTS, pe->path);
                        goto done;
                    }
                }
        }
        pe->variants = calloc(n_var, sizeof *pe->variants);
        if (!pe->variants) {
            pg_pipeline_free(pl);
            r = pg_fail(err, PG_ERR_OOM, "out of memory");
            goto done;
        }
        pe->n_variants = n_var;
        for (uint32_t v = 0; v < n_var; v++) {
            variant *va = &pe->variants[v];
            va->series = series++;
            pg_ov_list_format(&fixed, va->sets_label, sizeof va->sets_label);
            pg_param_override swept[MAX_SWEEPS];
            uint32_t n_swept = 0, rest = v, ll = 0;
            for (uint32_t k = 0; k < B->n_sweeps; k++) { /* the last declared sweep varies fastest */
                if (!declares[k]) continue;
                uint32_t div = 1;
                for (uint32_t k2 = k + 1; k2 < B->n_sweeps; k2++)
                    if (declares[k2]) div *= B->sweeps[k2].n;
                const char *val = B->sweeps[k].values[(rest / div) % B->sweeps[k].n];
                swept[n_swept++] = (pg_param_override){B->sweeps[k].key, val};
                ll += (uint32_t)snprintf(va->label + ll, ll < sizeof va->label ? sizeof va->label - ll : 0, "%s%s=%s",
                                         ll ? ";" : "", B->sweeps[k].key, val);
                if (ll >= sizeof va->label) ll = sizeof va->label - 1;
            }
            if (pl) pg_sides_pipeline(ss, pl, swept, n_swept, &va->ov); /* else it is never run */
            pg_ov_list rov;
            pg_sides_reference(ss, ref, swept, n_swept, &rov);
            bool oom = false;
            va->ref = find_or_add_ref(B, &rov, err, &oom);
            if (oom) {
                pg_pipeline_free(pl);
                r = PG_ERR_OOM;
                goto done;
            }
            if (!pe->loaded) {
                pg_strlcpy(va->msg, pe->msg, sizeof va->msg);
                continue;
            }
            pg_error ve = {0};
            pg_pipeline *vp = NULL;
            if (pg_pipeline_load(pe->path, va->ov.ov, va->ov.n, &vp, &ve)) {
                pg_strlcpy(va->msg, ve.msg, sizeof va->msg);
            } else {
                va->ok = true;
                pg_pipeline_free(vp);
            }
        }
        pg_pipeline_free(pl);
    }
    B->n_series = series;
    if (any_loaded) {
        for (uint32_t s = 0; s < ss->set.n; s++)
            if (!set_used[s]) {
                r = pg_fail(err, PG_ERR_INVALID_ARG, "--set %s=%s: no selected pipeline (nor the reference) declares '%s'",
                            ss->set.ov[s].key, ss->set.ov[s].value, ss->set.ov[s].key);
                goto done;
            }
        for (uint32_t s = 0; s < ss->pipeline.n; s++)
            if (!pset_used[s]) {
                r = pg_fail(err, PG_ERR_INVALID_ARG, "%s %s=%s: no selected pipeline declares '%s'", ss->pipeline.from[s],
                            ss->pipeline.ov[s].key, ss->pipeline.ov[s].value, ss->pipeline.ov[s].key);
                goto done;
            }
        for (uint32_t k = 0; k < B->n_sweeps; k++)
            if (!sweep_used[k]) {
                r = pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: no selected pipeline declares '%s'", B->sweeps[k].key,
                            B->sweeps[k].key);
                goto done;
            }
    }
    /* a value the reference refuses is a bad option, not a failure of every row */
    for (uint32_t k = 0; ref && k < B->n_refs; k++)
        if (pg_sides_check_values(B->ref_path, &B->refs[k].ov, "reference", err) == PG_ERR_INVALID_ARG) {
            r = PG_ERR_INVALID_ARG;
            goto done;
        }
    /* the last (pipeline, variant) of a block that needs each reference: it is freed after that row */
    for (uint32_t pi = 0, idx = 0; pi < B->n_pipes; pi++)
        for (uint32_t v = 0; v < B->pipes[pi].n_variants; v++, idx++) B->refs[B->pipes[pi].variants[v].ref].last_use = idx;
done:
    pg_pipeline_free(ref);
    return r;
}

/* The most lights the reference is rendered with at w x h: --reference-max-lights; else on a GPU
 * 1,000,000 and on a CPU device (lavapipe) CPU_REFERENCE_BUDGET / pixels. */
static uint32_t ref_limit(const bench *B, uint32_t w, uint32_t h)
{
    if (B->has_ref_max_lights) return B->ref_max_lights;
    if (!B->device_cpu) return GPU_REFERENCE_MAX_LIGHTS;
    double n = floor(CPU_REFERENCE_BUDGET / ((double)w * h));
    return n >= GPU_REFERENCE_MAX_LIGHTS ? GPU_REFERENCE_MAX_LIGHTS : (uint32_t)n;
}

/* Why a row above the limit has no error: the limit, and where it came from (brief: one line that
 * fits a chart panel). */
static void ref_skip_note(const bench *B, uint32_t w, uint32_t h, bool brief, char *buf, size_t size)
{
    uint32_t n = ref_limit(B, w, h);
    if (B->has_ref_max_lights)
        snprintf(buf, size, "%s skipped above %u lights (--reference-max-lights %u)", B->ref_name, n, n);
    else if (B->device_cpu && brief)
        snprintf(buf, size, "%s skipped above %u lights on a CPU device: set --reference-max-lights", B->ref_name, n);
    else if (B->device_cpu)
        snprintf(buf, size,
                 "%s skipped above %u lights on a CPU device (%.48s) at %ux%u, the default budget of %.4g light x "
                 "pixel evaluations per reference frame (about 10 s on lavapipe): set --reference-max-lights",
                 B->ref_name, n, B->device, w, h, CPU_REFERENCE_BUDGET);
    else
        snprintf(buf, size, "%s skipped above %u lights (the default on a GPU): set --reference-max-lights", B->ref_name, n);
}

/* ---------------------------------------------------------------- progress */

static void fmt_dur(double s, char *buf, size_t size)
{
    if (!isfinite(s) || s < 0) {
        snprintf(buf, size, "--:--");
        return;
    }
    long t = (long)(s + 0.5);
    if (t >= 3600) snprintf(buf, size, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
    else snprintf(buf, size, "%ld:%02ld", t / 60, t % 60);
}

/* Work units: pixels x (lights + 64) per frame, a rough cost model (per-pixel work plus per-light
 * work) that keeps the ETA sane when configurations differ by orders of magnitude. */
static double frame_work(uint32_t w, uint32_t h, uint32_t lights)
{
    return (double)w * h * ((double)lights + 64.0) * 1e-6;
}

static void progress_draw(bench *B, const char *what, bool row_done)
{
    if (!B->progress) return;
    double t = now_s();
    if (B->tty && !row_done && t - B->t_last_draw < 0.1) return;
    B->t_last_draw = t;
    double el = t - B->t_start;
    double frac = B->total_work > 0 ? B->done_work / B->total_work : 0;
    if (frac > 1) frac = 1;
    double eta = frac > 0.002 ? el * (1 - frac) / frac : NAN;
    char se[32], sr[32];
    fmt_dur(el, se, sizeof se);
    fmt_dur(eta, sr, sizeof sr);
    if (B->tty) {
        char shown[52]; /* keep the line short: a wrapped line defeats the carriage return */
        if (strlen(what) >= sizeof shown) snprintf(shown, sizeof shown, "%.*s...", (int)sizeof shown - 4, what);
        else snprintf(shown, sizeof shown, "%s", what);
        what = shown;
        char bar[25];
        int fill = (int)(frac * 24 + 0.5);
        for (int i = 0; i < 24; i++) bar[i] = i < fill ? '#' : '.';
        bar[24] = 0;
        fprintf(stderr, "\r\033[K[%s] %3.0f%% %u/%u  %s  elapsed %s  ETA %s", bar, 100 * frac, B->rows_done,
                B->rows_total, what, se, sr);
    } else if (row_done) {
        fprintf(stderr, "bench: [%u/%u] %3.0f%% %s (elapsed %s, ETA %s)\n", B->rows_done, B->rows_total, 100 * frac,
                what, se, sr);
    }
    fflush(stderr);
}

static void progress_clear(bench *B)
{
    if (B->progress && B->tty) fprintf(stderr, "\r\033[K");
}

/* ---------------------------------------------------------------- running */

static bench_row *new_row(bench *B, pg_error *err)
{
    if (B->n_rows == B->cap_rows) {
        uint32_t cap = B->cap_rows ? B->cap_rows * 2 : 16;
        bench_row *r = realloc(B->rows, cap * sizeof *r);
        if (!r) {
            pg_fail(err, PG_ERR_OOM, "out of memory");
            return NULL;
        }
        B->rows = r;
        B->cap_rows = cap;
    }
    bench_row *r = &B->rows[B->n_rows++];
    memset(r, 0, sizeof *r);
    r->gpu.median = r->gpu.mean = r->gpu.min = r->gpu.max = r->gpu.p95 = NAN;
    r->cpu = r->wait = r->gpu;
    return r;
}

static void reference_free(reference *ref)
{
    free(ref->hdr);
    free(ref->ldr);
    memset(ref, 0, sizeof *ref);
}

/* The 8-bit display and float HDR images of the session's last read-back frame (malloc'd copies). */
static pg_result grab_images(const pg_session *s, float **hdr, uint8_t **ldr, uint32_t *w, uint32_t *h, pg_error *err)
{
    const pg_pipeline *pl = s->pipeline;
    uint32_t lw, lh, hw, hh;
    pg_format lf, hf;
    const uint8_t *lp = pg_runtime_output(s->runtime, 0, &lw, &lh, &lf);
    if (!lp || (lf != PG_FMT_RGBA8_UNORM && lf != PG_FMT_RGBA8_SRGB))
        return pg_fail(err, PG_ERR_FORMAT, "output '%s' is not an 8-bit RGBA image", pl->output);
    const void *hp = pg_runtime_output(s->runtime, 1, &hw, &hh, &hf);
    if (!hp) return pg_fail(err, PG_ERR_NO_OUTPUT, "pipeline '%s' declares no hdr_output", pl->name);
    pg_result r = pg_image_sizes_match("hdr_output vs output", hw, hh, lw, lh, err);
    if (r) return r;
    *hdr = malloc((size_t)hw * hh * 4 * sizeof(float));
    *ldr = malloc((size_t)lw * lh * 4);
    if (!*hdr || !*ldr) {
        free(*hdr);
        free(*ldr);
        *hdr = NULL;
        *ldr = NULL;
        return pg_fail(err, PG_ERR_OOM, "out of memory");
    }
    memcpy(*ldr, lp, (size_t)lw * lh * 4);
    r = pg_hdr_to_float(hp, hf, hw, hh, *hdr, err);
    if (r) {
        free(*hdr);
        free(*ldr);
        *hdr = NULL;
        *ldr = NULL;
        return r;
    }
    *w = lw;
    *h = lh;
    return PG_OK;
}

static void reference_render(bench *B, pg_app *app, const pg_frame_info *fi0, const ref_variant *rv, reference *ref)
{
    ref->tried = true;
    pg_session_desc desc = {
        .pipeline_path = B->ref_path,
        .overrides = rv->ov.ov,
        .n_overrides = rv->ov.n,
        .registry = &app->registry,
        .disable_aliasing = B->opt.no_aliasing,
        .immediate = B->opt.immediate,
        .async_off = B->opt.async_compute == PG_ASYNC_OFF,
        .settings = app->opt.settings, /* OCIO config / display / view */
        .n_settings = app->opt.n_settings,
    };
    pg_session *s = NULL;
    pg_error e = {0};
    pg_frame_stats st;
    pg_frame_info fi = *fi0;
    fi.time = B->opt.time;
    if (!pg_session_create(app->gpu, app->scene_gpu, &desc, &s, &e) && !pg_session_render(s, &fi, true, &st, &e) &&
        !grab_images(s, &ref->hdr, &ref->ldr, &ref->w, &ref->h, &e)) {
        ref->ok = true;
    } else {
        snprintf(ref->msg, sizeof ref->msg, "%s", e.msg);
    }
    pg_session_destroy(s);
}

/* Stores the GPU times of runtime frames first..last that are known and not stored yet. */
static void fetch_gpu(const bench *B, const pg_runtime *rt, uint64_t first, uint64_t last, uint32_t n_passes,
                      double *samples)
{
    for (uint64_t fr = first; fr <= last && fr - first < B->opt.frames; fr++) {
        const uint64_t gi = fr - first;
        if (!isnan(samples[gi])) continue;
        double total, pass[PG_MAX_PASSES];
        if (!pg_runtime_gpu_times(rt, fr, &total, pass)) continue;
        samples[gi] = total;
        for (uint32_t p = 0; p < PG_MAX_PASSES && p < n_passes; p++)
            samples[(size_t)(2 + p) * B->opt.frames + gi] = pass[p];
    }
}

static void collect_stats(bench_row *row, const double *samples, uint32_t frames, uint32_t n_pass_cols)
{
    /* samples: [0] gpu total, [1] cpu, [2 + p] pass p, [2 + n_pass_cols] wait; each a run of
     * `frames` */
    pg_sample_stats_compute(samples, row->frames, &row->gpu, NULL);
    pg_sample_stats_compute(samples + frames, row->frames, &row->cpu, NULL);
    pg_sample_stats_compute(samples + (size_t)(2 + n_pass_cols) * frames, row->frames, &row->wait, NULL);
    for (uint32_t p = 0; p < row->n_passes && p < n_pass_cols; p++)
        pg_sample_stats_compute(samples + (size_t)(2 + p) * frames, row->frames, &row->passes[p].st, NULL);
}

/* One configuration: its timed frames, then the error frame. Fills row; failures are recorded in
 * it (status, message), never returned: only OOM of the row table stops the bench. */
static void run_row(bench *B, pg_app *app, const pg_frame_info *fi0, reference *refs, bench_row *row, const char *what)
{
    const pipe_entry *pe = &B->pipes[row->pipe];
    const variant *va = &pe->variants[row->variant];
    reference *ref = &refs[va->ref];
    double fw = frame_work(row->width, row->height, row->lights);
    uint32_t nf = B->warmup + B->opt.frames;
    uint32_t limit = ref_limit(B, row->width, row->height);
    bool ref_skipped = row->lights > limit;
    if (ref_skipped) ref_skip_note(B, row->width, row->height, false, row->error_note, sizeof row->error_note);
    if (!va->ok) {
        row->status = ROW_ERROR;
        snprintf(row->message, sizeof row->message, "%s", va->msg);
        B->done_work += fw * (nf + 1);
        return;
    }
    if (pe->is_reference && ref_skipped) {
        row->status = ROW_SKIPPED;
        snprintf(row->message, sizeof row->message, "the reference pipeline itself is not run: %s", row->error_note);
        B->done_work += fw * (nf + 1);
        return;
    }
    /* the reference first, so that only one session holds device memory at a time */
    if (!ref_skipped && !ref->tried) {
        char rw[PG_NAME_MAX + 64];
        snprintf(rw, sizeof rw, "%s (reference) %ux%u lights=%u", B->ref_name, row->width, row->height, row->lights);
        progress_draw(B, rw, false);
        reference_render(B, app, fi0, &B->refs[va->ref], ref);
        B->done_work += frame_work(row->width, row->height, row->lights) * 4;
    }
    pg_session_desc desc = {
        .pipeline_path = pe->path,
        .overrides = va->ov.ov,
        .n_overrides = va->ov.n,
        .registry = &app->registry,
        .disable_aliasing = B->opt.no_aliasing,
        .immediate = B->opt.immediate,
        .async_off = B->opt.async_compute == PG_ASYNC_OFF,
        .settings = app->opt.settings,
        .n_settings = app->opt.n_settings,
    };
    pg_session *s = NULL;
    pg_error e = {0};
    double *samples = NULL;
    float *hdr = NULL;
    uint8_t *ldr = NULL;
    if (pg_session_create(app->gpu, app->scene_gpu, &desc, &s, &e) ||
        pg_session_set_frames_in_flight(s, B->frames_in_flight, &e))
        goto fail;
    samples = calloc((size_t)B->opt.frames * (PG_MAX_PASSES + 3), sizeof *samples);
    if (!samples) {
        pg_fail(&e, PG_ERR_OOM, "out of memory");
        goto fail;
    }
    pg_frame_stats st;
    pg_frame_info fi = *fi0;
    uint64_t first_timed = UINT64_MAX; /* runtime frame number of the first timed frame */
    for (uint32_t f = 0; f < B->opt.frames; f++) samples[f] = NAN;
    for (size_t f = 2 * (size_t)B->opt.frames; f < (size_t)B->opt.frames * (PG_MAX_PASSES + 2); f++) samples[f] = NAN;
    for (uint32_t k = 0; k < nf && !g_interrupted; k++) {
        fi.time = (float)(B->opt.time + k * B->time_step);
        if (pg_session_render(s, &fi, false, &st, &e)) goto fail;
        B->done_work += fw;
        row->grow_events += st.n_grown;
        if (k >= B->warmup) {
            uint32_t f = k - B->warmup;
            /* GPU times arrive later with 2 in flight: each timed frame's are fetched by its
             * frame number (pg_runtime_gpu_times) and stored at its own timed index */
            if (first_timed == UINT64_MAX) first_timed = st.frame;
            fetch_gpu(B, s->runtime, first_timed, st.frame, st.n_passes, samples);
            samples[B->opt.frames + f] = st.cpu_ms;
            samples[(size_t)(2 + PG_MAX_PASSES) * B->opt.frames + f] = st.wait_ms;
            if (f == 0) {
                row->n_passes = st.n_passes;
                for (uint32_t p = 0; p < st.n_passes; p++)
                    pg_strlcpy(row->passes[p].name, st.pass_names[p], sizeof row->passes[p].name);
            }
            if (st.n_counters) {
                row->has_overflow = true;
                if (st.overflow_clusters > row->ov_clusters_max) row->ov_clusters_max = st.overflow_clusters;
            }
            row->frames = f + 1;
        }
        progress_draw(B, what, false);
    }
    if (first_timed != UINT64_MAX && !pg_runtime_wait_idle(s->runtime, &e))
        fetch_gpu(B, s->runtime, first_timed, first_timed + B->opt.frames - 1, row->n_passes, samples);
    if (s->plan) {
        row->has_memory = true;
        row->plan_unaliased = s->plan->transient_bytes_unaliased;
        row->plan_aliased = s->plan->transient_bytes_aliased;
        pg_runtime_stats rs = pg_runtime_get_stats(s->runtime);
        row->dev_unaliased = rs.memory_bytes_unaliased;
        row->dev_aliased = rs.memory_bytes_transient;
    }
    collect_stats(row, samples, B->opt.frames, PG_MAX_PASSES);
    if (g_interrupted) {
        row->status = ROW_INTERRUPTED;
        snprintf(row->message, sizeof row->message, "interrupted after %u of %u timed frames", row->frames,
                 B->opt.frames);
        if (!row->error_note[0]) snprintf(row->error_note, sizeof row->error_note, "interrupted: no error frame");
        goto out;
    }
    /* the error frame: fixed time, read back */
    fi.time = B->opt.time;
    if (pg_session_render(s, &fi, true, &st, &e)) goto fail;
    B->done_work += fw;
    row->grow_events += st.n_grown;
    if (st.n_counters) {
        row->has_overflow = true;
        row->ov_clusters = st.overflow_clusters;
        row->ov_dropped = st.overflow_dropped;
        for (uint32_t k = 0; k < st.n_counters; k++) {
            if (!strcmp(st.counters[k].name, "total_refs")) row->light_refs += st.counters[k].value;
            if (!strcmp(st.counters[k].name, "list_bytes")) row->list_bytes += st.counters[k].value;
        }
    }
    uint32_t w = 0, h = 0;
    pg_error ie = {0};
    if (grab_images(s, &hdr, &ldr, &w, &h, &ie)) {
        snprintf(row->error_note, sizeof row->error_note, "%s", ie.msg);
    } else {
        row->has_nonfinite = true;
        row->nonfinite = pg_count_nonfinite(hdr, w, h);
        if (ref_skipped) {
            /* note already says so */
        } else if (!ref->ok) {
            snprintf(row->error_note, sizeof row->error_note, "reference failed: %s", ref->msg);
        } else if (pg_image_sizes_match("image vs reference", w, h, ref->w, ref->h, &ie) ||
                   pg_image_error_compute(hdr, ref->hdr, ldr, ref->ldr, w, h, 1.0, &row->e, &ie)) {
            snprintf(row->error_note, sizeof row->error_note, "%s", ie.msg);
        } else {
            row->has_error = true;
        }
    }
    row->status = ROW_OK;
    goto out;
fail:
    row->status = ROW_ERROR;
    snprintf(row->message, sizeof row->message, "%s", e.msg);
    if (samples) collect_stats(row, samples, B->opt.frames, PG_MAX_PASSES);
out:
    free(samples);
    free(hdr);
    free(ldr);
    pg_session_destroy(s);
}

static void print_row(const bench *B, const bench_row *r)
{
    const pipe_entry *pe = &B->pipes[r->pipe];
    const variant *va = &pe->variants[r->variant];
    printf("bench: %s%s%s %s %ux%u lights=%u %s", pe->name, va->label[0] ? " " : "", va->label,
           B->scene_names[r->scene], r->width, r->height, r->lights, status_names[r->status]);
    if (r->gpu.n) printf(" gpu=%.3f ms (median of %u)", r->gpu.median, r->gpu.n);
    if (r->has_error) {
        if (isinf(r->e.psnr_linear)) printf(" rmse=%.4g psnr=inf", r->e.rmse_linear);
        else printf(" rmse=%.4g psnr=%.2f dB", r->e.rmse_linear, r->e.psnr_linear);
    }
    if (r->has_overflow)
        printf(" overflow=%llu dropped=%llu refs=%llu lists=%.1fMiB", (unsigned long long)r->ov_clusters,
               (unsigned long long)r->ov_dropped, (unsigned long long)r->light_refs, r->list_bytes / 1048576.0);
    if (r->grow_events) printf(" grew=%u", r->grow_events);
    if (r->status == ROW_ERROR || r->status == ROW_SKIPPED) printf(": %s", r->message);
    printf("\n");
    fflush(stdout);
}

/* ---------------------------------------------------------------- output: CSV and JSON */

typedef struct pass_union {
    uint32_t n;
    char names[PG_MAX_PASSES * 4][PG_NAME_MAX];
} pass_union;

static void union_passes(const bench *B, pass_union *u)
{
    u->n = 0;
    for (uint32_t i = 0; i < B->n_rows; i++)
        for (uint32_t p = 0; p < B->rows[i].n_passes; p++) {
            bool found = false;
            for (uint32_t k = 0; k < u->n && !found; k++) found = !strcmp(u->names[k], B->rows[i].passes[p].name);
            if (!found && u->n < PG_MAX_PASSES * 4) pg_strlcpy(u->names[u->n++], B->rows[i].passes[p].name, PG_NAME_MAX);
        }
}

static void csv_str(FILE *f, const char *s, bool first)
{
    if (!first) fputc(',', f);
    bool quote = strpbrk(s, ",\"\n\r") != NULL;
    if (!quote) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"') fputs("\"\"", f);
        else if (*s == '\n' || *s == '\r') fputc(' ', f);
        else fputc(*s, f);
    }
    fputc('"', f);
}

static void csv_num(FILE *f, double v)
{
    if (isnan(v)) fputs(",", f);
    else if (isinf(v)) fputs(v > 0 ? ",inf" : ",-inf", f);
    else fprintf(f, ",%.6g", v);
}

static void csv_u64(FILE *f, bool has, uint64_t v)
{
    if (has) fprintf(f, ",%llu", (unsigned long long)v);
    else fputs(",", f);
}

static const char *const stat_names[] = {"median", "mean", "min", "max", "p95"};

static double stat_get(const pg_sample_stats *s, int k)
{
    if (!s->n) return NAN;
    switch (k) {
    case 0: return s->median;
    case 1: return s->mean;
    case 2: return s->min;
    case 3: return s->max;
    default: return s->p95;
    }
}

static pg_result write_csv(const bench *B, const char *path, pg_error *err)
{
    FILE *f = fopen(path, "w");
    if (!f) return pg_fail(err, PG_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
    pass_union *u = malloc(sizeof *u);
    if (!u) {
        fclose(f);
        return pg_fail(err, PG_ERR_OOM, "out of memory");
    }
    union_passes(B, u);
    fputs("scene,pipeline,variant,sets,lights,width,height,status,message,warmup,frames,time,seed", f);
    for (int k = 0; k < 5; k++) fprintf(f, ",gpu_ms_%s", stat_names[k]);
    for (int k = 0; k < 5; k++) fprintf(f, ",cpu_ms_%s", stat_names[k]);
    fputs(",plan_transient_bytes_unaliased,plan_transient_bytes_aliased,device_transient_bytes_unaliased,"
          "device_transient_bytes_aliased,overflow_clusters,overflow_dropped,overflow_clusters_max,light_refs,list_bytes,"
          "grow_events,reference,"
          "rmse_linear,psnr_linear,max_abs_linear,peak_linear,rmse_display,psnr_display,max_abs_display,"
          "share_over_1,nonfinite,error_note,pipeline_path,reference_sets,frames_in_flight",
          f);
    for (int k = 0; k < 5; k++) fprintf(f, ",wait_ms_%s", stat_names[k]);
    for (uint32_t p = 0; p < u->n; p++)
        for (int k = 0; k < 5; k++) fprintf(f, ",pass_%s_ms_%s", u->names[p], stat_names[k]);
    fputc('\n', f);
    for (uint32_t i = 0; i < B->n_rows; i++) {
        const bench_row *r = &B->rows[i];
        const pipe_entry *pe = &B->pipes[r->pipe];
        const variant *va = &pe->variants[r->variant];
        csv_str(f, B->scene_names[r->scene], true);
        csv_str(f, pe->name, false);
        csv_str(f, va->label, false);
        csv_str(f, va->sets_label, false);
        fprintf(f, ",%u,%u,%u", r->lights, r->width, r->height);
        csv_str(f, status_names[r->status], false);
        csv_str(f, r->message, false);
        fprintf(f, ",%u,%u,%g,%u", B->warmup, r->frames, (double)B->opt.time, B->opt.seed);
        for (int k = 0; k < 5; k++) csv_num(f, stat_get(&r->gpu, k));
        for (int k = 0; k < 5; k++) csv_num(f, stat_get(&r->cpu, k));
        csv_u64(f, r->has_memory, r->plan_unaliased);
        csv_u64(f, r->has_memory, r->plan_aliased);
        csv_u64(f, r->has_memory, r->dev_unaliased);
        csv_u64(f, r->has_memory, r->dev_aliased);
        bool ov_now = r->has_overflow && r->status == ROW_OK;
        csv_u64(f, ov_now, r->ov_clusters);
        csv_u64(f, ov_now, r->ov_dropped);
        csv_u64(f, r->has_overflow, r->ov_clusters_max);
        csv_u64(f, ov_now, r->light_refs);
        csv_u64(f, ov_now, r->list_bytes);
        csv_u64(f, r->status == ROW_OK || r->status == ROW_INTERRUPTED, r->grow_events);
        csv_str(f, B->ref_name, false);
        const pg_image_error *e = &r->e;
        bool he = r->has_error;
        csv_num(f, he ? e->rmse_linear : NAN);
        csv_num(f, he ? e->psnr_linear : NAN);
        csv_num(f, he ? e->max_abs_linear : NAN);
        csv_num(f, he ? e->peak_linear : NAN);
        csv_num(f, he ? e->rmse_display : NAN);
        csv_num(f, he ? e->psnr_display : NAN);
        csv_num(f, he ? e->max_abs_display : NAN);
        csv_num(f, he ? e->share_over_threshold : NAN);
        csv_u64(f, r->has_nonfinite, r->nonfinite);
        csv_str(f, r->error_note, false);
        csv_str(f, pe->path, false);
        csv_str(f, B->refs[va->ref].label, false);
        fprintf(f, ",%u", B->frames_in_flight);
        for (int k = 0; k < 5; k++) csv_num(f, stat_get(&r->wait, k));
        for (uint32_t p = 0; p < u->n; p++) {
            const pass_stat *ps = NULL;
            for (uint32_t q = 0; q < r->n_passes && !ps; q++)
                if (!strcmp(r->passes[q].name, u->names[p])) ps = &r->passes[q];
            for (int k = 0; k < 5; k++) csv_num(f, ps ? stat_get(&ps->st, k) : NAN);
        }
        fputc('\n', f);
    }
    free(u);
    bool ok = !ferror(f);
    int saved = errno;
    if (fclose(f)) ok = false, saved = errno;
    if (!ok) return pg_fail(err, PG_ERR_IO, "%s: cannot write: %s", path, strerror(saved));
    return PG_OK;
}

/* Finite numbers as numbers, inf as "inf" / "-inf" (like `compare --json`), NaN (unknown) as null. */
static cJSON *jnum(double v)
{
    if (isnan(v)) return cJSON_CreateNull();
    if (isinf(v)) return cJSON_CreateString(v > 0 ? "inf" : "-inf");
    return cJSON_CreateNumber(v);
}

static cJSON *jstats(const pg_sample_stats *s)
{
    cJSON *o = cJSON_CreateObject();
    if (!o) return NULL;
    cJSON_AddNumberToObject(o, "n", s->n);
    for (int k = 0; k < 5; k++) cJSON_AddItemToObject(o, stat_names[k], jnum(stat_get(s, k)));
    return o;
}

static cJSON *json_meta(const bench *B)
{
    cJSON *m = cJSON_CreateObject();
    if (!m) return NULL;
    cJSON_AddStringToObject(m, "device", B->device);
    cJSON *sc = cJSON_AddArrayToObject(m, "scenes");
    for (uint32_t i = 0; sc && i < B->n_scenes; i++) cJSON_AddItemToArray(sc, cJSON_CreateString(B->scene_names[i]));
    if (B->opt.scenario) cJSON_AddStringToObject(m, "scenario", B->opt.scenario);
    cJSON_AddStringToObject(m, "reference", B->ref_name);
    cJSON_AddStringToObject(m, "reference_path", B->ref_path);
    cJSON *rl = cJSON_AddObjectToObject(m, "reference_max_lights");
    if (rl) {
        cJSON_AddStringToObject(rl, "source", B->has_ref_max_lights ? "--reference-max-lights"
                                              : !B->device_known ? "default (no device opened)"
                                              : B->device_cpu   ? "default on a CPU device: a light x pixel budget"
                                                                : "default on a GPU");
        if (!B->has_ref_max_lights && B->device_cpu) cJSON_AddNumberToObject(rl, "budget", CPU_REFERENCE_BUDGET);
        cJSON *bs = cJSON_AddObjectToObject(rl, "by_size");
        for (uint32_t i = 0; bs && i < B->n_sizes; i++) {
            char b[32];
            snprintf(b, sizeof b, "%ux%u", B->widths[i], B->heights[i]);
            cJSON_AddNumberToObject(bs, b, ref_limit(B, B->widths[i], B->heights[i]));
        }
    }
    cJSON *sides = cJSON_AddArrayToObject(m, "sides"); /* what each pipeline and its reference used */
    for (uint32_t p = 0; sides && p < B->n_pipes; p++) {
        const pipe_entry *pe = &B->pipes[p];
        cJSON *o = cJSON_CreateObject();
        if (!o) break;
        cJSON_AddStringToObject(o, "pipeline", pe->name);
        cJSON_AddStringToObject(o, "pipeline_path", pe->path);
        cJSON_AddStringToObject(o, "pipeline_sets", pe->n_variants ? pe->variants[0].sets_label : "");
        cJSON *rs = cJSON_AddArrayToObject(o, "reference_sets"); /* one per distinct set over the variants */
        for (uint32_t v = 0; rs && v < pe->n_variants; v++) {
            bool seen = false;
            for (uint32_t w = 0; w < v && !seen; w++) seen = pe->variants[w].ref == pe->variants[v].ref;
            if (!seen) cJSON_AddItemToArray(rs, cJSON_CreateString(B->refs[pe->variants[v].ref].label));
        }
        cJSON_AddStringToObject(o, "reference", B->ref_name);
        cJSON_AddStringToObject(o, "reference_path", B->ref_path);
        cJSON_AddItemToArray(sides, o);
    }
    cJSON *so = cJSON_AddObjectToObject(m, "pipeline_sets"); /* --pipeline-set and the debug view */
    for (uint32_t i = 0; so && i < B->sides.pipeline.n; i++)
        cJSON_AddStringToObject(so, B->sides.pipeline.ov[i].key, B->sides.pipeline.ov[i].value);
    so = cJSON_AddObjectToObject(m, "reference_sets"); /* --reference-set */
    for (uint32_t i = 0; so && i < B->sides.reference.n; i++)
        cJSON_AddStringToObject(so, B->sides.reference.ov[i].key, B->sides.reference.ov[i].value);
    cJSON_AddStringToObject(m, "reference_sweeps", B->ref_sweeps);
    cJSON_AddNumberToObject(m, "warmup", B->warmup);
    cJSON_AddNumberToObject(m, "frames_in_flight", B->frames_in_flight);
    cJSON_AddNumberToObject(m, "frames", B->opt.frames);
    cJSON_AddNumberToObject(m, "time", B->opt.time);
    cJSON_AddNumberToObject(m, "time_step", B->time_step);
    cJSON_AddNumberToObject(m, "seed", B->opt.seed);
    cJSON_AddBoolToObject(m, "validation", B->opt.validation);
    cJSON_AddBoolToObject(m, "no_aliasing", B->opt.no_aliasing);
    cJSON_AddBoolToObject(m, "immediate", B->opt.immediate);
    cJSON_AddBoolToObject(m, "interrupted", B->interrupted);
    cJSON *l = cJSON_AddArrayToObject(m, "lights");
    for (uint32_t i = 0; l && i < B->n_lights; i++) cJSON_AddItemToArray(l, cJSON_CreateNumber(B->lights[i]));
    cJSON *sz = cJSON_AddArrayToObject(m, "sizes");
    for (uint32_t i = 0; sz && i < B->n_sizes; i++) {
        char b[32];
        snprintf(b, sizeof b, "%ux%u", B->widths[i], B->heights[i]);
        cJSON_AddItemToArray(sz, cJSON_CreateString(b));
    }
    cJSON *st = cJSON_AddObjectToObject(m, "sets"); /* --set */
    for (uint32_t i = 0; st && i < B->sides.set.n; i++)
        cJSON_AddStringToObject(st, B->sides.set.ov[i].key, B->sides.set.ov[i].value);
    cJSON *sw = cJSON_AddObjectToObject(m, "sweeps");
    for (uint32_t k = 0; sw && k < B->n_sweeps; k++) {
        cJSON *a = cJSON_AddArrayToObject(sw, B->sweeps[k].key);
        for (uint32_t v = 0; a && v < B->sweeps[k].n; v++) cJSON_AddItemToArray(a, cJSON_CreateString(B->sweeps[k].values[v]));
    }
    cJSON_AddItemToObject(m, "elapsed_s", jnum(now_s() - B->t_start));
    return m;
}

static cJSON *json_row(const bench *B, const bench_row *r)
{
    const pipe_entry *pe = &B->pipes[r->pipe];
    const variant *va = &pe->variants[r->variant];
    cJSON *o = cJSON_CreateObject();
    if (!o) return NULL;
    cJSON_AddStringToObject(o, "scene", B->scene_names[r->scene]);
    cJSON_AddStringToObject(o, "pipeline", pe->name);
    cJSON_AddStringToObject(o, "pipeline_path", pe->path);
    cJSON_AddStringToObject(o, "variant", va->label);
    cJSON_AddStringToObject(o, "sets", va->sets_label);
    cJSON_AddNumberToObject(o, "lights", r->lights);
    cJSON_AddNumberToObject(o, "width", r->width);
    cJSON_AddNumberToObject(o, "height", r->height);
    cJSON_AddStringToObject(o, "status", status_names[r->status]);
    cJSON_AddStringToObject(o, "message", r->message);
    cJSON_AddNumberToObject(o, "frames", r->frames);
    cJSON_AddItemToObject(o, "gpu_ms", jstats(&r->gpu));
    cJSON_AddItemToObject(o, "cpu_ms", jstats(&r->cpu));
    cJSON_AddItemToObject(o, "wait_ms", jstats(&r->wait));
    cJSON *ps = cJSON_AddArrayToObject(o, "passes");
    for (uint32_t p = 0; ps && p < r->n_passes; p++) {
        cJSON *x = jstats(&r->passes[p].st);
        if (x) cJSON_AddStringToObject(x, "name", r->passes[p].name);
        cJSON_AddItemToArray(ps, x);
    }
    if (r->has_memory) {
        cJSON *m = cJSON_AddObjectToObject(o, "memory");
        cJSON_AddNumberToObject(m, "plan_transient_bytes_unaliased", (double)r->plan_unaliased);
        cJSON_AddNumberToObject(m, "plan_transient_bytes_aliased", (double)r->plan_aliased);
        cJSON_AddNumberToObject(m, "device_transient_bytes_unaliased", (double)r->dev_unaliased);
        cJSON_AddNumberToObject(m, "device_transient_bytes_aliased", (double)r->dev_aliased);
    } else {
        cJSON_AddNullToObject(o, "memory");
    }
    if (r->has_overflow) {
        cJSON *m = cJSON_AddObjectToObject(o, "overflow");
        if (r->status == ROW_OK) {
            cJSON_AddNumberToObject(m, "clusters", (double)r->ov_clusters);
            cJSON_AddNumberToObject(m, "dropped", (double)r->ov_dropped);
            cJSON_AddNumberToObject(m, "light_refs", (double)r->light_refs);
            cJSON_AddNumberToObject(m, "list_bytes", (double)r->list_bytes);
        }
        cJSON_AddNumberToObject(m, "clusters_max", (double)r->ov_clusters_max);
    } else {
        cJSON_AddNullToObject(o, "overflow");
    }
    cJSON_AddNumberToObject(o, "grow_events", r->grow_events);
    cJSON_AddStringToObject(o, "reference", B->ref_name);
    cJSON_AddStringToObject(o, "reference_sets", B->refs[va->ref].label);
    if (r->has_error) {
        const pg_image_error *e = &r->e;
        cJSON *m = cJSON_AddObjectToObject(o, "error");
        cJSON_AddItemToObject(m, "rmse_linear", jnum(e->rmse_linear));
        cJSON_AddItemToObject(m, "psnr_linear", jnum(e->psnr_linear));
        cJSON_AddItemToObject(m, "max_abs_linear", jnum(e->max_abs_linear));
        cJSON_AddItemToObject(m, "peak_linear", jnum(e->peak_linear));
        cJSON_AddItemToObject(m, "rmse_display", jnum(e->rmse_display));
        cJSON_AddItemToObject(m, "psnr_display", jnum(e->psnr_display));
        cJSON_AddItemToObject(m, "max_abs_display", jnum(e->max_abs_display));
        cJSON_AddItemToObject(m, "share_over_1", jnum(e->share_over_threshold));
        cJSON_AddNumberToObject(m, "reference_nonfinite", (double)e->nonfinite_b);
    } else {
        cJSON_AddNullToObject(o, "error");
    }
    if (r->has_nonfinite) cJSON_AddNumberToObject(o, "nonfinite", (double)r->nonfinite);
    else cJSON_AddNullToObject(o, "nonfinite");
    cJSON_AddStringToObject(o, "error_note", r->error_note);
    return o;
}

static pg_result write_json(const bench *B, const char *path, pg_error *err)
{
    cJSON *root = cJSON_CreateObject();
    if (!root) return pg_fail(err, PG_ERR_OOM, "out of memory");
    cJSON_AddNumberToObject(root, "passgraph_bench", 1);
    cJSON_AddItemToObject(root, "meta", json_meta(B));
    cJSON *rows = cJSON_AddArrayToObject(root, "rows");
    for (uint32_t i = 0; rows && i < B->n_rows; i++) cJSON_AddItemToArray(rows, json_row(B, &B->rows[i]));
    char *txt = cJSON_Print(root);
    cJSON_Delete(root);
    if (!txt) return pg_fail(err, PG_ERR_OOM, "out of memory");
    FILE *f = fopen(path, "w");
    bool ok = f && fputs(txt, f) >= 0 && fputc('\n', f) != EOF;
    int saved = errno;
    if (f && fclose(f)) ok = false, saved = errno;
    cJSON_free(txt);
    if (!ok) return pg_fail(err, PG_ERR_IO, "%s: cannot write: %s", path, strerror(saved));
    return PG_OK;
}

/* ---------------------------------------------------------------- output: charts */

static const char *scene_short(const char *s)
{
    const char *b = strrchr(s, '/');
    return b ? b + 1 : s;
}

static void series_label(const bench *B, uint32_t pipe, uint32_t var, char *buf, size_t size)
{
    const pipe_entry *pe = &B->pipes[pipe];
    const variant *va = &pe->variants[var];
    snprintf(buf, size, "%s%s%s", pe->name, va->label[0] ? " " : "", va->label);
}

static bool row_timed(const bench_row *r)
{
    return (r->status == ROW_OK || r->status == ROW_INTERRUPTED) && r->gpu.n > 0;
}

/* Colour and marker of a pipeline/variant in every chart: up to 10 series each has its own colour
 * (and variants of one pipeline different markers); beyond that a pipeline has one colour and its
 * variants differ by marker. */
static void series_style(const bench *B, uint32_t pipe, uint32_t var, int *color, pg_plot_marker *marker)
{
    if (B->n_series <= PG_PLOT_PALETTE_SIZE) *color = (int)B->pipes[pipe].variants[var].series;
    else *color = (int)(pipe % PG_PLOT_PALETTE_SIZE);
    *marker = (pg_plot_marker)((var + pipe / PG_PLOT_PALETTE_SIZE) % PG_PLOT_FILLED_MARKERS);
}

/* Per-chart scratch: arrays the plot structs point into; freed together. */
typedef struct chart_mem {
    void **ptrs;
    uint32_t n, cap;
    bool oom;
} chart_mem;

static void *cm_alloc(chart_mem *m, size_t bytes)
{
    if (m->n == m->cap) {
        uint32_t cap = m->cap ? m->cap * 2 : 64;
        void **p = realloc(m->ptrs, cap * sizeof *p);
        if (!p) {
            m->oom = true;
            return NULL;
        }
        m->ptrs = p;
        m->cap = cap;
    }
    void *q = calloc(1, bytes ? bytes : 1);
    if (!q) {
        m->oom = true;
        return NULL;
    }
    m->ptrs[m->n++] = q;
    return q;
}

static char *cm_str(chart_mem *m, const char *s)
{
    char *c = cm_alloc(m, strlen(s) + 1);
    if (c) memcpy(c, s, strlen(s) + 1);
    return c;
}

static void cm_free(chart_mem *m)
{
    for (uint32_t i = 0; i < m->n; i++) free(m->ptrs[i]);
    free(m->ptrs);
    memset(m, 0, sizeof *m);
}

static void doc_subtitle(const bench *B, char *buf, size_t size, const char *what)
{
    snprintf(buf, size, "%s\n%s | median of %u timed frames after %u warm-up, time step %g s | seed %u, error frame at time %g%s",
             what, B->device, B->opt.frames, B->warmup, B->time_step, B->opt.seed, (double)B->opt.time,
             B->interrupted ? " | INTERRUPTED: partial results" : "");
}

static pg_result chart_time_vs_lights(const bench *B, const char *path, pg_error *err)
{
    chart_mem m = {0};
    uint32_t n_panels = B->n_scenes * B->n_sizes;
    pg_plot *plots = cm_alloc(&m, n_panels * sizeof *plots);
    uint32_t np = 0;
    for (uint32_t sc = 0; plots && sc < B->n_scenes; sc++)
        for (uint32_t si = 0; si < B->n_sizes; si++) {
            pg_plot *pl = &plots[np++];
            pg_plot_series *ser = cm_alloc(&m, (B->n_series ? B->n_series : 1) * sizeof *ser);
            if (!ser) break;
            char t[PG_PATH_MAX + 64];
            snprintf(t, sizeof t, "%s, %ux%u", scene_short(B->scene_names[sc]), B->widths[si], B->heights[si]);
            pl->title = cm_str(&m, t);
            pl->x = (pg_plot_axis){.label = "point lights (log)", .scale = PG_PLOT_LOG10, .zero_label = "0"};
            pl->y = (pg_plot_axis){.label = "GPU ms per frame, median (log)", .scale = PG_PLOT_LOG10, .zero_label = "0"};
            pl->series = ser;
            pl->empty_message = "no timed configuration";
            for (uint32_t pi = 0; pi < B->n_pipes; pi++)
                for (uint32_t v = 0; v < B->pipes[pi].n_variants; v++) {
                    double *x = cm_alloc(&m, B->n_lights * sizeof *x), *y = cm_alloc(&m, B->n_lights * sizeof *y);
                    if (!x || !y) goto oom;
                    uint32_t n = 0;
                    for (uint32_t li = 0; li < B->n_lights; li++)
                        for (uint32_t i = 0; i < B->n_rows; i++) {
                            const bench_row *r = &B->rows[i];
                            if (r->scene != sc || r->pipe != pi || r->variant != v || r->lights != B->lights[li] ||
                                r->width != B->widths[si] || r->height != B->heights[si] || !row_timed(r))
                                continue;
                            x[n] = r->lights;
                            y[n] = r->gpu.median;
                            n++;
                        }
                    if (!n) continue;
                    char lab[PG_NAME_MAX + 260];
                    series_label(B, pi, v, lab, sizeof lab);
                    int color;
                    pg_plot_marker mk;
                    series_style(B, pi, v, &color, &mk);
                    static const char *const dashes[] = {NULL, "7,3", "2,2.5", "9,3,2,3", "4,4"};
                    ser[pl->n_series++] = (pg_plot_series){.name = cm_str(&m, lab), .x = x, .y = y, .n = n,
                                                           .color = color, .marker = mk, .line = true,
                                                           .dasharray = dashes[v % 5]};
                }
        }
oom:
    if (m.oom) {
        cm_free(&m);
        return pg_fail(err, PG_ERR_OOM, "out of memory");
    }
    char sub[512];
    doc_subtitle(B, sub, sizeof sub, "log-log");
    pg_svg_doc_desc d = {.title = "passgraph bench: GPU time against light count", .subtitle = sub};
    pg_result r = pg_svg_write(path, plots, np, &d, err);
    cm_free(&m);
    return r;
}

/* The (scene, size, lights) blocks in run order. */
static uint32_t n_blocks(const bench *B)
{
    return B->n_scenes * B->n_sizes * B->n_lights;
}

static void block_of(const bench *B, uint32_t b, uint32_t *sc, uint32_t *si, uint32_t *li)
{
    *li = b % B->n_lights;
    *si = (b / B->n_lights) % B->n_sizes;
    *sc = b / (B->n_lights * B->n_sizes);
}

static bool row_in_block(const bench *B, const bench_row *r, uint32_t sc, uint32_t si, uint32_t li)
{
    return r->scene == sc && r->width == B->widths[si] && r->height == B->heights[si] && r->lights == B->lights[li];
}

static pg_result chart_passes(const bench *B, const char *path, pg_error *err)
{
    chart_mem m = {0};
    pass_union *u = cm_alloc(&m, sizeof *u);
    uint32_t nb = n_blocks(B);
    pg_plot *plots = cm_alloc(&m, (nb ? nb : 1) * sizeof *plots);
    uint32_t np = 0;
    if (!u || !plots) goto oom;
    union_passes(B, u);
    const char **stack_names = cm_alloc(&m, (u->n ? u->n : 1) * sizeof *stack_names);
    if (!stack_names) goto oom;
    for (uint32_t k = 0; k < u->n; k++) stack_names[k] = u->names[k];
    for (uint32_t b = 0; b < nb; b++) {
        uint32_t sc, si, li;
        block_of(B, b, &sc, &si, &li);
        uint32_t nbars = 0;
        for (uint32_t i = 0; i < B->n_rows; i++) nbars += row_in_block(B, &B->rows[i], sc, si, li) && row_timed(&B->rows[i]);
        bool any_row = false;
        for (uint32_t i = 0; i < B->n_rows; i++) any_row |= row_in_block(B, &B->rows[i], sc, si, li);
        if (!any_row) continue; /* not reached (interrupted) */
        pg_plot *pl = &plots[np++];
        pg_plot_bars *bars = cm_alloc(&m, sizeof *bars);
        const char **labels = cm_alloc(&m, (nbars ? nbars : 1) * sizeof *labels);
        double *vals = cm_alloc(&m, (size_t)(nbars ? nbars : 1) * (u->n ? u->n : 1) * sizeof *vals);
        uint32_t *order = cm_alloc(&m, (size_t)(nbars ? nbars : 1) * (u->n ? u->n : 1) * sizeof *order);
        if (!bars || !labels || !vals || !order) goto oom;
        uint32_t k = 0;
        for (uint32_t i = 0; i < B->n_rows; i++) {
            const bench_row *r = &B->rows[i];
            if (!row_in_block(B, r, sc, si, li) || !row_timed(r)) continue;
            char lab[PG_NAME_MAX + 260];
            series_label(B, r->pipe, r->variant, lab, sizeof lab);
            labels[k] = cm_str(&m, lab);
            /* segments in this row's execution order, then the passes it did not run (value 0) */
            uint32_t no = 0;
            bool *used = cm_alloc(&m, u->n ? u->n : 1);
            if (!used) goto oom;
            for (uint32_t p = 0; p < r->n_passes; p++)
                for (uint32_t q = 0; q < u->n; q++)
                    if (!used[q] && !strcmp(u->names[q], r->passes[p].name)) {
                        vals[(size_t)k * u->n + q] = r->passes[p].st.median;
                        order[(size_t)k * u->n + no++] = q;
                        used[q] = true;
                    }
            for (uint32_t q = 0; q < u->n; q++)
                if (!used[q]) order[(size_t)k * u->n + no++] = q;
            k++;
        }
        *bars = (pg_plot_bars){.n_bars = nbars, .n_stack = u->n, .bar_labels = labels, .stack_names = stack_names,
                               .values = vals, .order = order, .show_totals = true, .total_unit = " ms"};
        char t[PG_PATH_MAX + 96];
        snprintf(t, sizeof t, "%s, %ux%u, %u lights", scene_short(B->scene_names[sc]), B->widths[si], B->heights[si],
                 B->lights[li]);
        pl->title = cm_str(&m, t);
        pl->x = (pg_plot_axis){.label = "GPU ms per frame (median of each pass, stacked in execution order)"};
        pl->bars = bars;
        pl->empty_message = "no timed configuration";
    }
oom:
    if (m.oom) {
        cm_free(&m);
        return pg_fail(err, PG_ERR_OOM, "out of memory");
    }
    char sub[512];
    doc_subtitle(B, sub, sizeof sub, "per-pass GPU timestamps (a pass includes its barriers)");
    pg_svg_doc_desc d = {.title = "passgraph bench: GPU time per pass", .subtitle = sub};
    pg_result r = pg_svg_write(path, plots, np, &d, err);
    cm_free(&m);
    return r;
}

static pg_result chart_error(const bench *B, const char *path, pg_error *err)
{
    chart_mem m = {0};
    uint32_t nb = n_blocks(B);
    pg_plot *plots = cm_alloc(&m, (nb ? nb : 1) * sizeof *plots);
    uint32_t np = 0;
    if (!plots) goto oom;
    for (uint32_t b = 0; b < nb; b++) {
        uint32_t sc, si, li;
        block_of(B, b, &sc, &si, &li);
        uint32_t n = 0;
        bool any_row = false;
        for (uint32_t i = 0; i < B->n_rows; i++) {
            const bench_row *r = &B->rows[i];
            if (!row_in_block(B, r, sc, si, li)) continue;
            any_row = true;
            n += row_timed(r) && r->has_error;
        }
        if (!any_row) continue;
        pg_plot *pl = &plots[np++];
        pg_plot_series *ser = cm_alloc(&m, (n + 1) * sizeof *ser);
        double *xs = cm_alloc(&m, (n + 1) * sizeof *xs), *ys = cm_alloc(&m, (n + 1) * sizeof *ys);
        uint32_t *order = cm_alloc(&m, (n + 1) * sizeof *order);
        double *fx = cm_alloc(&m, (n + 1) * sizeof *fx), *fy = cm_alloc(&m, (n + 1) * sizeof *fy);
        const char **flabels = cm_alloc(&m, (n + 1) * sizeof *flabels);
        if (!ser || !xs || !ys || !order || !fx || !fy || !flabels) goto oom;
        uint32_t k = 0;
        for (uint32_t i = 0; i < B->n_rows; i++) {
            const bench_row *r = &B->rows[i];
            if (!row_in_block(B, r, sc, si, li) || !row_timed(r) || !r->has_error) continue;
            xs[k] = r->gpu.median;
            ys[k] = r->e.rmse_linear;
            char lab[PG_NAME_MAX + 260];
            series_label(B, r->pipe, r->variant, lab, sizeof lab);
            int color;
            pg_plot_marker mk;
            series_style(B, r->pipe, r->variant, &color, &mk);
            ser[k] = (pg_plot_series){.name = cm_str(&m, lab), .x = &xs[k], .y = &ys[k], .n = 1, .color = color,
                                      .marker = mk, .marker_size = 5};
            k++;
        }
        uint32_t nf = pg_pareto_front(xs, ys, k, NULL, order);
        for (uint32_t j = 0; j < nf; j++) {
            fx[j] = xs[order[j]];
            fy[j] = ys[order[j]];
            flabels[j] = ser[order[j]].name;
        }
        pl->n_series = k;
        if (nf) {
            ser[k] = (pg_plot_series){.name = "Pareto front", .x = fx,
                                      .y = fy, .n = nf, .labels = flabels, .color = -1, .marker = PG_MARKER_RING,
                                      .marker_size = 8.5, .line = true, .dashed = true, .line_width = 1.2};
            pl->n_series = k + 1;
        }
        char t[PG_PATH_MAX + 96];
        snprintf(t, sizeof t, "%s, %ux%u, %u lights", scene_short(B->scene_names[sc]), B->widths[si], B->heights[si],
                 B->lights[li]);
        pl->title = cm_str(&m, t);
        char note[300];
        const char *en = NULL;
        for (uint32_t i = 0; i < B->n_rows && !en; i++)
            if (row_in_block(B, &B->rows[i], sc, si, li) && B->rows[i].error_note[0]) en = B->rows[i].error_note;
        if (B->lights[li] > ref_limit(B, B->widths[si], B->heights[si])) {
            char why[256];
            ref_skip_note(B, B->widths[si], B->heights[si], true, why, sizeof why);
            snprintf(note, sizeof note, "no error measured: %s", why);
        } else
            snprintf(note, sizeof note, "no error measured%s%s", en ? ": " : "", en ? en : "");
        pl->empty_message = cm_str(&m, note);
        pl->series = ser;
        pl->x = (pg_plot_axis){.label = "GPU ms per frame, median (log)", .scale = PG_PLOT_LOG10};
        pl->y = (pg_plot_axis){.label = "RMSE vs reference, linear HDR (log)", .scale = PG_PLOT_LOG10,
                               .zero_label = "0 (exact)"};
    }
oom:
    if (m.oom) {
        cm_free(&m);
        return pg_fail(err, PG_ERR_OOM, "out of memory");
    }
    char sub[700];
    char what[300];
    snprintf(what, sizeof what,
             "RMSE against %s (lower left is better); dashed: the Pareto front (no other point is both faster "
             "and more accurate)",
             B->ref_name);
    doc_subtitle(B, sub, sizeof sub, what);
    pg_svg_doc_desc d = {.title = "passgraph bench: image error against GPU time", .subtitle = sub};
    pg_result r = pg_svg_write(path, plots, np, &d, err);
    cm_free(&m);
    return r;
}

static pg_result write_outputs(const bench *B, pg_error *err)
{
    char p[PG_PATH_MAX + 64];
    pg_result r;
    snprintf(p, sizeof p, "%s/results.csv", B->out_dir);
    if ((r = write_csv(B, p, err))) return r;
    snprintf(p, sizeof p, "%s/results.json", B->out_dir);
    if ((r = write_json(B, p, err))) return r;
    snprintf(p, sizeof p, "%s/gpu_time_vs_lights.svg", B->out_dir);
    if ((r = chart_time_vs_lights(B, p, err))) return r;
    snprintf(p, sizeof p, "%s/passes_stacked.svg", B->out_dir);
    if ((r = chart_passes(B, p, err))) return r;
    snprintf(p, sizeof p, "%s/error_vs_time.svg", B->out_dir);
    return chart_error(B, p, err);
}

/* mkdir -p */
static pg_result make_dirs(const char *dir, pg_error *err)
{
    char p[PG_PATH_MAX];
    if (!pg_strlcpy(p, dir, sizeof p)) return pg_fail(err, PG_ERR_INVALID_ARG, "--out %s: path too long", dir);
    for (char *c = p + 1;; c++) {
        if (*c == '/' || !*c) {
            char save = *c;
            *c = 0;
            if (mkdir(p, 0777) && errno != EEXIST)
                return pg_fail(err, PG_ERR_IO, "--out %s: cannot create %s: %s", dir, p, strerror(errno));
            *c = save;
            if (!save) break;
        }
    }
    struct stat st;
    if (stat(dir, &st) || !S_ISDIR(st.st_mode))
        return pg_fail(err, PG_ERR_IO, "--out %s: not a directory", dir);
    return PG_OK;
}

/* ---------------------------------------------------------------- the command */

static void bench_free(bench *B)
{
    for (uint32_t i = 0; i < B->n_pipes; i++) free(B->pipes[i].variants);
    free(B->pipes);
    free(B->refs);
    free(B->rows);
}

/* Position of (pipeline, variant) in a block's run order (what ref_variant.last_use counts). */
static uint32_t var_index(const bench *B, uint32_t pipe, uint32_t var)
{
    uint32_t idx = 0;
    for (uint32_t p = 0; p < pipe; p++) idx += B->pipes[p].n_variants;
    return idx + var;
}

/* Work for the progress bar's ETA: every row's frames and the reference frames (one per distinct
 * reference set per block, up to the limit, which depends on the device). */
static void estimate_work(bench *B, uint32_t vars)
{
    B->total_work = 0;
    for (uint32_t si = 0; si < B->n_sizes; si++)
        for (uint32_t li = 0; li < B->n_lights; li++) {
            double fw = frame_work(B->widths[si], B->heights[si], B->lights[li]);
            bool ref = B->lights[li] <= ref_limit(B, B->widths[si], B->heights[si]);
            B->total_work += B->n_scenes * (vars * fw * (B->warmup + B->opt.frames + 1) + (ref ? 4 * fw * B->n_refs : 0));
        }
}

/* The header: for every pipeline, the file and overrides it takes and what its reference takes
 * (several reference sets when the reference follows a sweep). */
static void print_sides(const bench *B)
{
    for (uint32_t p = 0; p < B->n_pipes; p++) {
        const pipe_entry *pe = &B->pipes[p];
        char refs[1024] = "";
        size_t l = 0;
        for (uint32_t v = 0; v < pe->n_variants && l < sizeof refs; v++) {
            bool seen = false;
            for (uint32_t w = 0; w < v && !seen; w++) seen = pe->variants[w].ref == pe->variants[v].ref;
            if (seen) continue;
            const char *lab = B->refs[pe->variants[v].ref].label;
            int n = snprintf(refs + l, sizeof refs - l, "%s%s", l ? "|" : "", lab[0] ? lab : "none");
            if (n < 0) break;
            l += (size_t)n;
        }
        const char *sets = pe->n_variants && pe->variants[0].sets_label[0] ? pe->variants[0].sets_label : "none";
        char sweeps[256] = "";
        size_t sl = 0;
        for (uint32_t k = 0; k < B->n_sweeps && sl < sizeof sweeps; k++)
            if (pe->n_variants && pg_ov_list_get(&pe->variants[0].ov, B->sweeps[k].key)) {
                int n = snprintf(sweeps + sl, sizeof sweeps - sl, "%s%s", sl ? "," : "", B->sweeps[k].key);
                if (n < 0) break;
                sl += (size_t)n;
            }
        printf("bench: sides: pipeline=%s pipeline_path=%s pipeline_sets=%s sweeps=%s reference=%s reference_path=%s "
               "reference_sets=%s\n",
               pe->name, pe->path, sets, sweeps[0] ? sweeps : "none", B->ref_name, B->ref_path, refs);
    }
    fflush(stdout);
}

int pg_cmd_bench(int argc, char **argv)
{
    bench *B = calloc(1, sizeof *B);
    if (!B) {
        fprintf(stderr, "passgraph bench: out of memory\n");
        return 1;
    }
    pg_cli_defaults(&B->opt);
    B->opt.frames = 10;
    B->warmup = 2;
    B->frames_in_flight = 2;
    B->time_step = 1.0 / 60.0;
    pg_error err = {0};
    char *pipelines = NULL, *lights = NULL, *sizes = NULL, *scenes = NULL;
    const char *ref_arg = NULL;
    bool warned_naive = false;
    int rc = 2;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        char *v = i + 1 < argc ? argv[i + 1] : NULL;
        pg_result r = PG_OK;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            printf("%s%s%s", bench_help, bench_help_options, pg_cli_common_help);
            rc = 0;
            goto out;
        }
        bool takes = !strcmp(a, "--pipelines") || !strcmp(a, "--lights") || !strcmp(a, "--size") ||
                     !strcmp(a, "--scene") || !strcmp(a, "--sweep") || !strcmp(a, "--warmup") ||
                     !strcmp(a, "--frames-in-flight") ||
                     !strcmp(a, "--naive-max-lights") || !strcmp(a, "--reference-max-lights") ||
                     !strcmp(a, "--time-step") || !strcmp(a, "--reference");
        if (takes) {
            if (!v) {
                fprintf(stderr, "passgraph bench: %s: missing value\n", a);
                goto out;
            }
            i++;
            if (!strcmp(a, "--pipelines")) {
                if (pipelines) r = pg_fail(&err, PG_ERR_INVALID_ARG, "--pipelines: given twice");
                pipelines = v;
            } else if (!strcmp(a, "--lights")) {
                lights = v;
            } else if (!strcmp(a, "--size")) {
                sizes = v;
            } else if (!strcmp(a, "--scene")) {
                scenes = v;
            } else if (!strcmp(a, "--sweep")) {
                r = parse_sweep(B, v, &err);
            } else if (!strcmp(a, "--warmup")) {
                r = parse_u32_opt(a, v, 10000, &B->warmup, &err);
            } else if (!strcmp(a, "--frames-in-flight")) {
                r = parse_u32_opt(a, v, PG_MAX_FRAMES_IN_FLIGHT, &B->frames_in_flight, &err);
                if (!r && !B->frames_in_flight)
                    r = pg_fail(&err, PG_ERR_INVALID_ARG, "--frames-in-flight: 1 or %d", PG_MAX_FRAMES_IN_FLIGHT);
            } else if (!strcmp(a, "--reference-max-lights") || !strcmp(a, "--naive-max-lights")) {
                if (!strcmp(a, "--naive-max-lights") && !warned_naive) {
                    fprintf(stderr, "passgraph bench: warning: --naive-max-lights is deprecated; use "
                                    "--reference-max-lights (same meaning)\n");
                    warned_naive = true;
                }
                r = parse_u32_opt(a, v, PG_MAX_LIGHTS, &B->ref_max_lights, &err);
                B->has_ref_max_lights = true;
            } else if (!strcmp(a, "--reference")) {
                ref_arg = v;
            } else { /* --time-step */
                errno = 0;
                char *end;
                double t = strtod(v, &end);
                if (errno || *end || !*v || !isfinite(t) || t < 0 || t > 1e4)
                    r = pg_fail(&err, PG_ERR_INVALID_ARG, "--time-step %s: expected a finite number in [0, 10000]", v);
                B->time_step = t;
            }
        } else if (!strcmp(a, "--explain") || !strcmp(a, "--view")) {
            r = pg_fail(&err, PG_ERR_INVALID_ARG, "%s: not supported by bench (use passgraph render %s)", a, a);
        } else {
            bool used;
            r = pg_sides_parse(&B->sides, argc, argv, &i, &used, &err); /* --pipeline-set, --reference-set */
            if (!r && !used) r = pg_cli_parse_common(&B->opt, argc, argv, &i, &used, &err);
            if (!r && !used) {
                fprintf(stderr, "passgraph bench: unknown option '%s' (see passgraph bench --help)\n", a);
                goto out;
            }
        }
        if (r) {
            fprintf(stderr, "passgraph bench: %s\n", err.msg);
            goto out;
        }
    }
    /* lists (parsed after the loop so that the common parser's single values do not interfere) */
    pg_result r = PG_OK;
    static char def_lights[] = "100,1000,5000";
    if (!r) r = parse_lights(B, lights ? lights : def_lights, &err);
    if (!r && sizes) r = parse_sizes(B, sizes, &err);
    if (!r && !sizes) {
        B->n_sizes = 1;
        B->widths[0] = 640;
        B->heights[0] = 360;
    }
    if (!r && scenes) {
        char *parts[MAX_LIST];
        int n = split_list(scenes, ',', parts, MAX_LIST);
        if (n < 0) r = pg_fail(&err, PG_ERR_INVALID_ARG, "--scene: at most %d scenes", MAX_LIST);
        for (int k = 0; !r && k < n; k++) {
            if (!parts[k][0]) r = pg_fail(&err, PG_ERR_INVALID_ARG, "--scene: empty entry in the list");
            B->scenes[k] = parts[k];
        }
        if (!r) B->n_scenes = (uint32_t)n;
    } else if (!r) {
        B->scenes[0] = B->opt.scene ? B->opt.scene : "default";
        B->n_scenes = 1;
    }
    if (!r && !B->opt.out) r = pg_fail(&err, PG_ERR_INVALID_ARG, "--out DIR is required");
    if (!r && pipelines && B->opt.pipeline)
        r = pg_fail(&err, PG_ERR_INVALID_ARG, "--pipeline and --pipelines: give one of them");
    if (!r && !pg_sides_from_common(&B->sides, &B->opt)) r = pg_fail(&err, PG_ERR_INVALID_ARG, "--set: too many overrides");
    if (r) {
        fprintf(stderr, "passgraph bench: %s\n", err.msg);
        goto out;
    }
    B->out_dir = B->opt.out;
    if (ref_arg) pg_strlcpy(B->ref_path, ref_arg, sizeof B->ref_path);
    else pg_data_path(B->ref_path, sizeof B->ref_path, "pipelines/reference.json");
    {
        char one[PG_PATH_MAX];
        char *plist = pipelines;
        if (!plist && B->opt.pipeline) {
            pg_strlcpy(one, B->opt.pipeline, sizeof one);
            plist = one;
        }
        if ((r = resolve_pipelines(B, plist, &err)) || (r = plan_variants(B, &err))) {
            fprintf(stderr, "passgraph bench: %s\n", err.msg);
            rc = r == PG_ERR_INVALID_ARG ? 2 : 1;
            goto out;
        }
    }
    if ((r = make_dirs(B->out_dir, &err))) {
        fprintf(stderr, "passgraph bench: %s\n", err.msg);
        rc = 1;
        goto out;
    }
    for (uint32_t s = 0; s < B->n_scenes; s++) pg_strlcpy(B->scene_names[s], B->scenes[s], PG_PATH_MAX);

    print_sides(B);
    uint32_t vars = 0;
    for (uint32_t p = 0; p < B->n_pipes; p++) vars += B->pipes[p].n_variants;
    B->rows_total = B->n_scenes * B->n_sizes * B->n_lights * vars;
    B->progress = !B->opt.quiet;
    B->tty = isatty(STDERR_FILENO);
    B->t_start = B->t_last_draw = now_s();
    pg_strlcpy(B->device, "(no device)", sizeof B->device);

    struct sigaction sa, old_sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART | SA_RESETHAND; /* a second Ctrl-C kills as usual */
    g_interrupted = 0;
    sigaction(SIGINT, &sa, &old_sa);

    rc = 0;
    for (uint32_t sc = 0; sc < B->n_scenes && !g_interrupted && rc == 0; sc++) {
        pg_cli_common o = B->opt;
        o.scene = B->scenes[sc];
        o.width = B->widths[0];
        o.height = B->heights[0];
        pg_app app;
        pg_error ae = {0};
        if (pg_app_open(&app, &o, true, &ae)) {
            pg_app_close(&app);
            progress_clear(B);
            /* no device is fatal; a scene that does not load fails its rows */
            if (ae.code == PG_ERR_NO_DEVICE || ae.code == PG_ERR_VULKAN || ae.code == PG_ERR_INVALID_ARG) {
                fprintf(stderr, "passgraph bench: %s\n", ae.msg);
                rc = 1;
                break;
            }
            for (uint32_t si = 0; si < B->n_sizes && !rc; si++)
                for (uint32_t li = 0; li < B->n_lights && !rc; li++)
                    for (uint32_t p = 0; p < B->n_pipes && !rc; p++)
                        for (uint32_t v = 0; v < B->pipes[p].n_variants; v++) {
                            bench_row *row = new_row(B, &err);
                            if (!row) {
                                rc = 1;
                                break;
                            }
                            *row = (bench_row){.scene = sc, .pipe = p, .variant = v, .lights = B->lights[li],
                                               .width = B->widths[si], .height = B->heights[si], .status = ROW_ERROR};
                            row->gpu.median = row->gpu.mean = row->gpu.min = row->gpu.max = row->gpu.p95 = NAN;
                            row->cpu = row->wait = row->gpu;
                            snprintf(row->message, sizeof row->message, "%s", ae.msg);
                            B->rows_done++;
                        }
            fprintf(stderr, "passgraph bench: %s\n", ae.msg);
            continue;
        }
        if (!B->device_known) { /* the default reference limit depends on the device type */
            snprintf(B->device, sizeof B->device, "%s", app.gpu->props.deviceName);
            B->device_known = true;
            B->device_cpu = app.gpu->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
            estimate_work(B, vars);
        }
        for (uint32_t si = 0; si < B->n_sizes && !g_interrupted && !rc; si++) {
            for (uint32_t li = 0; li < B->n_lights && !g_interrupted && !rc; li++) {
                pg_frame_info fi = pg_app_frame(&app);
                fi.width = B->widths[si];
                fi.height = B->heights[si];
                fi.camera.aspect = (float)fi.width / (float)fi.height;
                fi.lights.count = B->lights[li];
                if (app.object_lights) /* the object rule keeps the total over the lights: per count */
                    fi.lights.intensity = pg_light_setup_object(app.scene, B->lights[li], fi.lights.seed).intensity;
                fi.time = B->opt.time;
                reference *refs = calloc(B->n_refs ? B->n_refs : 1, sizeof *refs);
                if (!refs) {
                    pg_fail(&err, PG_ERR_OOM, "out of memory");
                    rc = 1;
                    break;
                }
                for (uint32_t p = 0; p < B->n_pipes && !g_interrupted && !rc; p++)
                    for (uint32_t v = 0; v < B->pipes[p].n_variants && !g_interrupted; v++) {
                        bench_row *row = new_row(B, &err);
                        if (!row) {
                            rc = 1;
                            break;
                        }
                        row->scene = sc;
                        row->pipe = p;
                        row->variant = v;
                        row->lights = B->lights[li];
                        row->width = B->widths[si];
                        row->height = B->heights[si];
                        char what[PG_NAME_MAX + 400];
                        char lab[PG_NAME_MAX + 260];
                        series_label(B, p, v, lab, sizeof lab);
                        snprintf(what, sizeof what, "%s %ux%u lights=%u", lab, row->width, row->height, row->lights);
                        run_row(B, &app, &fi, refs, row, what);
                        for (uint32_t k = 0; k < B->n_refs; k++) /* needed by no later row of this block */
                            if (B->refs[k].last_use <= var_index(B, p, v)) reference_free(&refs[k]);
                        if (row->status == ROW_INTERRUPTED && row->frames == 0) {
                            B->n_rows--; /* nothing measured */
                            break;
                        }
                        if (row->status == ROW_ERROR) B->n_failed++;
                        B->rows_done++;
                        progress_clear(B);
                        print_row(B, row);
                        snprintf(what, sizeof what, "%s %ux%u lights=%u", lab, row->width, row->height, row->lights);
                        progress_draw(B, what, true);
                    }
                for (uint32_t k = 0; k < B->n_refs; k++) reference_free(&refs[k]);
                free(refs);
            }
        }
        if (app.gpu->validation) B->validation_messages += app.gpu->validation_messages;
        pg_app_close(&app);
    }
    sigaction(SIGINT, &old_sa, NULL);
    progress_clear(B);
    B->interrupted = g_interrupted != 0;
    if (rc && err.code == PG_ERR_OOM) fprintf(stderr, "passgraph bench: %s\n", err.msg);
    pg_error we = {0};
    if (write_outputs(B, &we)) {
        fprintf(stderr, "passgraph bench: %s\n", we.msg);
        rc = 1;
    } else {
        printf("bench: %u rows (%u failed)%s -> %s/results.csv, results.json, gpu_time_vs_lights.svg, "
               "passes_stacked.svg, error_vs_time.svg\n",
               B->n_rows, B->n_failed, B->interrupted ? " INTERRUPTED" : "", B->out_dir);
    }
    if (B->validation_messages) {
        fprintf(stderr, "passgraph bench: %u validation message(s)\n", B->validation_messages);
        if (!rc) rc = 1;
    }
    if (B->n_failed) {
        fprintf(stderr, "passgraph bench: %u configuration(s) failed (see 'status' and 'message' in results.csv)\n",
                B->n_failed);
        if (!rc) rc = 1;
    }
    if (B->interrupted) {
        fprintf(stderr, "passgraph bench: interrupted; wrote the %u configuration(s) measured so far\n", B->n_rows);
        rc = 130;
    }
out:
    bench_free(B);
    free(B);
    return rc;
}
