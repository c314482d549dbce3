/* bench_merge_check.h - the type of every field of a results.json row, checked before bench-merge
 * reads it: "'a/results.json' rows[2].gpu_ms: expected an object of statistics, got string
 * \"fast\"" (row: the JSON index in "rows", from 0; a missing field that must be there is
 * "nothing (missing)"). */
#ifndef PG_BENCH_MERGE_CHECK_H
#define PG_BENCH_MERGE_CHECK_H

#include "pg_common.h"

#include <cjson/cJSON.h>

pg_result pg_bench_row_check(const char *file, uint32_t row, const cJSON *o, pg_error *err);

#endif
