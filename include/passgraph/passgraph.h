/* passgraph.h - passgraph as a library (docs/embedding.md): open a session on a pipeline file and
 * a scene, set the camera and the lights, render frames into memory or into a VkImage of the
 * session's device, read the GPU time of every pass and the image error against a reference
 * pipeline. Installed with `cmake --install` under <prefix>/include/passgraph/; link with
 * find_package(passgraph) (target passgraph::passgraph) or `pkg-config --cflags --libs passgraph`.
 *
 * Errors are values: every function that can fail returns a pg_result (PG_OK = 0) and fills the
 * pg_error's message ("FILE: JSON.PATH: cause" for a bad pipeline file, as the passgraph tool
 * prints them). A session is not thread-safe; separate sessions may live in one process.
 * The pass API (writing pass types in C: pass_api.h, pass_plugin.h) is installed alongside. */
#ifndef PASSGRAPH_H
#define PASSGRAPH_H

#include <stddef.h>
#include <stdint.h>

#include <vulkan/vulkan.h>

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PASSGRAPH_EMBED_VERSION 1

/* The PASSGRAPH_EMBED_VERSION the library was built with: a program compares it with the one it
 * was compiled against (the structs of this header change only with it). */
uint32_t passgraph_embed_version(void);

typedef struct passgraph passgraph;

typedef struct passgraph_desc {
    const char *pipeline;          /* a pipeline file (NULL: the data folder's pipelines/forward_plus.json) */
    const char *scene;             /* a glTF 2.0 file (NULL or "default": the built-in atrium) */
    uint32_t width, height;        /* the output size (both 0: 1280 x 720; one 0 is refused) */
    const char *const *params;     /* "key=value" pipeline parameter overrides, as --set */
    uint32_t n_params;
    int device;                    /* Vulkan device index (-1: the first suitable: discrete, integrated, cpu) */
    bool validation;               /* the Khronos validation layer with synchronization validation */
} passgraph_desc;

/* Opens a session: a Vulkan device, the scene uploaded, the pass types the pipeline file lists
 * ("plugins") loaded, the pipeline compiled for the output size (a value a pass refuses fails
 * here), the scene's default camera and 256 generated lights (seed 7) at time 0. Every call given a
 * NULL session or a NULL required pointer returns PG_ERR_INVALID_ARG (getters: 0, NULL or NaN). */
pg_result passgraph_open(const passgraph_desc *desc, passgraph **out, pg_error *err);
void passgraph_close(passgraph *p);

/* The camera: eye and target (world space), up, vertical field of view in degrees (0 < fov < 180),
 * near and far distances (0: keep the current ones). */
pg_result passgraph_set_camera(passgraph *p, const float eye[3], const float target[3], const float up[3],
                               float fov_y_deg, float near_z, float far_z, pg_error *err);
/* The generated lights: how many (0 .. 2^24; a scene file's own lights are added to them), their
 * random seed, and the time in seconds their animation is at (and the glTF animation's), |time| at
 * most 1e5 (a float steps by more than 1/128 s past it). */
pg_result passgraph_set_lights(passgraph *p, uint32_t count, uint32_t seed, float time, pg_error *err);
/* A pipeline parameter (as --set key=value); the pipeline is compiled again for the next frame
 * when it selects another variant, and nothing is rebuilt for a run-time value. */
pg_result passgraph_set_param(passgraph *p, const char *key, const char *value, pg_error *err);

/* Renders one frame and keeps its images for passgraph_read_*. */
pg_result passgraph_render(passgraph *p, pg_error *err);
/* The last frame's display image: width x height RGBA8 (sRGB-encoded), row-major from the top. */
pg_result passgraph_read_rgba8(const passgraph *p, uint8_t *dst, size_t dst_bytes, pg_error *err);
/* The last frame's scene-linear HDR image (the pipeline's hdr_output): width x height RGBA32F. */
pg_result passgraph_read_hdr(const passgraph *p, float *dst, size_t dst_bytes, pg_error *err);

/* The Vulkan objects the session renders with (to create images for passgraph_render_to_image). */
typedef struct passgraph_vulkan {
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;                 /* the graphics queue passgraph submits to */
    uint32_t queue_family;
} passgraph_vulkan;
void passgraph_get_vulkan(const passgraph *p, passgraph_vulkan *out);
/* Renders one frame and copies its display image into dst, a 2D colour image of the session's
 * device of the output's size or larger, created with VK_IMAGE_USAGE_TRANSFER_DST_BIT and the
 * format `format` (any format vkCmdBlitImage can write from RGBA8: not an integer or depth/stencil
 * one, PG_ERR_FORMAT). dst is in old_layout before the
 * call (UNDEFINED: its contents are discarded) and in new_layout after it; the copy is complete
 * when the call returns (the device is idle). */
pg_result passgraph_render_to_image(passgraph *p, VkImage dst, VkFormat format, VkImageLayout old_layout,
                                    VkImageLayout new_layout, pg_error *err);

/* The last frame's passes in execution order with their GPU times (from timestamps). */
uint32_t passgraph_pass_count(const passgraph *p);
const char *passgraph_pass_name(const passgraph *p, uint32_t i);
double passgraph_pass_ms(const passgraph *p, uint32_t i);
/* The last frame's GPU time, first to last timestamp. */
double passgraph_gpu_ms(const passgraph *p);
/* Messages the validation layer reported so far (passgraph_desc.validation; each is also printed to
 * stderr). */
uint32_t passgraph_validation_messages(const passgraph *p);
/* The folder passgraph reads its shaders, pipelines and assets from (<prefix>/share/passgraph next
 * to the installed library, or $PASSGRAPH_DATA_DIR). */
const char *passgraph_data_dir(void);
/* The output size. */
void passgraph_size(const passgraph *p, uint32_t *width, uint32_t *height);

/* The image error of the last frame against the same frame (camera, lights, time) rendered by a
 * reference pipeline (NULL: the data folder's pipelines/reference.json, every light for every
 * pixel): RMSE, PSNR and max abs over the scene-linear RGB (PSNR against the reference's peak),
 * and the share of pixels whose 8-bit display value differs by more than one step. The reference
 * gets the parameter overrides it declares (as `passgraph compare --set` gives them). */
typedef struct passgraph_error_stats {
    double rmse, psnr_db, max_abs;
    double share_over_1;
} passgraph_error_stats;
pg_result passgraph_error_against(passgraph *p, const char *reference, passgraph_error_stats *out, pg_error *err);

#ifdef __cplusplus
}
#endif
#endif
