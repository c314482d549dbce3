/* image_error_json.h - the one writer of an image error (image/image_compare.h) as JSON, used by
 * `compare --json` (app/cmd_compare.c) and bench's results.json (app/bench/bench_output.c).
 *
 * The two outputs keep the names their readers know: the share of pixels over the threshold is
 * "over_threshold" in compare's JSON (after "threshold") and "share_over_1" in results.json
 * (docs/performance.md); an unknown (NaN) metric is the string "nan" in compare's JSON and null in
 * results.json. */
#ifndef PG_IMAGE_ERROR_JSON_H
#define PG_IMAGE_ERROR_JSON_H

#include "image_compare.h"

#include <cjson/cJSON.h>
#include <stdbool.h>

/* A finite v as a number, +-inf as "inf" / "-inf", NaN as null (nan_as_null) or "nan". */
cJSON *pg_json_metric(double v, bool nan_as_null);

typedef struct pg_image_error_json_style {
    const char *share_key;   /* the key of share_over_threshold */
    const double *threshold; /* written as "threshold" before it when not NULL */
    bool nan_as_null;
} pg_image_error_json_style;

/* Adds rmse_linear, psnr_linear, max_abs_linear, peak_linear, rmse_display, psnr_display,
 * max_abs_display, [threshold,] and the share under style->share_key to o, in that order. */
void pg_image_error_json_add(cJSON *o, const pg_image_error *e, const pg_image_error_json_style *style);

#endif
