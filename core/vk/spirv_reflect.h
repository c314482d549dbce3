/* spirv_reflect.h - the interface of one SPIR-V module, read from its words: the descriptor
 * bindings (images, samplers, uniform and storage blocks, with set, binding, image dimension and
 * format, readonly / writeonly, array size and block size), the push-constant block and its
 * members (offsets, sizes, scalar types), the fragment outputs with their locations, the
 * execution model and a compute shader's workgroup size and shared-memory bytes.
 *
 * Written from the SPIR-V specification (section 2.3 "Physical Layout of a SPIR-V Module" and
 * the instruction / enumerant tables of section 3); no Vulkan call, no glslang call. The reader
 * checks every word it reads against the stream's length: a module that is truncated, not
 * SPIR-V or otherwise malformed gives PG_ERR_SHADER with a message (never a read out of bounds),
 * a module over one of the fixed limits below gives PG_ERR_LIMIT naming the limit.
 */
#ifndef PG_SPIRV_REFLECT_H
#define PG_SPIRV_REFLECT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pg_spv_kind {
    PG_SPV_COMBINED_IMAGE_SAMPLER, /* sampler2D etc. */
    PG_SPV_SAMPLED_IMAGE,          /* texture2D (separate), textureBuffer (dim 5) */
    PG_SPV_SAMPLER,                /* sampler */
    PG_SPV_STORAGE_IMAGE,          /* image2D, imageBuffer (dim 5) */
    PG_SPV_UNIFORM_BUFFER,         /* uniform block */
    PG_SPV_STORAGE_BUFFER,         /* buffer block (StorageBuffer class, or Uniform class + BufferBlock) */
    PG_SPV_INPUT_ATTACHMENT,       /* subpassInput (image of dim SubpassData) */
    PG_SPV_ACCELERATION_STRUCTURE, /* accelerationStructureEXT */
} pg_spv_kind;
/* "combined image sampler", "sampled image", "sampler", "storage image", "uniform buffer",
 * "storage buffer", "input attachment", "acceleration structure"; "?" for another value. */
const char *pg_spv_kind_name(pg_spv_kind k);
/* The GLSL layout qualifier of a SpvImageFormat value: 0 "unknown", 1 "rgba32f", 2 "rgba16f",
 * 3 "r32f", 4 "rgba8", 5 "rgba8_snorm", ... 30 "rgba32ui", ... 39 "r8ui", 40 "r64ui", 41 "r64i";
 * "?" past the table. */
const char *pg_spv_image_format_name(uint32_t fmt);

typedef enum pg_spv_scalar { PG_SPV_FLOAT, PG_SPV_INT, PG_SPV_UINT, PG_SPV_BOOL, PG_SPV_OTHER } pg_spv_scalar;

typedef struct pg_spv_binding {
    char name[64];         /* the variable's OpName; for an instance-less block the block type's name */
    char type_name[64];    /* the block's struct type name ("" for images) */
    uint32_t set, binding;
    pg_spv_kind kind;
    uint32_t dim;          /* SpvDim: 0 1D, 1 2D, 2 3D, 3 Cube, 4 Rect, 5 Buffer, 6 SubpassData (images only) */
    bool depth;            /* a depth image (Depth operand 1: GLSL's shadow samplers, sampler2DShadow) */
    bool arrayed, multisampled;
    uint32_t image_format; /* SpvImageFormat operand (0 Unknown, 1 Rgba32f, 2 Rgba16f, 3 R32f, 4 Rgba8, ...) */
    uint32_t array_size;   /* 1 for a non-array, N for [N] (the product for [N][M]), 0 for a runtime array */
    bool non_writable;     /* NonWritable on the variable, or on every member of its block (readonly) */
    bool non_readable;     /* NonReadable likewise (writeonly) */
    pg_spv_scalar sampled_type; /* images: the pg_spv_scalar of the texel components (float for sampler2D /
                            * image2D, uint for usampler2D / uimage2D, int for isampler2D / iimage2D) */
    uint32_t block_size;   /* bytes of a uniform/storage block's struct up to the end of its last member
                            * (a runtime array last counts 0 bytes: then the fixed part's size) */
} pg_spv_binding;

typedef struct pg_spv_member {
    char name[64];
    uint32_t offset, size;   /* bytes (an array: length * ArrayStride; a runtime array: 0) */
    pg_spv_scalar scalar;    /* of a scalar, vector or matrix member; PG_SPV_OTHER for structs/arrays */
    uint32_t components;     /* 1 scalar, 2..4 vector, columns*rows for a matrix; 0 for structs/arrays */
    uint32_t array_size;     /* 1 non-array, N for [N] (the product for [N][M]), 0 for a runtime array */
    uint32_t bits;           /* push-constant members: the scalar's width (16, 32, 64; 0 for structs/arrays) */
} pg_spv_member;

#define PG_SPV_MAX_BINDINGS 32
#define PG_SPV_MAX_MEMBERS 24
#define PG_SPV_MAX_OUTPUTS 8
typedef struct pg_spv_output {
    char name[64];
    uint32_t location;
    uint32_t components;     /* 1..4 */
    pg_spv_scalar scalar;
} pg_spv_output;

typedef struct pg_spv_reflection {
    uint32_t version;           /* the module's SPIR-V version, e.g. 0x10600 for 1.6 */
    uint32_t execution_model;   /* SpvExecutionModel of the first OpEntryPoint: 0 Vertex, 4 Fragment, 5 GLCompute */
    char entry_point[64];       /* its name, e.g. "main" */
    uint32_t local_size[3];     /* compute: LocalSize, or LocalSizeId resolved through OpConstant /
                                 * OpSpecConstant (its default); a WorkgroupSize built-in constant takes
                                 * precedence (SPIR-V < 1.6). 0 0 0 when the module has none. */
    uint32_t shared_bytes;      /* compute: bytes of its Workgroup (shared) variables, each the sum of its
                                 * scalars without padding (bool 4): a lower bound of any layout */
    uint32_t n_bindings;
    pg_spv_binding bindings[PG_SPV_MAX_BINDINGS]; /* sorted by (set, binding) */
    bool has_push;
    char push_name[64];         /* the push-constant block's type name */
    uint32_t push_size;         /* bytes to the end of its last member */
    uint32_t n_push;
    pg_spv_member push[PG_SPV_MAX_MEMBERS];
    uint32_t n_outputs;         /* Output-class variables with a Location (fragment outputs), sorted by location */
    pg_spv_output outputs[PG_SPV_MAX_OUTPUTS];
} pg_spv_reflection;

/* Reads the interface of one SPIR-V module (words as glslang emits them, host endianness). Every
 * module-scope OpVariable of storage class UniformConstant, Uniform, StorageBuffer, PushConstant
 * or Output is part of the interface (glslang removes declared but unused globals). Built-in
 * outputs (BuiltIn, gl_PerVertex) and outputs without a Location are left out. Limits exceeded
 * -> PG_ERR_LIMIT naming the limit (also a name longer than 63 bytes). Not a SPIR-V module
 * (magic), truncated or malformed -> PG_ERR_SHADER; words or out NULL -> PG_ERR_INVALID_ARG. err may
 * be NULL. *out is cleared first, and again on an error. */
pg_result pg_spirv_reflect(const uint32_t *words, size_t n_words, pg_spv_reflection *out, pg_error *err);
/* The binding of that set and binding number (the first when several alias it), or NULL. */
const pg_spv_binding *pg_spv_find_binding(const pg_spv_reflection *r, uint32_t set, uint32_t binding);
/* The binding whose name (or type name) is `name`, or NULL. */
const pg_spv_binding *pg_spv_find_name(const pg_spv_reflection *r, const char *name);

#ifdef __cplusplus
}
#endif
#endif
