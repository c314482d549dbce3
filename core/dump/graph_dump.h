/* graph_dump.h - what a compiled graph does, for people and tools, without rendering.
 *
 * Four views of one pg_graph_plan (and the pg_pipeline it was compiled from), all pure functions
 * of the plan: they read it, never change it, and make no Vulkan calls.
 *
 *   pg_dump_text          the readable report (pg_graph_plan_print: passes in execution order with
 *                         their reads, writes and barriers, culls and left-out features with their
 *                         reasons, resources with lifetimes, blocks and offsets, a text memory
 *                         timeline, totals), preceded by the pipeline's parameter values
 *   pg_dump_json          the same facts as JSON for tools (diff two pipelines); format version 1,
 *                         every key documented in docs/dump-format.md; keys always in the same
 *                         order, arrays in execution / declaration order
 *   pg_dump_dot           a Graphviz graph: passes (rounded boxes) and resources (notes), read and
 *                         write edges, barriers as edge labels, culled and omitted items dashed grey
 *   pg_dump_timeline_svg  an SVG chart of the transient resources over the executed passes, one row
 *                         per memory block, one bar per resource lifetime, coloured by block
 *
 * pipeline may be NULL (names then come from the plan only; parameters and omitted items are left
 * out). A NULL plan prints a placeholder (text/dot/svg) or returns NULL (json).
 * The FILE writers do not check the stream: the caller checks ferror()/fclose().
 *
 * pg_dump_run_graphviz is the one function here that is not pure: it runs Graphviz's `dot`.
 */
#ifndef PG_GRAPH_DUMP_H
#define PG_GRAPH_DUMP_H

#include <stdio.h>

#include "graph.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PG_DUMP_FORMAT_VERSION 1

void pg_dump_text(const pg_graph_plan *plan, const pg_pipeline *pipeline, FILE *f);

/* malloc'd, NUL-terminated, pretty-printed JSON; free() it. NULL when out of memory or plan is
 * NULL. */
char *pg_dump_json(const pg_graph_plan *plan, const pg_pipeline *pipeline);

void pg_dump_dot(const pg_graph_plan *plan, const pg_pipeline *pipeline, FILE *f);

void pg_dump_timeline_svg(const pg_graph_plan *plan, const pg_pipeline *pipeline, FILE *f);

/* Short label of a barrier for graph edges, e.g. "RAW+layout color→sampled\ncolor_att→shader_ro"
 * (lines separated by '\n'; UTF-8 arrows). Always NUL-terminates buf. */
void pg_dump_barrier_label(const pg_graph_plan *plan, const pg_barrier *b, char *buf, size_t size);

/* Runs `dot -T<format> -o out_path` (fork/exec through posix_spawnp, never a shell) with dot_text
 * on its standard input and waits for it. format: "svg", "png", "pdf", ... (letters and digits
 * only). Fails with PG_ERR_IO naming the package 'graphviz' when dot is not on PATH, and with
 * PG_ERR_IO when dot cannot be started, is killed or exits non-zero (its exit status in the
 * message; dot's own messages go to stderr). */
pg_result pg_dump_run_graphviz(const char *dot_text, const char *format, const char *out_path,
                               pg_error *err);

/* Output format implied by a file name's extension for Graphviz: "svg", "png", "pdf" or NULL
 * when the name should just receive the DOT text (".dot", ".gv", anything else). */
const char *pg_dump_graphviz_format_for(const char *path);

#ifdef __cplusplus
}
#endif
#endif
