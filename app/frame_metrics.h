/* frame_metrics.h - what `compare`, `bench` and `view` measure besides pg_image_error
 * (image/image_compare.h): the perceptual metrics of a frame against the reference (LDR-FLIP of
 * the display images, HDR-FLIP of the scene-linear images, SSIM), the mean of N frames of a
 * stochastic pipeline (accumulation: frame k renders with pg_frame_info.sample = k) and the flicker
 * of K frames with one time, camera and lights (docs/accuracy.md, "Perceptual and temporal error").
 *
 * - Accumulation: the HDR images are averaged per channel (summed in double, stored as float); the
 *   display image is the per-channel mean of the N 8-bit display images, rounded to nearest. (Not
 *   the display transform of the averaged HDR: the pipeline's display pass is on the GPU; averaging
 *   what a viewer would see frame by frame is what temporal accumulation of display frames gives.)
 * - Flicker of frames 0..K-1 (sample = 0..K-1): the mean over the K-1 consecutive pairs, the pixels
 *   and R, G, B of |a_k - a_{k-1}| (linear HDR; a pixel with a non-finite channel in either frame is
 *   left out), divided by the mean R, G, B of the reference's HDR image. The reference is fixed, so
 *   this is the mean frame-to-frame change of the error: exactly 0 for a deterministic pipeline. */
#ifndef PG_FRAME_METRICS_H
#define PG_FRAME_METRICS_H

#include "image_flip.h"
#include "render_session.h"

#define PG_ACCUMULATE_MAX 4096u
#define PG_FLICKER_FRAMES_MAX 1024u
#define PG_FLICKER_FRAMES_DEFAULT 4u

typedef struct pg_perceptual {
    double flip;            /* LDR-FLIP mean of the display images */
    double hdr_flip;        /* HDR-FLIP mean of the HDR images; NaN when not asked for */
    pg_flip_hdr_stats hdr;  /* its exposures (start, stop, count); zero when not asked for */
    double ssim;            /* mean SSIM; NaN when a side is under PG_SSIM_WINDOW pixels */
    double cpu_ms;          /* host time the three took */
} pg_perceptual;

/* The perceptual metrics of a (hdr_a, ldr_a) against b (w*h RGBA32F and RGBA8 images).
 * flip_map: w*h floats (the LDR-FLIP map) or NULL. with_hdr_flip false leaves hdr_flip NaN. */
pg_result pg_perceptual_compute(const float *hdr_a, const float *hdr_b, const uint8_t *ldr_a, const uint8_t *ldr_b,
                                uint32_t w, uint32_t h, bool with_hdr_flip, float *flip_map, pg_perceptual *out,
                                pg_error *err);

/* The flicker sums of consecutive frames. */
typedef struct pg_flicker {
    double sum;      /* of |cur - prev| over RGB of the pixels finite in both */
    uint64_t count;  /* channel values summed */
    uint32_t pairs;  /* frame pairs added */
} pg_flicker;

void pg_flicker_add(pg_flicker *f, const float *prev, const float *cur, uint32_t w, uint32_t h);
/* The flicker (see above) against the reference's mean RGB: 0 when no pair changed; NaN without a
 * pair or when the reference's mean is not positive while frames changed. */
double pg_flicker_value(const pg_flicker *f, const float *ref_hdr, uint32_t w, uint32_t h);

/* The session's last read-back frame: hdr_out (w*h RGBA32F) and ldr_out (w*h RGBA8) copied out,
 * after checking that both outputs have size w x h and the display output is 8-bit. */
pg_result pg_session_read_images(const pg_session *s, uint32_t w, uint32_t h, float *hdr_out, uint8_t *ldr_out,
                                 pg_error *err);

/* The frames a stochastic measure needs beyond frame 0: frames sample = 1 .. max(accumulate,
 * flicker_frames) - 1 of session s (*fi otherwise), each read back. hdr0 / ldr0: frame 0 (rendered
 * and read back by the caller; w x h). hdr_mean / ldr_mean (w x h, caller-allocated): the mean of
 * frames 0 .. accumulate-1 (frame 0 copied when accumulate is 1). fl: the flicker sums of frames
 * 0 .. flicker_frames-1 (none when flicker_frames < 2). *frames_rendered: the extra frames. */
pg_result pg_sample_frames(pg_session *s, const pg_frame_info *fi, uint32_t accumulate, uint32_t flicker_frames,
                           const float *hdr0, const uint8_t *ldr0, uint32_t w, uint32_t h, float *hdr_mean,
                           uint8_t *ldr_mean, pg_flicker *fl, uint32_t *frames_rendered, pg_error *err);

/* --accumulate N: a whole number in [1, PG_ACCUMULATE_MAX]; --flicker-frames K: 0 (off) or a whole
 * number in [2, PG_FLICKER_FRAMES_MAX]. opt names the option in the message. */
pg_result pg_parse_accumulate(const char *opt, const char *v, uint32_t *out, pg_error *err);
pg_result pg_parse_flicker_frames(const char *opt, const char *v, uint32_t *out, pg_error *err);

/* A FLIP map (w*h floats in [0, 1]) as RGBA8 through pg_colormap over the fixed range [0, 1]. */
void pg_flip_map_rgba(const float *map, uint32_t w, uint32_t h, uint8_t *rgba);

#endif
