/* graph_dump.c - text, JSON, Graphviz DOT and memory-timeline SVG views of a compiled graph
 * (see graph_dump.h; the formats are documented in docs/dump-format.md). This file: the shared
 * helpers and the text view; graph_dump_internal.h lists the others.
 *
 * Everything here reads the plan only. pg_dump_run_graphviz() (graph_dump_dot.c) is the one
 * function with a side effect: it runs `dot` through posix_spawnp (no shell). */
#include "graph_dump_internal.h"

#include <inttypes.h>
#include <string.h>

/* ------------------------------------------------------------------------------------------ */
/* shared helpers                                                                             */

bool pg_dmp_res_ok(const pg_graph_plan *plan, int r)
{
    return r >= 0 && (uint32_t)r < plan->n_resources;
}

const char *pg_dmp_res_name(const pg_graph_plan *plan, int r)
{
    return pg_dmp_res_ok(plan, r) ? plan->resources[r].name : "?";
}

const char *pg_dmp_type_name(const pg_plan_pass *pp)
{
    return pp->type && pp->type->name ? pp->type->name : "?";
}

/* name of the executed pass at position pos; "(end)" past the last pass */
const char *pg_dmp_pass_at(const pg_graph_plan *plan, int pos)
{
    if (pos < 0) return NULL;
    if ((uint32_t)pos >= plan->n_order) return "(end)";
    return plan->passes[plan->order[pos]].name;
}

/* position of pass index p in the execution order, -1 when culled */
int pg_dmp_position_of(const pg_graph_plan *plan, uint32_t p)
{
    for (uint32_t k = 0; k < plan->n_order; k++)
        if (plan->order[k] == (int)p) return (int)k;
    return -1;
}

void pg_dmp_markup_esc(FILE *f, const char *s, bool dot_label)
{
    for (; s && *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'':
            if (dot_label) fputc('\'', f);
            else fputs("&apos;", f);
            break;
        case '\n':
            if (dot_label) fputs("<br/>", f);
            else fputc('\n', f);
            break;
        default: fputc(*s, f);
        }
    }
}

/* Colours of memory blocks, shared by the DOT graph and the timeline (ColorBrewer Set3: light
 * enough for black text). stroke is a darker shade of the same hue. */
const char *const pg_dmp_block_fill[] = {"#8dd3c7", "#ffffb3", "#bebada", "#fb8072",
                                           "#80b1d3", "#fdb462", "#b3de69", "#fccde5",
                                           "#bc80bd", "#ccebc5", "#ffed6f", "#d9d9d9"};
const char *const pg_dmp_block_stroke[] = {"#3c8c80", "#a6a64d", "#6f6a99", "#b04032",
                                             "#3a6f94", "#b06e1c", "#6a9a22", "#b06e99",
                                             "#7a3f7b", "#6e9a6a", "#a89a1a", "#808080"};

/* ------------------------------------------------------------------------------------------ */
/* short names for edge labels                                                                */

/* Adds word to the '+'-joined list in buf unless it is there already ("depth_read|depth_write"
 * -> "depth"). */
static void add_short_word(char *buf, size_t size, size_t *len, const char *word)
{
    for (const char *s = buf; *s;) {
        size_t n = strcspn(s, "+");
        if (n == strlen(word) && !strncmp(s, word, n)) return;
        s += n;
        if (*s) s++;
    }
    if (*len >= size) return;
    int w = snprintf(buf + *len, size - *len, "%s%s", *len ? "+" : "", word);
    if (w > 0) *len += (size_t)w;
}

/* Access mask -> "color", "sampled", "depth", "storage" ... (read/write suffixes dropped: the
 * hazard name says which side writes), joined with '+'; "-" for none. */
static void short_access(uint64_t access, char *buf, size_t size)
{
    buf[0] = 0;
    if (!access) {
        pg_strlcpy(buf, "-", size);
        return;
    }
    const char *names[64];
    uint64_t unnamed = 0;
    const uint32_t n = pg_access_bit_names(access, names, 64, &unnamed);
    size_t len = 0;
    for (uint32_t i = 0; i < n; i++) {
        char word[64];
        pg_strlcpy(word, names[i], sizeof word);
        size_t wl = strlen(word);
        if (wl > 6 && !strcmp(word + wl - 6, "_write")) word[wl - 6] = 0;
        else if (wl > 5 && !strcmp(word + wl - 5, "_read")) word[wl - 5] = 0;
        add_short_word(buf, size, &len, word);
    }
    if (unnamed) {
        char word[32];
        snprintf(word, sizeof word, "0x%" PRIx64, unnamed);
        add_short_word(buf, size, &len, word);
    }
}

static const char *short_layout(uint32_t layout)
{
    const char *n = pg_layout_name(layout);
    if (!strcmp(n, "undefined")) return "undef";
    if (!strcmp(n, "color_attachment")) return "color_att";
    if (!strcmp(n, "depth_stencil_attachment")) return "ds_att";
    if (!strcmp(n, "depth_stencil_read_only")) return "ds_ro";
    if (!strcmp(n, "depth_attachment")) return "depth_att";
    if (!strcmp(n, "depth_read_only")) return "depth_ro";
    if (!strcmp(n, "shader_read_only")) return "shader_ro";
    if (!strcmp(n, "transfer_src")) return "xfer_src";
    if (!strcmp(n, "transfer_dst")) return "xfer_dst";
    return n;
}

void pg_dump_barrier_label(const pg_graph_plan *plan, const pg_barrier *b, char *buf, size_t size)
{
    if (!buf || !size) return;
    char sa[128], da[128], why[96];
    short_access(b->src_access, sa, sizeof sa);
    short_access(b->dst_access, da, sizeof da);
    pg_strlcpy(why, b->why, sizeof why);
    if (b->alias_prev >= 0 && plan && pg_dmp_res_ok(plan, b->alias_prev)) {
        /* "alias first use" -> "alias after depth" */
        snprintf(why, sizeof why, "alias after %s", plan->resources[b->alias_prev].name);
    }
    const char *wrap = b->wrap && !b->first_frame ? " (prev frame)" : "";
    int w = b->src_access ? snprintf(buf, size, "%s%s %s\xe2\x86\x92%s", why, wrap, sa, da)
                          : snprintf(buf, size, "%s%s: %s", why, wrap, da);
    if (w < 0 || (size_t)w >= size) return;
    if (b->is_image && b->old_layout != b->new_layout)
        snprintf(buf + w, size - (size_t)w, "\n%s\xe2\x86\x92%s", short_layout(b->old_layout),
                 short_layout(b->new_layout));
}

/* ------------------------------------------------------------------------------------------ */
/* text                                                                                       */

void pg_dump_text(const pg_graph_plan *plan, const pg_pipeline *pipeline, FILE *f)
{
    if (!f) return;
    if (!plan) {
        fprintf(f, "(no plan)\n");
        return;
    }
    if (pipeline) {
        if (pipeline->description[0]) fprintf(f, "description: %s\n", pipeline->description);
        fprintf(f, "parameters:%s", pipeline->n_params ? "" : " none");
        for (uint32_t i = 0; i < pipeline->n_params && i < PG_MAX_PARAMS; i++) {
            char v[PG_NAME_MAX + 32];
            pg_param_format(&pipeline->params[i], v, sizeof v);
            fprintf(f, " %s=%s%s", pipeline->params[i].name, v,
                    pipeline->params[i].overridden ? " (--set)" : "");
        }
        fprintf(f, "\n");
    }
    pg_graph_plan_print(plan, pipeline, f);
}
