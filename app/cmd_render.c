/* cmd_render.c - `passgraph render`: one reproducible frame to a PNG (the display image, through
 * the pipeline's display pass) and optionally an OpenEXR file (the linear HDR output), with GPU
 * timings. */
#include "pg_file.h"
#include "size_note.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "app.h"
#include "bench_stats.h"
#include "commands.h"
#include "exr.h"
#include "image_util.h"
#include "rdoc.h"
#include "sides.h"

static const char *const render_help =
    "usage: passgraph render [options] --out FILE.png|FILE.jpg|FILE.exr [--hdr-out FILE.exr]\n"
    "Renders one frame of a scene with a pipeline, headless, and writes the display image.\n"
    "Prints one summary line: GPU ms in total and per pass (timestamps; median over --frames),\n"
    "and the number of non-finite pixels in the HDR output.\n\n"
    "options:\n";

static const char *const render_out_help =
    "  --out FILE.png       where to write the display image (8-bit, through the display pass: the\n"
    "                       OCIO view, see --display / --view); FILE.jpg / FILE.jpeg write a JPEG\n"
    "                       (quality 95); other extensions are refused\n"
    "  --out FILE.exr       write the linear HDR image (the pipeline's hdr_output, scene-linear\n"
    "                       Rec.709, RGBA half floats for rgba16f, floats for rgba32f) to FILE.exr\n"
    "                       AND the display image to FILE.png\n"
    "  --hdr-out FILE.exr   write the linear HDR image to FILE.exr as well (with --out FILE.png)\n"
    "  --capture FILE.rdc   capture the last frame with RenderDoc's in-application API into\n"
    "                       FILE.rdc (every pass a labelled region, every resource named); needs\n"
    "                       passgraph started under RenderDoc: renderdoccmd capture -w passgraph\n"
    "                       render --capture FILE.rdc ... (else an error, exit status 1)\n";

static bool ends_with_exr(const char *p)
{
    size_t n = strlen(p);
    return n >= 4 && !strcasecmp(p + n - 4, ".exr");
}

void pg_print_explain(const pg_session *s, FILE *f)
{
    const pg_graph_plan *p = s->plan;
    fprintf(f, "explain: %s: %u passes run, %u culled; transient memory %.2f MiB -> %.2f MiB with aliasing%s\n",
            s->pipeline->name, p->n_order, p->n_passes - p->n_order, p->transient_bytes_unaliased / 1048576.0,
            p->transient_bytes_aliased / 1048576.0, p->aliasing_disabled ? " (aliasing disabled)" : "");
    for (uint32_t i = 0; i < p->n_explain; i++) fprintf(f, "explain:   %s\n", p->explain[i]);
    pg_graph_plan_print(p, s->pipeline, f);
}

/* the command line of one render, and the files it writes */
typedef struct render_opts {
    pg_cli_common opt;
    const char *hdr_out, *capture;
    char png_path[PG_PATH_MAX], exr_path[PG_PATH_MAX]; /* exr_path "" when none */
} render_opts;

/* --hdr-out FILE.exr and --capture FILE.rdc: the value, or NULL (said on stderr) */
static const char *file_option(const char *option, const char *ext, int argc, char **argv, int *i)
{
    if (*i + 1 >= argc) {
        fprintf(stderr, "passgraph render: %s: missing value\n", option);
        return NULL;
    }
    const char *v = argv[++*i];
    size_t n = strlen(v);
    bool ok = !strcmp(ext, ".exr") ? ends_with_exr(v) : !(n < 5 || strcasecmp(v + n - 4, ext));
    if (!ok) {
        fprintf(stderr, "passgraph render: %s %s: expected a %s file name\n", option, v, ext);
        return NULL;
    }
    return v;
}

/* the render options, then the common ones; -1 to go on, else the exit code (0 after --help, 2
 * after a message on stderr) */
static int parse_render_options(render_opts *ro, int argc, char **argv)
{
    pg_error err = {0};
    for (int i = 0; i < argc; i++) {
        bool used;
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("%s%s%s", render_help, pg_cli_common_help, render_out_help);
            return 0;
        }
        if (!strcmp(argv[i], "--hdr-out")) {
            if (!(ro->hdr_out = file_option("--hdr-out", ".exr", argc, argv, &i))) return 2;
            continue;
        }
        if (!strcmp(argv[i], "--capture")) {
            if (!(ro->capture = file_option("--capture", ".rdc", argc, argv, &i))) return 2;
            continue;
        }
        if (pg_cli_parse_common(&ro->opt, argc, argv, &i, &used, &err)) {
            fprintf(stderr, "passgraph render: %s\n", err.msg);
            return 2;
        }
        if (!used) {
            fprintf(stderr, "passgraph render: unknown option '%s' (see passgraph render --help)\n", argv[i]);
            return 2;
        }
    }
    return -1;
}

/* The files written: --out x.exr is the HDR image to x.exr and the display image to x.png; every
 * output can be written (checked before the device is made, with the OS reason). false after a
 * message on stderr. */
static bool resolve_outputs(render_opts *ro)
{
    const pg_cli_common *opt = &ro->opt;
    pg_error err = {0};
    if (!opt->out) {
        fprintf(stderr, "passgraph render: --out FILE.png is required\n");
        return false;
    }
    if (pg_image_path_check(opt->out, true, &err)) {
        fprintf(stderr, "passgraph render: --out %s\n", err.msg);
        return false;
    }
    ro->exr_path[0] = 0;
    if (ends_with_exr(opt->out)) {
        if (ro->hdr_out) {
            fprintf(stderr, "passgraph render: --out %s and --hdr-out %s: give one EXR file\n", opt->out, ro->hdr_out);
            return false;
        }
        size_t n = strlen(opt->out);
        if (n >= sizeof ro->png_path) {
            fprintf(stderr, "passgraph render: --out %s: path too long\n", opt->out);
            return false;
        }
        pg_strlcpy(ro->exr_path, opt->out, sizeof ro->exr_path);
        pg_strlcpy(ro->png_path, opt->out, sizeof ro->png_path);
        memcpy(ro->png_path + n - 4, ".png", 4);
    } else {
        if (!pg_strlcpy(ro->png_path, opt->out, sizeof ro->png_path)) { /* cut, it named another file */
            fprintf(stderr, "passgraph render: --out %s: path too long\n", opt->out);
            return false;
        }
        if (ro->hdr_out && !pg_strlcpy(ro->exr_path, ro->hdr_out, sizeof ro->exr_path)) {
            fprintf(stderr, "passgraph render: --hdr-out %s: path too long\n", ro->hdr_out);
            return false;
        }
    }
    const char *outs[3] = {ro->png_path, ro->exr_path[0] ? ro->exr_path : NULL, ro->capture};
    const char *names[3] = {"--out", ro->exr_path[0] && !ro->hdr_out ? "--out" : "--hdr-out", "--capture"};
    for (int k = 0; k < 3; k++) {
        if (!outs[k]) continue;
        if (pg_file_check_writable(outs[k], names[k], &err)) {
            fprintf(stderr, "passgraph render: %s\n", err.msg);
            return false;
        }
    }
    return true;
}

/* RenderDoc for --capture FILE.rdc, its captures named FILE; false (said on stderr) without it */
static bool open_capture(const char *capture, pg_rdoc **out)
{
    char why[512];
    pg_rdoc *rdoc = pg_rdoc_open(why, sizeof why);
    if (!rdoc) {
        fprintf(stderr, "passgraph render: --capture %s: %s\n", capture, why);
        return false;
    }
    char tmpl[PG_PATH_MAX];
    snprintf(tmpl, sizeof tmpl, "%.*s", (int)(strlen(capture) - 4), capture);
    pg_rdoc_set_path_template(rdoc, tmpl);
    *out = rdoc;
    return true;
}

/* What the frames measured: per frame the GPU total, every pass's time, then (two-queue plans)
 * every pass's start, the compute/graphics overlap and the assign_lights/G-buffer overlap, each
 * a row of `frames` samples; the last frame's stats; waits checked on the common timebase;
 * buffers that grew. */
typedef struct render_run {
    uint32_t frames;
    double *samples;
    pg_frame_stats st;
    uint32_t waits_checked, waits_unordered;
    pg_grow_event grown[4];
    uint32_t n_grown, rerenders;
} render_run;

/* row r of the samples (0 total, 1 + p pass p's time, PG_MAX_PASSES + 1 + p pass p's start,
 * 2 * PG_MAX_PASSES + 1 and + 2 the two overlaps) */
static double *sample_row(const render_run *r, size_t row) { return r->samples + row * r->frames; }

/* a two-queue frame f: pass starts, overlaps (intervals on one timebase, both queues'
 * timestamps), and whether every wait's batch ended before the waiting batch did */
static void record_queue_samples(const pg_graph_plan *pl, render_run *r, uint32_t f)
{
    const pg_frame_stats *st = &r->st;
    double ov = 0, ov_ag = 0;
    for (uint32_t c = 0; c < st->n_passes; c++)
        for (uint32_t g = 0; g < st->n_passes; g++) {
            if (st->pass_queue[c] != PG_QUEUE_COMPUTE || st->pass_queue[g] != PG_QUEUE_GRAPHICS) continue;
            const double cs = st->pass_start_ms[c], ce = cs + st->pass_ms[c];
            const double gs = st->pass_start_ms[g], ge = gs + st->pass_ms[g];
            const double o = (ce < ge ? ce : ge) - (cs > gs ? cs : gs);
            if (o > 0) ov += o;
            if (o > 0 && !strcmp(st->pass_names[c], "assign_lights") && !strncmp(st->pass_names[g], "gbuffer", 7))
                ov_ag += o;
        }
    for (uint32_t p = 0; p < st->n_passes; p++) sample_row(r, PG_MAX_PASSES + 1 + p)[f] = st->pass_start_ms[p];
    sample_row(r, 2 * PG_MAX_PASSES + 1)[f] = ov;
    sample_row(r, 2 * PG_MAX_PASSES + 2)[f] = ov_ag;
    for (uint32_t b = 0; b < pl->n_batches; b++)
        for (uint32_t w = 0; w < pl->batches[b].n_waits; w++) {
            const pg_plan_batch *A = &pl->batches[pl->batches[b].waits[w].batch], *B = &pl->batches[b];
            double ea = 0, eb = 0;
            for (uint32_t o = A->first; o < A->first + A->count; o++)
                if (st->pass_start_ms[o] + st->pass_ms[o] > ea) ea = st->pass_start_ms[o] + st->pass_ms[o];
            for (uint32_t o = B->first; o < B->first + B->count; o++)
                if (st->pass_start_ms[o] + st->pass_ms[o] > eb) eb = st->pass_start_ms[o] + st->pass_ms[o];
            r->waits_checked++;
            if (B->count && eb + 1e-6 < ea) r->waits_unordered++;
        }
}

/* the frames, the last one read back (and captured with --capture) */
static pg_result render_frames(pg_session *s, const pg_frame_info *fi, pg_rdoc *rdoc, const char *capture,
                               render_run *r, pg_error *err)
{
    pg_frame_stats *st = &r->st;
    for (uint32_t f = 0; f < r->frames; f++) {
        bool captured = rdoc && f + 1 == r->frames;
        if (captured) pg_rdoc_begin(rdoc);
        pg_result fr = pg_session_render(s, fi, f + 1 == r->frames, st, err);
        char why[600];
        if (captured && !pg_rdoc_end(rdoc, capture, why, sizeof why) && !fr) {
            pg_fail(err, PG_ERR_IO, "--capture %s: %s", capture, why);
            fr = err->code;
        }
        if (fr) return fr;
        for (uint32_t k = 0; k < st->n_grown && r->n_grown < 4; k++) r->grown[r->n_grown++] = st->grown[k];
        r->rerenders += st->rerenders;
        r->samples[f] = st->gpu_total_ms;
        for (uint32_t p = 0; p < st->n_passes; p++) sample_row(r, p + 1)[f] = st->pass_ms[p];
        if (st->n_batches > 1) record_queue_samples(s->plan, r, f);
    }
    return PG_OK;
}

/* --explain: the camera, lights, plan, device memory, run-time options and scene warnings */
static void print_render_explain(const pg_app *app, const pg_session *s)
{
    pg_app_print_explain_lighting(app, s, NULL, stdout);
    pg_print_explain(s, stdout);
    const pg_runtime_stats rs = pg_runtime_get_stats(s->runtime);
    printf("explain: device transient memory %llu B unaliased -> %llu B aliased (real memory "
           "requirements; %u block(s) split at run time)\n",
           (unsigned long long)rs.memory_bytes_unaliased, (unsigned long long)rs.memory_bytes_transient,
           rs.blocks_fallback);
    printf("explain: runtime: plans set: memory %u, resources %u, pipelines %u, values %u (last: %s); run-time "
           "options (a new value re-creates nothing):",
           rs.memory_rebuilds, rs.resource_rebuilds, rs.pipeline_rebuilds, rs.value_updates,
           pg_rebuild_kind_name(rs.last_rebuild));
    uint32_t n_rt = 0;
    for (uint32_t o = 0; o < s->plan->n_order; o++) {
        const pg_plan_pass *pp = &s->plan->passes[s->plan->order[o]];
        for (uint32_t k = 0; pp->type->runtime_options && pp->type->runtime_options[k]; k++, n_rt++)
            printf(" %s.%s", pp->name, pp->type->runtime_options[k]);
    }
    printf("%s\n", n_rt ? "" : " none");
    for (uint32_t k = 0; k < app->scene->n_warnings; k++)
        printf("explain: scene warning: %s\n", app->scene->warnings[k]);
}

/* the written images: the display image's size, and the HDR output's non-finite pixel count (-1
 * when there is none to count) */
typedef struct render_images {
    uint32_t w, h;
    long long nonfinite;
    float *hdr; /* the HDR output as floats (owned), or NULL */
} render_images;

/* the display image to png_path; the HDR output counted and, with an EXR path, written */
static pg_result write_outputs(const pg_session *s, const render_opts *ro, render_images *im, pg_error *err)
{
    pg_format fmt;
    const uint8_t *ldr = pg_runtime_output(s->runtime, 0, &im->w, &im->h, &fmt);
    if (!ldr || (fmt != PG_FMT_RGBA8_UNORM && fmt != PG_FMT_RGBA8_SRGB)) /* 4 bytes a pixel is not enough: d32f, r32f */
        return pg_fail(err, PG_ERR_FORMAT, "%s: output '%s' must be an 8-bit RGBA image (rgba8 or rgba8_srgb) to write %s%s%s",
                       s->pipeline->path, s->pipeline->output, ro->png_path, ldr ? ", not " : "",
                       ldr ? pg_format_get(fmt)->name : "");
    pg_result r = pg_write_image(ro->png_path, ldr, im->w, im->h, err);
    if (r) return r;
    im->nonfinite = -1;
    uint32_t hw, hh;
    pg_format hfmt;
    const void *hpix = pg_runtime_output(s->runtime, 1, &hw, &hh, &hfmt);
    if (hpix) {
        im->hdr = malloc((size_t)hw * hh * 4 * sizeof(float));
        if (im->hdr && !pg_hdr_to_float(hpix, hfmt, hw, hh, im->hdr, err))
            im->nonfinite = (long long)pg_count_nonfinite(im->hdr, hw, hh);
    }
    if (!ro->exr_path[0]) return PG_OK;
    if (!hpix || im->nonfinite < 0) {
        if (!hpix)
            pg_fail(err, PG_ERR_NO_OUTPUT, "%s: pipeline '%s' declares no hdr_output to write to %s",
                    s->pipeline->path, s->pipeline->name, ro->exr_path);
        else if (!im->hdr)
            pg_fail(err, PG_ERR_OOM, "out of memory");
        return err->code ? err->code : PG_ERR_IO;
    }
    return pg_exr_write_rgba(ro->exr_path, im->hdr, hw, hh, hfmt != PG_FMT_RGBA32F, err);
}

/* the clustered passes' counters: overflow, light references and list bytes */
static void print_cluster_counters(const pg_frame_stats *st)
{
    if (!pg_frame_counter_has(st, "overflow_clusters")) return;
    printf(" overflow=%llu clusters (%llu light refs dropped)", (unsigned long long)pg_frame_counter_sum(st, "overflow_clusters"),
           (unsigned long long)pg_frame_counter_sum(st, "overflow_dropped"));
    uint64_t list_bytes = 0, refs = 0;
    for (uint32_t k = 0; k < st->n_counters; k++) {
        if (!strcmp(st->counters[k].name, "list_bytes")) list_bytes += st->counters[k].value;
        if (!strcmp(st->counters[k].name, "total_refs")) refs += st->counters[k].value;
    }
    printf(" refs=%llu lists=%.2f MiB", (unsigned long long)refs, list_bytes / 1048576.0);
}

/* the two-queue plan: where each pass ran and when (medians), the overlaps, the waits ordered */
static void print_queues(const render_run *r)
{
    const pg_frame_stats *st = &r->st;
    const uint32_t n = r->frames;
    printf("queues: %u batches [", st->n_batches);
    for (uint32_t p = 0; p < st->n_passes; p++)
        printf("%s%s %s @%.3f+%.3f", p ? ", " : "", st->pass_names[p], pg_queue_name((pg_queue)st->pass_queue[p]),
               pg_median(sample_row(r, PG_MAX_PASSES + 1 + p), n), pg_median(sample_row(r, p + 1), n));
    printf("] overlap compute/graphics=%.3f ms, assign_lights/gbuffer=%.3f ms; waits ordered on the common "
           "timebase: %u of %u\n",
           pg_median(sample_row(r, 2 * PG_MAX_PASSES + 1), n), pg_median(sample_row(r, 2 * PG_MAX_PASSES + 2), n),
           r->waits_checked - r->waits_unordered, r->waits_checked);
}

/* the notes, the render: line (medians per pass, non-finite pixels, counters, growth, files) and
 * the queues: line of a two-queue plan */
static void print_summary(const pg_session *s, const render_opts *ro, const pg_frame_info *fi,
                          const render_run *r, const render_images *im)
{
    const pg_frame_stats *st = &r->st;
    const uint32_t n = r->frames;
    for (uint32_t k = 0; k < st->n_notes; k++) printf("note: %s\n", st->notes[k]);
    printf("render: %s %ux%u lights=%u gpu=%.3f ms [", s->pipeline->name, im->w, im->h, fi->lights.count,
           pg_median(r->samples, n));
    for (uint32_t p = 0; p < st->n_passes; p++)
        printf("%s%s %.3f", p ? ", " : "", st->pass_names[p], pg_median(sample_row(r, p + 1), n));
    if (im->nonfinite >= 0) printf("] nonfinite=%lld", im->nonfinite);
    else printf("] nonfinite=n/a");
    print_cluster_counters(st);
    bool evals = false;
    for (uint32_t k = 0; k < st->n_counters; k++) evals |= !strcmp(st->counters[k].name, "light_evals");
    if (evals) {
        uint64_t ev = pg_frame_counter_sum(st, "light_evals");
        printf(" light_evals=%llu (%.1f a pixel)", (unsigned long long)ev, (double)ev / ((double)im->w * im->h));
    }
    /* buffers that grew while rendering (the frames were rendered again: see pg_session_render) */
    for (uint32_t k = 0; k < r->n_grown; k++)
        printf(" grew %s %.2f->%.2f MiB", r->grown[k].resource, r->grown[k].old_bytes / 1048576.0,
               r->grown[k].new_bytes / 1048576.0);
    if (r->n_grown) printf(" (%u re-render%s)", r->rerenders, r->rerenders == 1 ? "" : "s");
    printf(" frames=%u -> %s%s%s%s%s\n", n, ro->png_path, ro->exr_path[0] ? ", " : "", ro->exr_path,
           ro->capture ? ", capture " : "", ro->capture ? ro->capture : "");
    if (st->n_batches > 1) print_queues(r);
}

/* the session on an open app: the frames, --explain, the files, the summary; the exit code */
static int render_on_app(pg_app *app, const render_opts *ro, pg_rdoc *rdoc)
{
    pg_error err = {0};
    int rc = 1;
    pg_session *s = NULL;
    render_images im = {0};
    render_run run = {.frames = ro->opt.frames}, *r = &run;
    pg_session_desc sd = pg_app_session_desc(app);
    if (pg_app_session_create(app, &sd, &s, &err)) goto done;
    pg_frame_info fi = pg_app_frame(app);
    r->samples = calloc((size_t)r->frames * (2 * PG_MAX_PASSES + 3), sizeof(double));
    if (!r->samples) {
        pg_fail(&err, PG_ERR_OOM, "out of memory");
        goto done;
    }
    if (render_frames(s, &fi, rdoc, ro->capture, r, &err)) goto done;
    pg_app_note_unused_colour(app, s->plan, "passgraph render"); /* it was silent */
    if (ro->opt.explain) print_render_explain(app, s);
    if (write_outputs(s, ro, &im, &err)) goto done;
    print_summary(s, ro, &fi, r, &im);
    rc = pg_app_check_exact("passgraph render", "the image", &r->st, ro->opt.require_exact) && ro->opt.require_exact;
    if (app->gpu->validation && app->gpu->validation_messages) {
        fprintf(stderr, "passgraph render: %u validation message(s)\n", app->gpu->validation_messages);
        rc = 1;
    }
done:
    if (rc && err.code) fprintf(stderr, "passgraph render: %s\n", err.msg);
    free(r->samples);
    free(im.hdr);
    pg_session_destroy(s);
    return rc;
}

int pg_cmd_render(int argc, char **argv)
{
    render_opts ro = {0};
    pg_cli_defaults(&ro.opt);
    int rc = parse_render_options(&ro, argc, argv);
    if (rc >= 0) return rc;
    if (!resolve_outputs(&ro)) return 2;
    { /* --set and --debug-view against the pipeline's parameters: bad options, before a device is made */
        pg_error se = {0};
        if (pg_sides_check_common(&ro.opt, &se)) {
            fprintf(stderr, "passgraph render: %s\n", se.msg);
            return 2;
        }
    }
    /* RenderDoc first: without it there is nothing to do, and the device need not be made */
    pg_rdoc *rdoc = NULL;
    if (ro.capture && !open_capture(ro.capture, &rdoc)) return 1;
    pg_app app;
    pg_error err = {0};
    if (pg_app_open(&app, &ro.opt, true, &err)) {
        fprintf(stderr, "passgraph render: %s\n", err.msg);
        return 1;
    }
    /* --size against the device, and a word when the frame is big */
    if (pg_size_note_check(&app, "passgraph render", stderr, &err)) {
        fprintf(stderr, "passgraph render: %s\n", err.msg);
        rc = 2;
    } else {
        rc = render_on_app(&app, &ro, rdoc);
    }
    pg_app_close(&app);
    free(rdoc);
    return rc;
}
