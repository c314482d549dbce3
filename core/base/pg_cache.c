/* pg_cache.c - cache folder, hashing and atomic files for the SPIR-V and pipeline caches. */
#include "pg_cache.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pg_common.h"

static int g_enabled = -1; /* -1: from the environment */

bool pg_cache_enabled(void)
{
    if (g_enabled < 0) {
        const char *e = getenv("PASSGRAPH_NO_SHADER_CACHE");
        g_enabled = !(e && e[0] && strcmp(e, "0"));
    }
    return g_enabled == 1;
}

void pg_cache_set_enabled(bool on) { g_enabled = on ? 1 : 0; }

bool pg_cache_dir(char *buf, size_t size)
{
    const char *e = getenv("PASSGRAPH_CACHE_DIR");
    int n;
    if (e && e[0]) n = snprintf(buf, size, "%s", e);
    else if ((e = getenv("XDG_CACHE_HOME")) && e[0]) n = snprintf(buf, size, "%s/passgraph", e);
    else if ((e = getenv("HOME")) && e[0]) n = snprintf(buf, size, "%s/.cache/passgraph", e);
    else return false;
    return n > 0 && (size_t)n < size;
}

bool pg_cache_mkdirs(const char *dir)
{
    char p[PG_PATH_MAX];
    if (snprintf(p, sizeof p, "%s", dir) >= (int)sizeof p) return false;
    for (char *s = p + 1; *s; s++) {
        if (*s != '/') continue;
        *s = 0;
        if (mkdir(p, 0755) && errno != EEXIST) return false;
        *s = '/';
    }
    if (mkdir(p, 0755) && errno != EEXIST) return false;
    struct stat st;
    return stat(p, &st) == 0 && S_ISDIR(st.st_mode);
}

void pg_cache_note(const char *fmt, ...)
{
    char msg[PG_PATH_MAX * 2];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fprintf(stderr, "passgraph: note: %s\n", msg);
}

pg_hash128 pg_hash128_init(void) { return (pg_hash128){0xcbf29ce484222325ull, 0x9e3779b97f4a7c15ull}; }

void pg_hash128_add(pg_hash128 *h, const void *data, size_t n)
{
    const unsigned char *p = data;
    uint64_t a = h->a, b = h->b;
    for (size_t i = 0; i < n; i++) {
        a = (a ^ p[i]) * 0x100000001b3ull;                   /* FNV-1a */
        b = (b ^ (p[i] + 0x9e3779b97f4a7c15ull)) * 0xc2b2ae3d27d4eb4full;
        b ^= b >> 29;
    }
    h->a = a;
    h->b = b;
}

bool pg_cache_write(const char *path, const void *head, size_t head_bytes, const void *body, size_t body_bytes)
{
    char tmp[PG_PATH_MAX + 32];
    snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid());
    FILE *f = fopen(tmp, "wb");
    bool ok = f && fwrite(head, 1, head_bytes, f) == head_bytes &&
              (!body_bytes || fwrite(body, 1, body_bytes, f) == body_bytes);
    if (f && fclose(f)) ok = false;
    if (ok && rename(tmp, path)) ok = false;
    if (!ok) {
        static bool noted; /* once per process */
        if (!noted) pg_cache_note("cache file %s not written (%s)", path, strerror(errno));
        noted = true;
        unlink(tmp);
    }
    return ok;
}

void *pg_cache_read(const char *path, size_t *bytes)
{
    *bytes = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *data = NULL;
    if (fseek(f, 0, SEEK_END) == 0) {
        long n = ftell(f);
        if (n >= 0 && fseek(f, 0, SEEK_SET) == 0 && (data = malloc((size_t)n + 1))) {
            if (fread(data, 1, (size_t)n, f) == (size_t)n) *bytes = (size_t)n;
            else {
                free(data);
                data = NULL;
            }
        }
    }
    fclose(f);
    return data;
}
