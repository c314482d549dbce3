/* bench_merge_check.h - the type of every field of a results.json row, checked before bench-merge
 * reads it: "'a/results.json' row 3 field 'gpu_ms': expected an object of statistics, got string
 * \"fast\"" (rows counted from 1). */
#ifndef PG_BENCH_MERGE_CHECK_H
#define PG_BENCH_MERGE_CHECK_H

#include "pg_common.h"

#include <cjson/cJSON.h>

pg_result pg_bench_row_check(const char *file, uint32_t row, const cJSON *o, pg_error *err);

#endif
