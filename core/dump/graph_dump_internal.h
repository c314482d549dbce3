/* graph_dump_internal.h - the helpers the dump's files share; not part of the dump library's
 * interface (only core/dump/graph_dump*.c include it).
 *
 *   graph_dump.c        shared helpers, block colours, short names, barrier labels, text
 *   graph_dump_json.c   JSON (docs/dump-format.md)
 *   graph_dump_dot.c    Graphviz DOT, and running Graphviz
 *   graph_dump_svg.c    the memory-timeline SVG
 */
#ifndef PG_GRAPH_DUMP_INTERNAL_H
#define PG_GRAPH_DUMP_INTERNAL_H

#include "graph_dump.h"
#include "graph_report.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* graph_dump.c: colours of memory blocks, shared by the DOT graph and the timeline */
extern const char *const pg_dmp_block_fill[12];
extern const char *const pg_dmp_block_stroke[12];
#define PG_DMP_N_BLOCK_COLOURS (sizeof pg_dmp_block_fill / sizeof pg_dmp_block_fill[0])


/* graph_dump.c */
bool pg_dmp_res_ok(const pg_graph_plan *plan, int r);
const char *pg_dmp_res_name(const pg_graph_plan *plan, int r);
const char *pg_dmp_type_name(const pg_plan_pass *pp);
const char *pg_dmp_pass_at(const pg_graph_plan *plan, int pos);
int pg_dmp_position_of(const pg_graph_plan *plan, uint32_t p);
/* Writes s with & < > " escaped; dot_label (a Graphviz HTML-like label): '\n' -> <br/>, else
 * (SVG text and attributes) ' -> &apos;. */
void pg_dmp_markup_esc(FILE *f, const char *s, bool dot_label);

#endif
