/* graph_dump_dot.c - the Graphviz DOT view of a compiled graph, and running `dot` on it. */
#include "graph_dump_internal.h"

#include <errno.h>
#include <inttypes.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* ------------------------------------------------------------------------------------------ */
/* Graphviz DOT                                                                               */

/* Writes s escaped for a Graphviz HTML-like label ('\n' -> <br/>). */
static void html_esc(FILE *f, const char *s)
{
    pg_dmp_markup_esc(f, s, true);
}

/* Writes s escaped for a double-quoted DOT string ('\n' -> "\n", a centred line break). */
static void dot_esc(FILE *f, const char *s)
{
    for (; s && *s; s++) {
        if (*s == '"' || *s == '\\') fputc('\\', f);
        if (*s == '\n') fputs("\\n", f);
        else fputc(*s, f);
    }
}

/* Writes text word-wrapped at about width characters (HTML-escaped; lines joined with <br/>). */
static void html_wrapped(FILE *f, const char *text, size_t width)
{
    size_t col = 0;
    const char *p = text;
    while (p && *p) {
        size_t n = strcspn(p, " ");
        if (col && col + 1 + n > width) {
            fputs("<br/>", f);
            col = 0;
        } else if (col) {
            fputc(' ', f);
            col++;
        }
        char word[PG_EXPLAIN_MAX];
        size_t k = n < sizeof word - 1 ? n : sizeof word - 1;
        memcpy(word, p, k);
        word[k] = 0;
        html_esc(f, word);
        col += n;
        p += n;
        while (*p == ' ') p++;
    }
}

static void dot_pass_node(FILE *f, const pg_graph_plan *plan, uint32_t i)
{
    const pg_plan_pass *pp = &plan->passes[i];
    fprintf(f, "  p%u [", i);
    if (pp->culled)
        fputs("shape=box, style=\"rounded,dashed\", color=\"#9a9a9a\", fontcolor=\"#8a8a8a\", ", f);
    else
        fputs("shape=box, style=\"rounded,filled\", fillcolor=\"#dde8f8\", color=\"#3a66a8\", ", f);
    fputs("label=<<b>", f);
    html_esc(f, pp->name);
    fputs("</b><br/><font point-size=\"9\">", f);
    html_esc(f, pg_dmp_type_name(pp));
    const int pos = pg_dmp_position_of(plan, i);
    if (pos >= 0) fprintf(f, " \xc2\xb7 #%d", pos);
    fputs("</font>", f);
    if (pp->culled) {
        fputs("<br/><font point-size=\"8\"><i>culled: ", f);
        html_wrapped(f, pp->cull_reason, 40);
        fputs("</i></font>", f);
    } else {
        if (pp->decl.n_defines) {
            char defs[PG_MAX_DEFINES * (PG_NAME_MAX + 1)] = "";
            size_t len = 0;
            for (uint32_t d = 0; d < pp->decl.n_defines && d < PG_MAX_DEFINES; d++) {
                int w = snprintf(defs + len, sizeof defs - len, "%s%s", d ? " " : "", pp->decl.defines[d]);
                if (w < 0 || (size_t)w >= sizeof defs - len) break;
                len += (size_t)w;
            }
            fputs("<br/><font point-size=\"8\" color=\"#4a4a4a\">", f);
            html_wrapped(f, defs, 34);
            fputs("</font>", f);
        }
        for (uint32_t e = 0; e < pp->decl.n_explain && e < 8; e++) {
            fputs("<br/><font point-size=\"8\" color=\"#7a7a7a\"><i>", f);
            html_wrapped(f, pp->decl.explain[e], 40);
            fputs("</i></font>", f);
        }
    }
    fputs(">];\n", f);
}

static void dot_resource_node(FILE *f, const pg_graph_plan *plan, uint32_t r)
{
    const pg_plan_resource *pr = &plan->resources[r];
    char bytes[32];
    pg_fmt_bytes(pr->size_bytes, bytes, sizeof bytes);
    fprintf(f, "  r%u [shape=note, ", r);
    if (pr->culled) {
        fputs("style=dashed, color=\"#9a9a9a\", fontcolor=\"#8a8a8a\", ", f);
    } else if (pr->block >= 0) {
        fprintf(f, "style=filled, fillcolor=\"%s\", color=\"%s\", ", pg_dmp_block_fill[(uint32_t)pr->block % PG_DMP_N_BLOCK_COLOURS],
                pg_dmp_block_stroke[(uint32_t)pr->block % PG_DMP_N_BLOCK_COLOURS]);
    } else {
        fputs("style=filled, fillcolor=\"#f4f4f4\", color=\"#505050\", ", f);
    }
    if (pr->is_output && !pr->culled) fputs("penwidth=2.2, ", f);
    fputs("label=<<b>", f);
    html_esc(f, pr->name);
    fputs("</b><br/><font point-size=\"9\">", f);
    if (pr->kind == PG_RES_IMAGE) {
        html_esc(f, pg_format_get(pr->format)->name);
        fprintf(f, " %u\xc3\x97%u \xc2\xb7 %s", pr->width, pr->height, bytes);
    } else {
        fprintf(f, "buffer \xc2\xb7 %s", bytes);
    }
    fputs("</font>", f);
    if (pr->culled) {
        fputs("<br/><font point-size=\"8\"><i>culled: ", f);
        html_wrapped(f, pr->cull_reason, 36);
        fputs("</i></font>", f);
    } else {
        fputs("<br/><font point-size=\"9\">", f);
        if (pr->block >= 0)
            fprintf(f, "block #%d @ %" PRIu64, pr->block, pr->block_offset);
        else
            fputs(pg_lifetime_name(pr->lifetime), f);
        if ((int)r == plan->output) fputs(" \xc2\xb7 <b>output</b>", f);
        else if ((int)r == plan->hdr_output) fputs(" \xc2\xb7 <b>hdr output</b>", f);
        fputs("</font>", f);
    }
    fputs(">];\n", f);
}

/* Label of the barriers placed at pass pp for resource r (several joined by '\n'). */
static size_t barrier_labels_for(const pg_graph_plan *plan, const pg_plan_pass *pp, int r, char *buf, size_t size)
{
    size_t len = 0, n = 0;
    buf[0] = 0;
    for (uint32_t b = 0; b < pp->n_barriers && b < PG_MAX_BARRIERS_PER_PASS; b++) {
        if (pp->barriers[b].resource != r) continue;
        char one[256];
        pg_dump_barrier_label(plan, &pp->barriers[b], one, sizeof one);
        int w = snprintf(buf + len, size - len, "%s%s", len ? "\n" : "", one);
        if (w < 0 || (size_t)w >= size - len) break;
        len += (size_t)w;
        n++;
    }
    return n;
}

static void dot_edges_of_pass(FILE *f, const pg_graph_plan *plan, uint32_t i)
{
    const pg_plan_pass *pp = &plan->passes[i];
    for (uint32_t s = 0; s < pp->n_slots && s < 2 * PG_MAX_SLOTS; s++) {
        const pg_plan_slot *sl = &pp->slots[s];
        if (!pg_dmp_res_ok(plan, sl->resource)) continue;
        /* one edge per (resource, direction): skip a slot when an earlier one had the same */
        bool seen = false, all_unused = sl->decl.unused;
        for (uint32_t t = 0; t < s; t++)
            if (pp->slots[t].resource == sl->resource && pp->slots[t].is_write == sl->is_write) seen = true;
        if (seen) continue;
        char access[160] = "";
        size_t alen = 0;
        for (uint32_t t = s; t < pp->n_slots && t < 2 * PG_MAX_SLOTS; t++) {
            const pg_plan_slot *o = &pp->slots[t];
            if (o->resource != sl->resource || o->is_write != sl->is_write) continue;
            all_unused &= o->decl.unused;
            int w = snprintf(access + alen, sizeof access - alen, "%s%s %s", alen ? ", " : "", o->decl.name,
                             o->decl.unused ? "unused" : pg_access_name(o->decl.access));
            if (w > 0 && (size_t)w < sizeof access - alen) alen += (size_t)w;
        }
        /* the barriers for this resource go on the read edge when the pass reads it */
        bool reads_it = false;
        for (uint32_t t = 0; t < pp->n_slots && t < 2 * PG_MAX_SLOTS; t++)
            if (pp->slots[t].resource == sl->resource && !pp->slots[t].is_write && !pp->slots[t].decl.unused)
                reads_it = true;
        char label[1024] = "";
        size_t n_b = 0;
        if (!pp->culled && (sl->is_write ? !reads_it : true) && !all_unused)
            n_b = barrier_labels_for(plan, pp, sl->resource, label, sizeof label);
        if (sl->is_write)
            fprintf(f, "  p%u -> r%d [", i, sl->resource);
        else
            fprintf(f, "  r%d -> p%u [", sl->resource, i);
        if (all_unused)
            fputs("style=dotted, color=\"#a0a0a0\", fontcolor=\"#8a8a8a\", label=\"unused\", ", f);
        else if (pp->culled || plan->resources[sl->resource].culled)
            fputs("style=dashed, color=\"#a0a0a0\", ", f);
        else if (n_b) {
            fputs("color=\"#c0392b\", fontcolor=\"#a02818\", label=\"", f);
            dot_esc(f, label);
            fputs("\", ", f);
        }
        if (sl->is_write) fputs("penwidth=1.4, ", f);
        fputs("tooltip=\"", f);
        dot_esc(f, access);
        fputs("\"];\n", f);
    }
}

void pg_dump_dot(const pg_graph_plan *plan, const pg_pipeline *pipeline, FILE *f)
{
    if (!f) return;
    if (!plan) {
        fputs("digraph passgraph { label=\"(no plan)\"; }\n", f);
        return;
    }
    const char *font = "Helvetica,Arial,sans-serif";
    fputs("digraph passgraph {\n", f);
    fprintf(f, "  graph [rankdir=TB, fontname=\"%s\", fontsize=12, labelloc=t, labeljust=l, nodesep=0.22, "
               "ranksep=0.45, pad=0.25,\n         label=<<b>",
            font);
    html_esc(f, pipeline ? pipeline->name : "graph");
    fputs("</b>", f);
    if (pipeline && pipeline->path[0]) {
        fputs(" \xc2\xb7 ", f);
        html_esc(f, pipeline->path);
    }
    if (pg_dmp_res_ok(plan, plan->output))
        fprintf(f, " \xc2\xb7 %u\xc3\x97%u", plan->resources[plan->output].width,
                plan->resources[plan->output].height);
    char un[32], al[32];
    pg_fmt_bytes(plan->transient_bytes_unaliased, un, sizeof un);
    pg_fmt_bytes(plan->transient_bytes_aliased, al, sizeof al);
    fprintf(f, "<br/><font point-size=\"10\">%u passes run, %u culled \xc2\xb7 %u barriers (+%u after the last pass) "
               "\xc2\xb7 transient memory %s \xe2\x86\x92 %s %s (saving %.1f%%)</font>",
            plan->n_order, pg_graph_plan_count_culled(plan), pg_graph_plan_count_barriers(plan), plan->n_final_barriers, un, al,
            plan->aliasing_disabled ? "(aliasing disabled)" : "with aliasing", pg_graph_plan_saving_percent(plan));
    fputs("<br/><font point-size=\"9\" color=\"#555555\">rounded box = pass (type \xc2\xb7 #execution position) "
          "\xc2\xb7 note = resource, colour = memory block \xc2\xb7 arrows: resource \xe2\x86\x92 pass = read, "
          "pass \xe2\x86\x92 resource = write<br/>red edge = barrier before the pass: hazard, access "
          "src\xe2\x86\x92" "dst, layout old\xe2\x86\x92new \xc2\xb7 plain edge = no barrier needed \xc2\xb7 "
          "dashed grey = culled or left out</font>>];\n",
          f);
    fprintf(f, "  node [fontname=\"%s\", fontsize=11, penwidth=1.2, margin=\"0.12,0.05\"];\n", font);
    fprintf(f, "  edge [fontname=\"%s\", fontsize=9, color=\"#606060\", arrowsize=0.7];\n\n", font);

    fputs("  // passes (p<index in the pipeline>)\n", f);
    for (uint32_t i = 0; i < plan->n_passes; i++) dot_pass_node(f, plan, i);
    fputs("\n  // resources (r<index in the pipeline>)\n", f);
    for (uint32_t r = 0; r < plan->n_resources; r++) {
        /* a culled resource no pass touches at all would float alone: still draw it */
        dot_resource_node(f, plan, r);
    }
    fputs("\n  // reads (resource -> pass) and writes (pass -> resource); labels = barriers before the pass\n", f);
    for (uint32_t i = 0; i < plan->n_passes; i++) dot_edges_of_pass(f, plan, i);

    if (plan->n_final_barriers) {
        fputs("\n  // after the last pass: outputs are read back\n", f);
        fputs("  readback [shape=cds, style=filled, fillcolor=\"#eeeeee\", color=\"#707070\", "
              "label=<<b>read back</b><br/><font point-size=\"9\">after the last pass</font>>];\n",
              f);
        for (uint32_t b = 0; b < plan->n_final_barriers && b < PG_MAX_RESOURCES; b++) {
            const pg_barrier *bar = &plan->final_barriers[b];
            if (!pg_dmp_res_ok(plan, bar->resource)) continue;
            char label[256];
            pg_dump_barrier_label(plan, bar, label, sizeof label);
            fprintf(f, "  r%d -> readback [color=\"#c0392b\", fontcolor=\"#a02818\", style=dashed, label=\"",
                    bar->resource);
            dot_esc(f, label);
            fputs("\"];\n", f);
        }
    }

    if (pipeline && pipeline->n_omitted) {
        fputs("\n  // items dropped by a false 'when' condition (not in the plan)\n", f);
        fputs("  omitted [shape=note, style=dashed, color=\"#9a9a9a\", fontcolor=\"#7a7a7a\", "
              "label=<<table border=\"0\" cellspacing=\"0\" cellpadding=\"1\">"
              "<tr><td align=\"left\" colspan=\"2\"><b>left out by 'when'</b></td></tr>",
              f);
        for (uint32_t i = 0; i < pipeline->n_omitted && i < PG_MAX_PASSES + PG_MAX_RESOURCES; i++) {
            fputs("<tr><td align=\"left\">", f);
            html_esc(f, pipeline->omitted[i].what);
            fputs("</td><td align=\"left\"><font point-size=\"9\">", f);
            html_esc(f, pipeline->omitted[i].why);
            fputs("</font></td></tr>", f);
        }
        fputs("</table>>];\n", f);
        fputs("  { rank=sink; omitted; }\n", f);
    }
    fputs("}\n", f);
}

/* ------------------------------------------------------------------------------------------ */
/* running Graphviz                                                                           */

const char *pg_dump_graphviz_format_for(const char *path)
{
    if (!path) return NULL;
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash)) return NULL;
    static const char *const fmts[] = {"svg", "png", "pdf", NULL};
    for (int i = 0; fmts[i]; i++) {
        const char *a = dot + 1, *b = fmts[i];
        while (*a && *b && (*a | 0x20) == *b) a++, b++;
        if (!*a && !*b) return fmts[i];
    }
    return NULL;
}

/* Finds an executable named name on PATH; returns false when there is none. */
static bool find_on_path(const char *name, char *out, size_t size)
{
    const char *path = getenv("PATH");
    if (!path || !*path) path = "/usr/local/bin:/usr/bin:/bin";
    while (*path) {
        size_t n = strcspn(path, ":");
        char cand[PG_PATH_MAX];
        if (n == 0) {
            snprintf(cand, sizeof cand, "./%s", name);
        } else if (n + 1 + strlen(name) < sizeof cand) {
            memcpy(cand, path, n);
            snprintf(cand + n, sizeof cand - n, "/%s", name);
        } else {
            cand[0] = 0;
        }
        struct stat st;
        if (cand[0] && stat(cand, &st) == 0 && S_ISREG(st.st_mode) && access(cand, X_OK) == 0) {
            pg_strlcpy(out, cand, size);
            return true;
        }
        path += n;
        if (*path == ':') path++;
    }
    return false;
}

pg_result pg_dump_run_graphviz(const char *dot_text, const char *format, const char *out_path, pg_error *err)
{
    if (!dot_text || !format || !*format || !out_path || !*out_path)
        return pg_fail(err, PG_ERR_INVALID_ARG, "graphviz: missing DOT text, format or output path");
    for (const char *c = format; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9')))
            return pg_fail(err, PG_ERR_INVALID_ARG, "graphviz: bad output format '%s'", format);
    char exe[PG_PATH_MAX];
    if (!find_on_path("dot", exe, sizeof exe))
        return pg_fail(err, PG_ERR_IO,
                       "Graphviz's 'dot' was not found on PATH; install the package 'graphviz' "
                       "(Debian/Ubuntu: apt-get install graphviz) to render %s, or write the DOT text "
                       "itself (--out FILE.dot)",
                       out_path);
    char targ[32], oarg[PG_PATH_MAX + 3];
    snprintf(targ, sizeof targ, "-T%s", format);
    if (snprintf(oarg, sizeof oarg, "-o%s", out_path) >= (int)sizeof oarg)
        return pg_fail(err, PG_ERR_INVALID_ARG, "graphviz: output path too long: %s", out_path);
    char *const argv[] = {"dot", targ, oarg, NULL};

    int fds[2];
    if (pipe(fds) != 0) return pg_fail(err, PG_ERR_IO, "graphviz: pipe: %s", strerror(errno));
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fds[0], STDIN_FILENO);
    posix_spawn_file_actions_addclose(&fa, fds[0]);
    posix_spawn_file_actions_addclose(&fa, fds[1]);
    pid_t pid;
    int rc = posix_spawn(&pid, exe, &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    close(fds[0]);
    if (rc != 0) {
        close(fds[1]);
        return pg_fail(err, PG_ERR_IO, "graphviz: cannot run %s: %s%s", exe, strerror(rc),
                       rc == ENOENT ? " (install the package 'graphviz')" : "");
    }
    /* dot may exit early (bad input): write with SIGPIPE ignored so that shows as EPIPE */
    struct sigaction ign, old;
    memset(&ign, 0, sizeof ign);
    ign.sa_handler = SIG_IGN;
    sigemptyset(&ign.sa_mask);
    sigaction(SIGPIPE, &ign, &old);
    const char *p = dot_text;
    size_t left = strlen(dot_text);
    int write_errno = 0;
    while (left) {
        ssize_t w = write(fds[1], p, left);
        if (w < 0) {
            if (errno == EINTR) continue;
            write_errno = errno;
            break;
        }
        p += w;
        left -= (size_t)w;
    }
    close(fds[1]);
    sigaction(SIGPIPE, &old, NULL);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) return pg_fail(err, PG_ERR_IO, "graphviz: waitpid: %s", strerror(errno));
    }
    if (WIFSIGNALED(status))
        return pg_fail(err, PG_ERR_IO, "graphviz: dot -T%s killed by signal %d while writing %s", format,
                       WTERMSIG(status), out_path);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return pg_fail(err, PG_ERR_IO, "graphviz: dot -T%s failed with exit status %d writing %s (its message is above)",
                       format, WIFEXITED(status) ? WEXITSTATUS(status) : -1, out_path);
    if (write_errno)
        return pg_fail(err, PG_ERR_IO, "graphviz: writing to dot: %s", strerror(write_errno));
    return PG_OK;
}
