/* shader.h - GLSL -> SPIR-V through glslang's C interface, with per-variant defines.
 *
 * Shaders live in shaders/ (found through pg_data_dir()). `#include "file.glsl"` lines are
 * expanded by passgraph itself (relative to the shaders folder, depth <= 8). Defines are inserted
 * after the #version line. Compile errors name the file and glslang's log.
 */
#ifndef PG_SHADER_H
#define PG_SHADER_H

#include <vulkan/vulkan.h>

#include <stdbool.h>

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

struct pg_gpu;

/* Text made at run time (e.g. OpenColorIO's shader code) that a shader pulls in with
 * `#include "NAME"`: such an include is resolved from these before the shaders folder. */
typedef struct pg_shader_source {
    const char *name;
    const char *text;
} pg_shader_source;

/* Compiles shaders/<name> for stage (VK_SHADER_STAGE_*_BIT). defines: "NAME" or "NAME=VALUE".
 * *spirv is malloc'd (free it). */
pg_result pg_shader_compile(const char *name, VkShaderStageFlagBits stage,
                            const char *const *defines, uint32_t n_defines, uint32_t **spirv,
                            size_t *n_words, pg_error *err);
/* Same, then wraps it in a VkShaderModule named after the file. */
pg_result pg_shader_module(struct pg_gpu *gpu, const char *name, VkShaderStageFlagBits stage,
                           const char *const *defines, uint32_t n_defines, VkShaderModule *out,
                           pg_error *err);
/* The same with generated sources for #include (n_sources may be 0). */
pg_result pg_shader_compile_ex(const char *name, VkShaderStageFlagBits stage, const char *const *defines,
                               uint32_t n_defines, const pg_shader_source *sources, uint32_t n_sources,
                               uint32_t **spirv, size_t *n_words, pg_error *err);
pg_result pg_shader_module_ex(struct pg_gpu *gpu, const char *name, VkShaderStageFlagBits stage,
                              const char *const *defines, uint32_t n_defines, const pg_shader_source *sources,
                              uint32_t n_sources, VkShaderModule *out, pg_error *err);

/* A user's shader file (the `shader` pass type): path is the file itself (any folder; the caller
 * confines it). Its `#include "x"` lines read x from the file's own folder first (a name without
 * ".." or a leading '/'), then from the shaders folder (passgraph's shader library). glslang's
 * messages name the user's files and lines (GL_GOOGLE_cpp_style_line_directive). vulkan12: the
 * Vulkan 1.2 / SPIR-V 1.5 target of a 1.2 device (pg_gpu.vulkan12), else 1.3 / 1.6. */
/* A SPIR-V capability of a user shader (code, words) that needs a device feature passgraph does
 * not enable, or the device lacks (int64: shaderInt64, int64_atomics: shaderBufferInt64Atomics),
 * named ("Float64 (64-bit floats, double)"): the shader is refused by name instead of a validation
 * error, or an undefined result without the layer. NULL when every capability is fine. */
const char *pg_spirv_missing_capability(const uint32_t *code, size_t words, bool int64, bool int64_atomics);
pg_result pg_shader_compile_user(const char *path, VkShaderStageFlagBits stage, const char *const *defines,
                                 uint32_t n_defines, bool vulkan12, uint32_t **spirv, size_t *n_words, pg_error *err);
/* A VkShaderModule over SPIR-V words, named name. */
pg_result pg_shader_module_words(struct pg_gpu *gpu, const char *name, const uint32_t *code, size_t words,
                                 VkShaderModule *out, pg_error *err);

#ifdef __cplusplus
}
#endif
#endif
