/* graph_dump_svg.c - the memory-timeline SVG view of a compiled graph. */
#include "graph_dump_internal.h"

#include <inttypes.h>
#include <string.h>

/* ------------------------------------------------------------------------------------------ */
/* memory timeline SVG                                                                        */

static void xml_esc(FILE *f, const char *s)
{
    pg_dmp_markup_esc(f, s, false);
}

/* Rough width of text in a sans-serif font of size px (Helvetica's average advance is ~0.55 em;
 * a little more so labels never overflow). Counts UTF-8 code points. */
static double text_w(const char *s, double px)
{
    size_t n = 0;
    for (; s && *s; s++)
        if (((unsigned char)*s & 0xc0) != 0x80) n++;
    return (double)n * px * 0.6;
}

/* Writes s XML-escaped, cut with an ellipsis to fit width pixels at font size px. */
static void xml_fit(FILE *f, const char *s, double width, double px)
{
    if (text_w(s, px) <= width) {
        xml_esc(f, s);
        return;
    }
    char cut[PG_NAME_MAX];
    size_t keep = width > px ? (size_t)(width / (px * 0.6)) : 1;
    if (keep > 1) keep--;
    if (keep >= sizeof cut) keep = sizeof cut - 1;
    pg_strlcpy(cut, s, keep + 1);
    /* do not split a UTF-8 sequence */
    size_t n = strlen(cut);
    while (n && ((unsigned char)cut[n - 1] & 0xc0) == 0x80) n--;
    if (n && ((unsigned char)cut[n - 1] & 0xc0) == 0xc0) n--;
    cut[n] = 0;
    xml_esc(f, cut);
    fputs("\xe2\x80\xa6", f);
}

/* The timeline's geometry: columns (the executed passes, then "read back"), and the rows, one lane
 * per resource alive at once in each memory block. */
typedef struct tl_geo {
    const pg_graph_plan *plan;
    double left, end_w, row_h, bar_h, col_w, grid_w, top, live_h, rows_bottom;
    uint32_t n_cols, n_rows;
    double row_y[PG_MAX_RESOURCES + 1];
    uint32_t lanes_in[PG_MAX_RESOURCES];
    int *lane_of; /* per resource */
} tl_geo;

static double col_x(const tl_geo *g, uint32_t k)
{
    return g->left + (k < g->plan->n_order ? g->col_w * (double)k : g->col_w * (double)g->plan->n_order);
}

static double col_wd(const tl_geo *g, uint32_t k)
{
    return k < g->plan->n_order ? g->col_w : g->end_w;
}

/* a block gets one lane per resource alive at the same time (members sorted by offset, each in
 * the first lane free at its first pass), so bars never overlap */
static void tl_lanes(tl_geo *g)
{
    const pg_graph_plan *plan = g->plan;
    uint32_t n_lanes_total = 0;
    for (uint32_t b = 0; b < plan->n_blocks && b < PG_MAX_RESOURCES; b++) {
        const pg_plan_block *bl = &plan->blocks[b];
        int order_m[PG_MAX_RESOURCES], lane_end[PG_MAX_RESOURCES];
        uint32_t n = 0, lanes = 0;
        for (uint32_t m = 0; m < bl->n_members && m < PG_MAX_RESOURCES; m++) {
            const int r = bl->members[m];
            if (!pg_dmp_res_ok(plan, r)) continue;
            uint32_t k = n++;
            while (k > 0 && plan->resources[order_m[k - 1]].block_offset > plan->resources[r].block_offset) {
                order_m[k] = order_m[k - 1];
                k--;
            }
            order_m[k] = r;
        }
        for (uint32_t i = 0; i < n; i++) {
            const pg_plan_resource *pr = &plan->resources[order_m[i]];
            uint32_t l = 0;
            while (l < lanes && lane_end[l] >= pr->first_pass) l++;
            if (l == lanes) lanes++;
            lane_end[l] = pr->last_pass;
            g->lane_of[order_m[i]] = (int)l;
        }
        g->lanes_in[b] = lanes ? lanes : 1;
        g->row_y[b] = g->top + g->row_h * n_lanes_total;
        n_lanes_total += g->lanes_in[b];
    }
    g->n_rows = n_lanes_total ? n_lanes_total : 1;
}

/* the svg element, its title, the background and the two heading lines */
static void tl_head(FILE *f, const tl_geo *g, const pg_pipeline *pipeline, double width, double height,
                    const char *font, const char *un, const char *al)
{
    const pg_graph_plan *plan = g->plan;
    fprintf(f,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
            "font-family=\"%s\" font-size=\"12\">\n",
            width, height, width, height, font);
    fputs("  <title>memory timeline", f);
    if (pipeline) {
        fputs(": ", f);
        xml_esc(f, pipeline->name);
    }
    fputs("</title>\n", f);
    fputs("  <defs><pattern id=\"hatch\" width=\"6\" height=\"6\" patternUnits=\"userSpaceOnUse\" "
          "patternTransform=\"rotate(45)\"><rect width=\"6\" height=\"6\" fill=\"#f2f2f2\"/>"
          "<line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"6\" stroke=\"#dddddd\" stroke-width=\"2\"/></pattern></defs>\n",
          f);
    fprintf(f, "  <rect x=\"0\" y=\"0\" width=\"%.0f\" height=\"%.0f\" fill=\"#ffffff\"/>\n", width, height);

    /* title */
    fputs("  <text x=\"16\" y=\"26\" font-size=\"16\" font-weight=\"bold\">Memory timeline", f);
    if (pipeline) {
        fputs(" \xe2\x80\x94 ", f);
        xml_esc(f, pipeline->name);
    }
    if (pg_dmp_res_ok(plan, plan->output))
        fprintf(f, " \xc2\xb7 %u\xc3\x97%u", plan->resources[plan->output].width, plan->resources[plan->output].height);
    fputs("</text>\n", f);
    uint32_t n_transient = 0;
    for (uint32_t b = 0; b < plan->n_blocks; b++) n_transient += plan->blocks[b].n_members;
    fprintf(f,
            "  <text x=\"16\" y=\"46\" fill=\"#333333\">%u transient resources in %u memory blocks: %s unaliased "
            "\xe2\x86\x92 %s %s (saving %.1f%%)</text>\n",
            n_transient, plan->n_blocks, un, al, plan->aliasing_disabled ? "(aliasing disabled)" : "aliased",
            pg_graph_plan_saving_percent(plan));
}

/* column headers and grid */
static void tl_columns(FILE *f, const tl_geo *g)
{
    const pg_graph_plan *plan = g->plan;
    const double top = g->top, row_h = g->row_h;
    const uint32_t n_cols = g->n_cols, n_rows = g->n_rows;
    for (uint32_t k = 0; k < n_cols; k++) {
        const double x = col_x(g, k), w = col_wd(g, k);
        if (k < plan->n_order) {
            if (k % 2 == 1)
                fprintf(f, "  <rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#f7f9fc\"/>\n", x, top,
                        w, row_h * n_rows);
            const bool on_c = plan->async && plan->passes[plan->order[k]].queue == PG_QUEUE_COMPUTE;
            fprintf(f, "  <text x=\"%.1f\" y=\"72\" text-anchor=\"middle\" font-size=\"10\" fill=\"#777777\">#%u%s</text>\n",
                    x + w / 2, k, !plan->async ? "" : on_c ? " compute" : " graphics"); /* its queue, when two */
            fprintf(f, "  <text x=\"%.1f\" y=\"90\" text-anchor=\"middle\" font-weight=\"bold\">", x + w / 2);
            xml_fit(f, plan->passes[plan->order[k]].name, w - 8, 12);
            fputs("</text>\n", f);
        } else {
            fprintf(f, "  <rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"url(#hatch)\"/>\n", x, top,
                    w, row_h * n_rows);
            fprintf(f, "  <text x=\"%.1f\" y=\"72\" text-anchor=\"middle\" font-size=\"10\" fill=\"#777777\">after</text>\n",
                    x + w / 2);
            fprintf(f, "  <text x=\"%.1f\" y=\"90\" text-anchor=\"middle\" font-style=\"italic\">read back</text>\n",
                    x + w / 2);
        }
    }
    for (uint32_t k = 0; k <= n_cols; k++) {
        const double x = k < n_cols ? col_x(g, k) : col_x(g, plan->n_order) + g->end_w;
        fprintf(f, "  <line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#d0d0d0\"/>\n", x, top - 8, x,
                g->rows_bottom + g->live_h + 8);
    }
}

/* one bar: resource r of block b, in its lane of the block's row at y */
static void tl_bar(FILE *f, const tl_geo *g, uint32_t b, int r, double y, const char *fill, const char *stroke)
{
    const pg_graph_plan *plan = g->plan;
    const double row_h = g->row_h, bar_h = g->bar_h;
    const pg_plan_resource *pr = &plan->resources[r];
    int first = pr->first_pass < 0 ? 0 : pr->first_pass;
    int last = pr->last_pass < first ? first : pr->last_pass;
    if ((uint32_t)last > plan->n_order) last = (int)plan->n_order;
    const double x0 = col_x(g, (uint32_t)first) + 3, x1 = col_x(g, (uint32_t)last) + col_wd(g, (uint32_t)last) - 3;
    const double by = y + row_h * g->lane_of[r] + (row_h - bar_h) / 2;
    char rb[32], ro[32], detail[96];
    pg_fmt_bytes(pr->size_bytes, rb, sizeof rb);
    pg_fmt_bytes(pr->block_offset, ro, sizeof ro);
    if (pr->kind == PG_RES_IMAGE)
        snprintf(detail, sizeof detail, "%s \xc2\xb7 %s @ %s", pg_format_get(pr->format)->name, rb, ro);
    else
        snprintf(detail, sizeof detail, "%s @ %s", rb, ro);
    fprintf(f,
            "  <g><title>%s", "");
    xml_esc(f, pr->name);
    fprintf(f, ": %s%s, %s .. %s, block #%u @ %" PRIu64 "</title>\n", detail,
            pr->is_output ? " (output)" : "", pg_dmp_pass_at(plan, pr->first_pass) ? pg_dmp_pass_at(plan, pr->first_pass) : "-",
            pg_dmp_pass_at(plan, pr->last_pass) ? pg_dmp_pass_at(plan, pr->last_pass) : "-", b, pr->block_offset);
    fprintf(f,
            "    <rect class=\"bar\" data-resource=\"");
    xml_esc(f, pr->name);
    fprintf(f, "\" data-block=\"%u\" x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" rx=\"5\" "
               "fill=\"%s\" stroke=\"%s\" stroke-width=\"1.2\"/>\n",
            b, x0, by, x1 - x0, bar_h, fill, stroke);
    /* label: "name  format · size" when it fits, else the name, else a cut name */
    const double avail = x1 - x0 - 12;
    const double name_w = text_w(pr->name, 12), det_w = text_w(detail, 10) + 8;
    fprintf(f, "    <text x=\"%.1f\" y=\"%.1f\">", x0 + 6, by + bar_h / 2 + 4);
    if (name_w <= avail) {
        fputs("<tspan font-weight=\"bold\">", f);
        xml_esc(f, pr->name);
        fputs("</tspan>", f);
        if (name_w + det_w <= avail) {
            fputs("<tspan font-size=\"10\" fill=\"#333333\" dx=\"8\">", f);
            xml_esc(f, detail);
            fputs("</tspan>", f);
        }
    } else {
        fputs("<tspan font-weight=\"bold\">", f);
        xml_fit(f, pr->name, avail, 12);
        fputs("</tspan>", f);
    }
    fputs("</text></g>\n", f);
}

/* one row per memory block, one bar per member */
static void tl_blocks(FILE *f, const tl_geo *g)
{
    const pg_graph_plan *plan = g->plan;
    if (!plan->n_blocks)
        fprintf(f, "  <text x=\"%.1f\" y=\"%.1f\" fill=\"#777777\">no transient resources</text>\n", g->left + 10,
                g->top + g->row_h / 2 + 4);
    for (uint32_t b = 0; b < plan->n_blocks; b++) {
        const pg_plan_block *bl = &plan->blocks[b];
        const double y = g->row_y[b], block_h = g->row_h * g->lanes_in[b];
        const char *fill = pg_dmp_block_fill[b % PG_DMP_N_BLOCK_COLOURS], *stroke = pg_dmp_block_stroke[b % PG_DMP_N_BLOCK_COLOURS];
        char bytes[32];
        pg_fmt_bytes(bl->size_bytes, bytes, sizeof bytes);
        fprintf(f, "  <line x1=\"16\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#e4e4e4\"/>\n", y + block_h,
                g->left + g->grid_w, y + block_h);
        fprintf(f, "  <rect x=\"16\" y=\"%.1f\" width=\"10\" height=\"%.1f\" rx=\"2\" fill=\"%s\" stroke=\"%s\"/>\n",
                y + 8, block_h - 16, fill, stroke);
        fprintf(f, "  <text x=\"34\" y=\"%.1f\"><tspan font-weight=\"bold\">block #%u</tspan> %s</text>\n", y + 17, b,
                bytes);
        fprintf(f, "  <text x=\"34\" y=\"%.1f\" font-size=\"10\" fill=\"#666666\">%s%s</text>\n", y + 31,
                pg_res_kind_name(bl->kind),
                bl->n_members > 1 ? (bl->n_members == 2 ? " \xc2\xb7 shared by 2 resources" : " \xc2\xb7 shared")
                                  : "");
        for (uint32_t m = 0; m < bl->n_members && m < PG_MAX_RESOURCES; m++) {
            const int r = bl->members[m];
            if (!pg_dmp_res_ok(plan, r)) continue;
            tl_bar(f, g, b, r, y, fill, stroke);
        }
    }
}

/* live transient bytes per column, and the allocated bytes as the reference line */
static void tl_live(FILE *f, const tl_geo *g, const char *al)
{
    const pg_graph_plan *plan = g->plan;
    const uint32_t n_cols = g->n_cols;
    const double live_h = g->live_h;
    uint64_t live[PG_MAX_PASSES + 1] = {0}, max_live = 0;
    for (uint32_t k = 0; k < n_cols && k <= PG_MAX_PASSES; k++) {
        for (uint32_t r = 0; r < plan->n_resources; r++) {
            const pg_plan_resource *pr = &plan->resources[r];
            if (pr->block < 0 || pr->culled || pr->first_pass < 0) continue;
            if ((int)k >= pr->first_pass && (int)k <= pr->last_pass) live[k] += pr->size_bytes;
        }
        if (live[k] > max_live) max_live = live[k];
    }
    /* the memory the blocks take (all allocated for the whole frame) is the reference line */
    const uint64_t allocated = plan->transient_bytes_aliased;
    if (allocated > max_live) max_live = allocated;
    const double live_top = g->rows_bottom + 8, live_bar_max = live_h - 30;
    fprintf(f, "  <text x=\"16\" y=\"%.1f\" font-weight=\"bold\">live bytes</text>\n", live_top + 18);
    fprintf(f, "  <text x=\"16\" y=\"%.1f\" font-size=\"10\" fill=\"#666666\">sum of the live resources</text>\n",
            live_top + 32);
    for (uint32_t k = 0; k < n_cols && k <= PG_MAX_PASSES; k++) {
        const double w = col_wd(g, k) * 0.5, x = col_x(g, k) + (col_wd(g, k) - w) / 2;
        double h = max_live ? live_bar_max * (double)live[k] / (double)max_live : 0;
        if (live[k] && h < 1.5) h = 1.5;
        const double base = live_top + live_h - 16;
        char lb[32];
        pg_fmt_bytes(live[k], lb, sizeof lb);
        fprintf(f, "  <rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#9fb6d6\"/>\n", x, base - h, w,
                h);
        fprintf(f, "  <text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"10\" fill=\"#333333\">%s</text>\n",
                col_x(g, k) + col_wd(g, k) / 2, base + 12, lb);
    }

    if (allocated && plan->n_blocks) {
        const double base = live_top + live_h - 16;
        const double ya = base - live_bar_max * (double)allocated / (double)max_live;
        fprintf(f,
                "  <line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#b04032\" stroke-width=\"1\" "
                "stroke-dasharray=\"5,3\"/>\n",
                g->left, ya, g->left + g->grid_w, ya);
        fprintf(f,
                "  <text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\" font-size=\"10\" fill=\"#b04032\">allocated "
                "%s</text>\n",
                g->left + g->grid_w - 4, ya - 3, al);
    }
}

void pg_dump_timeline_svg(const pg_graph_plan *plan, const pg_pipeline *pipeline, FILE *f)
{
    if (!f) return;
    const char *font = "Helvetica, Arial, sans-serif";
    if (!plan) {
        fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200\" height=\"40\"><text x=\"10\" "
                   "y=\"24\" font-family=\"%s\">(no plan)</text></svg>\n",
                font);
        return;
    }
    /* geometry */
    static int lane_of[PG_MAX_RESOURCES];
    tl_geo geo;
    tl_geo *g = &geo;
    memset(g, 0, sizeof *g);
    g->plan = plan;
    g->lane_of = lane_of;
    g->left = 200;
    g->end_w = 78;
    g->row_h = 38;
    g->bar_h = 26;
    const double right_margin = 24;
    g->col_w = 100;
    for (uint32_t k = 0; k < plan->n_order; k++) {
        const double w = text_w(plan->passes[plan->order[k]].name, 12) + 20;
        if (w > g->col_w) g->col_w = w;
    }
    if (g->col_w > 200) g->col_w = 200;
    g->n_cols = plan->n_order + 1; /* + "read back" */
    g->grid_w = g->col_w * plan->n_order + g->end_w;
    g->top = 104; /* first row */
    tl_lanes(g);
    g->live_h = 84;
    g->rows_bottom = g->top + g->row_h * g->n_rows;
    const double legend_y = g->rows_bottom + g->live_h + 38;
    static const char *const legend[3] = {
        "Columns: the executed passes in order; \xe2\x80\x9cread back\xe2\x80\x9d: after the last pass (outputs "
        "live until then).",
        "Rows: memory blocks (one lane per resource alive at once); a bar is one transient resource from its "
        "first to its last pass, at the offset it names. Bars of one block share its memory.",
        "Colour = memory block (the same colours as the resources in the graph of passgraph dump --format dot). "
        "Persistent and imported resources are not shown.",
    };
    double width = g->left + g->grid_w + right_margin;
    for (int i = 0; i < 3; i++)
        if (text_w(legend[i], 11) + 40 > width) width = text_w(legend[i], 11) + 40;
    const double height = legend_y + 3 * 17 + 14;

    char un[32], al[32];
    pg_fmt_bytes(plan->transient_bytes_unaliased, un, sizeof un);
    pg_fmt_bytes(plan->transient_bytes_aliased, al, sizeof al);
    tl_head(f, g, pipeline, width, height, font, un, al);
    tl_columns(f, g);
    tl_blocks(f, g);
    tl_live(f, g, al);

    /* legend */
    for (int i = 0; i < 3; i++) {
        fprintf(f, "  <text x=\"16\" y=\"%.1f\" font-size=\"11\" fill=\"#444444\">", legend_y + 17 * i);
        xml_esc(f, legend[i]);
        fputs("</text>\n", f);
    }
    fputs("</svg>\n", f);
}
