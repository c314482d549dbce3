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

int pg_cmd_render(int argc, char **argv)
{
    pg_cli_common opt;
    pg_cli_defaults(&opt);
    pg_error err = {0};
    const char *hdr_out = NULL, *capture = NULL;
    for (int i = 0; i < argc; i++) {
        bool used;
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("%s%s%s", render_help, pg_cli_common_help, render_out_help);
            return 0;
        }
        if (!strcmp(argv[i], "--hdr-out")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "passgraph render: --hdr-out: missing value\n");
                return 2;
            }
            hdr_out = argv[++i];
            if (!ends_with_exr(hdr_out)) {
                fprintf(stderr, "passgraph render: --hdr-out %s: expected a .exr file name\n", hdr_out);
                return 2;
            }
            continue;
        }
        if (!strcmp(argv[i], "--capture")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "passgraph render: --capture: missing value\n");
                return 2;
            }
            capture = argv[++i];
            size_t n = strlen(capture);
            if (n < 5 || strcasecmp(capture + n - 4, ".rdc")) {
                fprintf(stderr, "passgraph render: --capture %s: expected a .rdc file name\n", capture);
                return 2;
            }
            continue;
        }
        if (pg_cli_parse_common(&opt, argc, argv, &i, &used, &err)) {
            fprintf(stderr, "passgraph render: %s\n", err.msg);
            return 2;
        }
        if (!used) {
            fprintf(stderr, "passgraph render: unknown option '%s' (see passgraph render --help)\n", argv[i]);
            return 2;
        }
    }
    if (!opt.out) {
        fprintf(stderr, "passgraph render: --out FILE.png is required\n");
        return 2;
    }
    if (pg_image_path_check(opt.out, true, &err)) {
        fprintf(stderr, "passgraph render: --out %s\n", err.msg);
        return 2;
    }
    /* --out x.exr: the HDR image to x.exr and the display image to x.png */
    char png_path[PG_PATH_MAX], exr_path[PG_PATH_MAX] = "";
    if (ends_with_exr(opt.out)) {
        if (hdr_out) {
            fprintf(stderr, "passgraph render: --out %s and --hdr-out %s: give one EXR file\n", opt.out, hdr_out);
            return 2;
        }
        size_t n = strlen(opt.out);
        if (n >= sizeof png_path) {
            fprintf(stderr, "passgraph render: --out %s: path too long\n", opt.out);
            return 2;
        }
        pg_strlcpy(exr_path, opt.out, sizeof exr_path);
        pg_strlcpy(png_path, opt.out, sizeof png_path);
        memcpy(png_path + n - 4, ".png", 4);
    } else {
        pg_strlcpy(png_path, opt.out, sizeof png_path);
        if (hdr_out && !pg_strlcpy(exr_path, hdr_out, sizeof exr_path)) {
            fprintf(stderr, "passgraph render: --hdr-out %s: path too long\n", hdr_out);
            return 2;
        }
    }
    /* every output can be written: checked before the device is made, with the OS reason */
    {
        const char *outs[3] = {png_path, exr_path[0] ? exr_path : NULL, capture};
        const char *names[3] = {"--out", exr_path[0] && !hdr_out ? "--out" : "--hdr-out", "--capture"};
        for (int k = 0; k < 3; k++) {
            if (!outs[k]) continue;
            if (pg_file_check_writable(outs[k], names[k], &err)) {
                fprintf(stderr, "passgraph render: %s\n", err.msg);
                return 2;
            }
        }
    }
    /* RenderDoc first: without it there is nothing to do, and the device need not be made */
    pg_rdoc *rdoc = NULL;
    if (capture) {
        char why[512];
        rdoc = pg_rdoc_open(why, sizeof why);
        if (!rdoc) {
            fprintf(stderr, "passgraph render: --capture %s: %s\n", capture, why);
            return 1;
        }
        char tmpl[PG_PATH_MAX];
        snprintf(tmpl, sizeof tmpl, "%.*s", (int)(strlen(capture) - 4), capture);
        pg_rdoc_set_path_template(rdoc, tmpl);
    }
    pg_app app;
    if (pg_app_open(&app, &opt, true, &err)) {
        fprintf(stderr, "passgraph render: %s\n", err.msg);
        return 1;
    }
    /* --size against the device, and a word when the frame is big */
    if (pg_size_note_check(&app, "passgraph render", stderr, &err)) {
        fprintf(stderr, "passgraph render: %s\n", err.msg);
        pg_app_close(&app);
        free(rdoc);
        return 2;
    }
    int rc = 1;
    pg_session *s = NULL;
    float *hdr = NULL;
    pg_session_desc sd = pg_app_session_desc(&app);
    if (pg_session_create(app.gpu, app.scene_gpu, &sd, &s, &err)) goto done;
    pg_frame_info fi = pg_app_frame(&app);
    /* per frame: GPU total, every pass's time, then (two-queue plans) every pass's start, the
     * compute/graphics overlap and the assign_lights/G-buffer overlap */
    double *samples = calloc((size_t)opt.frames * (2 * PG_MAX_PASSES + 3), sizeof(double));
    if (!samples) {
        pg_fail(&err, PG_ERR_OOM, "out of memory");
        goto done;
    }
    pg_frame_stats st = {0};
    uint32_t waits_checked = 0, waits_unordered = 0;
    pg_grow_event grown[4];
    uint32_t n_grown = 0, rerenders = 0;
    for (uint32_t f = 0; f < opt.frames; f++) {
        bool captured = rdoc && f + 1 == opt.frames;
        if (captured) pg_rdoc_begin(rdoc);
        pg_result fr = pg_session_render(s, &fi, f + 1 == opt.frames, &st, &err);
        char why[600];
        if (captured && !pg_rdoc_end(rdoc, capture, why, sizeof why) && !fr) {
            pg_fail(&err, PG_ERR_IO, "--capture %s: %s", capture, why);
            fr = err.code;
        }
        if (fr) {
            free(samples);
            goto done;
        }
        for (uint32_t k = 0; k < st.n_grown && n_grown < 4; k++) grown[n_grown++] = st.grown[k];
        rerenders += st.rerenders;
        samples[f] = st.gpu_total_ms;
        for (uint32_t p = 0; p < st.n_passes; p++) samples[(size_t)(p + 1) * opt.frames + f] = st.pass_ms[p];
        if (st.n_batches > 1) {
            /* intervals on one timebase (both queues' timestamps): overlaps, and every wait ordered */
            double ov = 0, ov_ag = 0;
            for (uint32_t c = 0; c < st.n_passes; c++)
                for (uint32_t g = 0; g < st.n_passes; g++) {
                    if (st.pass_queue[c] != PG_QUEUE_COMPUTE || st.pass_queue[g] != PG_QUEUE_GRAPHICS) continue;
                    const double cs = st.pass_start_ms[c], ce = cs + st.pass_ms[c];
                    const double gs = st.pass_start_ms[g], ge = gs + st.pass_ms[g];
                    const double o = (ce < ge ? ce : ge) - (cs > gs ? cs : gs);
                    if (o > 0) ov += o;
                    if (o > 0 && !strcmp(st.pass_names[c], "assign_lights") && !strncmp(st.pass_names[g], "gbuffer", 7))
                        ov_ag += o;
                }
            for (uint32_t p = 0; p < st.n_passes; p++)
                samples[(size_t)(PG_MAX_PASSES + 1 + p) * opt.frames + f] = st.pass_start_ms[p];
            samples[(size_t)(2 * PG_MAX_PASSES + 1) * opt.frames + f] = ov;
            samples[(size_t)(2 * PG_MAX_PASSES + 2) * opt.frames + f] = ov_ag;
            const pg_graph_plan *pl = s->plan;
            for (uint32_t b = 0; b < pl->n_batches; b++)
                for (uint32_t w = 0; w < pl->batches[b].n_waits; w++) {
                    const pg_plan_batch *A = &pl->batches[pl->batches[b].waits[w].batch], *B = &pl->batches[b];
                    double ea = 0, eb = 0;
                    for (uint32_t o = A->first; o < A->first + A->count; o++)
                        if (st.pass_start_ms[o] + st.pass_ms[o] > ea) ea = st.pass_start_ms[o] + st.pass_ms[o];
                    for (uint32_t o = B->first; o < B->first + B->count; o++)
                        if (st.pass_start_ms[o] + st.pass_ms[o] > eb) eb = st.pass_start_ms[o] + st.pass_ms[o];
                    waits_checked++;
                    if (B->count && eb + 1e-6 < ea) waits_unordered++;
                }
        }
    }
    if (opt.explain) {
        printf("explain: %s\nexplain: %s\n", app.camera_why, app.lights_why);
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
        for (uint32_t k = 0; k < app.scene->n_warnings; k++)
            printf("explain: scene warning: %s\n", app.scene->warnings[k]);
    }
    uint32_t w, h;
    pg_format fmt;
    const uint8_t *ldr = pg_runtime_output(s->runtime, 0, &w, &h, &fmt);
    if (!ldr || pg_format_get(fmt)->bytes_per_pixel != 4) {
        pg_fail(&err, PG_ERR_FORMAT, "%s: output '%s' must be an 8-bit RGBA image to write %s",
                s->pipeline->path, s->pipeline->output, png_path);
        free(samples);
        goto done;
    }
    if (pg_write_image(png_path, ldr, w, h, &err)) {
        free(samples);
        goto done;
    }
    long long nonfinite = -1;
    uint32_t hw, hh;
    pg_format hfmt;
    const void *hpix = pg_runtime_output(s->runtime, 1, &hw, &hh, &hfmt);
    if (hpix) {
        hdr = malloc((size_t)hw * hh * 4 * sizeof(float));
        if (hdr && !pg_hdr_to_float(hpix, hfmt, hw, hh, hdr, &err)) nonfinite = (long long)pg_count_nonfinite(hdr, hw, hh);
    }
    if (exr_path[0]) {
        if (!hpix || nonfinite < 0) {
            if (!hpix)
                pg_fail(&err, PG_ERR_NO_OUTPUT, "%s: pipeline '%s' declares no hdr_output to write to %s",
                        s->pipeline->path, s->pipeline->name, exr_path);
            else if (!hdr)
                pg_fail(&err, PG_ERR_OOM, "out of memory");
            free(samples);
            goto done;
        }
        if (pg_exr_write_rgba(exr_path, hdr, hw, hh, hfmt != PG_FMT_RGBA32F, &err)) {
            free(samples);
            goto done;
        }
    }
    for (uint32_t k = 0; k < st.n_notes; k++) printf("note: %s\n", st.notes[k]);
    printf("render: %s %ux%u lights=%u gpu=%.3f ms [", s->pipeline->name, w, h, fi.lights.count,
           pg_median(samples, opt.frames));
    for (uint32_t p = 0; p < st.n_passes; p++)
        printf("%s%s %.3f", p ? ", " : "", st.pass_names[p], pg_median(samples + (size_t)(p + 1) * opt.frames, opt.frames));
    if (nonfinite >= 0) printf("] nonfinite=%lld", nonfinite);
    else printf("] nonfinite=n/a");
    bool clustered = false;
    for (uint32_t k = 0; k < st.n_counters; k++) clustered |= !strcmp(st.counters[k].name, "overflow_clusters");
    if (clustered) {
        printf(" overflow=%llu clusters (%llu light refs dropped)", (unsigned long long)pg_frame_counter_sum(&st, "overflow_clusters"),
               (unsigned long long)pg_frame_counter_sum(&st, "overflow_dropped"));
        uint64_t list_bytes = 0, refs = 0;
        for (uint32_t k = 0; k < st.n_counters; k++) {
            if (!strcmp(st.counters[k].name, "list_bytes")) list_bytes += st.counters[k].value;
            if (!strcmp(st.counters[k].name, "total_refs")) refs += st.counters[k].value;
        }
        printf(" refs=%llu lists=%.2f MiB", (unsigned long long)refs, list_bytes / 1048576.0);
    }
    /* buffers that grew while rendering (the frames were rendered again: see pg_session_render) */
    for (uint32_t k = 0; k < n_grown; k++)
        printf(" grew %s %.2f->%.2f MiB", grown[k].resource, grown[k].old_bytes / 1048576.0,
               grown[k].new_bytes / 1048576.0);
    if (n_grown) printf(" (%u re-render%s)", rerenders, rerenders == 1 ? "" : "s");
    printf(" frames=%u -> %s%s%s%s%s\n", opt.frames, png_path, exr_path[0] ? ", " : "", exr_path,
           capture ? ", capture " : "", capture ? capture : "");
    if (st.n_batches > 1) { /* the two-queue plan: where each pass ran and when (medians) */
        printf("queues: %u batches [", st.n_batches);
        for (uint32_t p = 0; p < st.n_passes; p++)
            printf("%s%s %s @%.3f+%.3f", p ? ", " : "", st.pass_names[p], pg_queue_name((pg_queue)st.pass_queue[p]),
                   pg_median(samples + (size_t)(PG_MAX_PASSES + 1 + p) * opt.frames, opt.frames),
                   pg_median(samples + (size_t)(p + 1) * opt.frames, opt.frames));
        printf("] overlap compute/graphics=%.3f ms, assign_lights/gbuffer=%.3f ms; waits ordered on the common "
               "timebase: %u of %u\n",
               pg_median(samples + (size_t)(2 * PG_MAX_PASSES + 1) * opt.frames, opt.frames),
               pg_median(samples + (size_t)(2 * PG_MAX_PASSES + 2) * opt.frames, opt.frames),
               waits_checked - waits_unordered, waits_checked);
    }
    free(samples);
    rc = 0;
    if (app.gpu->validation && app.gpu->validation_messages) {
        fprintf(stderr, "passgraph render: %u validation message(s)\n", app.gpu->validation_messages);
        rc = 1;
    }
done:
    if (rc && err.code) fprintf(stderr, "passgraph render: %s\n", err.msg);
    free(hdr);
    pg_session_destroy(s);
    pg_app_close(&app);
    free(rdoc);
    return rc;
}
