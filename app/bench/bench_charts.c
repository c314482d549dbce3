/* bench_charts.c - `passgraph bench`: the SVG charts (GPU time vs lights, passes stacked,
 * error vs time), drawn with tools/stats/svg_plot.c. */
#include "bench.h"

/* ---------------------------------------------------------------- output: charts */

static const char *scene_short(const char *s)
{
    const char *b = strrchr(s, '/');
    return b ? b + 1 : s;
}

void series_label(const bench *B, uint32_t pipe, uint32_t var, char *buf, size_t size)
{
    const pipe_entry *pe = &B->pipes[pipe];
    const variant *va = &pe->variants[var];
    snprintf(buf, size, "%s%s%s", pe->name, va->label[0] ? " " : "", va->label);
}

static bool row_timed(const bench_row *r)
{
    return (ROW_RAN(r) || r->status == ROW_INTERRUPTED) && r->gpu.n > 0;
}

/* Colour and marker of a pipeline/variant in every chart: series s (their order) takes colour
 * s % 20 and marker (variant + s / 20) % 5, so no two of up to 100 series look alike (the variant
 * in the marker: variants of one pipeline differ by it too). It was the pipeline's colour and marker
 * (variant + pipeline / 10) beyond 10 series: pipeline 0's second variant looked like pipeline 10's
 * first. */
static void series_style(const bench *B, uint32_t pipe, uint32_t var, int *color, pg_plot_marker *marker)
{
    const uint32_t s = B->pipes[pipe].variants[var].series;
    *color = (int)(s % PG_PLOT_PALETTE_SIZE);
    *marker = (pg_plot_marker)((var + s / PG_PLOT_PALETTE_SIZE) % PG_PLOT_FILLED_MARKERS);
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

/* The end of every chart: out of memory -> PG_ERR_OOM, else the SVG under title with the subtitle
 * of what (doc_subtitle); frees m either way. */
static pg_result chart_finish(const bench *B, chart_mem *m, const char *path, const pg_plot *plots, uint32_t np,
                              const char *title, const char *what, pg_error *err)
{
    pg_result r;
    if (m->oom) {
        r = pg_fail(err, PG_ERR_OOM, "out of memory");
    } else {
        char sub[700];
        doc_subtitle(B, sub, sizeof sub, what);
        pg_svg_doc_desc d = {.title = title, .subtitle = sub};
        r = pg_svg_write(path, plots, np, &d, err);
    }
    cm_free(m);
    return r;
}

pg_result pg_bench_chart_time_vs_lights(const bench *B, const char *path, pg_error *err)
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
    return chart_finish(B, &m, path, plots, np, "passgraph bench: GPU time against light count", "log-log", err);
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

pg_result pg_bench_chart_passes(const bench *B, const char *path, pg_error *err)
{
    chart_mem m = {0};
    pass_union *u = cm_alloc(&m, sizeof *u);
    uint32_t nb = n_blocks(B);
    pg_plot *plots = cm_alloc(&m, (nb ? nb : 1) * sizeof *plots);
    uint32_t np = 0;
    if (!u || !plots) goto oom;
    pg_bench_union_passes(B, u);
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
    return chart_finish(B, &m, path, plots, np, "passgraph bench: GPU time per pass",
                        "per-pass GPU timestamps (a pass includes its barriers)", err);
}

/* the row's value on the error axis */
static double row_metric(const bench_row *r, bench_metric metric)
{
    return metric == BENCH_METRIC_FLIP ? r->pm.flip : r->e.rmse_linear;
}

/* the chart's error axis, and its subtitle */
static void error_axis(const bench *B, bench_metric metric, pg_plot_axis *y, char *what, size_t size)
{
    const bool flip = metric == BENCH_METRIC_FLIP;
    *y = (pg_plot_axis){.label = flip ? "LDR-FLIP mean vs reference, display images (log)"
                                      : "RMSE vs reference, linear HDR (log)",
                        .scale = PG_PLOT_LOG10, .zero_label = "0 (exact)"};
    char acc[96] = "";
    if (B->accumulate > 1)
        snprintf(acc, sizeof acc, "; each image the mean of %u frames, its time %u x the frame's", B->accumulate,
                 B->accumulate);
    snprintf(what, size,
             "%s against %s (lower left is better); dashed: the Pareto front (no other point is both faster "
             "and more accurate)%s",
             flip ? "LDR-FLIP" : "RMSE", B->ref_name, acc);
}

pg_result pg_bench_chart_error(const bench *B, const char *path, bench_metric metric, pg_error *err)
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
            n += row_timed(r) && r->has_error && !isnan(row_metric(r, metric));
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
            if (!row_in_block(B, r, sc, si, li) || !row_timed(r) || !r->has_error || isnan(row_metric(r, metric)))
                continue;
            xs[k] = r->gpu.median * B->accumulate;
            ys[k] = row_metric(r, metric);
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
        pl->x = (pg_plot_axis){.label = B->accumulate > 1 ? "GPU ms per image (accumulate x median frame, log)"
                                                          : "GPU ms per frame, median (log)",
                               .scale = PG_PLOT_LOG10};
        error_axis(B, metric, &pl->y, NULL, 0);
    }
oom:;
    char what[400];
    pg_plot_axis unused;
    error_axis(B, metric, &unused, what, sizeof what);
    return chart_finish(B, &m, path, plots, np,
                        metric == BENCH_METRIC_FLIP ? "passgraph bench: perceptual error (FLIP) against GPU time"
                                                    : "passgraph bench: image error against GPU time",
                        what, err);
}
