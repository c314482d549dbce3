/* bench_table.c - `passgraph bench`: what the outputs (bench_output.c) and the charts
 * (bench_charts.c) read of the table of rows: the pass columns. A leaf: it calls neither. */
#include "bench.h"

void pg_bench_union_passes(const bench *B, pass_union *u)
{
    u->n = 0;
    for (uint32_t i = 0; i < B->n_rows; i++)
        for (uint32_t p = 0; p < B->rows[i].n_passes; p++) {
            bool found = false;
            for (uint32_t k = 0; k < u->n && !found; k++) found = !strcmp(u->names[k], B->rows[i].passes[p].name);
            if (!found && u->n < PG_MAX_PASSES * 4) pg_strlcpy(u->names[u->n++], B->rows[i].passes[p].name, PG_NAME_MAX);
        }
}
