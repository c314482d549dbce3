#include "pg_common.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <vulkan/vulkan_core.h>

pg_result pg_fail(pg_error *err, pg_result code, const char *fmt, ...)
{
    if (err) {
        err->code = code;
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
    }
    return code;
}

pg_result pg_error_prefix(pg_error *err, const char *fmt, ...)
{
    if (!err) return PG_ERR_INVALID_ARG;
    char prefix[PG_ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(prefix, sizeof prefix - 2, fmt, ap);
    va_end(ap);
    if (n < 0) return err->code;
    size_t plen = strlen(prefix);
    memcpy(prefix + plen, ": ", 3);
    plen += 2;
    /* shift the old message right and put the prefix in front (truncating the tail) */
    size_t old = strnlen(err->msg, sizeof err->msg - 1);
    if (plen >= sizeof err->msg - 1) plen = sizeof err->msg - 1;
    size_t keep = old;
    if (plen + keep > sizeof err->msg - 1) keep = sizeof err->msg - 1 - plen;
    memmove(err->msg + plen, err->msg, keep);
    memcpy(err->msg, prefix, plen);
    err->msg[plen + keep] = 0;
    return err->code;
}

const char *pg_result_name(pg_result r)
{
    static const char *names[PG_ERR_COUNT] = {
        "PG_OK", "PG_ERR_IO", "PG_ERR_PARSE", "PG_ERR_SCHEMA", "PG_ERR_UNKNOWN_PASS",
        "PG_ERR_UNKNOWN_RESOURCE", "PG_ERR_WRITE_CONFLICT", "PG_ERR_CYCLE", "PG_ERR_NO_OUTPUT",
        "PG_ERR_FORMAT", "PG_ERR_PARAM", "PG_ERR_INCLUDE", "PG_ERR_LIMIT",
        "PG_ERR_READ_BEFORE_WRITE", "PG_ERR_GLTF", "PG_ERR_SHADER", "PG_ERR_VULKAN",
        "PG_ERR_NO_DEVICE", "PG_ERR_OOM", "PG_ERR_INVALID_ARG",
    };
    if ((int)r < 0 || r >= PG_ERR_COUNT) return "PG_ERR_?";
    return names[r];
}

static const pg_format_info g_formats[PG_FMT_COUNT] = {
    [PG_FMT_UNDEFINED] = {"undefined", VK_FORMAT_UNDEFINED, 0, PG_FMTCLASS_NONE, false, false},
    [PG_FMT_RGBA8_UNORM] = {"rgba8", VK_FORMAT_R8G8B8A8_UNORM, 4, PG_FMTCLASS_FLOAT, false, true},
    [PG_FMT_RGBA8_SRGB] = {"rgba8_srgb", VK_FORMAT_R8G8B8A8_SRGB, 4, PG_FMTCLASS_FLOAT, true, false},
    [PG_FMT_RGBA16F] = {"rgba16f", VK_FORMAT_R16G16B16A16_SFLOAT, 8, PG_FMTCLASS_FLOAT, false, true},
    [PG_FMT_RGBA32F] = {"rgba32f", VK_FORMAT_R32G32B32A32_SFLOAT, 16, PG_FMTCLASS_FLOAT, false, true},
    [PG_FMT_RG16F] = {"rg16f", VK_FORMAT_R16G16_SFLOAT, 4, PG_FMTCLASS_FLOAT, false, true},
    [PG_FMT_RGBA16_UNORM] = {"rgba16", VK_FORMAT_R16G16B16A16_UNORM, 8, PG_FMTCLASS_FLOAT, false, true},
    [PG_FMT_RG16_UNORM] = {"rg16", VK_FORMAT_R16G16_UNORM, 4, PG_FMTCLASS_FLOAT, false, true},
    [PG_FMT_RG16_SNORM] = {"rg16_snorm", VK_FORMAT_R16G16_SNORM, 4, PG_FMTCLASS_FLOAT, false, true},
    [PG_FMT_R32F] = {"r32f", VK_FORMAT_R32_SFLOAT, 4, PG_FMTCLASS_FLOAT, false, true},
    [PG_FMT_R32UI] = {"r32ui", VK_FORMAT_R32_UINT, 4, PG_FMTCLASS_UINT, false, true},
    [PG_FMT_RG32UI] = {"rg32ui", VK_FORMAT_R32G32_UINT, 8, PG_FMTCLASS_UINT, false, true},
    [PG_FMT_RGBA32UI] = {"rgba32ui", VK_FORMAT_R32G32B32A32_UINT, 16, PG_FMTCLASS_UINT, false, true},
    [PG_FMT_R11G11B10F] = {"r11g11b10f", VK_FORMAT_B10G11R11_UFLOAT_PACK32, 4, PG_FMTCLASS_FLOAT, false, false},
    [PG_FMT_D32F] = {"d32f", VK_FORMAT_D32_SFLOAT, 4, PG_FMTCLASS_DEPTH, false, false},
};

const pg_format_info *pg_format_get(pg_format f)
{
    if ((int)f < 0 || f >= PG_FMT_COUNT) return &g_formats[PG_FMT_UNDEFINED];
    return &g_formats[f];
}

pg_format pg_format_from_name(const char *name)
{
    if (!name) return PG_FMT_UNDEFINED;
    for (int i = 1; i < PG_FMT_COUNT; i++)
        if (strcmp(g_formats[i].name, name) == 0) return (pg_format)i;
    return PG_FMT_UNDEFINED;
}

bool pg_ident_ok(const char *s)
{
    if (!s || !*s) return false;
    size_t n = 0;
    for (; s[n]; n++) {
        const char c = s[n];
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
        if (!ok) return false;
    }
    return n < PG_NAME_MAX;
}

bool pg_strlcpy(char *dst, const char *src, size_t dst_size)
{
    if (!dst_size) return false;
    size_t n = src ? strlen(src) : 0;
    bool fits = n < dst_size;
    if (!fits) n = dst_size - 1;
    if (n) memcpy(dst, src, n);
    dst[n] = 0;
    return fits;
}

pg_result pg_read_file(const char *path, char **out_text, size_t *out_size, pg_error *err)
{
    return pg_read_file_as(path, NULL, out_text, out_size, err);
}

pg_result pg_read_file_as(const char *path, const char *expected, char **out_text, size_t *out_size,
                          pg_error *err)
{
    *out_text = NULL;
    if (out_size) *out_size = 0;
    /* a directory opens (and ftell reports LONG_MAX on some libcs): refuse it by name first */
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        const char *what = S_ISDIR(st.st_mode) ? "is a directory" : "is not a regular file";
        if (expected) return pg_fail(err, PG_ERR_IO, "%s: %s (expected %s)", path, what, expected);
        return pg_fail(err, PG_ERR_IO, "%s: %s", path, what);
    }
    FILE *f = fopen(path, "rb");
    if (!f) return pg_fail(err, PG_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    if (fseek(f, 0, SEEK_END) != 0) {
        fclose(f);
        return pg_fail(err, PG_ERR_IO, "%s: cannot seek (not a regular file?)", path);
    }
    long len = ftell(f);
    if (len < 0) {
        fclose(f);
        return pg_fail(err, PG_ERR_IO, "%s: cannot size file (not a regular file?)", path);
    }
    rewind(f);
    char *buf = malloc((size_t)len + 1);
    if (!buf) {
        fclose(f);
        return pg_fail(err, PG_ERR_OOM, "%s: out of memory reading %ld bytes", path, len);
    }
    size_t got = fread(buf, 1, (size_t)len, f);
    fclose(f);
    if (got != (size_t)len) {
        free(buf);
        return pg_fail(err, PG_ERR_IO, "%s: short read (%zu of %ld bytes)", path, got, len);
    }
    buf[len] = 0;
    *out_text = buf;
    if (out_size) *out_size = (size_t)len;
    return PG_OK;
}

double pg_time_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}
