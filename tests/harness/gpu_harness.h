/* gpu_harness.h - render one configuration and keep its images and stats (GPU tests). */
#ifndef PG_GPU_HARNESS_H
#define PG_GPU_HARNESS_H

#include "render_session.h"

typedef struct pg_th_frame {
    uint8_t *ldr;          /* w*h RGBA8 display image */
    float *hdr;            /* w*h RGBA32F scene-linear image (converted from hdr_raw) */
    void *hdr_raw;         /* the HDR output as read back, in hdr_format (for bit-exact compares) */
    size_t hdr_raw_bytes;  /* w*h*bytes_per_pixel(hdr_format) */
    pg_format hdr_format;  /* the pipeline's hdr_output format (rgba16f or rgba32f) */
    uint32_t w, h;
    pg_frame_stats stats;
    uint32_t creations;
    uint32_t n_order;      /* passes run */
    char order[256];       /* their names, comma separated */
    uint32_t shared_blocks;   /* the plan's memory blocks holding two or more resources */
    uint64_t transient_bytes_unaliased, transient_bytes_aliased; /* the plan's totals */
} pg_th_frame;

/* pipeline is relative to the data folder ("pipelines/naive.json"). Prints errors. */
bool pg_th_render(pg_gpu *gpu, const pg_pass_registry *reg, const pg_scene_gpu *sg, const char *pipeline,
                  const pg_param_override *sets, uint32_t n_sets, const pg_frame_info *fi, uint32_t frames,
                  bool no_alias, pg_th_frame *out);
void pg_th_release(pg_th_frame *f);
/* true when both frames have one size and HDR format and their read-back HDR bytes are equal. */
bool pg_th_hdr_identical(const pg_th_frame *a, const pg_th_frame *b);
/* Largest |a-b| over RGB and the largest reference value (for relative bounds). */
double pg_th_max_abs(const pg_th_frame *a, const pg_th_frame *b, double *ref_peak);
/* Pixels whose RGB (the converted HDR floats) are not bit-identical. */
uint32_t pg_th_differ_pixels(const pg_th_frame *a, const pg_th_frame *b);

/* The per-pixel bound |a - ref| <= A |ref| + B peak (accuracy_bounds.h) over RGB: usage = the
 * worst |a - ref| / (A |ref| + B peak) (<= 1: within the bound; 0 when identical), need_a = the
 * smallest A that would hold with this B. */
void pg_th_bound_usage(const pg_th_frame *a, const pg_th_frame *ref, double peak, double A, double B, double *usage,
                       double *need_a);
/* The same over the pixels p with (mask ? mask[p] : 0) == sel only (0 and 0 when there are none). */
void pg_th_bound_usage_masked(const pg_th_frame *a, const pg_th_frame *ref, double peak, double A, double B,
                              const uint8_t *mask, uint8_t sel, double *usage, double *need_a);

/* Every deterministic shipped pipeline (naive, forward_plus, deferred, deferred_oct16,
 * deferred_packed, visibility, lightcut) rendered with fi against the reference frame ref: every
 * pixel and RGB channel within its documented per-pixel bound (A |ref| + B peak: accuracy_bounds.h;
 * the lightcut's stated 2%), plus the rgba16f rounding (2e-3 |ref|) and `extra` (an absolute term:
 * the cut-off of unranged file lights); forward_plus bit-identical to naive. ray_ref (NULL: ref):
 * the reference with surface=ray, against which the pipelines whose surface is the pixel's ray
 * (visibility, lightcut) are measured: on an NVIDIA GPU the rasterizer's interpolated normal moves
 * a glossy glint by several times visibility's bound (docs/accuracy.md, one image, two devices).
 * Prints each usage ("label: PIPELINE vs reference[ ray]: bound usage U") and CHECKs. */
void pg_th_pipelines_vs_ref(pg_gpu *gpu, const pg_pass_registry *reg, const pg_scene_gpu *sg, const pg_frame_info *fi,
                            const pg_th_frame *ref, const pg_th_frame *ray_ref, const char *label, double extra);

/* The ray through pixel (x, y)'s centre of fi's camera (fi->width x fi->height): a on the near plane,
 * b on the far plane (world space, double). */
void pg_th_pixel_ray(const pg_frame_info *fi, uint32_t x, uint32_t y, double a[3], double b[3]);

/* The point of the floor y = 0 (the corpus' light scenes, tests/corpus/gltf/lights/) under pixel
 * (x, y)'s centre: false when the ray misses the floor, the point lies outside |x|, |z| < 4.9, or
 * (box) the unit box of sun.gltf (-0.5..0.5, 0..1, -0.5..0.5) hides it first. */
bool pg_th_floor_point(const pg_frame_info *fi, uint32_t x, uint32_t y, bool box, double p[3]);

/* A scene opened for a test: loaded ("default" = the built-in atrium), uploaded, and a frame
 * set-up: the scene's default camera for w x h, its default lights (seed 7) at time 0.5, then
 * the scenario (a data-folder path, or NULL) applied over them, and `lights` lights. */
typedef struct pg_th_scene {
    pg_scene *scene;
    pg_scene_gpu *sg;
    pg_frame_info fi;
} pg_th_scene;
/* Prints "label: error" and returns false (nothing left to close) when a step fails. */
bool pg_th_scene_open(pg_gpu *gpu, const char *label, const char *path, const char *scenario, uint32_t w, uint32_t h,
                      uint32_t lights, pg_th_scene *out);
void pg_th_scene_close(pg_gpu *gpu, pg_th_scene *s);
/* A corpus file (PG_TEST_DIR/corpus/gltf/REL) opened as the tools show it: its default view for
 * w x h (pg_scene_default_view: its camera or the object view, the object ambient) at time 0, lit
 * by its own lights alone; shading >= 0 sets the model "auto" picks (PG_SHADING_*) before the upload,
 * -1 keeps the file's. CHECKs and returns false (nothing left to close) when a step fails. */
bool pg_th_file_open(pg_gpu *gpu, const char *rel, uint32_t w, uint32_t h, int shading, pg_th_scene *out);

#endif
