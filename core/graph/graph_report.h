/* graph_report.h - the structured pieces of the plan report that core/dump's views share with
 * pg_graph_plan_print() (graph.h): totals, and the names of an access mask's bits one by one.
 * Defined in graph_report.c and graph_names.c; the dump calls these instead of re-parsing text.
 */
#ifndef PG_GRAPH_REPORT_H
#define PG_GRAPH_REPORT_H

#include "graph.h"

#include <stdint.h>

/* The plan's totals line: barriers before passes (not the final ones), culled passes, and the
 * share of unaliased transient memory that aliasing saved (0 when there is none to save). */
uint32_t pg_graph_plan_count_barriers(const pg_graph_plan *plan);
uint32_t pg_graph_plan_count_culled(const pg_graph_plan *plan);
double pg_graph_plan_saving_percent(const pg_graph_plan *plan);

/* The names pg_access_mask_names() joins with '|', one per set bit in its order (at most max;
 * the strings are static); *unnamed (when not NULL) gets the bits that have no name. */
uint32_t pg_access_bit_names(uint64_t access, const char **names, uint32_t max, uint64_t *unnamed);

#endif
