/* plplot_trial.c - a trial of PLplot (Debian libplplot-dev, its C API and svg driver) for the
 * bench's error-vs-time chart, to compare with tools/stats/svg_plot.c (docs/charts.md has the
 * verdict). Not part of the default build: cmake -DPG_PLPLOT_TRIAL=ON, then
 *
 *     build/plplot_trial DIR/results.csv OUT.svg [--plplot-labels]
 *
 * reads a real `passgraph bench` results.csv and draws what bench_charts.c's chart_error draws:
 * one panel per (scene, size, light count), x = gpu_ms_median and y = rmse_linear on log axes,
 * one marked series per pipeline (variant) in the bench's palette, the Pareto front dashed with
 * its points ringed and named, a legend and axis titles. A row with RMSE 0 (the reference
 * itself) cannot sit on a log axis: it is drawn in a grey band under the axis floor labelled
 * "0 (exact)", as svg_plot.c does. --plplot-labels: PLplot's own axis labels (decades only)
 * instead of the 1-2-5 labels placed by hand. Exit 0 on success, 1 on a bad file, 2 on bad arguments. */
#define _DEFAULT_SOURCE /* M_PI */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <plplot.h>

#include "bench_stats.h"
#include "svg_plot.h"

#define MAX_ROWS 4096
#define MAX_COLS 512
#define MAX_SERIES 64
#define MAX_BLOCKS 16

typedef struct row {
    char scene[128], label[256];
    unsigned lights, width, height;
    double gpu, rmse;
} row;

/* One CSV record (RFC 4180: quoted fields, "" inside quotes) split in place into fields. */
static int csv_split(char *line, char **fields, int max)
{
    int n = 0;
    char *p = line;
    for (;;) {
        if (n == max) return -1;
        char *out = p;
        fields[n++] = out;
        if (*p == '"') {
            p++;
            for (;;) {
                if (!*p) return -1;
                if (*p == '"' && p[1] == '"') {
                    *out++ = '"';
                    p += 2;
                } else if (*p == '"') {
                    p++;
                    break;
                } else
                    *out++ = *p++;
            }
        } else
            while (*p && *p != ',' && *p != '\n' && *p != '\r') *out++ = *p++;
        char c = *p;
        *out = 0;
        if (c != ',') return n;
        p++;
    }
}

static int col(char **names, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(names[i], name)) return i;
    return -1;
}

static int load(const char *path, row *rows, int *n_rows)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "plplot_trial: %s: cannot open\n", path);
        return 1;
    }
    static char head[1 << 16], line[1 << 16];
    char *names[MAX_COLS], *v[MAX_COLS];
    if (!fgets(head, sizeof head, f)) {
        fprintf(stderr, "plplot_trial: %s: empty\n", path);
        fclose(f);
        return 1;
    }
    int nc = csv_split(head, names, MAX_COLS);
    int c_scene = col(names, nc, "scene"), c_pipe = col(names, nc, "pipeline"), c_var = col(names, nc, "variant"),
        c_lights = col(names, nc, "lights"), c_w = col(names, nc, "width"), c_h = col(names, nc, "height"),
        c_status = col(names, nc, "status"), c_gpu = col(names, nc, "gpu_ms_median"),
        c_rmse = col(names, nc, "rmse_linear");
    if (c_scene < 0 || c_pipe < 0 || c_var < 0 || c_lights < 0 || c_w < 0 || c_h < 0 || c_status < 0 || c_gpu < 0 ||
        c_rmse < 0) {
        fprintf(stderr, "plplot_trial: %s: not a passgraph bench results.csv (a column is missing)\n", path);
        fclose(f);
        return 1;
    }
    *n_rows = 0;
    for (int ln = 2; fgets(line, sizeof line, f); ln++) {
        int n = csv_split(line, v, MAX_COLS);
        if (n != nc) {
            fprintf(stderr, "plplot_trial: %s:%d: %d fields, the header has %d\n", path, ln, n, nc);
            fclose(f);
            return 1;
        }
        /* the rows chart_error plots: timed (ok or interrupted) with an error measured */
        if ((strcmp(v[c_status], "ok") && strcmp(v[c_status], "interrupted")) || !v[c_gpu][0] || !v[c_rmse][0])
            continue;
        if (*n_rows == MAX_ROWS) break;
        row *r = &rows[(*n_rows)++];
        snprintf(r->scene, sizeof r->scene, "%s", v[c_scene]);
        snprintf(r->label, sizeof r->label, "%s%s%s", v[c_pipe], v[c_var][0] ? " " : "", v[c_var]);
        r->lights = (unsigned)strtoul(v[c_lights], NULL, 10);
        r->width = (unsigned)strtoul(v[c_w], NULL, 10);
        r->height = (unsigned)strtoul(v[c_h], NULL, 10);
        r->gpu = strtod(v[c_gpu], NULL);
        r->rmse = strtod(v[c_rmse], NULL);
    }
    fclose(f);
    return 0;
}

static void set_color(int index, int slot)
{
    unsigned rgb = (unsigned)strtoul(pg_plot_color(index) + 1, NULL, 16);
    plscol0(slot, (int)(rgb >> 16), (int)(rgb >> 8 & 255), (int)(rgb & 255));
    plcol0(slot);
}

/* A circle of radius r_mm around (x, y) in world units: PLplot's symbols are font glyphs in the
 * svg driver (sized and centred by the font: a ring around a dot drawn as glyphs sits off
 * centre), so the markers are polygons */
static void disc(double x, double y, double r_mm, bool filled)
{
    PLFLT vx0, vx1, vy0, vy1, wx0, wx1, wy0, wy1, sx0, sx1, sy0, sy1;
    plgvpd(&vx0, &vx1, &vy0, &vy1);
    plgvpw(&wx0, &wx1, &wy0, &wy1);
    plgspa(&sx0, &sx1, &sy0, &sy1);
    double kx = (wx1 - wx0) / ((vx1 - vx0) * (sx1 - sx0)), ky = (wy1 - wy0) / ((vy1 - vy0) * (sy1 - sy0));
    PLFLT px[33], py[33];
    for (int i = 0; i <= 32; i++) {
        double a = 2 * M_PI * i / 32;
        px[i] = x + r_mm * kx * cos(a);
        py[i] = y + r_mm * ky * sin(a);
    }
    if (filled) plfill(32, px, py);
    else plline(33, px, py);
}

/* Labels at 1, 2, 5 x 10^k inside [l0, l1] (log10 units) on one side of the viewport: plain
 * numbers from 1 to 99999, else "m×10^k" with a superscript. */
static void label_125(double l0, double l1, double w0, double w1, const char *side, double disp, double just)
{
    for (int k = (int)floor(l0) - 1; k <= (int)ceil(l1); k++)
        for (int m = 1; m <= 5; m += m == 1 ? 1 : 3) {
            double v = m * pow(10, k), lv = log10(v);
            if (lv < l0 || lv > l1) continue;
            char t[64];
            if (k >= 0 && k < 5) snprintf(t, sizeof t, "%g", v);
            else if (m == 1) snprintf(t, sizeof t, "10#u%d#d", k);
            else snprintf(t, sizeof t, "%d×10#u%d#d", m, k);
            plmtex(side, disp, (lv - w0) / (w1 - w0), just, t);
        }
}

int main(int argc, char **argv)
{
    bool native = argc == 4 && !strcmp(argv[3], "--plplot-labels");
    if (argc != 3 && !native) {
        fprintf(stderr, "usage: plplot_trial RESULTS.csv OUT.svg [--plplot-labels]\n");
        return 2;
    }
    static row rows[MAX_ROWS];
    int n_rows = 0;
    if (load(argv[1], rows, &n_rows)) return 1;
    /* series (pipeline + variant) in first-seen order, as the bench numbers them */
    char series[MAX_SERIES][256];
    int n_series = 0;
    for (int i = 0; i < n_rows; i++) {
        int k = 0;
        while (k < n_series && strcmp(series[k], rows[i].label)) k++;
        if (k == n_series && n_series < MAX_SERIES) snprintf(series[n_series++], 256, "%s", rows[i].label);
    }
    /* blocks: (scene, size, lights) in first-seen order */
    int block_first[MAX_BLOCKS], n_blocks = 0;
    for (int i = 0; i < n_rows && n_blocks < MAX_BLOCKS; i++) {
        bool seen = false;
        for (int b = 0; b < n_blocks && !seen; b++) {
            const row *o = &rows[block_first[b]];
            seen = !strcmp(o->scene, rows[i].scene) && o->width == rows[i].width && o->height == rows[i].height &&
                   o->lights == rows[i].lights;
        }
        if (!seen) block_first[n_blocks++] = i;
    }
    if (!n_blocks) {
        fprintf(stderr, "plplot_trial: %s: no row with a time and an error\n", argv[1]);
        return 1;
    }

    plsdev("svg");
    plsfnam(argv[2]);
    plspage(0, 0, 790 * n_blocks, 500, 0, 0); /* the size svg_plot.c gives one panel, roughly */
    plscolbg(255, 255, 255);
    plinit();
    plfontld(1);
    pladv(0);
    /* the document title over all panels (one page, the panels' viewports placed by hand) */
    plvpor(0, 1, 0, 1);
    plwind(0, 1, 0, 1);
    plscol0(1, 34, 34, 34);
    plcol0(1);
    plschr(4.2, 1.0);
    plmtex("t", -2.0, 0.01, 0.0, "passgraph bench: image error against GPU time");
    plscol0(12, 102, 102, 102);
    plcol0(12);
    plschr(2.8, 1.0);
    plmtex("t", -4.6, 0.01, 0.0,
           "RMSE against reference (lower left is better); dashed: the Pareto front (no other point is both faster "
           "and more accurate)");
    for (int b = 0; b < n_blocks; b++) {
        const row *r0 = &rows[block_first[b]];
        double xs[MAX_ROWS], ys[MAX_ROWS];
        int idx[MAX_ROWS], n = 0;
        double xmin = INFINITY, xmax = 0, ymin = INFINITY, ymax = 0;
        bool any_zero = false;
        for (int i = 0; i < n_rows; i++) {
            const row *r = &rows[i];
            if (strcmp(r->scene, r0->scene) || r->width != r0->width || r->height != r0->height || r->lights != r0->lights)
                continue;
            idx[n] = i;
            xs[n] = r->gpu;
            ys[n] = r->rmse;
            n++;
            if (r->gpu > 0) xmin = fmin(xmin, r->gpu), xmax = fmax(xmax, r->gpu);
            if (r->rmse > 0) ymin = fmin(ymin, r->rmse), ymax = fmax(ymax, r->rmse);
            else any_zero = true;
        }
        if (!(ymax > 0)) ymin = 1e-4, ymax = 1e-3;
        /* log ranges padded by 15% of a decade-ish factor; the zero band below the floor */
        double lx0 = log10(xmin) - 0.12, lx1 = log10(xmax) + 0.12;
        double ly0 = log10(ymin) - 0.15, ly1 = log10(ymax) + 0.15;
        double band = any_zero ? 0.09 * (ly1 - ly0) : 0;
        double lzero = ly0 - band * 0.5;

        plvpor((b + 0.12) / n_blocks, (b + 0.70) / n_blocks, 0.14, 0.76);
        plwind(lx0, lx1, ly0 - band, ly1);
        if (any_zero) { /* the grey band where RMSE 0 is drawn */
            PLFLT bx[4] = {lx0, lx1, lx1, lx0}, by[4] = {ly0 - band, ly0 - band, ly0, ly0};
            plscol0(15, 245, 245, 245);
            plcol0(15);
            plfill(4, bx, by);
        }
        /* grid first, faint: 'g' at the decades, 'h' at the minor ticks 2..9 */
        plscol0(14, 226, 226, 226);
        plcol0(14);
        plbox("gh", 0, 0, "gh", 0, 0);
        /* frame and log ticks ('l' log, 't' major at decades, 's' minor at 2..9). PLplot's own
         * labels ('n') are only at the decades (10^k): a range under a decade would get one label
         * or none, so the 1-2-5 labels are placed by hand with plmtex, as svg_plot.c places them */
        plscol0(1, 34, 34, 34);
        plscol0(12, 102, 102, 102);
        plcol0(12);
        plschr(2.6, 1.0);
        if (native) { /* --plplot-labels: PLplot's own log labels, for docs/charts.md */
            plbox("bclnst", 0, 0, "bclnstv", 0, 0);
        } else {
            plbox("bclst", 0, 0, "bclst", 0, 0);
            label_125(lx0, lx1, lx0, lx1, "b", 1.6, 0.5);
            label_125(ly0, ly1, ly0 - band, ly1, "lv", 0.7, 1.0);
        }
        plcol0(1);
        char title[512];
        snprintf(title, sizeof title, "%s, %ux%u, %u lights", r0->scene, r0->width, r0->height, r0->lights);
        plschr(3.2, 1.0);
        plmtex("t", 1.2, 0.0, 0.0, title);
        plschr(2.8, 1.0);
        plmtex("b", 3.4, 0.5, 0.5, "GPU ms per frame, median (log)");
        plmtex("l", 6.4, 0.5, 0.5, "RMSE vs reference, linear HDR (log)");
        plcol0(12);
        plschr(2.6, 1.0);
        if (any_zero) plmtex("lv", 0.7, (lzero - (ly0 - band)) / (ly1 - (ly0 - band)), 1.0, "0 (exact)");

        /* points: one filled circle per row, in its series' colour */
        double px[MAX_ROWS], py[MAX_ROWS];
        for (int k = 0; k < n; k++) {
            int s = 0;
            while (s < n_series && strcmp(series[s], rows[idx[k]].label)) s++;
            px[k] = log10(xs[k]);
            py[k] = ys[k] > 0 ? log10(ys[k]) : lzero;
            set_color(s, 2 + (s % 10));
            disc(px[k], py[k], 1.3, true);
        }
        /* the Pareto front (RMSE 0 counts as the smallest error) */
        double fyv[MAX_ROWS];
        for (int k = 0; k < n; k++) fyv[k] = ys[k];
        uint32_t order[MAX_ROWS];
        uint32_t nf = pg_pareto_front(xs, fyv, (uint32_t)n, NULL, order);
        double fx[MAX_ROWS], fy[MAX_ROWS];
        for (uint32_t j = 0; j < nf; j++) fx[j] = px[order[j]], fy[j] = py[order[j]];
        plscol0(13, 68, 68, 68);
        plcol0(13);
        pllsty(2);
        plline((int)nf, fx, fy);
        pllsty(1);
        for (uint32_t j = 0; j < nf; j++) disc(fx[j], fy[j], 2.4, false);
        plschr(2.4, 1.0);
        for (uint32_t j = 0; j < nf; j++)
            plptex(fx[j] + 0.02 * (lx1 - lx0), fy[j], 1, 0, 0, rows[idx[order[j]]].label);

        /* legend: every series, then the front */
        PLINT opts[MAX_SERIES + 1], tcol[MAX_SERIES + 1], lcol[MAX_SERIES + 1], lsty[MAX_SERIES + 1],
            scol[MAX_SERIES + 1], snum[MAX_SERIES + 1], boxc[MAX_SERIES + 1], boxp[MAX_SERIES + 1];
        PLFLT lwid[MAX_SERIES + 1], sscale[MAX_SERIES + 1], boxs[MAX_SERIES + 1], boxw[MAX_SERIES + 1];
        const char *text[MAX_SERIES + 1], *syms[MAX_SERIES + 1];
        int nl = 0;
        for (int s = 0; s < n_series; s++, nl++) {
            set_color(s, 2 + (s % 10));
            opts[nl] = PL_LEGEND_SYMBOL;
            tcol[nl] = 1;
            scol[nl] = 2 + (s % 10);
            sscale[nl] = 2.6;
            snum[nl] = 1;
            syms[nl] = "#(850)";
            text[nl] = series[s];
            lcol[nl] = 1, lsty[nl] = 1, lwid[nl] = 1, boxc[nl] = 0, boxp[nl] = 0, boxs[nl] = 0, boxw[nl] = 0;
        }
        opts[nl] = PL_LEGEND_LINE | PL_LEGEND_SYMBOL;
        tcol[nl] = 1, lcol[nl] = 13, lsty[nl] = 2, lwid[nl] = 1, scol[nl] = 13, sscale[nl] = 3.0, snum[nl] = 1;
        syms[nl] = "#(840)"; /* Hershey 840: circle */
        text[nl] = "Pareto front";
        boxc[nl] = 0, boxp[nl] = 0, boxs[nl] = 0, boxw[nl] = 0;
        nl++;
        PLFLT lw, lh;
        plschr(2.6, 1.0);
        pllegend(&lw, &lh, 0, PL_POSITION_OUTSIDE | PL_POSITION_RIGHT, 0.02, 0.0, 0.05, 0, 0, 1,
                 0, 0, nl, opts, 1.0, 1.0, 2.0, 0.0, tcol, text, boxc, boxp, boxs, boxw, lcol, lsty, lwid, scol, sscale,
                 snum, syms);
    }
    plend();
    printf("plplot_trial: %d rows, %d panels -> %s\n", n_rows, n_blocks, argv[2]);
    return 0;
}
