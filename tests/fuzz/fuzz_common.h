/* fuzz_common.h - helpers shared by the libFuzzer targets in tests/fuzz/ (header-only, static):
 * a private temporary directory created once per process and removed at exit, file writing and
 * copying, and abort-with-message for broken invariants (libFuzzer reports the abort as a crash
 * and saves the input). */
#ifndef PG_FUZZ_COMMON_H
#define PG_FUZZ_COMMON_H

#include <dirent.h>
#include <ftw.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char g_fuzz_dir[256];

static int fuzz_rm_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    return remove(path);
}

static void fuzz_cleanup(void)
{
    if (g_fuzz_dir[0]) nftw(g_fuzz_dir, fuzz_rm_entry, 16, FTW_DEPTH | FTW_PHYS);
}

/* Creates the private directory ($TMPDIR or /tmp) once; returns its path. */
static const char *fuzz_dir(const char *tag)
{
    if (g_fuzz_dir[0]) return g_fuzz_dir;
    const char *tmp = getenv("TMPDIR");
    if (!tmp || !tmp[0]) tmp = "/tmp";
    snprintf(g_fuzz_dir, sizeof g_fuzz_dir, "%s/pg_fuzz_%s.XXXXXX", tmp, tag);
    if (!mkdtemp(g_fuzz_dir)) {
        perror("mkdtemp");
        abort();
    }
    atexit(fuzz_cleanup);
    return g_fuzz_dir;
}

#if defined(__GNUC__)
__attribute__((format(printf, 1, 2), noreturn))
#endif
static void fuzz_die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "fuzz invariant broken: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    abort();
}

static void fuzz_write(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f) fuzz_die("cannot write %s", path);
    if (size && fwrite(data, 1, size, f) != size) fuzz_die("short write %s", path);
    fclose(f);
}

/* Copies every regular file of src_dir whose name passes keep() into dst_dir (not recursive).
 * A missing src_dir is not an error (the target still runs, with less to reach). */
static void fuzz_copy_dir(const char *src_dir, const char *dst_dir, int (*keep)(const char *name))
{
    DIR *d = opendir(src_dir);
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.' || !keep(e->d_name)) continue;
        char src[1024], dst[1024];
        snprintf(src, sizeof src, "%s/%s", src_dir, e->d_name);
        snprintf(dst, sizeof dst, "%s/%s", dst_dir, e->d_name);
        struct stat st;
        if (stat(src, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size > (1 << 20)) continue;
        FILE *in = fopen(src, "rb");
        if (!in) continue;
        char *buf = malloc((size_t)st.st_size + 1);
        size_t got = buf ? fread(buf, 1, (size_t)st.st_size, in) : 0;
        fclose(in);
        if (buf) fuzz_write(dst, buf, got);
        free(buf);
    }
    closedir(d);
}

static int fuzz_ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcmp(s + n - k, suffix) == 0;
}

#endif
