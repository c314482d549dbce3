/* cmd_bench.c - `passgraph bench`: error against run time for every pipeline, swept over light
 * counts, output sizes and pipeline parameters.
 *
 * For each scene x size x light count x pipeline x variant it renders --warmup + --frames timed
 * frames (frame k at --time + k * --time-step: the lights move as in an animation, reproducibly)
 * and then one frame at exactly --time with read-back, whose images are compared with the
 * reference pipeline's frame at the same time (pg_image_error_compute; the reference takes the
 * overrides sides.h describes, so one block may render it once per swept value it declares).
 * Results go to DIR/results.csv, DIR/results.json and three SVG charts written by tools/stats/svg_plot.c.
 * SIGINT stops after the current frame and writes what was measured (exit 130). */
#include "pg_file.h"
#include "bench.h"
#include "scenario.h"
#include "size_note.h"

static const char *const bench_help =
    "usage: passgraph bench [--pipelines LIST|all] [--lights N,N,...] [--size WxH,WxH,...] --out DIR [options]\n"
    "Renders every pipeline (x every --sweep variant) at every light count and output size and records,\n"
    "per configuration: GPU ms per pass and in total from timestamps (median, mean, min, max, p95 over\n"
    "--frames timed frames after --warmup), CPU time (cpu_ms: record + submit, host; wait_ms: host\n"
    "time blocked on fences; --frames-in-flight, default 2), transient memory\n"
    "before/after aliasing (the plan's numbers and the device memory allocated), light overflow of\n"
    "clustered pipelines, and the image error against the reference pipeline at --time (RMSE, PSNR,\n"
    "max abs; linear HDR and 8-bit display; LDR-FLIP, HDR-FLIP, SSIM; the flicker over\n"
    "--flicker-frames frames). Writes DIR/results.csv, DIR/results.json and the charts\n"
    "DIR/gpu_time_vs_lights.svg, DIR/passes_stacked.svg, DIR/error_vs_time.svg (RMSE) and\n"
    "DIR/flip_vs_time.svg (LDR-FLIP) (docs/performance.md documents every column). Timed frame k (warm-up frames included) renders at --time + k *\n"
    "--time-step, so the lights move; the error frame is rendered at exactly --time, after them.\n"
    "Progress and ETA go to stderr; Ctrl-C finishes the current frame, writes what was measured and\n"
    "exits 130. Exit 0 when every configuration ran, 1 when one failed (its rows say why in 'status'\n"
    "and 'message'; the others still run) or validation reported a message, 2 on bad options. A row\n"
    "that dropped light references reads status 'inexact' (a failure with --require-exact).\n\n"
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
    "  --lights N,N,...     light counts (default: a --scenario's lights.count, else 100,1000,5000);\n"
    "                       sorted, duplicates dropped\n"
    "  --size WxH,WxH,...   output sizes (default 640x360); in the given order, duplicates dropped\n"
    "  --scene FILE,...     one or more scenes (default: the built-in atrium); --scenario applies to each\n"
    "  --warmup N           untimed frames before the timed ones (default 2)\n"
    "  --warmup-ms T        and keep warming up until T ms have passed in the row (default 0): a\n"
    "                       GPU idle during the CPU-side error metrics clocks down\n"
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
    "  --reference FILE|NAME  the exact pipeline errors are measured against (default\n"
    "                       pipelines/reference.json: a compute pass shading every pixel with every light);\n"
    "                       a name as --pipelines takes (naive); one that does not load: exit 2\n"
    "  --reference-max-lights N  above N lights the reference is not rendered (error columns empty,\n"
    "                       'error_note' says why) and the reference pipeline's own rows are skipped.\n"
    "                       Default: 1000000 on a GPU; on a CPU device (lavapipe) what keeps a reference\n"
    "                       frame under 1.152e9 light x pixel evaluations: 20000\n"
    "                       lights at 320x180, 5000 at 640x360, 555 at 1920x1080\n"
    "  --naive-max-lights N deprecated name of --reference-max-lights (prints a warning)\n"
    "  --out DIR            output folder (created if missing)\n"
    "  --accumulate N       the measured image of a row is the mean of N frames at --time with sample\n"
    "                       index 0..N-1 (a stochastic pipeline's error after N frames; default 1);\n"
    "                       accumulated_ms_median = N x gpu_ms_median\n"
    "  --flicker-frames K   flicker of each row: K frames at --time with sample 0..K-1, mean |frame k -\n"
    "                       frame k-1| over RGB (linear) / the reference's mean RGB (default 4; 0: off)\n"
    "  --no-hdr-flip        skip HDR-FLIP (LDR-FLIP at 2..14+ exposures: seconds a row at 1080p)\n"
    "  --shard K/N          run only the configurations (scene x size x light count x pipeline x variant,\n"
    "                       numbered in run order from 0) whose index % N == K-1, 1 <= K <= N; each\n"
    "                       shard renders the references its rows need; join with passgraph bench-merge\n"
    "  --quiet              no progress bar\n\n"
    "common options (--lights, --size, --pipeline, --frames as above; --view and --explain are\n"
    "refused: use --debug-view, and passgraph render --explain):\n";

static void on_sigint(int sig)
{
    (void)sig;
    g_interrupted = 1;
}

/* ---------------------------------------------------------------- the command */

void bench_free(bench *B)
{
    for (uint32_t i = 0; i < B->n_pipes; i++) free(B->pipes[i].variants);
    free(B->pipes);
    free(B->refs);
    free(B->rows);
    for (uint32_t i = 0; i < B->n_args; i++) free(B->args[i]);
    free(B->args);
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
            const uint32_t extra = (B->accumulate > B->flicker_frames ? B->accumulate : B->flicker_frames) - 1;
            B->total_work += B->n_scenes * (vars * fw * (B->warmup + B->opt.frames + 1 + (ref && extra > 0 ? extra : 0)) +
                                            (ref ? 4 * fw * B->n_refs : 0));
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

/* Configuration index of a row: scene x size x light count x pipeline x variant, in run order
 * (what --shard K/N splits and bench-merge puts back in order). */
uint32_t config_index(const bench *B, uint32_t sc, uint32_t si, uint32_t li, uint32_t pipe, uint32_t var)
{
    return ((sc * B->n_sizes + si) * B->n_lights + li) * B->n_vars + var_index(B, pipe, var);
}

void config_row(const bench *B, uint32_t idx, bench_row *r)
{
    uint32_t rest = idx, var_all = rest % B->n_vars;
    rest /= B->n_vars;
    uint32_t li = rest % B->n_lights;
    rest /= B->n_lights;
    uint32_t si = rest % B->n_sizes, sc = rest / B->n_sizes;
    uint32_t p = 0, v = var_all;
    while (p < B->n_pipes && v >= B->pipes[p].n_variants) v -= B->pipes[p++].n_variants;
    r->index = idx;
    r->scene = sc;
    r->pipe = p;
    r->variant = v;
    r->lights = B->lights[li];
    r->width = B->widths[si];
    r->height = B->heights[si];
}

static bool in_shard(const bench *B, uint32_t idx)
{
    return !B->shard_n || idx % B->shard_n == B->shard_k - 1;
}

/* --shard K/N: 1 <= K <= N */
static pg_result parse_shard(bench *B, const char *v, pg_error *err)
{
    char *end;
    errno = 0;
    unsigned long k = strtoul(v, &end, 10), n = 0;
    bool ok = !errno && end != v && *end == '/' && v[0] >= '0' && v[0] <= '9';
    if (ok) {
        const char *nv = end + 1;
        n = strtoul(nv, &end, 10);
        ok = !errno && end != nv && !*end && nv[0] >= '0' && nv[0] <= '9';
    }
    if (!ok || k < 1 || n < 1 || k > n || n > 100000)
        return pg_fail(err, PG_ERR_INVALID_ARG, "--shard %s: expected K/N with 1 <= K <= N (e.g. 2/4)", v);
    B->shard_k = (uint32_t)k;
    B->shard_n = (uint32_t)n;
    return PG_OK;
}

/* What results.json's meta.argv keeps: the options that define the sweep, that is all but --shard,
 * --out, --device and --quiet (bench-merge parses them again to rebuild the sweep). */
static pg_result save_args(bench *B, int argc, char **argv, pg_error *err)
{
    B->args = calloc((size_t)argc + 1, sizeof *B->args);
    if (!B->args) return pg_fail(err, PG_ERR_OOM, "out of memory");
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--shard") || !strcmp(a, "--out") || !strcmp(a, "--device")) {
            i++;
            continue;
        }
        if (!strcmp(a, "--quiet")) continue;
        if (!(B->args[B->n_args++] = strdup(a))) return pg_fail(err, PG_ERR_OOM, "out of memory");
    }
    return PG_OK;
}

/* the list and single-value options bench_setup reads after its loop */
typedef struct setup_args {
    char *pipelines, *lights, *sizes, *scenes;
    const char *ref_arg;
    bool warned_naive;
} setup_args;

/* the bench options that take a value */
static bool takes_value(const char *a)
{
    return !strcmp(a, "--pipelines") || !strcmp(a, "--lights") || !strcmp(a, "--size") ||
           !strcmp(a, "--scene") || !strcmp(a, "--sweep") || !strcmp(a, "--warmup") || !strcmp(a, "--warmup-ms") ||
           !strcmp(a, "--frames-in-flight") ||
           !strcmp(a, "--naive-max-lights") || !strcmp(a, "--reference-max-lights") ||
           !strcmp(a, "--time-step") || !strcmp(a, "--reference") || !strcmp(a, "--shard") ||
           !strcmp(a, "--accumulate") || !strcmp(a, "--flicker-frames");
}

/* --time-step S: a finite number in [0, 10000] */
static pg_result parse_time_step(bench *B, const char *v, pg_error *err)
{
    pg_result r = PG_OK;
    errno = 0;
    char *end;
    double t = strtod(v, &end);
    if (errno || *end || !*v || !isfinite(t) || t < 0 || t > 1e4)
        r = pg_fail(err, PG_ERR_INVALID_ARG, "--time-step %s: expected a finite number in [0, 10000]", v);
    B->time_step = t;
    return r;
}

/* one bench option A (takes_value) with its value V: parsed now, or kept in sa for after the loop */
static pg_result parse_value_option(bench *B, setup_args *sa, const char *a, char *v, pg_error *err)
{
    pg_result r = PG_OK;
    if (!strcmp(a, "--pipelines")) {
        if (sa->pipelines) r = pg_fail(err, PG_ERR_INVALID_ARG, "--pipelines: given twice");
        sa->pipelines = v;
    } else if (!strcmp(a, "--lights")) {
        sa->lights = v;
    } else if (!strcmp(a, "--size")) {
        sa->sizes = v;
    } else if (!strcmp(a, "--scene")) {
        sa->scenes = v;
    } else if (!strcmp(a, "--sweep")) {
        r = parse_sweep(B, v, err);
    } else if (!strcmp(a, "--warmup")) {
        r = parse_u32_opt(a, v, 10000, &B->warmup, err);
    } else if (!strcmp(a, "--warmup-ms")) {
        r = parse_u32_opt(a, v, 600000, &B->warmup_ms, err);
    } else if (!strcmp(a, "--frames-in-flight")) {
        uint64_t n = 0;
        r = pg_cli_parse_u64(a, v, 1, PG_MAX_FRAMES_IN_FLIGHT, &n, err);
        B->frames_in_flight = (uint32_t)n;
    } else if (!strcmp(a, "--reference-max-lights") || !strcmp(a, "--naive-max-lights")) {
        if (!strcmp(a, "--naive-max-lights") && !sa->warned_naive) {
            fprintf(stderr, "passgraph bench: warning: --naive-max-lights is deprecated; use "
                            "--reference-max-lights (same meaning)\n");
            sa->warned_naive = true;
        }
        r = parse_u32_opt(a, v, PG_MAX_LIGHTS, &B->ref_max_lights, err);
        B->has_ref_max_lights = true;
    } else if (!strcmp(a, "--reference")) {
        sa->ref_arg = v;
    } else if (!strcmp(a, "--shard")) {
        r = parse_shard(B, v, err);
    } else if (!strcmp(a, "--accumulate")) {
        r = pg_parse_accumulate(a, v, &B->accumulate, err);
    } else if (!strcmp(a, "--flicker-frames")) {
        r = pg_parse_flicker_frames(a, v, &B->flicker_frames, err);
    } else { /* --time-step */
        r = parse_time_step(B, v, err);
    }
    return r;
}

/* the option loop: -1 when it went through, else the exit code (0 after --help, 2 after a
 * message on stderr) */
static int parse_bench_options(bench *B, setup_args *sa, int argc, char **argv)
{
    pg_error err = {0};
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        char *v = i + 1 < argc ? argv[i + 1] : NULL;
        pg_result r = PG_OK;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            printf("%s%s%s", bench_help, bench_help_options, pg_cli_common_help);
            return 0;
        }
        if (takes_value(a)) {
            if (!v) {
                fprintf(stderr, "passgraph bench: %s: missing value\n", a);
                return 2;
            }
            i++;
            r = parse_value_option(B, sa, a, v, &err);
        } else if (!strcmp(a, "--no-hdr-flip")) {
            B->no_hdr_flip = true;
        } else if (!strcmp(a, "--explain") || !strcmp(a, "--view")) {
            r = pg_fail(&err, PG_ERR_INVALID_ARG, "%s: not supported by bench (use passgraph render %s)", a, a);
        } else {
            bool used;
            r = pg_sides_parse(&B->sides, argc, argv, &i, &used, &err); /* --pipeline-set, --reference-set */
            if (!r && !used) r = pg_cli_parse_common(&B->opt, argc, argv, &i, &used, &err);
            if (!r && !used) {
                fprintf(stderr, "passgraph bench: unknown option '%s' (see passgraph bench --help)\n", a);
                return 2;
            }
        }
        if (r) {
            fprintf(stderr, "passgraph bench: %s\n", err.msg);
            return 2;
        }
    }
    return -1;
}

/* --scene FILE,...: the scenes (else --scene of the common options, else the built-in one) */
static pg_result parse_scenes(bench *B, char *scenes, pg_error *err)
{
    pg_result r = PG_OK;
    if (!scenes) {
        B->scenes[0] = B->opt.scene ? B->opt.scene : "default";
        B->n_scenes = 1;
        return PG_OK;
    }
    char *parts[MAX_LIST];
    int n = pg_bench_split_list(scenes, ',', parts, MAX_LIST);
    if (n < 0) r = pg_fail(err, PG_ERR_INVALID_ARG, "--scene: at most %d scenes", MAX_LIST);
    uint32_t kept = 0;
    for (int k = 0; !r && k < n; k++) {
        if (!parts[k][0]) r = pg_fail(err, PG_ERR_INVALID_ARG, "--scene: empty entry in the list");
        bool dup = false; /* the same file twice (by path, or both the built-in scene): run once */
        char a[PATH_MAX], b[PATH_MAX];
        for (uint32_t j = 0; j < kept && !dup; j++)
            dup = !strcmp(B->scenes[j], parts[k]) ||
                  (realpath(B->scenes[j], a) && realpath(parts[k], b) && !strcmp(a, b));
        if (dup) fprintf(stderr, "passgraph bench: --scene: '%s' is listed twice: run once\n", parts[k]);
        else B->scenes[kept++] = parts[k];
    }
    if (!r) B->n_scenes = kept;
    return r;
}

/* the lists (parsed after the loop so that the common parser's single values do not interfere)
 * and the checks between options */
static pg_result parse_lists(bench *B, const setup_args *sa, pg_error *err)
{
    pg_result r = PG_OK;
    static char def_lights[] = "100,1000,5000";
    char sc_lights[16] = "";
    if (B->opt.scenario) { /* as in render: its lights.count and lights.seed when --lights / --seed are not given */
        pg_scenario sc;
        if ((r = pg_scenario_load(B->opt.scenario, &sc, err))) return r;
        if (sc.has_light_count && !sa->lights) snprintf(sc_lights, sizeof sc_lights, "%u", sc.lights.count);
        if (sc.has_seed && !B->opt.has_seed) B->opt.seed = sc.lights.seed;
    }
    if (!r) r = pg_bench_parse_lights(B, sa->lights ? sa->lights : sc_lights[0] ? sc_lights : def_lights, err);
    B->lights_given = sa->lights != NULL || sc_lights[0];
    if (!r && sa->sizes) r = parse_sizes(B, sa->sizes, err);
    if (!r && !sa->sizes) {
        B->n_sizes = 1;
        B->widths[0] = 640;
        B->heights[0] = 360;
    }
    if (!r) r = parse_scenes(B, sa->scenes, err);
    if (!r && !B->opt.out) r = pg_fail(err, PG_ERR_INVALID_ARG, "--out DIR is required");
    if (!r && sa->pipelines && B->opt.pipeline)
        r = pg_fail(err, PG_ERR_INVALID_ARG, "--pipeline and --pipelines: give one of them");
    if (!r && !pg_sides_from_common(&B->sides, &B->opt)) r = pg_fail(err, PG_ERR_INVALID_ARG, "--set: too many overrides");
    return r;
}

/* Options, pipelines and variants: everything before the run. -1 when the bench should run,
 * else the exit code (0 after --help, 2 on bad options, 1 when a pipeline list fails). */
int bench_setup(bench *B, int argc, char **argv)
{
    pg_cli_defaults(&B->opt);
    B->opt.frames = 10;
    B->warmup = 2;
    B->frames_in_flight = 2;
    B->time_step = 1.0 / 60.0;
    B->accumulate = 1;
    B->flicker_frames = PG_FLICKER_FRAMES_DEFAULT;
    pg_error err = {0};
    setup_args sa = {0};
    if (save_args(B, argc, argv, &err)) { /* before the parsers split --set KEY=VALUE in place */
        fprintf(stderr, "passgraph bench: %s\n", err.msg);
        return 1;
    }
    int rc = parse_bench_options(B, &sa, argc, argv);
    if (rc >= 0) return rc;
    pg_result r = parse_lists(B, &sa, &err);
    if (r) {
        fprintf(stderr, "passgraph bench: %s\n", err.msg);
        return 2;
    }
    B->out_dir = B->opt.out;
    if (sa.ref_arg) pg_bench_pipeline_path(sa.ref_arg, B->ref_path, sizeof B->ref_path); /* a name as --pipelines takes */
    else pg_data_path(B->ref_path, sizeof B->ref_path, "pipelines/reference.json");
    char one[PG_PATH_MAX];
    char *plist = sa.pipelines;
    if (!plist && B->opt.pipeline) {
        pg_strlcpy(one, B->opt.pipeline, sizeof one);
        plist = one;
    }
    if ((r = resolve_pipelines(B, plist, &err)) || (r = pg_bench_plan_variants(B, &err))) {
        fprintf(stderr, "passgraph bench: %s\n", err.msg);
        return r == PG_ERR_INVALID_ARG ? 2 : 1;
    }
    for (uint32_t p = 0; p < B->n_pipes; p++) B->n_vars += B->pipes[p].n_variants;
    B->n_configs = B->n_scenes * B->n_sizes * B->n_lights * B->n_vars;
    for (uint32_t s = 0; s < B->n_scenes; s++) pg_strlcpy(B->scene_names[s], B->scenes[s], PG_PATH_MAX);
    return -1;
}

/* the shard's row count (said when sharded), progress, and no device yet */
static void bench_start(bench *B)
{
    for (uint32_t i = 0; i < B->n_configs; i++) B->rows_total += in_shard(B, i);
    if (B->shard_n)
        printf("bench: shard %u/%u: %u of %u configurations (index %% %u == %u)\n", B->shard_k, B->shard_n,
               B->rows_total, B->n_configs, B->shard_n, B->shard_k - 1);
    B->progress = !B->opt.quiet;
    B->tty = isatty(STDERR_FILENO);
    B->t_start = B->t_last_draw = pg_time_s();
    pg_strlcpy(B->device, "(no device)", sizeof B->device);
}

/* A scene that does not load: each of its rows (in this shard) fails with the message. 1 when the
 * row table cannot grow, else 0. */
static int fail_scene_rows(bench *B, uint32_t sc, const char *msg, pg_error *err)
{
    int rc = 0;
    for (uint32_t si = 0; si < B->n_sizes && !rc; si++)
        for (uint32_t li = 0; li < B->n_lights && !rc; li++)
            for (uint32_t p = 0; p < B->n_pipes && !rc; p++)
                for (uint32_t v = 0; v < B->pipes[p].n_variants; v++) {
                    uint32_t idx = config_index(B, sc, si, li, p, v);
                    if (!in_shard(B, idx)) continue;
                    bench_row *row = new_row(B, err);
                    if (!row) {
                        rc = 1;
                        break;
                    }
                    config_row(B, idx, row);
                    row->status = ROW_ERROR;
                    row->gpu.median = row->gpu.mean = row->gpu.min = row->gpu.max = row->gpu.p95 = NAN;
                    row->cpu = row->wait = row->gpu;
                    snprintf(row->message, sizeof row->message, "%s", msg);
                    B->rows_done++;
                    B->n_failed++; /* counted, and the exit code says so, as any failed row */
                }
    return rc;
}

/* the first device seen: its name, whether it is a CPU (the default reference limit depends on
 * the device type), and the work estimate (roughly: this shard's share) */
static void note_device(bench *B, const pg_app *app)
{
    if (B->device_known) return;
    snprintf(B->device, sizeof B->device, "%s", app->gpu->props.deviceName);
    B->device_known = true;
    B->device_cpu = app->gpu->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    estimate_work(B, B->n_vars);
    if (B->n_configs) B->total_work *= (double)B->rows_total / B->n_configs;
}

/* the frame of the block (size si, light count li) */
static pg_frame_info block_frame(const bench *B, const pg_app *app, uint32_t si, uint32_t li)
{
    pg_frame_info fi = pg_app_frame(app);
    fi.width = B->widths[si];
    fi.height = B->heights[si];
    fi.camera.aspect = (float)fi.width / (float)fi.height;
    /* a scene file's own lights come first; generated ones are added only when --lights asks */
    uint32_t generated = fi.lights.file_count && !B->lights_given ? 0 : B->lights[li];
    fi.lights.count = fi.lights.file_count + generated;
    if (app->object_lights) /* the object rule keeps the total over the lights: per count */
        fi.lights.intensity = pg_light_setup_object(app->scene, generated, fi.lights.seed).intensity;
    fi.time = B->opt.time;
    return fi;
}

/* One block (scene sc, size si, light count li): every pipeline and variant of this shard, the
 * references rendered when a row needs them and freed when no later row does. 1 when the row
 * table cannot grow, else 0 (an interrupt ends the block early). */
static int run_block(bench *B, pg_app *app, uint32_t sc, uint32_t si, uint32_t li, pg_error *err)
{
    /* a scene file with its own lights and no --lights: those lights alone, one block */
    if (app->lights.file_count && !B->lights_given && li > 0) return 0;
    pg_frame_info fi = block_frame(B, app, si, li);
    reference *refs = calloc(B->n_refs ? B->n_refs : 1, sizeof *refs);
    if (!refs) {
        pg_fail(err, PG_ERR_OOM, "out of memory");
        return 1;
    }
    int rc = 0;
    for (uint32_t p = 0; p < B->n_pipes && !g_interrupted && !rc; p++)
        for (uint32_t v = 0; v < B->pipes[p].n_variants && !g_interrupted; v++) {
            uint32_t idx = config_index(B, sc, si, li, p, v);
            if (!in_shard(B, idx)) continue; /* the references it would need are rendered when a row needs them */
            bench_row *row = new_row(B, err);
            if (!row) {
                rc = 1;
                break;
            }
            config_row(B, idx, row);
            row->lights = fi.lights.count; /* every light rendered: a file's own ones included */
            char what[PG_NAME_MAX + 400];
            char lab[PG_NAME_MAX + 260];
            series_label(B, p, v, lab, sizeof lab);
            snprintf(what, sizeof what, "%s %ux%u lights=%u", lab, row->width, row->height, row->lights);
            run_row(B, app, &fi, refs, row, what);
            for (uint32_t k = 0; k < B->n_refs; k++) /* needed by no later row of this block */
                if (B->refs[k].last_use <= var_index(B, p, v)) reference_free(&refs[k]);
            if (row->status == ROW_INTERRUPTED && row->frames == 0) {
                B->n_rows--; /* nothing measured */
                break;
            }
            if (row->status == ROW_ERROR || (row->status == ROW_INEXACT && B->opt.require_exact)) B->n_failed++;
            B->rows_done++;
            progress_clear(B);
            print_row(B, row);
            snprintf(what, sizeof what, "%s %ux%u lights=%u", lab, row->width, row->height, row->lights);
            progress_draw(B, what, true);
        }
    for (uint32_t k = 0; k < B->n_refs; k++) reference_free(&refs[k]);
    free(refs);
    return rc;
}

/* Every size of the sweep against the device's largest image side, and the plan's memory
 * estimate printed for each size over the threshold (app/size_note.h), before any row runs. */
static int size_notes(const bench *B, pg_app *app)
{
    const uint32_t w = app->opt.width, h = app->opt.height;
    int rc = 0;
    for (uint32_t si = 0; si < B->n_sizes && !rc; si++) {
        app->opt.width = B->widths[si];
        app->opt.height = B->heights[si];
        pg_error e = {0};
        if (pg_size_note_check(app, "passgraph bench", stderr, &e)) {
            fprintf(stderr, "passgraph bench: %s\n", e.msg);
            rc = 1;
        }
    }
    app->opt.width = w;
    app->opt.height = h;
    return rc;
}

/* One scene: its app (no device is fatal; a scene that does not load fails its rows), then every
 * block. The exit code so far: 0, or 1 to stop. */
static int run_scene(bench *B, uint32_t sc, pg_error *err)
{
    pg_cli_common o = B->opt;
    o.scene = B->scenes[sc];
    o.width = B->widths[0];
    o.height = B->heights[0];
    pg_app app;
    pg_error ae = {0};
    if (pg_app_open(&app, &o, true, &ae)) {
        pg_app_close(&app);
        progress_clear(B);
        /* no device stops the run; a scene's own failure (a file, or a --gltf-scene / --camera it lacks)
         * fails its rows and the others go on */
        if (ae.code == PG_ERR_NO_DEVICE || ae.code == PG_ERR_VULKAN) {
            fprintf(stderr, "passgraph bench: %s\n", ae.msg);
            return 1;
        }
        int rc = fail_scene_rows(B, sc, ae.msg, err);
        fprintf(stderr, "passgraph bench: %s\n", ae.msg);
        return rc;
    }
    note_device(B, &app);
    if (size_notes(B, &app)) {
        pg_app_close(&app);
        return 1;
    }
    int rc = 0;
    for (uint32_t si = 0; si < B->n_sizes && !g_interrupted && !rc; si++)
        for (uint32_t li = 0; li < B->n_lights && !g_interrupted && !rc; li++) rc = run_block(B, &app, sc, si, li, err);
    if (app.gpu->validation) B->validation_messages += app.gpu->validation_messages;
    pg_app_close(&app);
    return rc;
}

/* the results written and the closing lines; the exit code (1 on failures or validation
 * messages, 130 when interrupted) */
static int bench_finish(bench *B, int rc, const pg_error *err)
{
    B->interrupted = g_interrupted != 0;
    if (rc && err->code == PG_ERR_OOM) fprintf(stderr, "passgraph bench: %s\n", err->msg);
    pg_error we = {0};
    if (write_outputs(B, &we)) {
        fprintf(stderr, "passgraph bench: %s\n", we.msg);
        rc = 1;
    } else {
        printf("bench: %u rows (%u failed)%s -> %s/results.csv, results.json, gpu_time_vs_lights.svg, "
               "passes_stacked.svg, error_vs_time.svg, flip_vs_time.svg\n",
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
    return rc;
}

int pg_cmd_bench(int argc, char **argv)
{
    bench *B = calloc(1, sizeof *B);
    if (!B) {
        fprintf(stderr, "passgraph bench: out of memory\n");
        return 1;
    }
    pg_error err = {0};
    pg_result r;
    int rc = bench_setup(B, argc, argv);
    if (rc >= 0) goto out;
    if ((r = make_dirs(B->out_dir, &err)) || (r = pg_file_check_writable_dir(B->out_dir, "--out", &err))) {
        fprintf(stderr, "passgraph bench: %s\n", err.msg);
        rc = 2; /* an option's value, as compare's unwritable --json */
        goto out;
    }
    print_sides(B);
    bench_start(B);

    struct sigaction sa, old_sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART | SA_RESETHAND; /* a second Ctrl-C kills as usual */
    g_interrupted = 0;
    sigaction(SIGINT, &sa, &old_sa);
    rc = 0;
    for (uint32_t sc = 0; sc < B->n_scenes && !g_interrupted && rc == 0; sc++) rc = run_scene(B, sc, &err);
    sigaction(SIGINT, &old_sa, NULL);
    progress_clear(B);
    rc = bench_finish(B, rc, &err);
out:
    bench_free(B);
    free(B);
    return rc;
}
