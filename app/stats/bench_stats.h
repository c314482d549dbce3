/* bench_stats.h - summary statistics of timing samples and the Pareto front of (time, error)
 * points, for `passgraph bench` (pure C, no Vulkan).
 *
 * Conventions:
 * - Non-finite samples (NaN, +-Inf) are left out; n counts the samples that entered.
 * - median: the middle sample of the sorted finite samples; for an even count the mean of the
 *   two middle ones.
 * - p95: nearest rank: the sorted sample of rank ceil(0.95 * n) (1-based), so it is always one
 *   of the samples (n = 1: that sample; n = 10: the 10th = the max; n = 20: the 19th).
 * - No finite sample: n = 0 and every statistic NaN (not an error).
 */
#ifndef PG_BENCH_STATS_H
#define PG_BENCH_STATS_H

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pg_sample_stats {
    uint32_t n;          /* finite samples used */
    double median, mean, min, max, p95;
} pg_sample_stats;

/* v may be NULL only when n is 0. Works on a sorted copy (v is not modified): PG_ERR_OOM if
 * that copy cannot be allocated, PG_ERR_INVALID_ARG for NULL v with n > 0. */
pg_result pg_sample_stats_compute(const double *v, uint32_t n, pg_sample_stats *out, pg_error *err);

/* The median of v[0..n-1] (n > 0), every sample counted: sorts v in place (the single-frame
 * summaries of render and compare; pg_sample_stats_compute leaves v as it is and skips
 * non-finite samples). */
double pg_median(double *v, uint32_t n);

/* 1-based nearest rank of the q-quantile (0 < q <= 1) of n samples: ceil(q * n), at least 1;
 * 0 when n is 0. Exact for q given in percent (pg_nearest_rank_pct(95, n) = ceil(95 n / 100)). */
uint32_t pg_nearest_rank_pct(uint32_t pct, uint32_t n);

/* Pareto front of n points (x[i], y[i]), both minimised (x = time, y = error). Point i is on the
 * front when no other point j has x[j] <= x[i] and y[j] <= y[i] with at least one of the two
 * strictly smaller. Identical points do not dominate each other: all copies are on the front.
 * Points with a non-finite coordinate are never on the front and dominate nothing.
 * on_front (n entries, may be NULL) receives the flags; order (n entries, may be NULL) receives the
 * indexes of the front points sorted by x ascending, then y, then index (a polyline through them
 * in this order runs along the front from the fastest point to the most accurate one; y falls
 * as x rises). Returns the number of front points. O(n^2). */
uint32_t pg_pareto_front(const double *x, const double *y, uint32_t n, bool *on_front, uint32_t *order);

#ifdef __cplusplus
}
#endif
#endif
