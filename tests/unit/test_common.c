/* test_common.c - small shared helpers: error prefixing, formats, string copy, half floats,
 * non-finite counting. */
#include <math.h>
#include <string.h>

#include "image_util.h"
#include "pg_common.h"
#include "test_util.h"

int main(void)
{
    pg_error e = {0};
    CHECK(pg_fail(&e, PG_ERR_CYCLE, "cycle: %s -> %s", "a", "b") == PG_ERR_CYCLE);
    CHECK(pg_error_prefix(&e, "pass '%s'", "x") == PG_ERR_CYCLE);
    CHECK(strcmp(e.msg, "pass 'x': cycle: a -> b") == 0);
    /* prefixing a full message truncates its tail, never overflows */
    memset(e.msg, 'm', sizeof e.msg - 1);
    e.msg[sizeof e.msg - 1] = 0;
    pg_error_prefix(&e, "%s", "pre");
    CHECK(strncmp(e.msg, "pre: mmm", 8) == 0 && strlen(e.msg) == sizeof e.msg - 1);
    CHECK(strcmp(pg_result_name(PG_ERR_WRITE_CONFLICT), "PG_ERR_WRITE_CONFLICT") == 0);
    CHECK(strcmp(pg_result_name((pg_result)999), "PG_ERR_?") == 0);

    CHECK(pg_format_from_name("rgba16f") == PG_FMT_RGBA16F);
    CHECK(pg_format_from_name("d32f") == PG_FMT_D32F);
    CHECK(pg_format_from_name("rgba9") == PG_FMT_UNDEFINED);
    CHECK(pg_format_from_name(NULL) == PG_FMT_UNDEFINED);
    CHECK(pg_format_get(PG_FMT_RGBA32UI)->fmt_class == PG_FMTCLASS_UINT);
    CHECK(pg_format_get((pg_format)1000)->bytes_per_pixel == 0);
    for (int f = 1; f < PG_FMT_COUNT; f++) CHECK(pg_format_get((pg_format)f)->bytes_per_pixel > 0);

    char buf[4];
    CHECK(pg_strlcpy(buf, "abc", sizeof buf) && strcmp(buf, "abc") == 0);
    CHECK(!pg_strlcpy(buf, "abcdef", sizeof buf) && strcmp(buf, "abc") == 0);

    CHECK(pg_half_to_float(0x3c00) == 1.0f);
    CHECK(pg_half_to_float(0xc000) == -2.0f);
    CHECK(pg_half_to_float(0x7bff) == 65504.0f);
    CHECK(pg_half_to_float(0x0001) == ldexpf(1.0f, -24));
    CHECK(isinf(pg_half_to_float(0x7c00)));
    CHECK(isnan(pg_half_to_float(0x7e00)));
    float px[8] = {1, 2, 3, 1, 0, NAN, 0, 1};
    CHECK(pg_count_nonfinite(px, 2, 1) == 1);
    px[5] = 0;
    px[3] = INFINITY; /* alpha is not counted */
    CHECK(pg_count_nonfinite(px, 2, 1) == 0);
    return pg_test_finish("test_common");
}
