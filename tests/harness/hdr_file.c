/* hdr_file.c - the tests' Radiance HDR writer (hdr_file.h). */
#include "hdr_file.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

size_t pg_test_hdr_header(char *buf, size_t size, uint32_t w, uint32_t h)
{
    int n = snprintf(buf, size, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %u +X %u\n", h, w);
    return n > 0 && (size_t)n < size ? (size_t)n : 0;
}

void pg_test_rgbe_encode(const float rgb[3], unsigned char rgbe[4])
{
    float c[3];
    for (int k = 0; k < 3; k++) c[k] = rgb[k] > 0 ? rgb[k] : 0; /* NaN and negatives -> 0 */
    float mx = c[0] > c[1] ? c[0] : c[1];
    mx = mx > c[2] ? mx : c[2];
    int e = 0;
    (void)frexp(mx, &e);
    if (!(mx > 0) || e + 128 < 1 || e + 128 > 255 || !isfinite(mx)) {
        rgbe[0] = rgbe[1] = rgbe[2] = rgbe[3] = 0;
        return;
    }
    for (int k = 0; k < 3; k++) rgbe[k] = (unsigned char)floor(ldexp(c[k], 8 - e)); /* < 256 */
    rgbe[3] = (unsigned char)(e + 128);
}

void pg_test_rgbe_decode(const unsigned char rgbe[4], float rgb[3])
{
    if (rgbe[3] == 0) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
    float f = (float)ldexp(1.0f, rgbe[3] - (128 + 8)); /* stb_image's stbi__hdr_convert */
    for (int k = 0; k < 3; k++) rgb[k] = rgbe[k] * f;
}

void pg_test_rgbe_round(const float in[3], float out[3])
{
    unsigned char e[4];
    pg_test_rgbe_encode(in, e);
    pg_test_rgbe_decode(e, out);
}

int pg_test_write_bytes(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    size_t put = fwrite(data, 1, n, f);
    return fclose(f) == 0 && put == n ? 0 : -1;
}

int pg_test_write_hdr(const char *path, uint32_t w, uint32_t h, const float *rgb3)
{
    char head[128];
    size_t hl = pg_test_hdr_header(head, sizeof head, w, h);
    size_t n = (size_t)w * h;
    unsigned char *buf = malloc(hl + 4 * n);
    if (!hl || !buf) {
        free(buf);
        return -1;
    }
    for (size_t i = 0; i < hl; i++) buf[i] = (unsigned char)head[i];
    for (size_t t = 0; t < n; t++) pg_test_rgbe_encode(rgb3 + 3 * t, buf + hl + 4 * t);
    int r = pg_test_write_bytes(path, buf, hl + 4 * n);
    free(buf);
    return r;
}
