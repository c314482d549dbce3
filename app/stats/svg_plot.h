/* svg_plot.h - a small SVG chart writer (pure C, no Vulkan): line / scatter series with markers,
 * horizontal stacked bars, linear and log10 axes with "nice" ticks, legends, titles. One document
 * holds one or more charts ("panels") laid out on a grid, e.g. one chart per output size.
 *
 * Everything is described by plain structs whose zero value is the default; the writer borrows
 * the caller's arrays and strings (nothing is kept after the call). Text is XML-escaped.
 *
 * Layout: each panel has a title (and optional subtitle) above its plot area, tick labels and axis
 * labels left of and below it, and its legend in a column to the RIGHT of the plot area, so the
 * legend never covers data. Point labels (scatter) are placed beside their point where they do not
 * overlap another label or marker, and left out where no free spot exists (the legend still names
 * every series). Colours come from one fixed qualitative palette (Tableau 10 and ten more) by index.
 *
 * Log10 axes: labelled ticks at powers of ten (every k-th over more than 8 decades), plus 2 and 5
 * times them when the range spans at most two and a half decades (unlabelled minor ticks at the
 * other multiples up to 4 decades); a range under 0.6 decades gets linear-style ticks. Labels are
 * plain decimals from 0.001 to 99999, SI-suffixed above ("100k", "1M"); when an axis reaches below
 * 0.001 its labels below 1 are written as 10 with a superscript exponent. Values <= 0 cannot sit on a log axis:
 * with zero_label set they are drawn in a separate band at the low end of the axis (below the
 * plot area's log range, after a gap), labelled zero_label (e.g. "0" for zero lights, "0 (exact)"
 * for a zero error); without it they are left out.
 */
#ifndef PG_SVG_PLOT_H
#define PG_SVG_PLOT_H

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PG_PLOT_PALETTE_SIZE 20
/* Palette colour i (wraps around), as "#rrggbb". A negative index gives the neutral dark grey used
 * for reference lines. */
const char *pg_plot_color(int index);

typedef enum pg_plot_scale {
    PG_PLOT_LINEAR = 0,
    PG_PLOT_LOG10 = 1,
} pg_plot_scale;

typedef struct pg_plot_axis {
    const char *label;          /* axis title (NULL: none) */
    pg_plot_scale scale;
    bool fixed_range;           /* use min/max as given; else a nice range around the data */
    double min, max;
    bool include_zero;          /* linear: the range reaches 0 */
    const char *zero_label;     /* log10: label of the band for values <= 0 (see above) */
} pg_plot_axis;

typedef enum pg_plot_marker {
    PG_MARKER_CIRCLE = 0,
    PG_MARKER_SQUARE,
    PG_MARKER_TRIANGLE,
    PG_MARKER_DIAMOND,
    PG_MARKER_TRIANGLE_DOWN,
    PG_MARKER_NONE,
    PG_MARKER_RING,             /* hollow circle drawn around a point (highlight) */
    PG_MARKER_COUNT
} pg_plot_marker;
/* The filled markers in a fixed order, for cycling (i % PG_PLOT_FILLED_MARKERS). */
#define PG_PLOT_FILLED_MARKERS 5

typedef struct pg_plot_series {
    const char *name;           /* legend entry; NULL: not in the legend */
    const double *x, *y;        /* n points; a point with a non-finite coordinate is skipped (and breaks the line) */
    uint32_t n;
    const char *const *labels;  /* optional per-point labels (NULL entries: none) */
    int color;                  /* palette index; negative: neutral dark grey */
    pg_plot_marker marker;
    double marker_size;         /* radius-like size in px; 0: 4.5 */
    bool line;                  /* connect the points in the given order */
    bool dashed;                /* a "6,4" dash pattern */
    const char *dasharray;      /* any SVG stroke-dasharray (e.g. "2,3"); overrides dashed */
    double line_width;          /* 0: 1.8 */
} pg_plot_series;

/* Horizontal stacked bars: bar b's segment k is values[b * n_stack + k] (non-finite or negative:
 * 0). The value axis is the chart's x axis (linear), bars are listed top to bottom. */
typedef struct pg_plot_bars {
    uint32_t n_bars, n_stack;
    const char *const *bar_labels;   /* n_bars */
    const char *const *stack_names;  /* n_stack, legend entries */
    const double *values;
    const int *stack_colors;         /* optional palette indexes (default: k) */
    const uint32_t *order;           /* optional: bar b draws its segments left to right in the order
                                        order[b * n_stack + 0..n_stack-1] (stack indexes; default 0, 1, ...) */
    bool show_totals;                /* write each bar's total after it (3 significant digits) */
    const char *total_unit;          /* appended to the totals, e.g. " ms" (NULL: none) */
} pg_plot_bars;

typedef struct pg_plot {
    const char *title, *subtitle;
    pg_plot_axis x, y;
    const pg_plot_series *series;
    uint32_t n_series;
    const pg_plot_bars *bars;        /* optional: a stacked bar chart (x is the value axis; y unused) */
    double width, height;            /* plot area in px; 0: 520 x 340 (bars: height from the bar count) */
    bool no_legend;
    const char *empty_message;       /* drawn in the plot area when there is nothing to plot */
} pg_plot;

typedef struct pg_svg_doc_desc {
    const char *title;               /* document title above the panels (NULL: none) */
    const char *subtitle;            /* '\n' starts a new line */
    uint32_t columns;                /* panels per row; 0: 2 (or 1 for a single panel) */
} pg_svg_doc_desc;

/* Renders the panels into one SVG document: *out_svg is malloc'd, NUL-terminated (free it).
 * PG_ERR_INVALID_ARG for NULL plots with n > 0 or a series with NULL x/y and n > 0. */
pg_result pg_svg_render(const pg_plot *plots, uint32_t n_plots, const pg_svg_doc_desc *doc, char **out_svg,
                        size_t *out_len, pg_error *err);
/* Same, written to path (PG_ERR_IO naming the path and the cause). */
pg_result pg_svg_write(const char *path, const pg_plot *plots, uint32_t n_plots, const pg_svg_doc_desc *doc,
                       pg_error *err);

/* ---- building blocks, exposed for tests ---- */

typedef struct pg_plot_tick {
    double value;
    bool major;                      /* labelled; minor ticks get a faint grid line only */
} pg_plot_tick;

/* A nice axis range covering [dmin, dmax] (finite; log10: both > 0). Linear: rounded out to the
 * tick step (about 5 ticks). Log10: rounded out to 1, 2 or 5 times a power of ten. A degenerate
 * range is widened. */
void pg_plot_nice_range(pg_plot_scale scale, double dmin, double dmax, double *lo, double *hi);
/* Ticks within [lo, hi] (at most max_ticks written); returns the count. Linear: multiples of a
 * 1/2/2.5/5 x 10^k step, all major. Log10: see the header comment. */
uint32_t pg_plot_ticks(pg_plot_scale scale, double lo, double hi, pg_plot_tick *out, uint32_t max_ticks);
/* Tick label as plain text ("0.25", "100k", "1e-06" for the superscript cases); step is the
 * linear tick step (decides the decimals; ignored for log10). */
void pg_plot_format_tick(pg_plot_scale scale, double value, double step, char *buf, size_t size);
/* Writes s with &, <, >, " and ' escaped into buf (always NUL-terminated; truncates). */
void pg_svg_escape(const char *s, char *buf, size_t size);

#ifdef __cplusplus
}
#endif
#endif
