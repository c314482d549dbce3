#include "bench_stats.h"

#include <math.h>
#include <stdlib.h>

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double pg_median(double *v, uint32_t n)
{
    qsort(v, n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

uint32_t pg_nearest_rank_pct(uint32_t pct, uint32_t n)
{
    if (n == 0) return 0;
    uint64_t r = ((uint64_t)pct * n + 99) / 100; /* ceil(pct * n / 100) in integers: no rounding */
    if (r < 1) r = 1;
    if (r > n) r = n;
    return (uint32_t)r;
}

pg_result pg_sample_stats_compute(const double *v, uint32_t n, pg_sample_stats *out, pg_error *err)
{
    out->n = 0;
    out->median = out->mean = out->min = out->max = out->p95 = NAN;
    if (n == 0) return PG_OK;
    if (!v) return pg_fail(err, PG_ERR_INVALID_ARG, "sample stats: NULL samples with n = %u", n);
    double *s = malloc((size_t)n * sizeof *s);
    if (!s) return pg_fail(err, PG_ERR_OOM, "sample stats: out of memory (%u samples)", n);
    uint32_t m = 0;
    for (uint32_t i = 0; i < n; i++)
        if (isfinite(v[i])) s[m++] = v[i];
    if (m) {
        qsort(s, m, sizeof *s, cmp_double);
        double sum = 0;
        for (uint32_t i = 0; i < m; i++) sum += s[i];
        out->n = m;
        out->mean = sum / m;
        out->min = s[0];
        out->max = s[m - 1];
        out->median = m % 2 ? s[m / 2] : 0.5 * (s[m / 2 - 1] + s[m / 2]);
        out->p95 = s[pg_nearest_rank_pct(95, m) - 1];
    }
    free(s);
    return PG_OK;
}

/* Insertion sort of the front (small n): x, then y, then index. */
static bool front_before(const double *x, const double *y, uint32_t a, uint32_t b)
{
    if (x[a] != x[b]) return x[a] < x[b];
    if (y[a] != y[b]) return y[a] < y[b];
    return a < b;
}

uint32_t pg_pareto_front(const double *x, const double *y, uint32_t n, bool *on_front, uint32_t *order)
{
    uint32_t count = 0;
    for (uint32_t i = 0; i < n; i++) {
        bool front = isfinite(x[i]) && isfinite(y[i]);
        for (uint32_t j = 0; front && j < n; j++) {
            if (j == i || !isfinite(x[j]) || !isfinite(y[j])) continue;
            if (x[j] <= x[i] && y[j] <= y[i] && (x[j] < x[i] || y[j] < y[i])) front = false;
        }
        if (on_front) on_front[i] = front;
        if (!front) continue;
        if (order) {
            uint32_t k = count;
            while (k > 0 && front_before(x, y, i, order[k - 1])) {
                order[k] = order[k - 1];
                k--;
            }
            order[k] = i;
        }
        count++;
    }
    return count;
}
