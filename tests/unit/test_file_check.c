/* test_file_check.c - pg_file_check / pg_file_read / pg_file_check_writable (core/base/pg_file.h):
 * a FIFO, a directory, /dev/null and a sparse file over the cap are refused by stat() alone (no
 * open, so the FIFO cannot block), a regular file passes and reads whole. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "pg_file.h"
#include "test_util.h"

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

int main(void)
{
    char dir[] = "/tmp/pg_file_check_XXXXXX";
    if (!mkdtemp(dir)) return pg_test_skip("test_file_check", "mkdtemp failed");
    char fifo[256], big[256], ok[256], msg[PG_ERROR_MSG_MAX];
    snprintf(fifo, sizeof fifo, "%s/p.json", dir);
    snprintf(big, sizeof big, "%s/big.json", dir);
    snprintf(ok, sizeof ok, "%s/ok.json", dir);
    pg_error err = {0};
    uint64_t size = 123;
    char *buf = NULL;
    size_t len = 0;

    /* a FIFO: refused by name, and pg_file_read does not block on it */
    CHECK(mkfifo(fifo, 0600) == 0);
    CHECK(pg_file_check(fifo, "pipeline", PG_FILE_CAP_PIPELINE, &size, &err) == PG_ERR_IO);
    snprintf(msg, sizeof msg, "pipeline '%s': is a FIFO, not a regular file", fifo);
    CHECK_MSG(!strcmp(err.msg, msg), "%s", err.msg);
    CHECK(size == 0);
    CHECK(pg_file_read(fifo, "pipeline", PG_FILE_CAP_PIPELINE, &buf, &len, &err) == PG_ERR_IO && !buf);

    /* a directory */
    CHECK(pg_file_check(dir, "scene", PG_FILE_CAP_GLTF_JSON, NULL, &err) == PG_ERR_IO);
    snprintf(msg, sizeof msg, "scene '%s': is a directory, not a regular file", dir);
    CHECK_MSG(!strcmp(err.msg, msg), "%s", err.msg);

    /* a character device */
    CHECK(pg_file_read("/dev/null", "scenario", PG_FILE_CAP_SCENARIO, &buf, &len, &err) == PG_ERR_IO);
    CHECK_MSG(!strcmp(err.msg, "scenario '/dev/null': is a character device, not a regular file"), "%s", err.msg);
    CHECK(pg_file_check("/dev/zero", "scene", 0, NULL, &err) == PG_ERR_IO && strstr(err.msg, "character device"));

    /* missing */
    CHECK(pg_file_check("/nonexistent/x.json", "pipeline", 0, NULL, &err) == PG_ERR_IO);
    CHECK_MSG(!strcmp(err.msg, "pipeline '/nonexistent/x.json': cannot open: No such file or directory"), "%s", err.msg);

    /* over the cap: a 17 MiB sparse file, refused before any read */
    FILE *f = fopen(big, "wb");
    CHECK(f != NULL);
    if (f) {
        CHECK(ftruncate(fileno(f), (off_t)(17 * PG_MIB)) == 0);
        fclose(f);
    }
    double t0 = now_s();
    CHECK(pg_file_read(big, "pipeline", PG_FILE_CAP_PIPELINE, &buf, &len, &err) == PG_ERR_LIMIT && !buf);
    CHECK(now_s() - t0 < 0.5);
    snprintf(msg, sizeof msg, "pipeline '%s': is 17.0 MiB, over the 16 MiB cap for pipeline files", big);
    CHECK_MSG(!strcmp(err.msg, msg), "%s", err.msg);
    /* 0 = no cap */
    CHECK(pg_file_check(big, "pipeline", 0, &size, &err) == PG_OK && size == 17 * PG_MIB);

    /* a regular file: OK, read whole and NUL-terminated */
    f = fopen(ok, "wb");
    CHECK(f != NULL);
    if (f) {
        fputs("{\"a\": 1}", f);
        fclose(f);
    }
    CHECK(pg_file_check(ok, "pipeline", PG_FILE_CAP_PIPELINE, &size, &err) == PG_OK && size == 8);
    CHECK_MSG(pg_file_read(ok, "pipeline", PG_FILE_CAP_PIPELINE, &buf, &len, &err) == PG_OK, "%s", err.msg);
    CHECK(buf && len == 8 && !strcmp(buf, "{\"a\": 1}"));
    free(buf);
    buf = NULL;
    CHECK(pg_file_read(ok, "pipeline", 4, &buf, &len, &err) == PG_ERR_LIMIT && !buf);
    CHECK_MSG(strstr(err.msg, "is 8 bytes, over the 4 bytes cap for pipeline files") != NULL, "%s", err.msg);

    /* sizes */
    char s[32];
    pg_file_fmt_size(2254857830ull, s, sizeof s);
    CHECK_MSG(!strcmp(s, "2.1 GiB"), "%s", s);

    /* outputs */
    CHECK(pg_file_check_writable(ok, "--out", &err) == PG_OK);
    CHECK(pg_file_check_writable("/missing/dir/x.png", "--out", &err) == PG_ERR_IO);
    CHECK_MSG(!strcmp(err.msg, "--out '/missing/dir/x.png': cannot write: No such file or directory"), "%s", err.msg);
    CHECK(pg_file_check_writable(dir, "--out", &err) == PG_ERR_IO && strstr(err.msg, "Is a directory"));
    snprintf(msg, sizeof msg, "%s/x.png", ok); /* a folder that is a file */
    CHECK(pg_file_check_writable(msg, "--out", &err) == PG_ERR_IO && strstr(err.msg, "Not a directory"));
    CHECK(pg_file_check_writable_dir(dir, "--out", &err) == PG_OK);
    snprintf(msg, sizeof msg, "%s/new", dir);
    CHECK(pg_file_check_writable_dir(msg, "--out", &err) == PG_OK);
    CHECK(pg_file_check_writable_dir("/missing/dir/new", "--out", &err) == PG_ERR_IO);
    CHECK(pg_file_check_writable_dir(ok, "--out", &err) == PG_ERR_IO && strstr(err.msg, "Not a directory"));

    unlink(fifo);
    unlink(big);
    unlink(ok);
    rmdir(dir);
    return pg_test_finish("test_file_check");
}
