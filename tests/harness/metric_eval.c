/* metric_eval.c - passgraph's image metrics (image/image_flip.c, image/image_ssim.c) on raw image
 * files, for tests/oracle/metrics_oracle.py, which compares them with an independent
 * implementation written from the papers.
 *
 *   pg_metric_eval ldr  W H TEST.rgba8  REF.rgba8  MAP.f32 [PPD]   LDR-FLIP
 *   pg_metric_eval hdr  W H TEST.rgba32f REF.rgba32f MAP.f32 [PPD] HDR-FLIP
 *   pg_metric_eval ssim W H A.rgba8 B.rgba8                        SSIM
 *
 * Images are raw, row-major, 4 channels (uint8 or little-endian float32); MAP.f32 receives the
 * W*H per-pixel map as float32. One line of JSON on stdout: the mean (and HDR-FLIP's exposures).
 * Exit 0 on success, 1 on any error (with a message on stderr). */
#include "image_flip.h"
#include "image_ssim.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void *read_raw(const char *path, size_t bytes)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "pg_metric_eval: %s: %s\n", path, strerror(errno));
        return NULL;
    }
    void *p = malloc(bytes ? bytes : 1);
    size_t got = p ? fread(p, 1, bytes, f) : 0;
    int extra = fgetc(f);
    fclose(f);
    if (!p || got != bytes || extra != EOF) {
        fprintf(stderr, "pg_metric_eval: %s: expected exactly %zu bytes\n", path, bytes);
        free(p);
        return NULL;
    }
    return p;
}

static int write_raw(const char *path, const void *p, size_t bytes)
{
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(p, 1, bytes, f) != bytes || fclose(f) != 0) {
        fprintf(stderr, "pg_metric_eval: %s: cannot write\n", path);
        return 1;
    }
    return 0;
}

static int parse_size(const char *s, uint32_t *out)
{
    char *end = NULL;
    long v = strtol(s, &end, 10);
    if (!end || *end || v < 1 || v > 8192) return 1;
    *out = (uint32_t)v;
    return 0;
}

int main(int argc, char **argv)
{
    uint32_t w, h;
    if (argc < 6 || parse_size(argv[2], &w) || parse_size(argv[3], &h)) {
        fprintf(stderr, "usage: pg_metric_eval ldr|hdr W H TEST REF MAP.f32 [PPD] | ssim W H A B\n");
        return 1;
    }
    const char *mode = argv[1];
    const size_t n = (size_t)w * h;
    pg_error err = {0};
    pg_flip_opts o = {.ppd = argc > 7 ? atof(argv[7]) : 0.0};
    int rc = 1;
    if (!strcmp(mode, "ssim")) {
        uint8_t *a = read_raw(argv[4], n * 4), *b = read_raw(argv[5], n * 4);
        double s = 0.0;
        if (a && b && pg_ssim(a, b, w, h, &s, &err) == PG_OK) {
            printf("{\"ssim\": %.9g}\n", s);
            rc = 0;
        } else if (a && b) {
            fprintf(stderr, "pg_metric_eval: %s\n", err.msg);
        }
        free(a);
        free(b);
        return rc;
    }
    if (argc < 7) {
        fprintf(stderr, "pg_metric_eval: %s needs MAP.f32\n", mode);
        return 1;
    }
    float *map = malloc(n * sizeof(float));
    if (!strcmp(mode, "ldr")) {
        uint8_t *t = read_raw(argv[4], n * 4), *r = read_raw(argv[5], n * 4);
        double mean = 0.0;
        if (map && t && r && pg_flip_ldr(t, r, w, h, &o, map, &mean, &err) == PG_OK) {
            printf("{\"mean\": %.9g}\n", mean);
            rc = write_raw(argv[6], map, n * sizeof(float));
        } else if (t && r) {
            fprintf(stderr, "pg_metric_eval: %s\n", err.msg);
        }
        free(t);
        free(r);
    } else if (!strcmp(mode, "hdr")) {
        float *t = read_raw(argv[4], n * 16), *r = read_raw(argv[5], n * 16);
        pg_flip_hdr_stats st = {0};
        if (map && t && r && pg_flip_hdr(t, r, w, h, &o, map, &st, &err) == PG_OK) {
            printf("{\"mean\": %.9g, \"start_exposure\": %.9g, \"stop_exposure\": %.9g, \"exposures\": %u}\n", st.mean,
                   st.start_exposure, st.stop_exposure, st.exposures);
            rc = write_raw(argv[6], map, n * sizeof(float));
        } else if (t && r) {
            fprintf(stderr, "pg_metric_eval: %s\n", err.msg);
        }
        free(t);
        free(r);
    } else {
        fprintf(stderr, "pg_metric_eval: unknown mode '%s' (ldr, hdr, ssim)\n", mode);
    }
    free(map);
    return rc;
}
