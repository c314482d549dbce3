/* cmd_compare.c - `passgraph compare`: renders one frame with a pipeline and with a reference
 * pipeline (same device, scene, camera, lights, time, seed, size) and reports the image error of
 * the pipeline against the reference, linear (HDR) and display (8-bit), with both GPU timings. */
#include "pg_file.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cjson/cJSON.h>

#include "app.h"
#include "bench_stats.h"
#include "commands.h"
#include "frame_metrics.h"
#include "image_compare.h"
#include "image_error_json.h"
#include "image_util.h"
#include "shader.h"
#include "sides.h"

static const char *const compare_help =
    "usage: passgraph compare --pipeline FILE [--reference FILE] [options]\n"
    "Renders the same frame (scene, camera, lights, time, seed, size) with a pipeline and with a\n"
    "reference pipeline on one device and reports the error of the pipeline against the reference:\n"
    "RMSE, PSNR and max abs difference over RGB of the scene-linear HDR outputs (hdr_output; PSNR peak\n"
    "= the reference's largest RGB value; pixels with NaN/Inf are left out and counted) and of the\n"
    "8-bit display outputs (0..255 units, PSNR peak 255), the share of pixels whose display RGB differs\n"
    "by more than --threshold, the perceptual metrics LDR-FLIP (display images), HDR-FLIP (HDR images)\n"
    "and SSIM, the flicker of the pipeline over --flicker-frames frames, and both pipelines' GPU ms\n"
    "(total and per pass; median over --frames).\n"
    "The last line starts with 'compare:' and holds key=value pairs; PSNR of identical images is 'inf'.\n"
    "Counters the passes report (e.g. light overflow of a clustered pipeline) are printed too.\n"
    "Frames are rendered alternately (pipeline, reference, ...); the first frame of each includes\n"
    "one-time costs on some drivers, so compare GPU ms with --frames 3 or more.\n"
    "Both pipelines must declare an hdr_output. Exit 0 on success, 1 on a failure (load, render,\n"
    "validation message with --validation), 2 on bad options.\n\n"
    "--set KEY=VALUE applies to the pipeline, and to the reference too when the reference declares KEY\n"
    "(so --set shading=blinn_phong compares Blinn-Phong with Blinn-Phong); --pipeline-set KEY=VALUE\n"
    "applies to the pipeline only and --reference-set KEY=VALUE to the reference only, each winning\n"
    "over --set on its side. A debug view (--view NAME of no OCIO view, --debug-view) is the\n"
    "pipeline's only. The first line ('sides:') says which file and overrides each side used.\n"
    "The other options, --no-aliasing, --immediate and the OCIO display / view included, apply to both.\n\n"
    "options:\n";

static const char *const compare_help_own =
    "  --reference FILE     reference pipeline JSON (default: pipelines/reference.json of the data\n"
    "                       folder: a compute pass that shades every pixel with every light)\n"
    "  --pipeline-set KEY=VALUE   override a parameter of the pipeline only, not of the reference\n"
    "                       (repeatable; wins over --set)\n"
    "  --reference-set KEY=VALUE  override a parameter of the reference only (repeatable; wins over\n"
    "                       --set); e.g. --set shading=blinn_phong --reference-set shading=lambert\n"
    "  --threshold T        8-bit units; a pixel counts as different when its max |RGB difference|\n"
    "                       in the display images is > T (default 1)\n"
    "  --heatmap FILE.png   write a heatmap of the per-pixel linear error (max over RGB of |a - b|)\n"
    "                       in a dark-purple -> orange -> pale-yellow colormap; cyan marks pixels\n"
    "                       with NaN/Inf in either image\n"
    "  --heatmap-scale S|max  linear error mapped to the brightest colour; larger errors saturate.\n"
    "                       Default: the 99th percentile of the errors of the pixels that differ\n"
    "                       (HDR errors are heavy-tailed: the largest one leaves the rest black);\n"
    "                       'max' or 0: the largest error\n"
    "  --json FILE          also write the results as a JSON object (the 'compare:' keys, plus\n"
    "                       per-pass times; non-finite numbers as the strings \"inf\", \"-inf\", \"nan\");\n"
    "                       '-': the JSON alone on the standard output, the report on the standard error\n"
    "  --flip-map FILE.png  write the LDR-FLIP map (per-pixel perceptual error of the display images)\n"
    "                       in the heatmap's colormap over the fixed range 0..1, so maps compare\n"
    "  --no-hdr-flip        skip HDR-FLIP (it runs LDR-FLIP at 2..14+ exposures: seconds at 1080p);\n"
    "                       hdr_flip reads nan\n"
    "  --accumulate N       the pipeline's measured image is the mean of N frames with sample index\n"
    "                       0..N-1 (HDR averaged in float, display images averaged per channel and\n"
    "                       rounded); the error of a stochastic pipeline after N frames (default 1)\n"
    "  --flicker-frames K   render K frames of the pipeline (sample 0..K-1, same time, camera and\n"
    "                       lights) and report flicker = mean |frame k - frame k-1| over RGB (linear)\n"
    "                       / mean RGB of the reference: 0 for a deterministic pipeline (default 4;\n"
    "                       0: off, flicker reads nan)\n";

static pg_result parse_nonneg(const char *opt, const char *s, double *out, pg_error *err)
{
    if (!s || !*s) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: missing value", opt);
    errno = 0;
    char *end;
    double v = strtod(s, &end);
    if (errno || *end || !isfinite(v) || v < 0 || v > 1e30)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s: expected a finite number in [0, 1e+30]", opt, s);
    *out = v;
    return PG_OK;
}

/* %g, but "inf" / "-inf" / "nan" spelled the same on every libc. */
static const char *num(char *buf, size_t size, double v)
{
    if (isnan(v)) snprintf(buf, size, "nan");
    else if (isinf(v)) snprintf(buf, size, v > 0 ? "inf" : "-inf");
    else snprintf(buf, size, "%.6g", v);
    return buf;
}

static cJSON *json_num(double v)
{
    return pg_json_metric(v, false);
}

/* One side of the comparison: its session, per-frame timings and read-back images. */
typedef struct side {
    const char *label;       /* "pipeline" / "reference" */
    pg_session *s;
    double *samples;         /* frames x (1 + PG_MAX_PASSES): total, then per pass */
    pg_frame_stats st;       /* of the last frame */
    double gpu_ms, pass_ms[PG_MAX_PASSES];
    const uint8_t *ldr;
    uint8_t *ldr_own;        /* the accumulated display image, when ldr points at it */
    float *hdr;
    uint32_t lw, lh, hw, hh;
    pg_format hfmt;
} side;

static pg_result side_create(side *sd, const char *label, pg_app *app, const char *path, const pg_param_override *sets,
                             uint32_t n_sets, bool no_aliasing, bool immediate, uint32_t frames, pg_error *err)
{
    memset(sd, 0, sizeof *sd);
    sd->label = label;
    pg_session_desc desc = {
        .pipeline_path = path,
        .overrides = sets,
        .n_overrides = n_sets,
        .registry = &app->registry,
        .disable_aliasing = no_aliasing,
        .immediate = immediate,
        .settings = app->opt.settings, /* both sides: the same display / view */
        .n_settings = app->opt.n_settings,
    };
    if (pg_app_session_create(app, &desc, &sd->s, err)) return pg_error_prefix(err, "%s", label);
    if (!sd->s->pipeline->hdr_output[0])
        return pg_fail(err, PG_ERR_NO_OUTPUT,
                       "%s: %s: pipeline '%s' declares no hdr_output; compare needs the scene-linear HDR image", label,
                       sd->s->pipeline->path, sd->s->pipeline->name);
    sd->samples = calloc((size_t)frames * (PG_MAX_PASSES + 1), sizeof(double));
    if (!sd->samples) return pg_fail(err, PG_ERR_OOM, "out of memory");
    return PG_OK;
}

static pg_result side_render(side *sd, const pg_frame_info *fi, uint32_t f, uint32_t frames, pg_error *err)
{
    if (pg_session_render(sd->s, fi, f + 1 == frames, &sd->st, err)) return pg_error_prefix(err, "%s", sd->label);
    sd->samples[f] = sd->st.gpu_total_ms;
    for (uint32_t p = 0; p < sd->st.n_passes; p++) sd->samples[(size_t)(p + 1) * frames + f] = sd->st.pass_ms[p];
    return PG_OK;
}

static pg_result side_finish(side *sd, uint32_t frames, pg_error *err)
{
    sd->gpu_ms = pg_median(sd->samples, frames);
    for (uint32_t p = 0; p < sd->st.n_passes; p++) sd->pass_ms[p] = pg_median(sd->samples + (size_t)(p + 1) * frames, frames);
    const pg_pipeline *pl = sd->s->pipeline;
    pg_format fmt;
    sd->ldr = pg_runtime_output(sd->s->runtime, 0, &sd->lw, &sd->lh, &fmt);
    if (!sd->ldr || (fmt != PG_FMT_RGBA8_UNORM && fmt != PG_FMT_RGBA8_SRGB))
        return pg_fail(err, PG_ERR_FORMAT, "%s: %s: output '%s' must be an 8-bit RGBA image (rgba8 or rgba8_srgb)",
                       sd->label, pl->path, pl->output);
    const void *hpix = pg_runtime_output(sd->s->runtime, 1, &sd->hw, &sd->hh, &sd->hfmt);
    if (!hpix)
        return pg_fail(err, PG_ERR_NO_OUTPUT, "%s: %s: hdr_output '%s' was not read back", sd->label, pl->path,
                       pl->hdr_output);
    sd->hdr = malloc((size_t)sd->hw * sd->hh * 4 * sizeof(float));
    if (!sd->hdr) return pg_fail(err, PG_ERR_OOM, "out of memory");
    if (pg_hdr_to_float(hpix, sd->hfmt, sd->hw, sd->hh, sd->hdr, err))
        return pg_error_prefix(err, "%s: %s: hdr_output '%s'", sd->label, pl->path, pl->hdr_output);
    return PG_OK;
}

static void side_print(const side *sd, FILE *f)
{
    fprintf(f, "%-10s %s (%s, hdr %s) gpu=%.3f ms [", sd->label, sd->s->pipeline->name, sd->s->pipeline->path,
            pg_format_get(sd->hfmt)->name, sd->gpu_ms);
    for (uint32_t p = 0; p < sd->st.n_passes; p++)
        fprintf(f, "%s%s %.3f", p ? ", " : "", sd->st.pass_names[p], sd->pass_ms[p]);
    fprintf(f, "]");
    /* counters the passes report (pg_frame_stats.counters, e.g. light overflow of a cluster pass) */
    for (uint32_t k = 0; k < sd->st.n_counters; k++)
        fprintf(f, " %s.%s=%llu", sd->st.counters[k].pass, sd->st.counters[k].name,
                (unsigned long long)sd->st.counters[k].value);
    fprintf(f, "\n");
}

/* The overflow sums for the 'compare:' line, only for a pipeline whose passes report counters. */
static void side_print_overflow(const side *sd, const char *prefix, FILE *f)
{
    if (!sd->st.n_counters) return;
    fprintf(f, " %soverflow_clusters=%llu %soverflow_dropped=%llu", prefix,
            (unsigned long long)pg_frame_counter_sum(&sd->st, "overflow_clusters"), prefix, (unsigned long long)pg_frame_counter_sum(&sd->st, "overflow_dropped"));
}

static cJSON *side_counters_json(const side *sd)
{
    cJSON *o = cJSON_CreateObject();
    for (uint32_t k = 0; o && k < sd->st.n_counters; k++) {
        char key[PG_NAME_MAX + 40];
        snprintf(key, sizeof key, "%s.%s", sd->st.counters[k].pass, sd->st.counters[k].name);
        cJSON_AddNumberToObject(o, key, (double)sd->st.counters[k].value);
    }
    return o;
}

static cJSON *side_passes_json(const side *sd)
{
    cJSON *o = cJSON_CreateObject();
    for (uint32_t p = 0; o && p < sd->st.n_passes; p++) cJSON_AddItemToObject(o, sd->st.pass_names[p], json_num(sd->pass_ms[p]));
    return o;
}

static void side_free(side *sd)
{
    free(sd->samples);
    free(sd->hdr);
    free(sd->ldr_own);
    pg_session_destroy(sd->s);
    memset(sd, 0, sizeof *sd);
}

/* What the command line asked for, and the two sides it resolves to. */
typedef struct compare_job {
    pg_cli_common opt;
    pg_side_sets ss;
    const char *reference, *heatmap, *json, *flip_map;
    double threshold, heat_scale_arg; /* heat_scale_arg < 0: 99th percentile; 0: max */
    uint32_t accumulate, flicker_frames;
    bool no_hdr_flip;
    char ref_path[PG_PATH_MAX], pipe_path[PG_PATH_MAX];
    pg_ov_list pipe_ov, ref_ov;
    int json_fd;             /* --json -: the standard output the JSON goes to (the report goes to
                              * the standard error then); -1 otherwise */
} compare_job;

/* What compare measures besides pg_image_error (frame_metrics.h). */
typedef struct extra_measures {
    pg_perceptual pm;
    pg_flicker fl;
    double flicker;          /* NaN when --flicker-frames 0 */
    uint32_t extra_frames;   /* the pipeline's frames rendered for accumulation and flicker */
} extra_measures;

/* The perceptual and temporal numbers (and the options that shaped them) into compare's JSON. */
static void json_add_measures(cJSON *o, const compare_job *job, const extra_measures *m, double gpu_ms)
{
    cJSON_AddItemToObject(o, "flip", json_num(m->pm.flip));
    cJSON_AddItemToObject(o, "hdr_flip", json_num(m->pm.hdr_flip));
    if (!job->no_hdr_flip) {
        cJSON_AddItemToObject(o, "hdr_flip_start_exposure", json_num(m->pm.hdr.start_exposure));
        cJSON_AddItemToObject(o, "hdr_flip_stop_exposure", json_num(m->pm.hdr.stop_exposure));
        cJSON_AddNumberToObject(o, "hdr_flip_exposures", m->pm.hdr.exposures);
    }
    cJSON_AddItemToObject(o, "ssim", json_num(m->pm.ssim));
    cJSON_AddItemToObject(o, "flicker", json_num(m->flicker));
    cJSON_AddNumberToObject(o, "flicker_frames", job->flicker_frames);
    cJSON_AddNumberToObject(o, "accumulate", job->accumulate);
    cJSON_AddItemToObject(o, "accumulated_gpu_ms", json_num(gpu_ms * job->accumulate));
    cJSON_AddItemToObject(o, "metrics_cpu_ms", json_num(m->pm.cpu_ms));
    if (job->flip_map) cJSON_AddStringToObject(o, "flip_map", job->flip_map);
}

static cJSON *ov_json(const pg_ov_list *l)
{
    cJSON *o = cJSON_CreateObject();
    for (uint32_t k = 0; o && k < l->n; k++) cJSON_AddStringToObject(o, l->ov[k].key, l->ov[k].value);
    return o;
}

static pg_result write_json(const compare_job *job, const side *a, const side *r, const pg_app *app,
                            double heat_scale, const pg_image_error *e, const extra_measures *m, pg_error *err)
{
    const char *path = job->json, *heatmap = job->heatmap;
    const pg_ov_list *aov = &job->pipe_ov, *rov = &job->ref_ov;
    double threshold = job->threshold;
    cJSON *o = cJSON_CreateObject();
    if (!o) return pg_fail(err, PG_ERR_OOM, "out of memory");
    cJSON_AddStringToObject(o, "pipeline", a->s->pipeline->name);
    cJSON_AddStringToObject(o, "reference", r->s->pipeline->name);
    cJSON_AddStringToObject(o, "pipeline_path", a->s->pipeline->path);
    cJSON_AddStringToObject(o, "reference_path", r->s->pipeline->path);
    cJSON_AddItemToObject(o, "pipeline_sets", ov_json(aov)); /* the overrides each side used */
    cJSON_AddItemToObject(o, "reference_sets", ov_json(rov));
    cJSON_AddStringToObject(o, "scene", app->scene_path);
    cJSON_AddNumberToObject(o, "lights", app->lights.count);
    cJSON_AddNumberToObject(o, "width", e->width);
    cJSON_AddNumberToObject(o, "height", e->height);
    cJSON_AddNumberToObject(o, "time", app->opt.time);
    cJSON_AddNumberToObject(o, "seed", app->opt.seed);
    cJSON_AddNumberToObject(o, "frames", app->opt.frames);
    cJSON_AddStringToObject(o, "hdr_format", pg_format_get(a->hfmt)->name);
    cJSON_AddStringToObject(o, "reference_hdr_format", pg_format_get(r->hfmt)->name);
    const pg_image_error_json_style style = {.share_key = "over_threshold", .threshold = &threshold};
    pg_image_error_json_add(o, e, &style);
    cJSON_AddNumberToObject(o, "pixels_over_threshold", (double)e->over_threshold);
    cJSON_AddNumberToObject(o, "nonfinite", (double)e->nonfinite_a);
    cJSON_AddNumberToObject(o, "reference_nonfinite", (double)e->nonfinite_b);
    json_add_measures(o, job, m, a->gpu_ms);
    cJSON_AddItemToObject(o, "gpu_ms", json_num(a->gpu_ms));
    cJSON_AddItemToObject(o, "reference_gpu_ms", json_num(r->gpu_ms));
    cJSON_AddItemToObject(o, "passes", side_passes_json(a));
    cJSON_AddItemToObject(o, "reference_passes", side_passes_json(r));
    if (a->st.n_counters) {
        cJSON_AddNumberToObject(o, "overflow_clusters", (double)pg_frame_counter_sum(&a->st, "overflow_clusters"));
        cJSON_AddNumberToObject(o, "overflow_dropped", (double)pg_frame_counter_sum(&a->st, "overflow_dropped"));
        cJSON_AddItemToObject(o, "counters", side_counters_json(a));
    }
    if (r->st.n_counters) {
        cJSON_AddNumberToObject(o, "reference_overflow_clusters", (double)pg_frame_counter_sum(&r->st, "overflow_clusters"));
        cJSON_AddNumberToObject(o, "reference_overflow_dropped", (double)pg_frame_counter_sum(&r->st, "overflow_dropped"));
        cJSON_AddItemToObject(o, "reference_counters", side_counters_json(r));
    }
    if (heatmap) {
        cJSON_AddStringToObject(o, "heatmap", heatmap);
        cJSON_AddItemToObject(o, "heatmap_scale", json_num(heat_scale));
    }
    char *txt = cJSON_Print(o);
    cJSON_Delete(o);
    if (!txt) return pg_fail(err, PG_ERR_OOM, "out of memory");
    FILE *f = job->json_fd >= 0 ? fdopen(job->json_fd, "w") : fopen(path, "w");
    bool ok = f && fputs(txt, f) >= 0 && fputc('\n', f) != EOF;
    if (f && fclose(f)) ok = false;
    cJSON_free(txt);
    if (!ok) return pg_fail(err, PG_ERR_IO, "--json %s: cannot write: %s", path, strerror(errno));
    return PG_OK;
}

/* The overrides of each side (sides.h), checked before any device is opened: a key a side does not
 * declare or a value it refuses is an option error (exit 2) naming the option that gave it. A file
 * that does not load is left to the session, which reports it (exit 1). */
static int plan_sides(const pg_side_sets *ss, const char *pipe_path, const char *ref_path, pg_ov_list *pipe_ov,
                      pg_ov_list *ref_ov, pg_error *err)
{
    pg_pipeline *pl = NULL, *ref = NULL;
    pg_error ignored = {0};
    if (pg_pipeline_load(ref_path, NULL, 0, &ref, &ignored)) ref = NULL;
    pg_sides_pipeline(ss, NULL, NULL, 0, pipe_ov);
    pg_sides_reference(ss, ref, NULL, 0, ref_ov);
    int rc = 0;
    if (!pg_pipeline_load(pipe_path, NULL, 0, &pl, &ignored) &&
        (pg_sides_check_keys(pipe_ov, pl, "pipeline", err) ||
         pg_sides_check_values(pipe_path, pipe_ov, "pipeline", err) == PG_ERR_INVALID_ARG))
        rc = 2;
    if (!rc && ref &&
        (pg_sides_check_keys(ref_ov, ref, "reference", err) ||
         pg_sides_check_values(ref_path, ref_ov, "reference", err) == PG_ERR_INVALID_ARG))
        rc = 2;
    pg_pipeline_free(pl);
    pg_pipeline_free(ref);
    return rc;
}

static void print_sides(const side *a, const pg_ov_list *aov, const side *r, const pg_ov_list *rov, FILE *f)
{
    char sa[2048], sr[2048];
    pg_ov_list_format(aov, sa, sizeof sa);
    pg_ov_list_format(rov, sr, sizeof sr);
    fprintf(f, "sides: pipeline=%s pipeline_path=%s pipeline_sets=%s reference=%s reference_path=%s reference_sets=%s\n",
            a->s->pipeline->name, a->s->pipeline->path, aov->n ? sa : "none", r->s->pipeline->name,
            r->s->pipeline->path, rov->n ? sr : "none");
    fflush(f);
}


/* The heatmap's scale as used, and how it was chosen (for the report). */
typedef struct heat_scale_used {
    double scale;
    char how[64];
} heat_scale_used;

static bool is_valued_option(const char *a)
{
    return !strcmp(a, "--reference") || !strcmp(a, "--heatmap") || !strcmp(a, "--heatmap-scale") ||
           !strcmp(a, "--threshold") || !strcmp(a, "--json") || !strcmp(a, "--flip-map") ||
           !strcmp(a, "--accumulate") || !strcmp(a, "--flicker-frames");
}

/* The value v of one of compare's own options (is_valued_option). */
static pg_result parse_valued_option(compare_job *job, const char *a, const char *v, pg_error *err)
{
    pg_result r = PG_OK;
    if (!strcmp(a, "--reference")) {
        job->reference = v;
    } else if (!strcmp(a, "--heatmap")) {
        job->heatmap = v;
        if ((r = pg_image_path_check(v, false, err))) pg_error_prefix(err, "--heatmap");
    } else if (!strcmp(a, "--json")) {
        job->json = v;
    } else if (!strcmp(a, "--flip-map")) {
        job->flip_map = v;
        if ((r = pg_image_path_check(v, false, err))) pg_error_prefix(err, "--flip-map");
    } else if (!strcmp(a, "--accumulate")) {
        r = pg_parse_accumulate(a, v, &job->accumulate, err);
    } else if (!strcmp(a, "--flicker-frames")) {
        r = pg_parse_flicker_frames(a, v, &job->flicker_frames, err);
    } else if (!strcmp(a, "--threshold")) {
        r = parse_nonneg(a, v, &job->threshold, err);
    } else { /* --heatmap-scale */
        if (!strcmp(v, "max")) job->heat_scale_arg = 0;
        else r = parse_nonneg(a, v, &job->heat_scale_arg, err);
    }
    return r;
}

/* The option at argv[*i] (and its value, advancing *i): -1 to go on, else the exit status. */
static int parse_option(compare_job *job, int argc, char **argv, int *i, pg_error *err)
{
    const char *a = argv[*i];
    const char *v = *i + 1 < argc ? argv[*i + 1] : NULL;
    bool own = true;
    pg_result r = PG_OK;
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
        printf("%s%s%s", compare_help, pg_cli_common_help, compare_help_own);
        return 0;
    }
    if (is_valued_option(a)) {
        if (!v) {
            fprintf(stderr, "passgraph compare: %s: missing value\n", a);
            return 2;
        }
        (*i)++;
        r = parse_valued_option(job, a, v, err);
    } else if (!strcmp(a, "--no-hdr-flip")) {
        job->no_hdr_flip = true;
    } else if (!strcmp(a, "--out")) {
        own = false; /* compare writes no display image: --heatmap / --json */
    } else {
        r = pg_sides_parse(&job->ss, argc, argv, i, &own, err); /* --pipeline-set, --reference-set */
        if (!r && !own) r = pg_cli_parse_common(&job->opt, argc, argv, i, &own, err);
    }
    if (r) {
        fprintf(stderr, "passgraph compare: %s\n", err->msg);
        return 2;
    }
    if (!own) {
        fprintf(stderr, "passgraph compare: unknown option '%s' (see passgraph compare --help)\n", a);
        return 2;
    }
    return -1;
}

/* The command line into job: -1 to go on, else the exit status. */
static int parse_args(compare_job *job, int argc, char **argv, pg_error *err)
{
    pg_cli_defaults(&job->opt);
    job->reference = job->heatmap = job->json = job->flip_map = NULL;
    job->json_fd = -1;
    job->threshold = 1.0;
    job->accumulate = 1;
    job->flicker_frames = PG_FLICKER_FRAMES_DEFAULT;
    job->no_hdr_flip = false;
    job->heat_scale_arg = -1.0;
    memset(&job->ss, 0, sizeof job->ss);
    for (int i = 0; i < argc; i++) {
        const int rc = parse_option(job, argc, argv, &i, err);
        if (rc >= 0) return rc;
    }
    if (!pg_sides_from_common(&job->ss, &job->opt)) {
        fprintf(stderr, "passgraph compare: --set: too many overrides\n");
        return 2;
    }
    return -1;
}

/* The two pipelines' paths and overrides, and the outputs checked writable, all before any device
 * is opened: -1 to go on, else the exit status. */
static int resolve_sides(compare_job *job, pg_error *err)
{
    if (job->reference) pg_strlcpy(job->ref_path, job->reference, sizeof job->ref_path);
    else pg_data_path(job->ref_path, sizeof job->ref_path, "pipelines/reference.json");
    if (job->opt.pipeline) pg_strlcpy(job->pipe_path, job->opt.pipeline, sizeof job->pipe_path);
    else pg_data_path(job->pipe_path, sizeof job->pipe_path, "pipelines/naive.json"); /* pg_app_open's default */
    if (plan_sides(&job->ss, job->pipe_path, job->ref_path, &job->pipe_ov, &job->ref_ov, err)) {
        fprintf(stderr, "passgraph compare: %s\n", err->msg);
        return 2;
    }

    /* the outputs can be written: checked before rendering, with the OS reason */
    if ((job->heatmap && pg_file_check_writable(job->heatmap, "--heatmap", err)) ||
        (job->flip_map && pg_file_check_writable(job->flip_map, "--flip-map", err)) ||
        (job->json && strcmp(job->json, "-") && pg_file_check_writable(job->json, "--json", err))) {
        fprintf(stderr, "passgraph compare: %s\n", err->msg);
        return 2;
    }
    if (job->json && !strcmp(job->json, "-")) { /* the JSON alone on stdout, the report on stderr */
        fflush(stdout);
        job->json_fd = dup(STDOUT_FILENO);
        if (job->json_fd < 0 || dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
            fprintf(stderr, "passgraph compare: --json -: %s\n", strerror(errno));
            return 1;
        }
    }
    return -1;
}

/* Both sides created and rendered, frame by frame interleaved, then read back; the explain lines
 * between the two when asked for. */
static pg_result render_sides(const compare_job *job, pg_app *app, side *A, side *R, pg_frame_info *fi,
                              pg_error *err)
{
    const pg_cli_common *opt = &job->opt;
    pg_result r;
    if ((r = side_create(A, "pipeline", app, job->pipe_path, job->pipe_ov.ov, job->pipe_ov.n, opt->no_aliasing,
                         opt->immediate, opt->frames, err)))
        return r;
    if ((r = side_create(R, "reference", app, job->ref_path, job->ref_ov.ov, job->ref_ov.n, opt->no_aliasing,
                         opt->immediate, opt->frames, err)))
        return r;
    print_sides(A, &job->pipe_ov, R, &job->ref_ov, stdout);
    *fi = pg_app_frame(app);
    for (uint32_t f = 0; f < opt->frames; f++) { /* interleaved: both see the same device state */
        if ((r = side_render(A, fi, f, opt->frames, err))) return r;
        if ((r = side_render(R, fi, f, opt->frames, err))) return r;
    }
    if (opt->explain) {
        pg_app_print_explain_lighting(app, NULL, NULL, stdout);
        pg_app_print_explain_lighting(app, A->s, "the pipeline", stdout);
        pg_app_print_explain_lighting(app, R->s, "the reference", stdout);
        pg_print_explain(A->s, stdout);
        pg_print_explain(R->s, stdout);
        for (uint32_t k = 0; k < app->scene->n_warnings; k++)
            printf("explain: scene warning: %s\n", app->scene->warnings[k]);
    }
    if ((r = side_finish(A, opt->frames, err))) return r;
    return side_finish(R, opt->frames, err);
}

/* The image error of the pipeline against the reference, once the sizes agree. */
static pg_result measure_error(const side *A, const side *R, double threshold, pg_image_error *e, pg_error *err)
{
    pg_result r;
    if ((r = pg_image_sizes_match("output (display)", A->lw, A->lh, R->lw, R->lh, err)) ||
        (r = pg_image_sizes_match("hdr_output", A->hw, A->hh, R->hw, R->hh, err)) ||
        (r = pg_image_sizes_match("hdr_output vs output", A->hw, A->hh, A->lw, A->lh, err)))
        return r;
    return pg_image_error_compute(A->hdr, R->hdr, A->ldr, R->ldr, A->lw, A->lh, threshold, e, err);
}

/* The pipeline's frames beyond frame 0 (frame_metrics.h): its measured image becomes the mean of
 * --accumulate frames (sample 0..N-1), and the flicker sums of --flicker-frames frames are taken. */
static pg_result sample_pipeline(const compare_job *job, side *A, const pg_frame_info *fi, extra_measures *m,
                                 pg_error *err)
{
    if (job->accumulate <= 1 && job->flicker_frames < 2) return PG_OK;
    pg_result r = pg_image_sizes_match("hdr_output vs output", A->hw, A->hh, A->lw, A->lh, err);
    if (r) return r;
    const size_t n = (size_t)A->lw * A->lh * 4;
    uint8_t *ldr0 = malloc(n), *ldr = malloc(n);
    float *hdr = malloc(n * sizeof(float));
    if (!ldr0 || !ldr || !hdr) {
        r = pg_fail(err, PG_ERR_OOM, "out of memory");
    } else {
        memcpy(ldr0, A->ldr, n); /* the runtime's read-back memory: the next frame overwrites it */
        r = pg_sample_frames(A->s, fi, job->accumulate, job->flicker_frames, A->hdr, ldr0, A->lw, A->lh, hdr, ldr,
                             &m->fl, &m->extra_frames, err);
        if (r) pg_error_prefix(err, "pipeline");
    }
    free(ldr0);
    if (r) {
        free(ldr);
        free(hdr);
        return r;
    }
    free(A->hdr);
    A->hdr = hdr;
    free(A->ldr_own);
    A->ldr = A->ldr_own = ldr;
    return PG_OK;
}

/* The perceptual metrics and the flicker of the measured image, and the FLIP map (--flip-map). */
static pg_result measure_extra(const compare_job *job, const side *A, const side *R, const pg_image_error *e,
                               extra_measures *m, pg_error *err)
{
    const size_t px = (size_t)e->width * e->height;
    float *map = job->flip_map ? malloc(px * sizeof(float)) : NULL;
    uint8_t *rgba = job->flip_map ? malloc(px * 4) : NULL;
    pg_result r = PG_OK;
    if (job->flip_map && (!map || !rgba)) r = pg_fail(err, PG_ERR_OOM, "out of memory");
    if (!r) r = pg_perceptual_compute(A->hdr, R->hdr, A->ldr, R->ldr, e->width, e->height, !job->no_hdr_flip, map,
                                      &m->pm, err);
    m->flicker = job->flicker_frames >= 2 ? pg_flicker_value(&m->fl, R->hdr, e->width, e->height) : NAN;
    if (!r && job->flip_map) {
        pg_flip_map_rgba(map, e->width, e->height, rgba);
        if ((r = pg_write_image(job->flip_map, rgba, e->width, e->height, err))) pg_error_prefix(err, "--flip-map");
    }
    free(map);
    free(rgba);
    return r;
}

/* The report's perceptual and temporal lines. */
static void print_measures(const compare_job *job, const side *A, const extra_measures *m)
{
    char b1[32], b2[32], b3[32];
    printf("%-10s flip=%s (LDR-FLIP mean of the display images, %.4g ppd) ssim=%s (display luma)", "perceptual",
           num(b1, sizeof b1, m->pm.flip), PG_FLIP_DEFAULT_PPD, num(b2, sizeof b2, m->pm.ssim));
    if (job->no_hdr_flip) printf(" hdr_flip=nan (--no-hdr-flip)");
    else
        printf(" hdr_flip=%s (HDR-FLIP over %u exposures, %s .. %s stops)", num(b1, sizeof b1, m->pm.hdr_flip),
               m->pm.hdr.exposures, num(b2, sizeof b2, m->pm.hdr.start_exposure),
               num(b3, sizeof b3, m->pm.hdr.stop_exposure));
    printf("; %.0f ms CPU\n", m->pm.cpu_ms);
    char fl[96] = "not measured: --flicker-frames 0";
    if (job->flicker_frames)
        snprintf(fl, sizeof fl, "%u frames, sample 0..%u; mean |frame k - frame k-1| / reference mean RGB",
                 job->flicker_frames, job->flicker_frames - 1);
    printf("%-10s flicker=%s (%s) accumulate=%u (the measured image is the mean of %u frames: %.3f GPU ms)\n",
           "temporal", num(b1, sizeof b1, m->flicker), fl, job->accumulate, job->accumulate, A->gpu_ms * job->accumulate);
    if (job->flip_map) printf("%-10s %s (LDR-FLIP per pixel over [0, 1])\n", "flip map", job->flip_map);
}

/* The heatmap of the linear error, its scale chosen by --heatmap-scale (or the 99th percentile). */
static pg_result write_heatmap(const compare_job *job, const side *A, const side *R, const pg_image_error *e,
                               heat_scale_used *used, pg_error *err)
{
    uint8_t *heat = malloc((size_t)e->width * e->height * 4);
    if (!heat) return pg_fail(err, PG_ERR_OOM, "out of memory");
    const char *how = job->heat_scale_arg > 0 ? "--heatmap-scale" : "the largest error";
    double heat_scale;
    if (job->heat_scale_arg < 0) {
        heat_scale = pg_error_quantile(A->hdr, R->hdr, e->width, e->height, 0.99);
        if (heat_scale > 0) how = "99th percentile of the differing pixels' errors";
    } else {
        heat_scale = job->heat_scale_arg;
    }
    heat_scale = pg_error_heatmap_scale(A->hdr, R->hdr, e->width, e->height, heat_scale);
    used->scale = heat_scale;
    if (e->max_abs_linear == 0 && job->heat_scale_arg <= 0) { /* not the scale's internal floor */
        used->scale = 0;
        how = "no pixel differs: the map is black";
    }
    snprintf(used->how, sizeof used->how, "%s", how);
    pg_error_heatmap(A->hdr, R->hdr, e->width, e->height, heat_scale, heat);
    pg_result r = pg_write_image(job->heatmap, heat, e->width, e->height, err);
    if (r) pg_error_prefix(err, "--heatmap");
    free(heat);
    return r;
}

/* The report for people: both sides, the frame, the linear and display errors, the threshold,
 * the files written. */
static void print_report(const compare_job *job, const pg_app *app, const side *A, const side *R,
                         const pg_frame_info *fi, const pg_image_error *e, const heat_scale_used *heat)
{
    char b1[32], b2[32], b3[32], b4[32];
    side_print(A, stdout);
    side_print(R, stdout);
    printf("%-10s %s %ux%u lights=%u time=%g seed=%u frames=%u\n", "frame", app->scene_path, e->width, e->height,
           fi->lights.count, (double)job->opt.time, job->opt.seed, job->opt.frames);
    printf("%-10s rmse=%s psnr=%s dB max_abs=%s (HDR RGB; PSNR peak %s = reference max; %llu pixels compared;"
           " nonfinite pixels: pipeline %llu, reference %llu)\n",
           "linear", num(b1, sizeof b1, e->rmse_linear), num(b2, sizeof b2, e->psnr_linear),
           num(b3, sizeof b3, e->max_abs_linear), num(b4, sizeof b4, e->peak_linear),
           (unsigned long long)e->compared_linear, (unsigned long long)e->nonfinite_a,
           (unsigned long long)e->nonfinite_b);
    printf("%-10s rmse=%s psnr=%s dB max_abs=%s (8-bit RGB, 0..255; PSNR peak 255)\n", "display",
           num(b1, sizeof b1, e->rmse_display), num(b2, sizeof b2, e->psnr_display),
           num(b3, sizeof b3, e->max_abs_display));
    printf("%-10s %llu of %llu pixels (%.4f%%) differ by more than %g in some display channel\n", "threshold",
           (unsigned long long)e->over_threshold, (unsigned long long)e->width * e->height,
           100.0 * e->share_over_threshold, job->threshold);
    if (job->heatmap)
        printf("%-10s %s (max RGB |linear error| over [0, %s]: %s)\n", "heatmap", job->heatmap,
               num(b1, sizeof b1, heat->scale), heat->how);
    if (job->json) printf("%-10s %s\n", "json", job->json_fd >= 0 ? "(the standard output)" : job->json);
}

/* The one-line summary for scripts: "compare: key=value ...". */
static void print_summary_line(const side *A, const side *R, const pg_frame_info *fi, const pg_image_error *e,
                               const extra_measures *m, uint32_t accumulate)
{
    char b1[32], b2[32], b3[32], b4[32];
    printf("compare: pipeline=%s reference=%s lights=%u size=%ux%u", A->s->pipeline->name, R->s->pipeline->name,
           fi->lights.count, e->width, e->height);
    printf(" rmse_linear=%s psnr_linear=%s max_abs_linear=%s", num(b1, sizeof b1, e->rmse_linear),
           num(b2, sizeof b2, e->psnr_linear), num(b3, sizeof b3, e->max_abs_linear));
    printf(" rmse_display=%s psnr_display=%s max_abs_display=%s", num(b1, sizeof b1, e->rmse_display),
           num(b2, sizeof b2, e->psnr_display), num(b3, sizeof b3, e->max_abs_display));
    printf(" over_threshold=%s nonfinite=%llu reference_nonfinite=%llu gpu_ms=%.3f reference_gpu_ms=%.3f",
           num(b1, sizeof b1, e->share_over_threshold), (unsigned long long)e->nonfinite_a,
           (unsigned long long)e->nonfinite_b, A->gpu_ms, R->gpu_ms);
    side_print_overflow(A, "", stdout);
    side_print_overflow(R, "reference_", stdout);
    printf(" flip=%s hdr_flip=%s ssim=%s flicker=%s accumulate=%u\n", num(b1, sizeof b1, m->pm.flip),
           num(b2, sizeof b2, m->pm.hdr_flip), num(b3, sizeof b3, m->pm.ssim), num(b4, sizeof b4, m->flicker),
           accumulate);
}

/* Render both sides, measure, write the heatmap and JSON, report: the exit status (0 or 1). */
static int run_compare(const compare_job *job, pg_app *app, pg_error *err)
{
    int rc = 1;
    side A, R;
    memset(&A, 0, sizeof A);
    memset(&R, 0, sizeof R);
    pg_frame_info fi;
    pg_image_error e;
    heat_scale_used heat = {0, ""};
    extra_measures m;
    memset(&m, 0, sizeof m);
    m.flicker = m.pm.flip = m.pm.hdr_flip = m.pm.ssim = NAN;
    if (render_sides(job, app, &A, &R, &fi, err) || sample_pipeline(job, &A, &fi, &m, err) ||
        measure_error(&A, &R, job->threshold, &e, err) || measure_extra(job, &A, &R, &e, &m, err) ||
        (job->heatmap && write_heatmap(job, &A, &R, &e, &heat, err)) ||
        (job->json && write_json(job, &A, &R, app, heat.scale, &e, &m, err)))
        goto done;
    print_report(job, app, &A, &R, &fi, &e, &heat);
    print_measures(job, &A, &m);
    print_summary_line(&A, &R, &fi, &e, &m, job->accumulate);
    bool inexact = pg_app_check_exact("passgraph compare", "the pipeline's image", &A.st, job->opt.require_exact);
    inexact |= pg_app_check_exact("passgraph compare", "the reference image", &R.st, job->opt.require_exact) != 0;
    rc = inexact && job->opt.require_exact;
    if (app->gpu->validation && app->gpu->validation_messages) {
        fprintf(stderr, "passgraph compare: %u validation message(s)\n", app->gpu->validation_messages);
        rc = 1;
    }
done:
    if (rc && err->code) fprintf(stderr, "passgraph compare: %s\n", err->msg);
    side_free(&A);
    side_free(&R);
    return rc;
}

int pg_cmd_compare(int argc, char **argv)
{
    compare_job job;
    pg_error err = {0};
    int rc = parse_args(&job, argc, argv, &err);
    if (rc < 0) rc = resolve_sides(&job, &err);
    if (rc >= 0) return rc;
    pg_app app;
    if (pg_app_open(&app, &job.opt, true, &err)) {
        fprintf(stderr, "passgraph compare: %s\n", err.msg);
        return 1;
    }
    rc = run_compare(&job, &app, &err);
    pg_app_close(&app);
    return rc;
}
