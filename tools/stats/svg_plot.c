#include "svg_plot.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Tableau 10: a fixed qualitative palette. */
static const char *const palette[PG_PLOT_PALETTE_SIZE] = {
    "#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
    "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac",
};

const char *pg_plot_color(int index)
{
    if (index < 0) return "#444444";
    return palette[index % PG_PLOT_PALETTE_SIZE];
}

/* ---- string builder ---- */
typedef struct sb {
    char *p;
    size_t len, cap;
    bool oom;
} sb;

static void sb_put(sb *b, const char *s, size_t n)
{
    if (b->oom) return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 16384;
        while (cap < b->len + n + 1) cap *= 2;
        char *p = realloc(b->p, cap);
        if (!p) {
            b->oom = true;
            return;
        }
        b->p = p;
        b->cap = cap;
    }
    memcpy(b->p + b->len, s, n);
    b->len += n;
    b->p[b->len] = 0;
}

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void sb_printf(sb *b, const char *fmt, ...)
{
    char small[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(small, sizeof small, fmt, ap);
    va_end(ap);
    if (n < 0) return;
    if ((size_t)n < sizeof small) {
        sb_put(b, small, (size_t)n);
        return;
    }
    char *big = malloc((size_t)n + 1);
    if (!big) {
        b->oom = true;
        return;
    }
    va_start(ap, fmt);
    vsnprintf(big, (size_t)n + 1, fmt, ap);
    va_end(ap);
    sb_put(b, big, (size_t)n);
    free(big);
}

static const char *esc_of(char c)
{
    switch (c) {
    case '&': return "&amp;";
    case '<': return "&lt;";
    case '>': return "&gt;";
    case '"': return "&quot;";
    case '\'': return "&apos;";
    default: return NULL;
    }
}

/* Escaped text; control characters (invalid in XML 1.0) become spaces. */
static void sb_text(sb *b, const char *s)
{
    for (; s && *s; s++) {
        const char *e = esc_of(*s);
        if (e) sb_put(b, e, strlen(e));
        else if ((unsigned char)*s < 0x20) sb_put(b, " ", 1);
        else sb_put(b, s, 1);
    }
}

void pg_svg_escape(const char *s, char *buf, size_t size)
{
    if (!size) return;
    size_t n = 0;
    for (; s && *s; s++) {
        const char *e = esc_of(*s);
        char one[2] = {(unsigned char)*s < 0x20 ? ' ' : *s, 0};
        const char *piece = e ? e : one;
        size_t l = strlen(piece);
        if (n + l + 1 > size) break;
        memcpy(buf + n, piece, l);
        n += l;
    }
    buf[n] = 0;
}

/* Approximate width of s in px at a font size, from DejaVu Sans's advance widths (the widest of the
 * fonts the documents name, so layouts err on the roomy side); stops at a newline; UTF-8
 * continuation bytes do not count. */
static double text_w(const char *s, double font)
{
    double n = 0;
    for (; s && *s && *s != '\n'; s++) {
        unsigned char c = (unsigned char)*s;
        if ((c & 0xC0) == 0x80) continue;
        if (strchr("il.,:;|!'j", c)) n += 0.29;
        else if (strchr(" ftr()[]-/", c)) n += 0.4;
        else if ((c >= 'A' && c <= 'Z') || c == 'm' || c == 'w' || c == '@' || c == '%') n += 0.76;
        else n += 0.62;
    }
    return n * font;
}

/* Lines of s separated by '\n' (at least 1). */
static uint32_t text_lines(const char *s)
{
    uint32_t n = 1;
    for (; s && *s; s++) n += *s == '\n';
    return n;
}

/* Widest line of a multi-line text. */
static double text_w_lines(const char *s, double font)
{
    double w = 0;
    for (const char *l = s; l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) w = fmax(w, text_w(l, font));
    return w;
}

/* ---- ticks ---- */
static double nice_step(double raw)
{
    if (!(raw > 0) || !isfinite(raw)) return 1;
    double e = floor(log10(raw));
    double p = pow(10, e);
    double f = raw / p;
    double m = f < 1.5 ? 1 : f < 2.25 ? 2 : f < 3.5 ? 2.5 : f < 7.5 ? 5 : 10;
    return m * p;
}

/* Largest 1/2/5 x 10^k <= v (v > 0), and the smallest >= v. */
static double log_floor125(double v)
{
    double p = pow(10, floor(log10(v)));
    double m = v / p * (1 + 1e-12);
    return (m >= 5 ? 5 : m >= 2 ? 2 : 1) * p;
}

static double log_ceil125(double v)
{
    double p = pow(10, floor(log10(v)));
    double m = v / p * (1 - 1e-12);
    return (m <= 1 ? 1 : m <= 2 ? 2 : m <= 5 ? 5 : 10) * p;
}

void pg_plot_nice_range(pg_plot_scale scale, double dmin, double dmax, double *lo, double *hi)
{
    if (dmin > dmax) {
        double t = dmin;
        dmin = dmax;
        dmax = t;
    }
    if (scale == PG_PLOT_LOG10) {
        if (!(dmin > 0) || !isfinite(dmin)) dmin = dmax > 0 && isfinite(dmax) ? dmax : 1;
        if (!(dmax > 0) || !isfinite(dmax)) dmax = dmin;
        if (dmax <= dmin * 1.0001) {
            dmin /= 1.5;
            dmax *= 1.5;
        }
        *lo = log_floor125(dmin);
        *hi = log_ceil125(dmax);
        return;
    }
    if (!isfinite(dmin) || !isfinite(dmax)) dmin = 0, dmax = 1;
    if (dmax - dmin <= 1e-12 * fmax(fabs(dmin), fabs(dmax))) {
        double w = dmin != 0 ? fabs(dmin) * 0.1 : 1;
        dmin -= w;
        dmax += w;
    }
    double step = nice_step((dmax - dmin) / 5);
    *lo = floor(dmin / step + 1e-9) * step;
    *hi = ceil(dmax / step - 1e-9) * step;
}

static uint32_t linear_ticks(double lo, double hi, pg_plot_tick *out, uint32_t max_ticks, double *step_out)
{
    double step = nice_step((hi - lo) / 5);
    if (step_out) *step_out = step;
    uint32_t n = 0;
    double k0 = ceil(lo / step - 1e-9);
    for (double k = k0; n < max_ticks && k * step <= hi + step * 1e-9; k++) {
        double v = k * step;
        if (fabs(v) < step * 1e-9) v = 0;
        out[n].value = v;
        out[n].major = true;
        n++;
    }
    return n;
}

uint32_t pg_plot_ticks(pg_plot_scale scale, double lo, double hi, pg_plot_tick *out, uint32_t max_ticks)
{
    if (!(hi > lo) || !isfinite(lo) || !isfinite(hi) || !max_ticks) return 0;
    if (scale == PG_PLOT_LINEAR) return linear_ticks(lo, hi, out, max_ticks, NULL);
    if (!(lo > 0)) return 0;
    double decades = log10(hi / lo);
    if (decades < 0.6) return linear_ticks(lo, hi, out, max_ticks, NULL);
    uint32_t n = 0;
    int e0 = (int)floor(log10(lo) + 1e-9), e1 = (int)ceil(log10(hi) - 1e-9);
    int label_every = decades <= 8 ? 1 : (int)ceil(decades / 8);
    for (int e = e0; e <= e1 && n < max_ticks; e++) {
        double p = pow(10, e);
        for (int m = 1; m <= 9 && n < max_ticks; m++) {
            double v = m * p;
            if (v < lo * (1 - 1e-9) || v > hi * (1 + 1e-9)) continue;
            bool major;
            if (decades <= 2.5) major = m == 1 || m == 2 || m == 5;
            else if (m == 1) major = ((e % label_every) + label_every) % label_every == 0;
            else if (decades <= 4) major = false;
            else continue; /* many decades: powers of ten only */
            out[n].value = v;
            out[n].major = major;
            n++;
        }
    }
    return n;
}

/* Tick label split as "base" and an optional superscript exponent (then base is "10" or "Mx10"). */
static void tick_label(pg_plot_scale scale, double v, double step, bool sci, char *base, size_t bsize, char *sup,
                       size_t ssize)
{
    sup[0] = 0;
    if (!isfinite(v)) {
        snprintf(base, bsize, "%s", isnan(v) ? "nan" : v > 0 ? "inf" : "-inf");
        return;
    }
    if (scale == PG_PLOT_LINEAR) {
        if (fabs(v) >= 1e6 || (fabs(v) > 0 && fabs(v) < 1e-4)) {
            snprintf(base, bsize, "%g", v);
            return;
        }
        int d = 0;
        double s = fabs(step) > 0 ? fabs(step) : 1;
        while (d < 8 && fabs(s * pow(10, d) - round(s * pow(10, d))) > 1e-6 * s * pow(10, d)) d++;
        snprintf(base, bsize, "%.*f", d, v);
        return;
    }
    double a = fabs(v);
    if (a >= 1e5) {
        static const char *const suffix[] = {"k", "M", "G", "T", "P"};
        int i = 0;
        double s = a / 1e3;
        while (s >= 1000 * (1 - 1e-9) && i < 4) {
            s /= 1000;
            i++;
        }
        snprintf(base, bsize, "%s%.3g%s", v < 0 ? "-" : "", s, suffix[i]);
    } else if (a >= 1 - 1e-9) {
        if (fabs(a - round(a)) < 1e-9 * a) snprintf(base, bsize, "%.0f", v);
        else snprintf(base, bsize, "%.4g", v);
    } else if (a >= 1e-3 * (1 - 1e-9) && !sci) {
        int d = (int)ceil(-log10(a) - 1e-9);
        /* 1 significant digit for 1/2/5 ticks, more if the value needs it */
        while (d < 12 && fabs(a * pow(10, d) - round(a * pow(10, d))) > 1e-6 * a * pow(10, d)) d++;
        snprintf(base, bsize, "%.*f", d, v);
    } else if (a > 0) {
        int e = (int)floor(log10(a) + 1e-9);
        double m = a / pow(10, e);
        if (fabs(m - round(m)) < 1e-6 && round(m) == 1) snprintf(base, bsize, "%s10", v < 0 ? "-" : "");
        else snprintf(base, bsize, "%s%.3g\xc3\x97" "10", v < 0 ? "-" : "", m); /* U+00D7 multiplication sign */
        snprintf(sup, ssize, "%d", e);
    } else {
        snprintf(base, bsize, "0");
    }
}

void pg_plot_format_tick(pg_plot_scale scale, double value, double step, char *buf, size_t size)
{
    char base[64], sup[16];
    tick_label(scale, value, step, false, base, sizeof base, sup, sizeof sup);
    if (sup[0]) snprintf(buf, size, "%s^%s", base, sup);
    else snprintf(buf, size, "%s", base);
}

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
    if (m->scale == PG_PLOT_LINEAR || log10(m->hi / m->lo) < 0.6) m->step = nice_step((m->hi - m->lo) / 5);
}

static double tick_w(const axis_map *m, double v)
{
    char base[64], sup[16];
    tick_label(m->scale, v, m->step, m->sci, base, sizeof base, sup, sizeof sup);
    return text_w(base, FONT_TICK) + text_w(sup, FONT_TICK * 0.75);
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
            double w = text_w(l, FONT_TICK);
            if (l && strlen(l) > BAR_LABEL_MAX) w = text_w("x", FONT_TICK) * BAR_LABEL_MAX;
            if (w > yw) yw = w;
        }
        P->left = 12 + yw + 10;
    } else {
        for (uint32_t t = 0; t < P->ym.n_ticks; t++)
            if (P->ym.ticks[t].major) yw = fmax(yw, tick_w(&P->ym, P->ym.ticks[t].value));
        if (P->ym.band) yw = fmax(yw, text_w(pl->y.zero_label, FONT_TICK));
        P->left = 12 + (pl->y.label ? 20 : 0) + yw + 8;
    }
    double lastx = P->xm.n_ticks ? tick_w(&P->xm, P->xm.ticks[P->xm.n_ticks - 1].value) / 2 : 0;
    if (P->n_legend) {
        double nw = 0;
        for (uint32_t i = 0; i < P->n_legend; i++) nw = fmax(nw, text_w(P->legend[i].name, FONT_LEGEND));
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
    double tw = fmax(text_w(pl->title, FONT_TITLE) * 1.05, text_w(pl->subtitle, FONT_SUB));
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
        sb_printf(b, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"%s\" stroke=\"#fff\" stroke-width=\"0.8\"/>\n",
                  x, y, r, color);
        break;
    case PG_MARKER_RING:
        sb_printf(b, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"none\" stroke=\"%s\" stroke-width=\"1.6\"/>\n",
                  x, y, r, color);
        break;
    case PG_MARKER_SQUARE:
        sb_printf(b,
                  "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"%s\" stroke=\"#fff\" "
                  "stroke-width=\"0.8\"/>\n",
                  x - r * 0.88, y - r * 0.88, r * 1.76, r * 1.76, color);
        break;
    case PG_MARKER_TRIANGLE:
    case PG_MARKER_TRIANGLE_DOWN: {
        double s = m == PG_MARKER_TRIANGLE ? 1 : -1, rr = r * 1.25;
        sb_printf(b,
                  "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f\" fill=\"%s\" stroke=\"#fff\" stroke-width=\"0.8\"/>\n",
                  x, y - s * rr, x - rr * 0.87, y + s * rr * 0.5, x + rr * 0.87, y + s * rr * 0.5, color);
        break;
    }
    case PG_MARKER_DIAMOND:
    default: {
        double rr = r * 1.2;
        sb_printf(b,
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
    tick_label(m->scale, v, m->step, m->sci, base, sizeof base, sup, sizeof sup);
    sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\" font-size=\"%.0f\" fill=\"#333\">", x, y, anchor,
              FONT_TICK);
    sb_text(b, base);
    if (sup[0]) {
        sb_printf(b, "<tspan dy=\"-5\" font-size=\"%.1f\">", FONT_TICK * 0.75);
        sb_text(b, sup);
        sb_put(b, "</tspan>", 8);
    }
    sb_put(b, "</text>\n", 8);
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
            sb_printf(b, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"1\"/>\n", px,
                      T, px, B, pass ? "#dddddd" : "#f0f0f0");
        }
        if (pl->bars) continue;
        for (uint32_t t = 0; t < y->n_ticks; t++) {
            if (y->ticks[t].major != (pass == 1)) continue;
            bool ok;
            double py = amap(y, y->ticks[t].value, &ok);
            if (!ok) continue;
            sb_printf(b, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"1\"/>\n", L,
                      py, R, py, pass ? "#dddddd" : "#f0f0f0");
        }
    }
    /* zero bands: a shaded strip and a dashed separator */
    if (x->band) {
        sb_printf(b, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#f6f6f6\"/>\n", L, T,
                  x->band_edge - L, P->ph);
        sb_printf(b,
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#999\" stroke-dasharray=\"3,3\"/>\n",
                  x->band_edge, T, x->band_edge, B);
    }
    if (y->band) {
        sb_printf(b, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#f6f6f6\"/>\n", L,
                  y->band_edge, P->pw, B - y->band_edge);
        sb_printf(b,
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#999\" stroke-dasharray=\"3,3\"/>\n", L,
                  y->band_edge, R, y->band_edge);
    }
    sb_printf(b, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"#888\"/>\n", L, T,
              P->pw, P->ph);
    /* tick marks and labels */
    for (uint32_t t = 0; t < x->n_ticks; t++) {
        bool ok;
        double px = amap(x, x->ticks[t].value, &ok);
        if (!ok) continue;
        sb_printf(b, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#888\"/>\n", px, B, px,
                  B + (x->ticks[t].major ? 5 : 3));
        if (x->ticks[t].major) draw_tick_label(b, x, x->ticks[t].value, px, B + 17, "middle");
    }
    if (x->band) {
        sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"%.0f\" fill=\"#333\">",
                  x->band_pos, B + 17, FONT_TICK);
        sb_text(b, pl->x.zero_label);
        sb_put(b, "</text>\n", 8);
    }
    if (!pl->bars) {
        for (uint32_t t = 0; t < y->n_ticks; t++) {
            bool ok;
            double py = amap(y, y->ticks[t].value, &ok);
            if (!ok) continue;
            sb_printf(b, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#888\"/>\n",
                      L - (y->ticks[t].major ? 5 : 3), py, L, py);
            if (y->ticks[t].major) draw_tick_label(b, y, y->ticks[t].value, L - 7, py + 4, "end");
        }
        if (y->band) {
            sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\" font-size=\"%.0f\" fill=\"#333\">", L - 7,
                      y->band_pos + 4, FONT_TICK);
            sb_text(b, pl->y.zero_label);
            sb_put(b, "</text>\n", 8);
        }
    }
    /* axis titles */
    if (pl->x.label) {
        sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"%.0f\" fill=\"#222\">",
                  (L + R) / 2, B + 37, FONT_AXIS);
        sb_text(b, pl->x.label);
        sb_put(b, "</text>\n", 8);
    }
    if (pl->y.label && !pl->bars) {
        double cx = ox + 12 + 9, cy = (T + B) / 2;
        sb_printf(b,
                  "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"%.0f\" fill=\"#222\" "
                  "transform=\"rotate(-90 %.1f %.1f)\">",
                  cx, cy, FONT_AXIS, cx, cy);
        sb_text(b, pl->y.label);
        sb_put(b, "</text>\n", 8);
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
                if (open) sb_put(b, "\"/>\n", 4);
                open = false;
                continue;
            }
            if (!open) {
                sb_printf(b, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"%.1f\" stroke-linejoin=\"round\"",
                          pg_plot_color(se->color), se->line_width > 0 ? se->line_width : 1.8);
                if (series_dash(se)) {
                    sb_put(b, " stroke-dasharray=\"", 19);
                    sb_text(b, series_dash(se));
                    sb_put(b, "\"", 1);
                }
                sb_put(b, " points=\"", 9);
                open = true;
            }
            sb_printf(b, "%.1f,%.1f ", px, py);
        }
        if (open) sb_put(b, "\"/>\n", 4);
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
            double w = text_w(se->labels[i], FONT_POINT), h = FONT_POINT;
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
                sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\" font-size=\"%.0f\" fill=\"#333\">",
                          cand[c].x, cand[c].y, cand[c].anchor, FONT_POINT);
                sb_text(b, se->labels[i]);
                sb_put(b, "</text>\n", 8);
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
        sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\" font-size=\"%.0f\" fill=\"#222\">", L - 7,
                  cy + 4, FONT_TICK);
        sb_text(b, lab);
        sb_put(b, "</text>\n", 8);
        double acc = 0;
        for (uint32_t j = 0; j < bars->n_stack; j++) {
            uint32_t k = bars->order ? bars->order[(size_t)i * bars->n_stack + j] : j;
            if (k >= bars->n_stack) continue;
            double v = bars->values[(size_t)i * bars->n_stack + k];
            if (!isfinite(v) || v <= 0) continue;
            bool ok;
            double x0 = amap(&P->xm, acc, &ok), x1 = amap(&P->xm, acc + v, &ok);
            int c = bars->stack_colors ? bars->stack_colors[k] : (int)k;
            sb_printf(b,
                      "<rect x=\"%.2f\" y=\"%.1f\" width=\"%.2f\" height=\"%.1f\" fill=\"%s\" stroke=\"#fff\" "
                      "stroke-width=\"0.5\"><title>",
                      x0, cy - bh / 2, fmax(x1 - x0, 0), bh, pg_plot_color(c));
            sb_text(b, bars->stack_names ? bars->stack_names[k] : "");
            sb_printf(b, ": %.4g</title></rect>\n", v);
            acc += v;
        }
        if (bars->show_totals) {
            bool ok;
            double xe = amap(&P->xm, acc, &ok);
            char t[96];
            if (fabs(acc) >= 1000) snprintf(t, sizeof t, "%.0f%s", acc, bars->total_unit ? bars->total_unit : "");
            else snprintf(t, sizeof t, "%.3g%s", acc, bars->total_unit ? bars->total_unit : "");
            sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"%.0f\" fill=\"#333\">", xe + 4, cy + 3.5, FONT_POINT);
            sb_text(b, t);
            sb_put(b, "</text>\n", 8);
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
            sb_printf(b, "<rect x=\"%.1f\" y=\"%.1f\" width=\"18\" height=\"10\" fill=\"%s\"/>\n", x + 2, y - 5,
                      e->color);
        } else {
            if (e->line)
            {
                sb_printf(b, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"1.8\"",
                          x, y, x + 22, y, e->color);
                if (e->dash) {
                    sb_put(b, " stroke-dasharray=\"", 19);
                    sb_text(b, e->dash);
                    sb_put(b, "\"", 1);
                }
                sb_put(b, "/>\n", 3);
            }
            draw_marker(b, e->marker, x + 11, y, e->marker == PG_MARKER_RING ? 5.5 : 4.2, e->color);
        }
        sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"%.0f\" fill=\"#222\">", x + 28, y + 4, FONT_LEGEND);
        sb_text(b, e->name);
        sb_put(b, "</text>\n", 8);
    }
}

static pg_result draw_panel(sb *b, panel *P, double ox, double oy, pg_error *err)
{
    const pg_plot *pl = P->pl;
    panel_place(P, ox, oy);
    sb_put(b, "<g>\n", 4);
    double y = oy + 12;
    if (pl->title) {
        y += 16;
        sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"%.0f\" font-weight=\"bold\" fill=\"#111\">",
                  ox + P->left, y, FONT_TITLE);
        sb_text(b, pl->title);
        sb_put(b, "</text>\n", 8);
    }
    if (pl->subtitle) {
        y += 16;
        sb_printf(b, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"%.1f\" fill=\"#555\">", ox + P->left, y, FONT_SUB);
        sb_text(b, pl->subtitle);
        sb_put(b, "</text>\n", 8);
    }
    draw_axes(b, P, ox, oy);
    pg_result r = PG_OK;
    if (pl->bars) draw_bars(b, P, ox, oy);
    else r = draw_series(b, P, err);
    if (!P->has_data && pl->empty_message) {
        sb_printf(b,
                  "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"%.0f\" fill=\"#777\" "
                  "font-style=\"italic\">",
                  ox + P->left + P->pw / 2, oy + P->top + P->ph / 2, FONT_AXIS);
        sb_text(b, pl->empty_message);
        sb_put(b, "</text>\n", 8);
    }
    draw_legend(b, P, ox, oy);
    sb_put(b, "</g>\n", 5);
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
           head = (d.title ? 30 : 0) + (d.subtitle ? 18 * text_lines(d.subtitle) : 0) + (d.title || d.subtitle ? 6 : 0);
    double W = 2 * pad + cols * cw, H = 2 * pad + head + rows * ch;
    if (d.title) W = fmax(W, 2 * pad + text_w(d.title, 17) * 1.05);
    if (d.subtitle) W = fmax(W, 2 * pad + text_w_lines(d.subtitle, 12.5) + 8);
    if (W < 200) W = 200;
    if (H < 60) H = 60;
    sb_printf(&b,
              "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
              "font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n",
              W, H, W, H);
    if (d.title) {
        sb_put(&b, "<title>", 7);
        sb_text(&b, d.title);
        sb_put(&b, "</title>\n", 9);
    }
    sb_printf(&b, "<rect x=\"0\" y=\"0\" width=\"%.0f\" height=\"%.0f\" fill=\"#ffffff\"/>\n", W, H);
    double y = pad;
    if (d.title) {
        y += 22;
        sb_printf(&b, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"17\" font-weight=\"bold\" fill=\"#111\">", pad + 4, y);
        sb_text(&b, d.title);
        sb_put(&b, "</text>\n", 8);
    }
    for (const char *l = d.subtitle; l;) { /* one <text> per line */
        const char *nl = strchr(l, '\n');
        size_t len = nl ? (size_t)(nl - l) : strlen(l);
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)(len < sizeof line ? len : sizeof line - 1), l);
        y += 18;
        sb_printf(&b, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"12.5\" fill=\"#555\">", pad + 4, y);
        sb_text(&b, line);
        sb_put(&b, "</text>\n", 8);
        l = nl ? nl + 1 : NULL;
    }
    for (uint32_t i = 0; i < n_plots && !r; i++) {
        double ox = pad + (i % cols) * cw, oy = pad + head + (i / cols) * ch;
        r = draw_panel(&b, &P[i], ox, oy, err);
    }
    sb_put(&b, "</svg>\n", 7);
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
