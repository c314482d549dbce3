/* hdr_file.h - a tiny Radiance HDR (.hdr, RGBE) writer for the tests, and the RGBE encoding so a
 * test knows exactly what a written value reads back as (stb_image decodes a pixel (r, g, b, e)
 * as m x 2^(e - 136) per channel, e = 0 being black).
 *
 * Exact values: a colour reads back unchanged when every channel is m x 2^(k - 8) for integers
 * m < 256 and the exponent k of the largest channel (max = f 2^k, f in [0.5, 1)): e.g. 1, 0.5,
 * 0.25, 3, 0.75, 2^-10, and any small integer up to 255 in a pixel whose largest channel is
 * below 256 with the same or a larger exponent. pg_test_rgbe_round() gives what any colour reads
 * back as, so a test can compare for equality. */
#ifndef PG_TEST_HDR_FILE_H
#define PG_TEST_HDR_FILE_H

#include <stddef.h>
#include <stdint.h>

/* Writes w x h RGB floats (rows top first) as "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y H +X W\n"
 * and flat (uncompressed) RGBE pixels. Returns 0, or -1 when the file cannot be written. */
int pg_test_write_hdr(const char *path, uint32_t w, uint32_t h, const float *rgb3);
/* The header above for w x h into buf (NUL-terminated); returns its length in bytes (without the
 * NUL), 0 if it does not fit. */
size_t pg_test_hdr_header(char *buf, size_t size, uint32_t w, uint32_t h);
/* Writes n bytes to path (for truncated and foreign files). Returns 0 or -1. */
int pg_test_write_bytes(const char *path, const void *data, size_t n);
/* RGBE of a colour (the usual encoder: frexp of the largest channel, mantissas truncated; values
 * too small for the exponent byte, negative or NaN channels give 0). */
void pg_test_rgbe_encode(const float rgb[3], unsigned char rgbe[4]);
/* What stb_image decodes an RGBE pixel to. */
void pg_test_rgbe_decode(const unsigned char rgbe[4], float rgb[3]);
/* decode(encode(in)): the value a written colour reads back as. */
void pg_test_rgbe_round(const float in[3], float out[3]);

#endif
