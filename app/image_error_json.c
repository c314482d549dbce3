/* image_error_json.c - image-error metrics as JSON (image_error_json.h). */
#include "image_error_json.h"

#include <math.h>

cJSON *pg_json_metric(double v, bool nan_as_null)
{
    if (isnan(v)) return nan_as_null ? cJSON_CreateNull() : cJSON_CreateString("nan");
    if (isinf(v)) return cJSON_CreateString(v > 0 ? "inf" : "-inf");
    return cJSON_CreateNumber(v);
}

void pg_image_error_json_add(cJSON *o, const pg_image_error *e, const pg_image_error_json_style *style)
{
    const bool nn = style->nan_as_null;
    cJSON_AddItemToObject(o, "rmse_linear", pg_json_metric(e->rmse_linear, nn));
    cJSON_AddItemToObject(o, "psnr_linear", pg_json_metric(e->psnr_linear, nn));
    cJSON_AddItemToObject(o, "max_abs_linear", pg_json_metric(e->max_abs_linear, nn));
    cJSON_AddItemToObject(o, "peak_linear", pg_json_metric(e->peak_linear, nn));
    cJSON_AddItemToObject(o, "rmse_display", pg_json_metric(e->rmse_display, nn));
    cJSON_AddItemToObject(o, "psnr_display", pg_json_metric(e->psnr_display, nn));
    cJSON_AddItemToObject(o, "max_abs_display", pg_json_metric(e->max_abs_display, nn));
    if (style->threshold) cJSON_AddNumberToObject(o, "threshold", *style->threshold);
    cJSON_AddItemToObject(o, style->share_key, pg_json_metric(e->share_over_threshold, nn));
}
