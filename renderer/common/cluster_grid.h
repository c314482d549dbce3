/* cluster_grid.h - the cluster grid is a fact of the cluster_counts resource: its count is the grid
 * (["$grid_x", "$grid_y", "$grid_z"] in pipelines/fragments/clusters.json, 16 bytes per cluster), and
 * cluster_assign and every pass that reads the lists take it from there in declare, so it is declared
 * once and no pass option can disagree with the buffers. */
#ifndef PG_CLUSTER_GRID_H
#define PG_CLUSTER_GRID_H

#include "pass_api.h"

/* The largest grid edge and cluster count a pass accepts. */
#define PG_CLUSTER_GRID_EDGE_MAX 1024u
#define PG_CLUSTER_GRID_CELLS_MAX (1u << 22)

/* From declare: reads the grid (x, y, z) from the count of the resource bound to the slot counts
 * (exactly three constant terms, whole numbers in [1, PG_CLUSTER_GRID_EDGE_MAX], at most
 * PG_CLUSTER_GRID_CELLS_MAX clusters; a stride of at least 16 bytes) and checks that the count of the resource bound to the slot lists
 * starts with the same three terms. Anything else is PG_ERR_SCHEMA (PG_ERR_LIMIT: too many clusters)
 * naming the pass's file, JSON path, name and slot. A slot left unbound, or bound to a resource the
 * pipeline does not have or that is no buffer, is left to the graph's own checks (the grid is then the
 * default, PG_CLUSTER_GRID_DEFAULT_*). */
pg_result pg_cluster_grid_declare(const pg_declare_in *in, pg_slot counts, pg_slot lists, uint32_t grid[3],
                                  pg_error *err);

#endif
