/* exr.c - RGBA EXR write/read with OpenEXRCore (see exr.h). */
#include "exr.h"

#include "image_util.h"

#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* OpenEXR reports errors through a callback (default: print to stderr); keep the first message
 * for our pg_error instead. */
typedef struct exr_msg {
    char text[256];
} exr_msg;

static void on_exr_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    void *ud = NULL;
    if (exr_get_user_data(ctxt, &ud) != EXR_ERR_SUCCESS || !ud) return;
    exr_msg *m = ud;
    if (!m->text[0])
        snprintf(m->text, sizeof m->text, "%s", msg && msg[0] ? msg : exr_get_default_error_message(code));
}

static pg_result exr_fail(pg_error *err, const char *path, const char *what, exr_result_t rv, const exr_msg *m)
{
    const char *why = m->text[0] ? m->text : exr_get_default_error_message(rv);
    return pg_fail(err, rv == EXR_ERR_FILE_ACCESS || rv == EXR_ERR_MISSING_REQ_ATTR ? PG_ERR_IO : PG_ERR_PARSE,
                   "%s: %s: %s", path, what, why);
}

uint16_t pg_float_to_half(float f)
{
    uint32_t x;
    memcpy(&x, &f, 4);
    uint32_t sign = (x >> 16) & 0x8000u;
    uint32_t exp = (x >> 23) & 0xffu;
    uint32_t man = x & 0x7fffffu;
    if (exp == 0xffu) return (uint16_t)(sign | 0x7c00u | (man ? 0x200u | (man >> 13) : 0)); /* inf / NaN */
    int e = (int)exp - 127 + 15;
    if (e >= 31) return (uint16_t)(sign | 0x7c00u); /* overflow: inf */
    if (e <= 0) {                                     /* subnormal half or zero */
        if (e < -10) return (uint16_t)sign;
        man |= 0x800000u;
        uint32_t shift = (uint32_t)(14 - e);
        uint32_t h = man >> shift;
        uint32_t rem = man & ((1u << shift) - 1), halfway = 1u << (shift - 1);
        if (rem > halfway || (rem == halfway && (h & 1u))) h++;
        return (uint16_t)(sign | h);
    }
    uint32_t h = ((uint32_t)e << 10) | (man >> 13);
    uint32_t rem = man & 0x1fffu;
    if (rem > 0x1000u || (rem == 0x1000u && (h & 1u))) h++; /* may carry into the exponent: correct */
    return (uint16_t)(sign | h);
}

static int channel_index(const char *name)
{
    static const char *const names[4] = {"R", "G", "B", "A"};
    for (int i = 0; i < 4; i++)
        if (!strcmp(name, names[i])) return i;
    return -1;
}

/* OpenEXRCore 3.1.5 (Debian 12) keeps a chunk's compressed bytes when they are exactly as many as
 * its raw bytes, and every reader takes a chunk of its raw size as raw: such a chunk read back as
 * noise (NaN, negative alpha: a 1x256 image of 64 RIS-lit pixels had 16). Fixed upstream in 3.4;
 * here the default compression runs, and a result no smaller than the raw data is replaced by the
 * raw data, as the format intends. */
static _Thread_local exr_result_t (*g_default_compress)(exr_encode_pipeline_t *);

static exr_result_t compress_or_raw(exr_encode_pipeline_t *enc)
{
    exr_result_t rv = g_default_compress(enc);
    if (rv == EXR_ERR_SUCCESS && enc->compressed_bytes >= enc->packed_bytes &&
        enc->compressed_buffer != enc->packed_buffer && enc->compressed_alloc_size >= enc->packed_bytes) {
        memcpy(enc->compressed_buffer, enc->packed_buffer, enc->packed_bytes);
        enc->compressed_bytes = enc->packed_bytes;
    }
    return rv;
}

pg_result pg_exr_write_rgba(const char *path, const float *rgba, uint32_t w, uint32_t h, bool half,
                            pg_error *err)
{
    if (!w || !h || w > 65536 || h > 65536)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: cannot write a %ux%u EXR", path, w, h);
    size_t n = (size_t)w * h * 4;
    uint16_t *halves = NULL;
    if (half) {
        halves = malloc(n * sizeof(uint16_t));
        if (!halves) return pg_fail(err, PG_ERR_OOM, "%s: out of memory", path);
        for (size_t i = 0; i < n; i++) halves[i] = pg_float_to_half(rgba[i]);
    }
    const uint8_t *base = half ? (const uint8_t *)halves : (const uint8_t *)rgba;
    int32_t bytes = half ? 2 : 4;
    exr_msg m = {{0}};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_exr_error;
    init.user_data = &m;
    exr_context_t ctx = NULL;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool enc_ready = false;
    pg_result r = PG_OK;
    const char *what = "cannot write";
    exr_result_t rv = exr_start_write(&ctx, path, EXR_INTERMEDIATE_TEMP_FILE, &init);
    int part = 0;
    if (rv == EXR_ERR_SUCCESS) rv = exr_add_part(ctx, "rgba", EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctx, part, (int32_t)w, (int32_t)h, EXR_COMPRESSION_ZIP);
    static const char *const names[4] = {"R", "G", "B", "A"};
    for (int c = 0; c < 4 && rv == EXR_ERR_SUCCESS; c++)
        rv = exr_add_channel(ctx, part, names[c], half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT,
                             c == 3 ? EXR_PERCEPTUALLY_LINEAR : EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (rv == EXR_ERR_SUCCESS) rv = exr_write_header(ctx);
    int32_t lines = 1;
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_scanlines_per_chunk(ctx, part, &lines);
    if (rv == EXR_ERR_SUCCESS && lines < 1) lines = 1;
    for (int32_t y = 0; rv == EXR_ERR_SUCCESS && y < (int32_t)h; y += lines) {
        exr_chunk_info_t ci;
        what = "cannot encode";
        rv = exr_write_scanline_chunk_info(ctx, part, y, &ci);
        if (rv != EXR_ERR_SUCCESS) break;
        rv = enc_ready ? exr_encoding_update(ctx, part, &ci, &enc) : exr_encoding_initialize(ctx, part, &ci, &enc);
        if (rv != EXR_ERR_SUCCESS) break;
        for (int16_t k = 0; k < enc.channel_count; k++) {
            exr_coding_channel_info_t *ch = &enc.channels[k];
            int c = channel_index(ch->channel_name);
            ch->user_data_type = half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
            ch->user_bytes_per_element = (int16_t)bytes;
            ch->user_pixel_stride = 4 * bytes;
            ch->user_line_stride = (int32_t)w * 4 * bytes;
            ch->encode_from_ptr = base + ((size_t)ci.start_y * w * 4 + (size_t)(c < 0 ? 0 : c)) * (size_t)bytes;
        }
        if (!enc_ready) {
            rv = exr_encoding_choose_default_routines(ctx, part, &enc);
            if (rv != EXR_ERR_SUCCESS) break;
            enc_ready = true;
            if (enc.compress_fn) {
                g_default_compress = enc.compress_fn;
                enc.compress_fn = compress_or_raw;
            }
        }
        rv = exr_encoding_run(ctx, part, &enc);
    }
    if (rv != EXR_ERR_SUCCESS) r = exr_fail(err, path, what, rv, &m);
    if (enc_ready || enc.channels) exr_encoding_destroy(ctx, &enc);
    if (ctx) {
        exr_result_t fr = exr_finish(&ctx);
        if (!r && fr != EXR_ERR_SUCCESS) r = exr_fail(err, path, "cannot finish", fr, &m);
    }
    free(halves);
    return r;
}

/* the R, G and B channels are present and none of R, G, B, A is subsampled */
static pg_result check_channels(const char *path, const exr_attr_chlist_t *chl, pg_error *err)
{
    int have = 0;
    for (int i = 0; chl && i < chl->num_channels; i++) {
        int c = channel_index(chl->entries[i].name.str);
        if (c >= 0) {
            if (chl->entries[i].x_sampling != 1 || chl->entries[i].y_sampling != 1)
                return pg_fail(err, PG_ERR_PARSE, "%s: subsampled channel '%s' is not supported", path,
                               chl->entries[i].name.str);
            have |= 1 << c;
        }
    }
    if ((have & 7) != 7) return pg_fail(err, PG_ERR_PARSE, "%s: the EXR has no R, G and B channels", path);
    return PG_OK;
}

/* part 0's header: a scanline image, its data window (at most 65536 a side), its scanlines per
 * chunk and its channels */
static pg_result read_header(exr_context_t ctx, const char *path, const exr_msg *m, exr_attr_box2i_t *dw,
                             int32_t *lines, pg_error *err)
{
    exr_storage_t storage;
    const exr_attr_chlist_t *chl = NULL;
    exr_result_t rv;
    if ((rv = exr_get_storage(ctx, 0, &storage)) || (rv = exr_get_data_window(ctx, 0, dw)) ||
        (rv = exr_get_channels(ctx, 0, &chl)) || (rv = exr_get_scanlines_per_chunk(ctx, 0, lines)))
        return exr_fail(err, path, "cannot read the header", rv, m);
    if (storage != EXR_STORAGE_SCANLINE) return pg_fail(err, PG_ERR_PARSE, "%s: only scanline EXR images are read", path);
    int64_t w = (int64_t)dw->max.x - dw->min.x + 1, h = (int64_t)dw->max.y - dw->min.y + 1;
    if (w < 1 || h < 1 || w > 65536 || h > 65536)
        return pg_fail(err, PG_ERR_PARSE, "%s: unsupported data window %lldx%lld", path, (long long)w, (long long)h);
    return check_channels(path, chl, err);
}

/* each R, G, B, A channel of the chunk decoded in its own type into its plane (c) of `plane`
 * (plane_px pixels each); the others skipped */
static void bind_planes(exr_decode_pipeline_t *dec, uint8_t *plane, size_t plane_px, int64_t w)
{
    for (int16_t k = 0; k < dec->channel_count; k++) {
        exr_coding_channel_info_t *ch = &dec->channels[k];
        int c = channel_index(ch->channel_name);
        if (c < 0) {
            ch->decode_to_ptr = NULL; /* skipped */
            continue;
        }
        ch->user_data_type = ch->data_type;
        ch->user_bytes_per_element = ch->bytes_per_element;
        ch->user_pixel_stride = ch->bytes_per_element;
        ch->user_line_stride = (int32_t)(w * ch->bytes_per_element);
        ch->decode_to_ptr = plane + (size_t)c * plane_px * 4;
    }
}

/* the decoded planes converted to floats into dst's RGBA pixels */
static void planes_to_rgba(const exr_decode_pipeline_t *dec, const uint8_t *plane, size_t plane_px, float *dst)
{
    for (int16_t k = 0; k < dec->channel_count; k++) {
        const exr_coding_channel_info_t *ch = &dec->channels[k];
        int c = channel_index(ch->channel_name);
        if (c < 0) continue;
        const uint8_t *src = plane + (size_t)c * plane_px * 4;
        for (size_t i = 0; i < plane_px; i++) {
            float v;
            if (ch->data_type == EXR_PIXEL_HALF) {
                uint16_t hv;
                memcpy(&hv, src + i * 2, 2);
                v = pg_half_to_float(hv);
            } else if (ch->data_type == EXR_PIXEL_FLOAT) {
                memcpy(&v, src + i * 4, 4);
            } else {
                uint32_t u;
                memcpy(&u, src + i * 4, 4);
                v = (float)u;
            }
            dst[i * 4 + (size_t)c] = v;
        }
    }
}

/* Every chunk of the data window dw decoded into px (w pixels a line). Each channel is decoded in
 * its own type into its own plane of a chunk-sized buffer and converted here: OpenEXRCore 3.1.5's
 * converting / interleaving unpackers mix up the channels of 4 half channels decoded as
 * interleaved floats (found by tests/test_ocio.c). */
static exr_result_t decode_chunks(exr_context_t ctx, exr_decode_pipeline_t *dec, bool *dec_ready,
                                  const exr_attr_box2i_t *dw, int32_t lines, int64_t w, uint8_t *plane, float *px)
{
    exr_result_t rv = EXR_ERR_SUCCESS;
    for (int64_t y = dw->min.y; y <= dw->max.y; y += lines) {
        exr_chunk_info_t ci;
        if ((rv = exr_read_scanline_chunk_info(ctx, 0, (int)y, &ci))) break;
        rv = *dec_ready ? exr_decoding_update(ctx, 0, &ci, dec) : exr_decoding_initialize(ctx, 0, &ci, dec);
        if (rv != EXR_ERR_SUCCESS) break;
        if (ci.height > lines || ci.width != w) {
            rv = EXR_ERR_BAD_CHUNK_LEADER;
            break;
        }
        size_t plane_px = (size_t)ci.height * (size_t)w;
        bind_planes(dec, plane, plane_px, w);
        if ((rv = exr_decoding_choose_default_routines(ctx, 0, dec))) break;
        *dec_ready = true;
        if ((rv = exr_decoding_run(ctx, 0, dec))) break;
        planes_to_rgba(dec, plane, plane_px, px + (size_t)(ci.start_y - dw->min.y) * (size_t)w * 4);
    }
    return rv;
}

/* The file holds at least the chunk table its header announces (8 bytes a chunk) and each chunk's
 * 8-byte header: a file that cannot is refused before w x h pixels are allocated (a header of a
 * 16384 x 8192 image in a file of 377 bytes took 2 GiB). */
static pg_result check_size(exr_context_t ctx, const char *path, const exr_msg *m, int64_t w, int64_t h, pg_error *err)
{
    int32_t chunks = 0;
    exr_result_t rv = exr_get_chunk_count(ctx, 0, &chunks);
    if (rv) return exr_fail(err, path, "cannot read the header", rv, m);
    struct stat st;
    if (stat(path, &st) != 0) return pg_fail(err, PG_ERR_IO, "%s: cannot stat", path);
    const unsigned long long need = 16ull * (unsigned long long)(chunks > 0 ? chunks : 0);
    if ((unsigned long long)st.st_size < need)
        return pg_fail(err, PG_ERR_PARSE,
                       "%s: truncated: its header announces %lldx%lld pixels in %d chunks, at least %llu bytes, "
                       "and the file has %lld",
                       path, (long long)w, (long long)h, chunks, need, (long long)st.st_size);
    return PG_OK;
}

/* OpenEXRCore's sequence: open, header, then every chunk decoded; A is 1 where absent */
pg_result pg_exr_read_rgba(const char *path, float **out, uint32_t *out_w, uint32_t *out_h, pg_error *err)
{
    return pg_exr_read_rgba_within(path, UINT32_MAX, out, out_w, out_h, err);
}

pg_result pg_exr_read_rgba_within(const char *path, uint32_t max_side, float **out, uint32_t *out_w, uint32_t *out_h,
                                  pg_error *err)
{
    *out = NULL;
    *out_w = *out_h = 0;
    exr_msg m = {{0}};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_exr_error;
    init.user_data = &m;
    /* strict: every required attribute present (channels, compression, dataWindow, displayWindow,
     * lineOrder, pixelAspectRatio, screenWindowCenter and Width) and a chunk table that reads back;
     * otherwise OpenEXRCore fills a missing attribute with a default (compression ZIP, a 64 x 64 data
     * window) and the file fails later with a misleading message, or is read in part */
    init.flags |= EXR_CONTEXT_FLAG_STRICT_HEADER;
    exr_context_t ctx = NULL;
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    bool dec_ready = false;
    float *px = NULL;
    uint8_t *plane = NULL;
    pg_result r = PG_OK;
    exr_result_t rv = exr_start_read(&ctx, path, &init);
    if (rv != EXR_ERR_SUCCESS) {
        r = exr_fail(err, path, "cannot read", rv, &m);
        goto done;
    }
    exr_attr_box2i_t dw;
    int32_t lines = 1;
    if ((r = read_header(ctx, path, &m, &dw, &lines, err))) goto done;
    int64_t w = (int64_t)dw.max.x - dw.min.x + 1, h = (int64_t)dw.max.y - dw.min.y + 1;
    if ((r = check_size(ctx, path, &m, w, h, err))) goto done;
    if (w > (int64_t)max_side || h > (int64_t)max_side) {
        r = pg_fail(err, PG_ERR_LIMIT, "%s: %lld x %lld: wider or taller than %u", path, (long long)w, (long long)h,
                    max_side);
        goto done;
    }
    px = malloc((size_t)w * h * 4 * sizeof(float));
    if (!px) {
        r = pg_fail(err, PG_ERR_OOM, "%s: out of memory", path);
        goto done;
    }
    for (size_t i = 0; i < (size_t)w * h; i++) px[i * 4 + 3] = 1.0f;
    if (lines < 1) lines = 1;
    plane = malloc((size_t)lines * (size_t)w * 4 * 4);
    if (!plane) {
        r = pg_fail(err, PG_ERR_OOM, "%s: out of memory", path);
        goto done;
    }
    rv = decode_chunks(ctx, &dec, &dec_ready, &dw, lines, w, plane, px);
    if (rv != EXR_ERR_SUCCESS) {
        r = exr_fail(err, path, "cannot decode", rv, &m);
        goto done;
    }
    *out = px;
    px = NULL;
    *out_w = (uint32_t)w;
    *out_h = (uint32_t)h;
done:
    if (dec_ready || dec.channels) exr_decoding_destroy(ctx, &dec);
    if (ctx) exr_finish(&ctx);
    free(plane);
    free(px);
    return r;
}
