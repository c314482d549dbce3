/* bench_run.c - `passgraph bench`: the progress bar, the reference frames and one row's run
 * (warm-up, timed frames, the error frame) with its statistics and its summary line. */
#include "bench.h"

/* set by cmd_bench.c's SIGINT handler; the row loop here stops at the next frame */
volatile sig_atomic_t g_interrupted;

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
double frame_work(uint32_t w, uint32_t h, uint32_t lights)
{
    return (double)w * h * ((double)lights + 64.0) * 1e-6;
}

void progress_draw(bench *B, const char *what, bool row_done)
{
    if (!B->progress) return;
    double t = pg_time_s();
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

void progress_clear(bench *B)
{
    if (B->progress && B->tty) fprintf(stderr, "\r\033[K");
}

/* ---------------------------------------------------------------- running */

bench_row *new_row(bench *B, pg_error *err)
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

void reference_free(reference *ref)
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
    if (!pg_app_session_create(app, &desc, &s, &e) && !pg_session_render(s, &fi, true, &st, &e) &&
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

/* the session of one row: its pipeline with the variant's overrides, the bench's options */
static pg_result open_row_session(const bench *B, pg_app *app, const pipe_entry *pe, const variant *va,
                                  pg_session **s, pg_error *e)
{
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
    pg_result r = pg_app_session_create(app, &desc, s, e);
    if (r) return r;
    return pg_session_set_frames_in_flight(*s, B->frames_in_flight, e);
}

/* timed frame f (runtime frame st->frame): CPU and wait times, the GPU times known so far (they
 * arrive later with 2 in flight: each timed frame's are fetched by its frame number and stored at
 * its own timed index), the pass names, the worst overflow */
static void record_timed_frame(const bench *B, const pg_session *s, const pg_frame_stats *st, uint32_t f,
                               uint64_t *first_timed, bench_row *row, double *samples)
{
    if (*first_timed == UINT64_MAX) *first_timed = st->frame;
    fetch_gpu(B, s->runtime, *first_timed, st->frame, st->n_passes, samples);
    samples[B->opt.frames + f] = st->cpu_ms;
    samples[(size_t)(2 + PG_MAX_PASSES) * B->opt.frames + f] = st->wait_ms;
    if (f == 0) {
        row->n_passes = st->n_passes;
        for (uint32_t p = 0; p < st->n_passes; p++)
            pg_strlcpy(row->passes[p].name, st->pass_names[p], sizeof row->passes[p].name);
    }
    if (pg_frame_counter_has(st, "overflow_clusters")) { /* a clustered pipeline's (lightcut counts evaluations only) */
        row->has_overflow = true;
        if (pg_frame_counter_sum(st, "overflow_clusters") > row->ov_clusters_max)
            row->ov_clusters_max = pg_frame_counter_sum(st, "overflow_clusters");
    }
    row->frames = f + 1;
}

/* frame k of a row (its time: --time + k x --time-step) */
static pg_result one_frame(bench *B, pg_session *s, pg_frame_info *fi, uint32_t k, double fw, bench_row *row,
                           pg_frame_stats *st, pg_error *e)
{
    fi->time = (float)(B->opt.time + k * B->time_step);
    pg_result r = pg_session_render(s, fi, false, st, e);
    if (r) return r;
    B->done_work += fw;
    row->grow_events += st->n_grown;
    return PG_OK;
}

/* the warm-up and timed frames (until interrupted), then the GPU times still to come */
static pg_result timed_frames(bench *B, pg_session *s, pg_frame_info *fi, double fw, bench_row *row,
                              double *samples, const char *what, pg_error *e)
{
    pg_frame_stats st;
    uint64_t first_timed = UINT64_MAX; /* runtime frame number of the first timed frame */
    for (uint32_t f = 0; f < B->opt.frames; f++) samples[f] = NAN;
    for (size_t f = 2 * (size_t)B->opt.frames; f < (size_t)B->opt.frames * (PG_MAX_PASSES + 2); f++) samples[f] = NAN;
    /* warm-up: --warmup frames, and on until --warmup-ms have passed (at most 100,000 frames) */
    const double t0 = pg_time_s();
    uint32_t k = 0;
    for (; !g_interrupted && (k < B->warmup || (k < 100000 && (pg_time_s() - t0) * 1000.0 < B->warmup_ms)); k++) {
        pg_result r = one_frame(B, s, fi, k, fw, row, &st, e);
        if (r) return r;
        progress_draw(B, what, false);
    }
    for (uint32_t j = 0; j < B->opt.frames && !g_interrupted; j++, k++) {
        pg_result r = one_frame(B, s, fi, k, fw, row, &st, e);
        if (r) return r;
        record_timed_frame(B, s, &st, j, &first_timed, row, samples);
        progress_draw(B, what, false);
    }
    if (first_timed != UINT64_MAX && !pg_runtime_wait_idle(s->runtime, e))
        fetch_gpu(B, s->runtime, first_timed, first_timed + B->opt.frames - 1, row->n_passes, samples);
    return PG_OK;
}

/* the plan's and the device's transient bytes */
static void record_memory(const pg_session *s, bench_row *row)
{
    if (!s->plan) return;
    row->has_memory = true;
    row->plan_unaliased = s->plan->transient_bytes_unaliased;
    row->plan_aliased = s->plan->transient_bytes_aliased;
    pg_runtime_stats rs = pg_runtime_get_stats(s->runtime);
    row->dev_unaliased = rs.memory_bytes_unaliased;
    row->dev_aliased = rs.memory_bytes_transient;
}

/* the error frame's counters: overflow, light references, list bytes */
static void record_error_frame_counters(const pg_frame_stats *st, bench_row *row)
{
    if (!st->n_counters) return;
    row->has_overflow |= pg_frame_counter_has(st, "overflow_clusters"); /* the list columns: clustered pipelines' */
    row->ov_clusters = pg_frame_counter_sum(st, "overflow_clusters");
    row->ov_dropped = pg_frame_counter_sum(st, "overflow_dropped");
    for (uint32_t k = 0; k < st->n_counters; k++) {
        if (!strcmp(st->counters[k].name, "total_refs")) row->light_refs += st->counters[k].value;
        if (!strcmp(st->counters[k].name, "light_evals")) row->has_evals = true, row->light_evals += st->counters[k].value;
        if (!strcmp(st->counters[k].name, "list_bytes")) row->list_bytes += st->counters[k].value;
    }
}

/* The measured image (the mean of --accumulate frames from the error frame hdr / ldr on) and the
 * flicker of --flicker-frames frames (frame_metrics.h), then its error, perceptual metrics and
 * flicker against the reference. A frame that does not render is returned (the row fails); a
 * metric that cannot be computed leaves the note. */
static pg_result measure_error(bench *B, pg_session *s, const pg_frame_info *fi, const reference *ref,
                               bench_row *row, const float *hdr, const uint8_t *ldr, uint32_t w, uint32_t h,
                               pg_error *e)
{
    const size_t n = (size_t)w * h * 4;
    float *hm = malloc(n * sizeof *hm);
    uint8_t *lm = malloc(n);
    pg_flicker fl;
    uint32_t extra = 0;
    pg_result r = !hm || !lm ? pg_fail(e, PG_ERR_OOM, "out of memory")
                             : pg_sample_frames(s, fi, B->accumulate, B->flicker_frames, hdr, ldr, w, h, hm, lm, &fl,
                                                &extra, e);
    B->done_work += extra * frame_work(w, h, row->lights);
    pg_error ie = {0};
    if (!r) {
        if (pg_image_error_compute(hm, ref->hdr, lm, ref->ldr, w, h, 1.0, &row->e, &ie) ||
            pg_perceptual_compute(hm, ref->hdr, lm, ref->ldr, w, h, !B->no_hdr_flip, NULL, &row->pm, &ie)) {
            snprintf(row->error_note, sizeof row->error_note, "%s", ie.msg);
        } else {
            row->flicker = B->flicker_frames >= 2 ? pg_flicker_value(&fl, ref->hdr, w, h) : NAN;
            row->has_error = true;
        }
    }
    free(hm);
    free(lm);
    return r;
}

/* the error frame's images: non-finite pixels, and the error against the reference (or the note
 * that says why there is none); a failure to render the frames the measure needs is returned */
static pg_result compare_to_reference(bench *B, pg_session *s, const pg_frame_info *fi, const reference *ref,
                                      bool ref_skipped, bench_row *row, float **hdr, uint8_t **ldr, pg_error *e)
{
    uint32_t w = 0, h = 0;
    pg_error ie = {0};
    if (grab_images(s, hdr, ldr, &w, &h, &ie)) {
        snprintf(row->error_note, sizeof row->error_note, "%s", ie.msg);
        return PG_OK;
    }
    row->has_nonfinite = true;
    row->nonfinite = pg_count_nonfinite(*hdr, w, h);
    if (ref_skipped) {
        /* note already says so */
    } else if (!ref->ok) {
        snprintf(row->error_note, sizeof row->error_note, "reference failed: %s", ref->msg);
    } else if (pg_image_sizes_match("image vs reference", w, h, ref->w, ref->h, &ie)) {
        snprintf(row->error_note, sizeof row->error_note, "%s", ie.msg);
    } else {
        return measure_error(B, s, fi, ref, row, *hdr, *ldr, w, h, e);
    }
    return PG_OK;
}

/* a row that is not run: its variant did not load, or it is the reference past its light limit;
 * false when the row is to be run */
static bool row_not_run(bench *B, const pipe_entry *pe, const variant *va, bool ref_skipped, double work,
                        bench_row *row)
{
    if (!va->ok) {
        row->status = ROW_ERROR;
        snprintf(row->message, sizeof row->message, "%s", va->msg);
    } else if (pe->is_reference && ref_skipped) {
        row->status = ROW_SKIPPED;
        snprintf(row->message, sizeof row->message, "the reference pipeline itself is not run: %s", row->error_note);
    } else {
        return false;
    }
    B->done_work += work;
    return true;
}

/* One configuration: its timed frames, then the error frame. Fills row; failures are recorded in
 * it (status, message), never returned: only OOM of the row table stops the bench. */
void run_row(bench *B, pg_app *app, const pg_frame_info *fi0, reference *refs, bench_row *row, const char *what)
{
    const pipe_entry *pe = &B->pipes[row->pipe];
    const variant *va = &pe->variants[row->variant];
    reference *ref = &refs[va->ref];
    double fw = frame_work(row->width, row->height, row->lights);
    uint32_t nf = B->warmup + B->opt.frames;
    uint32_t limit = ref_limit(B, row->width, row->height);
    bool ref_skipped = row->lights > limit;
    if (ref_skipped) ref_skip_note(B, row->width, row->height, false, row->error_note, sizeof row->error_note);
    if (row_not_run(B, pe, va, ref_skipped, fw * (nf + 1), row)) return;
    /* the reference first, so that only one session holds device memory at a time */
    if (!ref_skipped && !ref->tried) {
        char rw[PG_NAME_MAX + 64];
        snprintf(rw, sizeof rw, "%s (reference) %ux%u lights=%u", B->ref_name, row->width, row->height, row->lights);
        progress_draw(B, rw, false);
        reference_render(B, app, fi0, &B->refs[va->ref], ref);
        B->done_work += frame_work(row->width, row->height, row->lights) * 4;
    }
    pg_session *s = NULL;
    pg_error e = {0};
    double *samples = NULL;
    float *hdr = NULL;
    uint8_t *ldr = NULL;
    if (open_row_session(B, app, pe, va, &s, &e)) goto fail;
    samples = calloc((size_t)B->opt.frames * (PG_MAX_PASSES + 3), sizeof *samples);
    if (!samples) {
        pg_fail(&e, PG_ERR_OOM, "out of memory");
        goto fail;
    }
    pg_frame_info fi = *fi0;
    if (timed_frames(B, s, &fi, fw, row, samples, what, &e)) goto fail;
    record_memory(s, row);
    collect_stats(row, samples, B->opt.frames, PG_MAX_PASSES);
    if (g_interrupted) {
        row->status = ROW_INTERRUPTED;
        snprintf(row->message, sizeof row->message, "interrupted after %u of %u timed frames", row->frames,
                 B->opt.frames);
        if (!row->error_note[0]) snprintf(row->error_note, sizeof row->error_note, "interrupted: no error frame");
        goto out;
    }
    /* the error frame: fixed time, read back */
    pg_frame_stats st;
    fi.time = B->opt.time;
    if (pg_session_render(s, &fi, true, &st, &e)) goto fail;
    B->done_work += fw;
    row->grow_events += st.n_grown;
    record_error_frame_counters(&st, row);
    if (compare_to_reference(B, s, &fi, ref, ref_skipped, row, &hdr, &ldr, &e)) goto fail;
    row->status = row->ov_dropped ? ROW_INEXACT : ROW_OK;
    if (row->ov_dropped)
        snprintf(row->message, sizeof row->message, "not exact: %llu light references dropped (list budget or "
                 "max_lights)", (unsigned long long)row->ov_dropped);
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

void print_row(const bench *B, const bench_row *r)
{
    const pipe_entry *pe = &B->pipes[r->pipe];
    const variant *va = &pe->variants[r->variant];
    printf("bench: %s%s%s %s %ux%u lights=%u %s", pe->name, va->label[0] ? " " : "", va->label,
           B->scene_names[r->scene], r->width, r->height, r->lights, status_names[r->status]);
    if (r->gpu.n) printf(" gpu=%.3f ms (median of %u)", r->gpu.median, r->gpu.n);
    if (r->has_error) {
        if (isinf(r->e.psnr_linear)) printf(" rmse=%.4g psnr=inf", r->e.rmse_linear);
        else printf(" rmse=%.4g psnr=%.2f dB", r->e.rmse_linear, r->e.psnr_linear);
        printf(" flip=%.4g", r->pm.flip);
        if (!isnan(r->pm.hdr_flip)) printf(" hdr_flip=%.4g", r->pm.hdr_flip);
        printf(" ssim=%.4g", r->pm.ssim);
        if (!isnan(r->flicker)) printf(" flicker=%.4g", r->flicker);
        if (B->accumulate > 1) printf(" accumulate=%u", B->accumulate);
        printf(" (metrics %.0f ms CPU)", r->pm.cpu_ms);
    }
    if (r->has_overflow)
        printf(" overflow=%llu dropped=%llu refs=%llu lists=%.1fMiB", (unsigned long long)r->ov_clusters,
               (unsigned long long)r->ov_dropped, (unsigned long long)r->light_refs, r->list_bytes / 1048576.0);
    if (r->grow_events) printf(" grew=%u", r->grow_events);
    if (r->status == ROW_ERROR || r->status == ROW_SKIPPED) printf(": %s", r->message);
    printf("\n");
    fflush(stdout);
}
