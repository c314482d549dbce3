/* svg_plot_internal.h - what the SVG chart writer's files share; not part of the stats
 * library's interface (only tools/stats/svg_plot*.c include it).
 *
 *   svg_plot_text.c   the palette, the string builder, XML escaping, text widths, ticks and
 *                     their labels
 *   svg_plot.c        layout (panels, axes, legends), drawing, pg_svg_render(), pg_svg_write()
 */
#ifndef PG_SVG_PLOT_INTERNAL_H
#define PG_SVG_PLOT_INTERNAL_H

#include "svg_plot.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
/* ---- string builder ---- */
typedef struct sb {
    char *p;
    size_t len, cap;
    bool oom;
} sb;

/* svg_plot_text.c */
void pg_plt_sb_put(sb *b, const char *s, size_t n);
void pg_plt_sb_printf(sb *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void pg_plt_sb_text(sb *b, const char *s);
double pg_plt_text_w(const char *s, double font);
uint32_t pg_plt_text_lines(const char *s);
double pg_plt_text_w_lines(const char *s, double font);
double pg_plt_nice_step(double raw);
void pg_plt_tick_label(pg_plot_scale scale, double v, double step, bool sci, char *base, size_t bsize, char *sup,
                       size_t ssize);

#endif
