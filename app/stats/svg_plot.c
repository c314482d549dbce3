/* svg_plot.c - the SVG chart writer (svg_plot.h): layout, drawing, the documents; svg_plot_text.c
 * has the text and tick helpers. */
#include "svg_plot_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- layout ---- */
#define FONT_TITLE 14.0
#define FONT_SUB 11.5
#define FONT_TICK 11.0
#define FONT_AXIS 12.0
#define FONT_LEGEND 11.0
#define FONT_POINT 10.0
#define LEGEND_ROW 17.0
#define BAND_W 30.0 /* the zero band of a log axis */
#define BAR_PITCH 22.0
#define BAR_LABEL_MAX 48
#define MAX_TICKS 64
#define DATA_PAD 8.0 /* the data range starts this far inside the plot frame: markers stay whole */

typedef struct axis_map {
    pg_plot_scale scale;
    double lo, hi;        /* range of the main part */
    double p0, p1;        /* pixels of lo and hi */
    bool band;            /* values <= 0 drawn at band_pos (log axes with zero_label) */
    double band_pos, band_edge;
    pg_plot_tick ticks[MAX_TICKS];
    uint32_t n_ticks;
    double step;          /* linear step, for labels */
    bool sci;             /* log10 axis reaching below 0.001: every label below 1 as 10^k */
} axis_map;

typedef struct legend_entry {
    const char *name;
    const char *color;
    pg_plot_marker marker;
    bool line, box;
    const char *dash;     /* stroke-dasharray or NULL */
} legend_entry;

typedef struct panel {
    const pg_plot *pl;
    double pw, ph;                  /* plot area */
    double left, top, right, bottom;
    double w, h;
    axis_map xm, ym;
    double fx, fy;                  /* the plot frame's top-left corner once placed */
    legend_entry *legend;
    uint32_t n_legend, legend_rows, legend_cols;
    double legend_col_w;
    bool has_data;
} panel;

static double amap(const axis_map *m, double v, bool *ok)
{
    *ok = isfinite(v);
    if (!*ok) return 0;
    if (m->scale == PG_PLOT_LOG10) {
        if (v <= 0) {
            *ok = m->band;
            return m->band_pos;
        }
        return m->p0 + (log10(v) - log10(m->lo)) / (log10(m->hi) - log10(m->lo)) * (m->p1 - m->p0);
    }
    return m->p0 + (v - m->lo) / (m->hi - m->lo) * (m->p1 - m->p0);
}

/* Data extent of one axis over the series (which: 0 x, 1 y). */
static void data_extent(const pg_plot *pl, int which, pg_plot_scale scale, double *mn, double *mx, bool *nonpos,
                        bool *any)
{
    *mn = INFINITY;
    *mx = -INFINITY;
    *nonpos = false;
    *any = false;
    for (uint32_t s = 0; s < pl->n_series; s++) {
        const pg_plot_series *se = &pl->series[s];
        for (uint32_t i = 0; i < se->n; i++) {
            double x = se->x[i], y = se->y[i];
            if (!isfinite(x) || !isfinite(y)) continue;
            double v = which ? y : x;
            if (scale == PG_PLOT_LOG10 && v <= 0) {
                *nonpos = true;
                continue;
            }
            *any = true;
            if (v < *mn) *mn = v;
            if (v > *mx) *mx = v;
        }
    }
}

static void axis_setup(axis_map *m, const pg_plot_axis *ax, double dmin, double dmax, bool any, bool nonpos)
{
    m->scale = ax->scale;
    if (ax->fixed_range && ax->max > ax->min && (ax->scale == PG_PLOT_LINEAR || ax->min > 0)) {
        m->lo = ax->min;
        m->hi = ax->max;
    } else if (!any) {
        m->lo = ax->scale == PG_PLOT_LOG10 ? 1 : 0;
        m->hi = ax->scale == PG_PLOT_LOG10 ? 10 : 1;
    } else {
        if (ax->scale == PG_PLOT_LINEAR && ax->include_zero) {
            if (dmin > 0) dmin = 0;
            if (dmax < 0) dmax = 0;
        }
        pg_plot_nice_range(ax->scale, dmin, dmax, &m->lo, &m->hi);
    }
    m->band = ax->scale == PG_PLOT_LOG10 && ax->zero_label && nonpos;
    m->n_ticks = pg_plot_ticks(m->scale, m->lo, m->hi, m->ticks, MAX_TICKS);
    m->step = 1;
    m->sci = false;
    for (uint32_t t = 0; m->scale == PG_PLOT_LOG10 && t < m->n_ticks; t++)
        if (m->ticks[t].major && m->ticks[t].value < 1e-3 * (1 - 1e-9)) m->sci = true;
    if (m->scale == PG_PLOT_LINEAR || log10(m->hi / m->lo) < 0.6) m->step = pg_plt_nice_step((m->hi - m->lo) / 5);
}

static double tick_w(const axis_map *m, double v)
{
    char base[64], sup[16];
    pg_plt_tick_label(m->scale, v, m->step, m->sci, base, sizeof base, sup, sizeof sup);
    return pg_plt_text_w(base, FONT_TICK) + pg_plt_text_w(sup, FONT_TICK * 0.75);
}

static bool bar_stack_used(const pg_plot_bars *b, uint32_t k)
{
    for (uint32_t i = 0; i < b->n_bars; i++) {
        double v = b->values[(size_t)i * b->n_stack + k];
        if (isfinite(v) && v > 0) return true;
    }
    return false;
}

static const char *series_dash(const pg_plot_series *se)
{
    if (se->dasharray && se->dasharray[0]) return se->dasharray;
    return se->dashed ? "6,4" : NULL;
}

static pg_result panel_layout(panel *P, const pg_plot *pl, pg_error *err)
{
    memset(P, 0, sizeof *P);
    P->pl = pl;
    const pg_plot_bars *bars = pl->bars;
    for (uint32_t s = 0; s < pl->n_series; s++)
        if (pl->series[s].n && (!pl->series[s].x || !pl->series[s].y))
            return pg_fail(err, PG_ERR_INVALID_ARG, "svg plot '%s': series %u has no x/y arrays",
                           pl->title ? pl->title : "", s);
    if (bars && bars->n_bars && bars->n_stack && !bars->values)
        return pg_fail(err, PG_ERR_INVALID_ARG, "svg plot '%s': bars without values", pl->title ? pl->title : "");
    P->pw = pl->width > 0 ? pl->width : 520;
    P->ph = pl->height > 0 ? pl->height : 340;
    double dmin, dmax;
    bool nonpos, any;
    if (bars) {
        double mx = 0;
        for (uint32_t b = 0; b < bars->n_bars; b++) {
            double t = 0;
            for (uint32_t k = 0; k < bars->n_stack; k++) {
                double v = bars->values[(size_t)b * bars->n_stack + k];
                if (isfinite(v) && v > 0) t += v;
            }
            if (t > mx) mx = t;
        }
        P->has_data = bars->n_bars > 0 && mx > 0;
        if (pl->height <= 0) P->ph = fmax(BAR_PITCH * bars->n_bars, 60);
        pg_plot_axis ax = pl->x;
        ax.scale = PG_PLOT_LINEAR;
        ax.include_zero = true;
        axis_setup(&P->xm, &ax, 0, mx * (bars->show_totals ? 1.14 : 1.0), P->has_data, false);
    } else {
        data_extent(pl, 0, pl->x.scale, &dmin, &dmax, &nonpos, &any);
        axis_setup(&P->xm, &pl->x, dmin, dmax, any, nonpos);
        bool xany = any || nonpos;
        data_extent(pl, 1, pl->y.scale, &dmin, &dmax, &nonpos, &any);
        axis_setup(&P->ym, &pl->y, dmin, dmax, any, nonpos);
        P->has_data = xany && (any || nonpos);
    }

    /* legend entries */
    uint32_t cap = (uint32_t)pl->n_series + (bars ? bars->n_stack : 0);
    if (cap && !pl->no_legend) {
        P->legend = calloc(cap, sizeof *P->legend);
        if (!P->legend) return pg_fail(err, PG_ERR_OOM, "svg plot: out of memory");
        for (uint32_t s = 0; s < pl->n_series; s++) {
            const pg_plot_series *se = &pl->series[s];
            if (!se->name) continue;
            P->legend[P->n_legend++] = (legend_entry){se->name, pg_plot_color(se->color), se->marker, se->line, false,
                                                      series_dash(se)};
        }
        for (uint32_t k = 0; bars && k < bars->n_stack; k++) {
            if (!bar_stack_used(bars, k)) continue;
            int c = bars->stack_colors ? bars->stack_colors[k] : (int)k;
            P->legend[P->n_legend++] = (legend_entry){bars->stack_names ? bars->stack_names[k] : "", pg_plot_color(c),
                                                      PG_MARKER_NONE, false, true, NULL};
        }
    }

    /* margins */
    P->top = 12 + (pl->title ? 20 : 0) + (pl->subtitle ? 16 : 0) + 10;
    P->bottom = 8 + 16 + (P->xm.band || pl->x.label ? 0 : 0) + (pl->x.label ? 20 : 0) + 10;
    double yw = 0;
    if (bars) {
        for (uint32_t b = 0; b < bars->n_bars; b++) {
            const char *l = bars->bar_labels ? bars->bar_labels[b] : "";
            double w = pg_plt_text_w(l, FONT_TICK);
            if (l && strlen(l) > BAR_LABEL_MAX) w = pg_plt_text_w("x", FONT_TICK) * BAR_LABEL_MAX;
            if (w > yw) yw = w;
        }
        P->left = 12 + yw + 10;
    } else {
        for (uint32_t t = 0; t < P->ym.n_ticks; t++)
            if (P->ym.ticks[t].major) yw = fmax(yw, tick_w(&P->ym, P->ym.ticks[t].value));
        if (P->ym.band) yw = fmax(yw, pg_plt_text_w(pl->y.zero_label, FONT_TICK));
        P->left = 12 + (pl->y.label ? 20 : 0) + yw + 8;
    }
    double lastx = P->xm.n_ticks ? tick_w(&P->xm, P->xm.ticks[P->xm.n_ticks - 1].value) / 2 : 0;
    if (P->n_legend) {
        double nw = 0;
        for (uint32_t i = 0; i < P->n_legend; i++) nw = fmax(nw, pg_plt_text_w(P->legend[i].name, FONT_LEGEND));
        P->legend_col_w = 30 + nw + 14;
        P->legend_rows = (uint32_t)floor((P->ph + P->bottom - 10) / LEGEND_ROW);
        if (P->legend_rows < 1) P->legend_rows = 1;
        P->legend_cols = (P->n_legend + P->legend_rows - 1) / P->legend_rows;
        P->legend_rows = (P->n_legend + P->legend_cols - 1) / P->legend_cols; /* balance the columns */
        P->right = fmax(lastx, 0) + 18 + P->legend_cols * P->legend_col_w;
    } else {
        P->right = fmax(lastx, 8) + 12;
    }
    P->w = P->left + P->pw + P->right;
    P->h = P->top + P->ph + P->bottom;
    /* title may be wider than the panel */
    double tw = fmax(pg_plt_text_w(pl->title, FONT_TITLE) * 1.05, pg_plt_text_w(pl->subtitle, FONT_SUB));
    if (P->left + tw + 12 > P->w) P->w = P->left + tw + 12;
    return PG_OK;
}

/* Pixel mapping once the panel's origin is known. */
static void panel_place(panel *P, double ox, double oy)
{
    double L = ox + P->left, T = oy + P->top;
    axis_map *x = &P->xm, *y = &P->ym;
    P->fx = L;
    P->fy = T;
    double pad = P->pl->bars ? 0 : DATA_PAD;
    x->p0 = L + (x->band ? BAND_W : 0) + pad;
    x->p1 = L + P->pw - pad;
    x->band_pos = L + BAND_W * 0.4;
    x->band_edge = L + BAND_W * 0.8;
    y->p0 = T + P->ph - (y->band ? BAND_W : 0) - pad;
    y->p1 = T + pad;
    y->band_pos = T + P->ph - BAND_W * 0.4;
    y->band_edge = T + P->ph - BAND_W * 0.8;
}

static void draw_marker(sb *b, pg_plot_marker m, double x, double y, double r, const char *color)
{
    switch (m) {
    case PG_MARKER_NONE: break;
    case PG_MARKER_CIRCLE:
        pg_plt_sb_printf(b, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"%s\" stroke=\"#fff\" stroke-width=\"0.8\"/>\n",
                  x, y, r, color);
        break;
    case PG_MARKER_RING:
        pg_plt_sb_printf(b, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"none\" stroke=\"%s\" stroke-width=\"1.6\"/>\n",
                  x, y, r, color);
        break;
    case PG_MARKER_SQUARE:
        pg_plt_sb_printf(b,
                  "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"%s\" stroke=\"#fff\" "
                  "stroke-width=\"0.8\"/>\n",
                  x - r * 0.88, y - r * 0.88, r * 1.76, r * 1.76, color);
        break;
    case PG_MARKER_TRIANGLE:
    case PG_MARKER_TRIANGLE_DOWN: {
        double s = m == PG_MARKER_TRIANGLE ? 1 : -1, rr = r * 1.25;
        pg_plt_sb_printf(b,
                  "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f\" fill=\"%s\" stroke=\"#fff\" stroke-width=\"0.8\"/>\n",
                  x, y - s * rr, x - rr * 0.87, y + s * rr * 0.5, x + rr * 0.87, y + s * rr * 0.5, color);
        break;
    }
    case PG_MARKER_DIAMOND:
    default: {
        double rr = r * 1.2;
        pg_plt_sb_printf(b,
                  "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f %.1f,%.1f\" fill=\"%s\" stroke=\"#fff\" "
                  "stroke-width=\"0.8\"/>\n",
                  x, y - rr, x + rr, y, x, y + rr, x - rr, y, color);
        break;
    }
    }
}

/* A tick label at (x, y) with the given anchor; superscript exponents as a raised tspan. */
static void draw_tick_label(sb *b, const axis_map *m, double v, double x, double y, const char *anchor)
{
    char base[64], sup[16];
    pg_plt_tick_label(m->scale, v, m->step, m->sci, base, sizeof base, sup, sizeof sup);
    pg_plt_sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\" font-size=\"%.0f\" fill=\"#333\">", x, y, anchor,
              FONT_TICK);
    pg_plt_sb_text(b, base);
    if (sup[0]) {
        pg_plt_sb_printf(b, "<tspan dy=\"-5\" font-size=\"%.1f\">", FONT_TICK * 0.75);
        pg_plt_sb_text(b, sup);
        pg_plt_sb_put(b, "</tspan>", 8);
    }
    pg_plt_sb_put(b, "</text>\n", 8);
}

typedef struct rect {
    double x0, y0, x1, y1;
} rect;

static bool rect_hits(const rect *rs, uint32_t n, rect r)
{
    for (uint32_t i = 0; i < n; i++)
        if (r.x0 < rs[i].x1 && r.x1 > rs[i].x0 && r.y0 < rs[i].y1 && r.y1 > rs[i].y0) return true;
    return false;
}

static void draw_axes(sb *b, const panel *P, double ox, double oy)
{
    const pg_plot *pl = P->pl;
    double L = ox + P->left, T = oy + P->top, R = L + P->pw, B = T + P->ph;
    const axis_map *x = &P->xm, *y = &P->ym;
    /* grid: minor first, then major */
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t t = 0; t < x->n_ticks; t++) {
            if (x->ticks[t].major != (pass == 1)) continue;
            bool ok;
            double px = amap(x, x->ticks[t].value, &ok);
            if (!ok) continue;
            pg_plt_sb_printf(b, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"1\"/>\n", px,
                      T, px, B, pass ? "#dddddd" : "#f0f0f0");
        }
        if (pl->bars) continue;
        for (uint32_t t = 0; t < y->n_ticks; t++) {
            if (y->ticks[t].major != (pass == 1)) continue;
            bool ok;
            double py = amap(y, y->ticks[t].value, &ok);
            if (!ok) continue;
            pg_plt_sb_printf(b, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"1\"/>\n", L,
                      py, R, py, pass ? "#dddddd" : "#f0f0f0");
        }
    }
    /* zero bands: a shaded strip and a dashed separator */
    if (x->band) {
        pg_plt_sb_printf(b, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#f6f6f6\"/>\n", L, T,
                  x->band_edge - L, P->ph);
        pg_plt_sb_printf(b,
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#999\" stroke-dasharray=\"3,3\"/>\n",
                  x->band_edge, T, x->band_edge, B);
    }
    if (y->band) {
        pg_plt_sb_printf(b, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#f6f6f6\"/>\n", L,
                  y->band_edge, P->pw, B - y->band_edge);
        pg_plt_sb_printf(b,
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#999\" stroke-dasharray=\"3,3\"/>\n", L,
                  y->band_edge, R, y->band_edge);
    }
    pg_plt_sb_printf(b, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"#888\"/>\n", L, T,
              P->pw, P->ph);
    /* tick marks and labels */
    for (uint32_t t = 0; t < x->n_ticks; t++) {
        bool ok;
        double px = amap(x, x->ticks[t].value, &ok);
        if (!ok) continue;
        pg_plt_sb_printf(b, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#888\"/>\n", px, B, px,
                  B + (x->ticks[t].major ? 5 : 3));
        if (x->ticks[t].major) draw_tick_label(b, x, x->ticks[t].value, px, B + 17, "middle");
    }
    if (x->band) {
        pg_plt_sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"%.0f\" fill=\"#333\">",
                  x->band_pos, B + 17, FONT_TICK);
        pg_plt_sb_text(b, pl->x.zero_label);
        pg_plt_sb_put(b, "</text>\n", 8);
    }
    if (!pl->bars) {
        for (uint32_t t = 0; t < y->n_ticks; t++) {
            bool ok;
            double py = amap(y, y->ticks[t].value, &ok);
            if (!ok) continue;
            pg_plt_sb_printf(b, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#888\"/>\n",
                      L - (y->ticks[t].major ? 5 : 3), py, L, py);
            if (y->ticks[t].major) draw_tick_label(b, y, y->ticks[t].value, L - 7, py + 4, "end");
        }
        if (y->band) {
            pg_plt_sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\" font-size=\"%.0f\" fill=\"#333\">", L - 7,
                      y->band_pos + 4, FONT_TICK);
            pg_plt_sb_text(b, pl->y.zero_label);
            pg_plt_sb_put(b, "</text>\n", 8);
        }
    }
    /* axis titles */
    if (pl->x.label) {
        pg_plt_sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"%.0f\" fill=\"#222\">",
                  (L + R) / 2, B + 37, FONT_AXIS);
        pg_plt_sb_text(b, pl->x.label);
        pg_plt_sb_put(b, "</text>\n", 8);
    }
    if (pl->y.label && !pl->bars) {
        double cx = ox + 12 + 9, cy = (T + B) / 2;
        pg_plt_sb_printf(b,
                  "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"%.0f\" fill=\"#222\" "
                  "transform=\"rotate(-90 %.1f %.1f)\">",
                  cx, cy, FONT_AXIS, cx, cy);
        pg_plt_sb_text(b, pl->y.label);
        pg_plt_sb_put(b, "</text>\n", 8);
    }
}

static pg_result draw_series(sb *b, const panel *P, pg_error *err)
{
    const pg_plot *pl = P->pl;
    /* lines under markers, markers under labels */
    for (uint32_t s = 0; s < pl->n_series; s++) {
        const pg_plot_series *se = &pl->series[s];
        if (!se->line) continue;
        bool open = false;
        for (uint32_t i = 0; i < se->n; i++) {
            bool okx, oky;
            double px = amap(&P->xm, se->x[i], &okx), py = amap(&P->ym, se->y[i], &oky);
            if (!okx || !oky) {
                if (open) pg_plt_sb_put(b, "\"/>\n", 4);
                open = false;
                continue;
            }
            if (!open) {
                pg_plt_sb_printf(b, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"%.1f\" stroke-linejoin=\"round\"",
                          pg_plot_color(se->color), se->line_width > 0 ? se->line_width : 1.8);
                if (series_dash(se)) {
                    pg_plt_sb_put(b, " stroke-dasharray=\"", 19);
                    pg_plt_sb_text(b, series_dash(se));
                    pg_plt_sb_put(b, "\"", 1);
                }
                pg_plt_sb_put(b, " points=\"", 9);
                open = true;
            }
            pg_plt_sb_printf(b, "%.1f,%.1f ", px, py);
        }
        if (open) pg_plt_sb_put(b, "\"/>\n", 4);
    }
    uint32_t n_pts = 0;
    for (uint32_t s = 0; s < pl->n_series; s++) n_pts += pl->series[s].n;
    rect *placed = calloc((size_t)n_pts * 2 + 1, sizeof *placed);
    if (!placed) return pg_fail(err, PG_ERR_OOM, "svg plot: out of memory");
    uint32_t n_placed = 0;
    for (uint32_t s = 0; s < pl->n_series; s++) {
        const pg_plot_series *se = &pl->series[s];
        double r = se->marker_size > 0 ? se->marker_size : 4.5;
        for (uint32_t i = 0; i < se->n; i++) {
            bool okx, oky;
            double px = amap(&P->xm, se->x[i], &okx), py = amap(&P->ym, se->y[i], &oky);
            if (!okx || !oky) continue;
            draw_marker(b, se->marker, px, py, r, pg_plot_color(se->color));
            if (se->marker != PG_MARKER_NONE) placed[n_placed++] = (rect){px - r, py - r, px + r, py + r};
        }
    }
    /* point labels where they fit */
    double L = P->fx, R = P->fx + P->pw, T = P->fy, B = P->fy + P->ph;
    for (uint32_t s = 0; s < pl->n_series; s++) {
        const pg_plot_series *se = &pl->series[s];
        if (!se->labels) continue;
        for (uint32_t i = 0; i < se->n; i++) {
            if (!se->labels[i] || !se->labels[i][0]) continue;
            bool okx, oky;
            double px = amap(&P->xm, se->x[i], &okx), py = amap(&P->ym, se->y[i], &oky);
            if (!okx || !oky) continue;
            double w = pg_plt_text_w(se->labels[i], FONT_POINT), h = FONT_POINT;
            double o = (se->marker == PG_MARKER_NONE ? 2 : se->marker_size > 0 ? se->marker_size : 4.5) + 3;
            struct {
                double x, y;
                const char *anchor;
                rect r;
            } cand[8] = {
                /* right, left, above, below, then the four diagonals */
                {px + o + 1, py + 3.5, "start", {px + o, py - h / 2 - 1, px + o + 2 + w, py + h / 2 + 1}},
                {px - o - 1, py + 3.5, "end", {px - o - 2 - w, py - h / 2 - 1, px - o, py + h / 2 + 1}},
                {px, py - o - 2, "middle", {px - w / 2 - 1, py - o - 2 - h, px + w / 2 + 1, py - o}},
                {px, py + o + h, "middle", {px - w / 2 - 1, py + o, px + w / 2 + 1, py + o + h + 2}},
                {px + o * 0.9, py + o * 0.9 + h, "start", {px + o * 0.9 - 1, py + o * 0.9, px + o * 0.9 + w + 1, py + o * 0.9 + h + 2}},
                {px + o * 0.9, py - o * 0.9 - 2, "start", {px + o * 0.9 - 1, py - o * 0.9 - h - 2, px + o * 0.9 + w + 1, py - o * 0.9}},
                {px - o * 0.9, py + o * 0.9 + h, "end", {px - o * 0.9 - w - 1, py + o * 0.9, px - o * 0.9 + 1, py + o * 0.9 + h + 2}},
                {px - o * 0.9, py - o * 0.9 - 2, "end", {px - o * 0.9 - w - 1, py - o * 0.9 - h - 2, px - o * 0.9 + 1, py - o * 0.9}},
            };
            for (int c = 0; c < 8; c++) {
                rect rr = cand[c].r;
                if (rr.x0 < L + 1 || rr.x1 > R - 1 || rr.y0 < T + 1 || rr.y1 > B - 1) continue;
                if (rect_hits(placed, n_placed, rr)) continue;
                pg_plt_sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\" font-size=\"%.0f\" fill=\"#333\">",
                          cand[c].x, cand[c].y, cand[c].anchor, FONT_POINT);
                pg_plt_sb_text(b, se->labels[i]);
                pg_plt_sb_put(b, "</text>\n", 8);
                placed[n_placed++] = rr;
                break;
            }
        }
    }
    free(placed);
    return PG_OK;
}

static void draw_bars(sb *b, const panel *P, double ox, double oy)
{
    const pg_plot_bars *bars = P->pl->bars;
    double L = ox + P->left, T = oy + P->top;
    double pitch = P->ph / (bars->n_bars ? bars->n_bars : 1), bh = fmin(pitch * 0.66, 16);
    for (uint32_t i = 0; i < bars->n_bars; i++) {
        double cy = T + pitch * (i + 0.5);
        char lab[BAR_LABEL_MAX + 8];
        const char *l = bars->bar_labels && bars->bar_labels[i] ? bars->bar_labels[i] : "";
        if (strlen(l) > BAR_LABEL_MAX) {
            memcpy(lab, l, BAR_LABEL_MAX - 3);
            memcpy(lab + BAR_LABEL_MAX - 3, "...", 4);
        } else {
            snprintf(lab, sizeof lab, "%s", l);
        }
        pg_plt_sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\" font-size=\"%.0f\" fill=\"#222\">", L - 7,
                  cy + 4, FONT_TICK);
        pg_plt_sb_text(b, lab);
        pg_plt_sb_put(b, "</text>\n", 8);
        double acc = 0;
        for (uint32_t j = 0; j < bars->n_stack; j++) {
            uint32_t k = bars->order ? bars->order[(size_t)i * bars->n_stack + j] : j;
            if (k >= bars->n_stack) continue;
            double v = bars->values[(size_t)i * bars->n_stack + k];
            if (!isfinite(v) || v <= 0) continue;
            bool ok;
            double x0 = amap(&P->xm, acc, &ok), x1 = amap(&P->xm, acc + v, &ok);
            int c = bars->stack_colors ? bars->stack_colors[k] : (int)k;
            pg_plt_sb_printf(b,
                      "<rect x=\"%.2f\" y=\"%.1f\" width=\"%.2f\" height=\"%.1f\" fill=\"%s\" stroke=\"#fff\" "
                      "stroke-width=\"0.5\"><title>",
                      x0, cy - bh / 2, fmax(x1 - x0, 0), bh, pg_plot_color(c));
            pg_plt_sb_text(b, bars->stack_names ? bars->stack_names[k] : "");
            pg_plt_sb_printf(b, ": %.4g</title></rect>\n", v);
            acc += v;
        }
        if (bars->show_totals) {
            bool ok;
            double xe = amap(&P->xm, acc, &ok);
            char t[96];
            if (fabs(acc) >= 1000) snprintf(t, sizeof t, "%.0f%s", acc, bars->total_unit ? bars->total_unit : "");
            else snprintf(t, sizeof t, "%.3g%s", acc, bars->total_unit ? bars->total_unit : "");
            pg_plt_sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"%.0f\" fill=\"#333\">", xe + 4, cy + 3.5, FONT_POINT);
            pg_plt_sb_text(b, t);
            pg_plt_sb_put(b, "</text>\n", 8);
        }
    }
}

static void draw_legend(sb *b, const panel *P, double ox, double oy)
{
    if (!P->n_legend) return;
    double x0 = ox + P->left + P->pw + (P->right - P->legend_cols * P->legend_col_w) - 4, y0 = oy + P->top + 4;
    for (uint32_t i = 0; i < P->n_legend; i++) {
        const legend_entry *e = &P->legend[i];
        uint32_t col = i / P->legend_rows, row = i % P->legend_rows;
        double x = x0 + col * P->legend_col_w, y = y0 + row * LEGEND_ROW + 8;
        if (e->box) {
            pg_plt_sb_printf(b, "<rect x=\"%.1f\" y=\"%.1f\" width=\"18\" height=\"10\" fill=\"%s\"/>\n", x + 2, y - 5,
                      e->color);
        } else {
            if (e->line)
            {
                pg_plt_sb_printf(b, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"1.8\"",
                          x, y, x + 22, y, e->color);
                if (e->dash) {
                    pg_plt_sb_put(b, " stroke-dasharray=\"", 19);
                    pg_plt_sb_text(b, e->dash);
                    pg_plt_sb_put(b, "\"", 1);
                }
                pg_plt_sb_put(b, "/>\n", 3);
            }
            draw_marker(b, e->marker, x + 11, y, e->marker == PG_MARKER_RING ? 5.5 : 4.2, e->color);
        }
        pg_plt_sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"%.0f\" fill=\"#222\">", x + 28, y + 4, FONT_LEGEND);
        pg_plt_sb_text(b, e->name);
        pg_plt_sb_put(b, "</text>\n", 8);
    }
}

static pg_result draw_panel(sb *b, panel *P, double ox, double oy, pg_error *err)
{
    const pg_plot *pl = P->pl;
    panel_place(P, ox, oy);
    pg_plt_sb_put(b, "<g>\n", 4);
    double y = oy + 12;
    if (pl->title) {
        y += 16;
        pg_plt_sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"%.0f\" font-weight=\"bold\" fill=\"#111\">",
                  ox + P->left, y, FONT_TITLE);
        pg_plt_sb_text(b, pl->title);
        pg_plt_sb_put(b, "</text>\n", 8);
    }
    if (pl->subtitle) {
        y += 16;
        pg_plt_sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"%.1f\" fill=\"#555\">", ox + P->left, y, FONT_SUB);
        pg_plt_sb_text(b, pl->subtitle);
        pg_plt_sb_put(b, "</text>\n", 8);
    }
    draw_axes(b, P, ox, oy);
    pg_result r = PG_OK;
    if (pl->bars) draw_bars(b, P, ox, oy);
    else r = draw_series(b, P, err);
    if (!P->has_data && pl->empty_message) {
        pg_plt_sb_printf(b,
                  "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"%.0f\" fill=\"#777\" "
                  "font-style=\"italic\">",
                  ox + P->left + P->pw / 2, oy + P->top + P->ph / 2, FONT_AXIS);
        pg_plt_sb_text(b, pl->empty_message);
        pg_plt_sb_put(b, "</text>\n", 8);
    }
    draw_legend(b, P, ox, oy);
    pg_plt_sb_put(b, "</g>\n", 5);
    return r;
}

pg_result pg_svg_render(const pg_plot *plots, uint32_t n_plots, const pg_svg_doc_desc *doc, char **out_svg,
                        size_t *out_len, pg_error *err)
{
    *out_svg = NULL;
    if (out_len) *out_len = 0;
    if (n_plots && !plots) return pg_fail(err, PG_ERR_INVALID_ARG, "svg: NULL plots");
    pg_svg_doc_desc d = doc ? *doc : (pg_svg_doc_desc){0};
    panel *P = calloc(n_plots ? n_plots : 1, sizeof *P);
    if (!P) return pg_fail(err, PG_ERR_OOM, "svg: out of memory");
    pg_result r = PG_OK;
    sb b = {0};
    double cw = 0, ch = 0;
    for (uint32_t i = 0; i < n_plots && !r; i++) {
        r = panel_layout(&P[i], &plots[i], err);
        cw = fmax(cw, P[i].w);
        ch = fmax(ch, P[i].h);
    }
    if (r) goto done;
    uint32_t cols = d.columns ? d.columns : (n_plots <= 1 ? 1 : 2);
    if (cols > n_plots && n_plots) cols = n_plots;
    uint32_t rows = n_plots ? (n_plots + cols - 1) / cols : 0;
    double pad = 10,
           head = (d.title ? 30 : 0) + (d.subtitle ? 18 * pg_plt_text_lines(d.subtitle) : 0) + (d.title || d.subtitle ? 6 : 0);
    double W = 2 * pad + cols * cw, H = 2 * pad + head + rows * ch;
    if (d.title) W = fmax(W, 2 * pad + pg_plt_text_w(d.title, 17) * 1.05);
    if (d.subtitle) W = fmax(W, 2 * pad + pg_plt_text_w_lines(d.subtitle, 12.5) + 8);
    if (W < 200) W = 200;
    if (H < 60) H = 60;
    pg_plt_sb_printf(&b,
              "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
              "font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n",
              W, H, W, H);
    if (d.title) {
        pg_plt_sb_put(&b, "<title>", 7);
        pg_plt_sb_text(&b, d.title);
        pg_plt_sb_put(&b, "</title>\n", 9);
    }
    pg_plt_sb_printf(&b, "<rect x=\"0\" y=\"0\" width=\"%.0f\" height=\"%.0f\" fill=\"#ffffff\"/>\n", W, H);
    double y = pad;
    if (d.title) {
        y += 22;
        pg_plt_sb_printf(&b, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"17\" font-weight=\"bold\" fill=\"#111\">", pad + 4, y);
        pg_plt_sb_text(&b, d.title);
        pg_plt_sb_put(&b, "</text>\n", 8);
    }
    for (const char *l = d.subtitle; l;) { /* one <text> per line */
        const char *nl = strchr(l, '\n');
        size_t len = nl ? (size_t)(nl - l) : strlen(l);
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)(len < sizeof line ? len : sizeof line - 1), l);
        y += 18;
        pg_plt_sb_printf(&b, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"12.5\" fill=\"#555\">", pad + 4, y);
        pg_plt_sb_text(&b, line);
        pg_plt_sb_put(&b, "</text>\n", 8);
        l = nl ? nl + 1 : NULL;
    }
    for (uint32_t i = 0; i < n_plots && !r; i++) {
        double ox = pad + (i % cols) * cw, oy = pad + head + (i / cols) * ch;
        r = draw_panel(&b, &P[i], ox, oy, err);
    }
    pg_plt_sb_put(&b, "</svg>\n", 7);
    if (!r && b.oom) r = pg_fail(err, PG_ERR_OOM, "svg: out of memory");
done:
    for (uint32_t i = 0; i < n_plots; i++) free(P[i].legend);
    free(P);
    if (r) {
        free(b.p);
        return r;
    }
    *out_svg = b.p;
    if (out_len) *out_len = b.len;
    return PG_OK;
}

pg_result pg_svg_write(const char *path, const pg_plot *plots, uint32_t n_plots, const pg_svg_doc_desc *doc,
                       pg_error *err)
{
    char *svg = NULL;
    size_t len = 0;
    pg_result r = pg_svg_render(plots, n_plots, doc, &svg, &len, err);
    if (r) return r;
    FILE *f = fopen(path, "wb");
    if (!f) {
        r = pg_fail(err, PG_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
        free(svg);
        return r;
    }
    bool ok = fwrite(svg, 1, len, f) == len;
    int saved = errno;
    if (fclose(f)) ok = false, saved = errno;
    free(svg);
    if (!ok) return pg_fail(err, PG_ERR_IO, "%s: cannot write: %s", path, strerror(saved));
    return PG_OK;
}
