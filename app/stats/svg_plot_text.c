/* svg_plot_text.c - the SVG chart writer's palette, string builder, text widths and ticks; see
 * svg_plot_internal.h. */
#include "svg_plot_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A fixed qualitative palette: Tableau 10, then ten darker or lighter colours told apart from
 * them (a bench over every pipeline stacks 15 and more passes: with 10 colours, display and
 * assign_lights shared one in one bar) */
static const char *const palette[PG_PLOT_PALETTE_SIZE] = {
    "#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac",
    "#1b3a5c", "#a0cbe8", "#8c2d04", "#2f6b3a", "#b6992d", "#5c3a6e", "#d37295", "#3d3d3d", "#7fc97f", "#00a0b0",
};

const char *pg_plot_color(int index)
{
    if (index < 0) return "#444444";
    return palette[index % PG_PLOT_PALETTE_SIZE];
}

void pg_plt_sb_put(sb *b, const char *s, size_t n)
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
void pg_plt_sb_printf(sb *b, const char *fmt, ...)
{
    char small[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(small, sizeof small, fmt, ap);
    va_end(ap);
    if (n < 0) return;
    if ((size_t)n < sizeof small) {
        pg_plt_sb_put(b, small, (size_t)n);
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
    pg_plt_sb_put(b, big, (size_t)n);
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
void pg_plt_sb_text(sb *b, const char *s)
{
    for (; s && *s; s++) {
        const char *e = esc_of(*s);
        if (e) pg_plt_sb_put(b, e, strlen(e));
        else if ((unsigned char)*s < 0x20) pg_plt_sb_put(b, " ", 1);
        else pg_plt_sb_put(b, s, 1);
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
double pg_plt_text_w(const char *s, double font)
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
uint32_t pg_plt_text_lines(const char *s)
{
    uint32_t n = 1;
    for (; s && *s; s++) n += *s == '\n';
    return n;
}

/* Widest line of a multi-line text. */
double pg_plt_text_w_lines(const char *s, double font)
{
    double w = 0;
    for (const char *l = s; l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) w = fmax(w, pg_plt_text_w(l, font));
    return w;
}

/* ---- ticks ---- */
double pg_plt_nice_step(double raw)
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
    double step = pg_plt_nice_step((dmax - dmin) / 5);
    *lo = floor(dmin / step + 1e-9) * step;
    *hi = ceil(dmax / step - 1e-9) * step;
}

static uint32_t linear_ticks(double lo, double hi, pg_plot_tick *out, uint32_t max_ticks, double *step_out)
{
    double step = pg_plt_nice_step((hi - lo) / 5);
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
void pg_plt_tick_label(pg_plot_scale scale, double v, double step, bool sci, char *base, size_t bsize, char *sup,
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
    pg_plt_tick_label(scale, value, step, false, base, sizeof base, sup, sizeof sup);
    if (sup[0]) snprintf(buf, size, "%s^%s", base, sup);
    else snprintf(buf, size, "%s", base);
}
