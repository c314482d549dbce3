/* test_spirv_reflect.c - the SPIR-V reflection reader (core/vk/spirv_reflect.c) on modules that
 * glslang makes from small generated GLSL shaders (SPIR-V 1.6, as pg_shader_compile_ex compiles)
 * and on modules assembled word by word here (the SPIR-V 1.0 forms glslang no longer emits for
 * 1.6: LocalSize, a WorkgroupSize built-in, a Uniform-class BufferBlock). No GPU.
 *
 * Checked against exact numbers: every binding's set, binding, kind, dimension, image format,
 * arrayed / multisampled, readonly / writeonly, array size and block size; instance-less and
 * named blocks; the push-constant members' offsets, sizes, scalar types and component counts;
 * fragment outputs with their locations (built-ins and gl_PerVertex left out); the workgroup
 * size in the LocalSizeId (1.6), spec-constant and LocalSize / WorkgroupSize forms; the limits
 * (bindings, push members, name length) as PG_ERR_LIMIT. Robustness: NULL and short input, bad
 * and byte-swapped magic, every prefix of a valid module, and thousands of copies with random
 * words changed (a fixed seed) give an error with a message or a result, never a crash or a read
 * out of bounds (each input is a heap block of its exact size, so ASan sees any overread).
 */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "shader.h"
#include "spirv_reflect.h"
#include "test_util.h"

/* Compiles generated GLSL text (no file) for stage. NULL on failure (a failed CHECK). */
static uint32_t *compile(const char *name, const char *text, VkShaderStageFlagBits stage, size_t *n)
{
    pg_shader_source src = {name, text};
    uint32_t *spv = NULL;
    pg_error err = {0};
    pg_result r = pg_shader_compile_ex(name, stage, NULL, 0, &src, 1, &spv, n, &err);
    CHECK_MSG(r == PG_OK, "%s: %s", name, err.msg);
    return r == PG_OK ? spv : NULL;
}

/* Reflects words, expecting success. */
static bool reflect_ok(const char *what, const uint32_t *w, size_t n, pg_spv_reflection *out)
{
    pg_error err = {0};
    pg_result r = pg_spirv_reflect(w, n, out, &err);
    CHECK_MSG(r == PG_OK, "%s: %s %s", what, pg_result_name(r), err.msg);
    return r == PG_OK;
}

/* Whether an instruction with this opcode is in the module. */
static bool has_opcode(const uint32_t *w, size_t n, uint32_t op)
{
    for (size_t i = 5; i < n && (w[i] >> 16); i += w[i] >> 16)
        if ((w[i] & 0xffffu) == op) return true;
    return false;
}

static void check_binding(const pg_spv_reflection *r, uint32_t set, uint32_t binding, const char *name,
                          const char *type_name, pg_spv_kind kind, uint32_t array_size, bool nw, bool nr)
{
    const pg_spv_binding *b = pg_spv_find_binding(r, set, binding);
    CHECK_MSG(b != NULL, "no binding %u.%u (%s)", set, binding, name);
    if (!b) return;
    CHECK_MSG(!strcmp(b->name, name), "%u.%u: name \"%s\", want \"%s\"", set, binding, b->name, name);
    CHECK_MSG(!strcmp(b->type_name, type_name), "%s: type name \"%s\", want \"%s\"", name, b->type_name, type_name);
    CHECK_MSG(b->kind == kind, "%s: kind %s, want %s", name, pg_spv_kind_name(b->kind), pg_spv_kind_name(kind));
    CHECK_MSG(b->array_size == array_size, "%s: array size %u, want %u", name, b->array_size, array_size);
    CHECK_MSG(b->non_writable == nw, "%s: non_writable %d, want %d", name, b->non_writable, nw);
    CHECK_MSG(b->non_readable == nr, "%s: non_readable %d, want %d", name, b->non_readable, nr);
    CHECK_MSG(pg_spv_find_name(r, name) == b, "%s: find_name gives another binding", name);
}

static void check_image(const pg_spv_reflection *r, uint32_t set, uint32_t binding, uint32_t dim, bool arrayed,
                        bool ms, uint32_t format)
{
    const pg_spv_binding *b = pg_spv_find_binding(r, set, binding);
    if (!b) return;
    CHECK_MSG(b->dim == dim && b->arrayed == arrayed && b->multisampled == ms, "%s: dim %u arrayed %d ms %d, want %u %d %d",
              b->name, b->dim, b->arrayed, b->multisampled, dim, arrayed, ms);
    CHECK_MSG(b->image_format == format, "%s: format %u (%s), want %u (%s)", b->name, b->image_format,
              pg_spv_image_format_name(b->image_format), format, pg_spv_image_format_name(format));
}

static void check_member(const pg_spv_reflection *r, uint32_t k, const char *name, uint32_t offset, uint32_t size,
                         pg_spv_scalar scalar, uint32_t components, uint32_t array_size)
{
    if (k >= r->n_push) {
        CHECK_MSG(k < r->n_push, "push member %u (%s) missing: %u members", k, name, r->n_push);
        return;
    }
    const pg_spv_member *m = &r->push[k];
    CHECK_MSG(!strcmp(m->name, name), "push member %u: name \"%s\", want \"%s\"", k, m->name, name);
    CHECK_MSG(m->offset == offset && m->size == size, "push %s: offset %u size %u, want %u %u", name, m->offset,
              m->size, offset, size);
    CHECK_MSG(m->scalar == scalar && m->components == components && m->array_size == array_size,
              "push %s: scalar %d x %u [%u], want %d x %u [%u]", name, m->scalar, m->components, m->array_size, scalar,
              components, array_size);
}

static const char *const COMPUTE_SRC =
    "#version 460\n"
    "#extension GL_EXT_nonuniform_qualifier : require\n"
    "layout(local_size_x = 16, local_size_y = 8, local_size_z = 2) in;\n"
    "layout(set = 0, binding = 0) uniform sampler2D tex_in;\n"
    "layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D img_out;\n"
    "layout(set = 0, binding = 2, r32ui) uniform readonly uimage3D counts;\n"
    "layout(set = 0, binding = 3) uniform texture2DArray layers[4];\n"
    "layout(set = 0, binding = 4) uniform sampler samp;\n"
    "layout(set = 1, binding = 0, std140) uniform Params { mat4 view; vec3 tint; float gain; };\n"
    "layout(set = 1, binding = 1, std430) readonly buffer Lights { uint count; vec4 data[]; } lights;\n"
    "layout(set = 1, binding = 2, std430) buffer Out { float total; vec2 pair[3]; } result;\n"
    "layout(set = 2, binding = 5) uniform sampler2DMS ms_tex;\n"
    "layout(set = 2, binding = 1, std430) writeonly buffer W { vec4 w[]; } wo;\n"
    "layout(set = 2, binding = 0, rgba8) uniform image2D rw_img[];\n"
    "layout(push_constant) uniform Push {\n"
    "    float f; vec2 g; vec4 h; int i; uint u; mat4 m; float k[2]; layout(row_major) mat4x3 rm;\n"
    "} pc;\n"
    "void main() {\n"
    "    ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n"
    "    vec4 c = texture(tex_in, vec2(p) * pc.f) + texture(sampler2DArray(layers[2], samp), vec3(pc.g, 1.0));\n"
    "    c += texelFetch(ms_tex, p, 1) * gain + view * vec4(tint, 1.0) + pc.h + pc.m[0] + pc.k[1];\n"
    "    c += vec4(float(pc.i), float(pc.u), 0.0, 0.0) + imageLoad(rw_img[nonuniformEXT(pc.i)], p);\n"
    "    uint n = imageLoad(counts, ivec3(p, 0)).x + lights.count;\n"
    "    c += lights.data[n];\n"
    "    c.xyz += pc.rm * c;\n"
    "    result.total = c.x;\n"
    "    result.pair[1] = c.yz;\n"
    "    wo.w[n] = c;\n"
    "    imageStore(img_out, p, c);\n"
    "}\n";

static void check_compute_bindings(const pg_spv_reflection *r)
{
    CHECK_MSG(r->n_bindings == 11, "%u bindings, want 11", r->n_bindings);
    static const uint32_t order[][2] = {{0, 0}, {0, 1}, {0, 2}, {0, 3}, {0, 4}, {1, 0},
                                        {1, 1}, {1, 2}, {2, 0}, {2, 1}, {2, 5}};
    for (uint32_t i = 0; i < 11 && i < r->n_bindings; i++)
        CHECK_MSG(r->bindings[i].set == order[i][0] && r->bindings[i].binding == order[i][1],
                  "bindings[%u] is %u.%u, want %u.%u (sorted)", i, r->bindings[i].set, r->bindings[i].binding,
                  order[i][0], order[i][1]);
    check_binding(r, 0, 0, "tex_in", "", PG_SPV_COMBINED_IMAGE_SAMPLER, 1, false, false);
    check_image(r, 0, 0, 1, false, false, 0);
    check_binding(r, 0, 1, "img_out", "", PG_SPV_STORAGE_IMAGE, 1, false, true);
    check_image(r, 0, 1, 1, false, false, 2);
    check_binding(r, 0, 2, "counts", "", PG_SPV_STORAGE_IMAGE, 1, true, false);
    check_image(r, 0, 2, 2, false, false, 33);
    check_binding(r, 0, 3, "layers", "", PG_SPV_SAMPLED_IMAGE, 4, false, false);
    check_image(r, 0, 3, 1, true, false, 0);
    check_binding(r, 0, 4, "samp", "", PG_SPV_SAMPLER, 1, false, false);
    check_binding(r, 1, 0, "Params", "Params", PG_SPV_UNIFORM_BUFFER, 1, false, false);
    check_binding(r, 1, 1, "lights", "Lights", PG_SPV_STORAGE_BUFFER, 1, true, false);
    check_binding(r, 1, 2, "result", "Out", PG_SPV_STORAGE_BUFFER, 1, false, false);
    check_binding(r, 2, 0, "rw_img", "", PG_SPV_STORAGE_IMAGE, 0, false, false);
    check_image(r, 2, 0, 1, false, false, 4);
    check_binding(r, 2, 1, "wo", "W", PG_SPV_STORAGE_BUFFER, 1, false, true);
    check_binding(r, 2, 5, "ms_tex", "", PG_SPV_COMBINED_IMAGE_SAMPLER, 1, false, false);
    check_image(r, 2, 5, 1, false, true, 0);
    /* std140 Params: mat4 at 0 (64), vec3 at 64 (12), float at 76 -> 80; std430 Lights: uint at 0,
     * vec4[] at 16 -> 16; Out: float at 0, vec2[3] at 8 (stride 8) -> 32; W: vec4[] at 0 -> 0 */
    const uint32_t sizes[][3] = {{1, 0, 80}, {1, 1, 16}, {1, 2, 32}, {2, 1, 0}};
    for (int i = 0; i < 4; i++) {
        const pg_spv_binding *b = pg_spv_find_binding(r, sizes[i][0], sizes[i][1]);
        CHECK_MSG(b && b->block_size == sizes[i][2], "%u.%u: block size %u, want %u", sizes[i][0], sizes[i][1],
                  b ? b->block_size : 0, sizes[i][2]);
    }
    CHECK(pg_spv_find_name(r, "Lights") == pg_spv_find_binding(r, 1, 1));
    /* the texel type: float (sampler2D, image2D rgba16f), uint (uimage3D r32ui) */
    const pg_spv_binding *t0 = pg_spv_find_binding(r, 0, 0), *t1 = pg_spv_find_binding(r, 0, 1),
                         *t2 = pg_spv_find_binding(r, 0, 2);
    CHECK_MSG(t0 && t1 && t2 && t0->sampled_type == PG_SPV_FLOAT && t1->sampled_type == PG_SPV_FLOAT &&
                  t2->sampled_type == PG_SPV_UINT,
              "sampled types %d %d %d, want float float uint", t0 ? (int)t0->sampled_type : -1,
              t1 ? (int)t1->sampled_type : -1, t2 ? (int)t2->sampled_type : -1);
    CHECK(pg_spv_find_name(r, "nothing") == NULL);
    CHECK(pg_spv_find_binding(r, 0, 9) == NULL);
    CHECK(pg_spv_find_binding(r, 3, 0) == NULL);
}

static void test_compute(void)
{
    size_t n = 0;
    uint32_t *w = compile("reflect_test.comp", COMPUTE_SRC, VK_SHADER_STAGE_COMPUTE_BIT, &n);
    pg_spv_reflection r;
    if (!w || !reflect_ok("compute", w, n, &r)) {
        free(w);
        return;
    }
    CHECK_MSG(has_opcode(w, n, 331), "glslang's SPIR-V 1.6 module has no OpExecutionModeId (LocalSizeId)");
    CHECK_MSG(r.version == 0x10600, "version 0x%x, want 0x10600", r.version);
    CHECK_MSG(r.execution_model == 5, "execution model %u, want 5 (GLCompute)", r.execution_model);
    CHECK_MSG(!strcmp(r.entry_point, "main"), "entry point \"%s\"", r.entry_point);
    CHECK_MSG(r.local_size[0] == 16 && r.local_size[1] == 8 && r.local_size[2] == 2, "local size %u %u %u, want 16 8 2",
              r.local_size[0], r.local_size[1], r.local_size[2]);
    check_compute_bindings(&r);
    CHECK(r.has_push);
    CHECK_MSG(!strcmp(r.push_name, "Push"), "push name \"%s\"", r.push_name);
    /* push constants are std430: f 0, g 8, h 16, i 32, u 36, m 48 (64 bytes), k[2] 112 (stride 4),
     * row-major mat4x3 at 128: 3 rows of stride 16 (48 bytes; column-major it would be 64) */
    CHECK_MSG(r.n_push == 8, "%u push members, want 8", r.n_push);
    check_member(&r, 0, "f", 0, 4, PG_SPV_FLOAT, 1, 1);
    check_member(&r, 1, "g", 8, 8, PG_SPV_FLOAT, 2, 1);
    check_member(&r, 2, "h", 16, 16, PG_SPV_FLOAT, 4, 1);
    check_member(&r, 3, "i", 32, 4, PG_SPV_INT, 1, 1);
    check_member(&r, 4, "u", 36, 4, PG_SPV_UINT, 1, 1);
    check_member(&r, 5, "m", 48, 64, PG_SPV_FLOAT, 16, 1);
    check_member(&r, 6, "k", 112, 8, PG_SPV_OTHER, 0, 2);
    check_member(&r, 7, "rm", 128, 48, PG_SPV_FLOAT, 12, 1);
    CHECK_MSG(r.push_size == 176, "push size %u, want 176", r.push_size);
    CHECK_MSG(r.n_outputs == 0, "%u outputs in a compute shader", r.n_outputs);
    free(w);
}

static const char *const FRAGMENT_SRC =
    "#version 460\n"
    "layout(location = 0) in vec2 uv;\n"
    "layout(location = 0) out vec4 color;\n"
    "layout(location = 2) out uvec2 ids;\n"
    "layout(location = 1) out float weight;\n"
    "layout(location = 3) out ivec3 cell;\n"
    "layout(set = 0, binding = 0) uniform sampler2D tex;\n"
    "layout(set = 0, binding = 1) uniform textureCube env;\n"
    "layout(set = 0, binding = 2) uniform sampler samp;\n"
    "layout(set = 0, binding = 3, std140) uniform Frame { vec4 tint; mat3 rot; float exposure[3]; } frame;\n"
    "layout(set = 1, binding = 0) uniform sampler2D many[3][2];\n"
    "layout(push_constant) uniform P { layout(offset = 16) vec2 scale; } p;\n"
    "void main() {\n"
    "    color = texture(tex, uv * p.scale) * frame.tint * frame.exposure[2] + texture(many[2][1], uv);\n"
    "    color += texture(samplerCube(env, samp), frame.rot * vec3(uv, 1.0));\n"
    "    ids = uvec2(3u, 4u);\n"
    "    weight = 0.5;\n"
    "    cell = ivec3(1, 2, 3);\n"
    "    gl_FragDepth = 0.25;\n"
    "}\n";

static void test_fragment(void)
{
    size_t n = 0;
    uint32_t *w = compile("reflect_test.frag", FRAGMENT_SRC, VK_SHADER_STAGE_FRAGMENT_BIT, &n);
    pg_spv_reflection r;
    if (!w || !reflect_ok("fragment", w, n, &r)) {
        free(w);
        return;
    }
    CHECK_MSG(r.execution_model == 4, "execution model %u, want 4 (Fragment)", r.execution_model);
    CHECK_MSG(r.local_size[0] == 0 && r.local_size[1] == 0 && r.local_size[2] == 0, "local size in a fragment shader");
    CHECK_MSG(r.n_outputs == 4, "%u outputs, want 4 (gl_FragDepth left out)", r.n_outputs);
    static const struct { const char *name; uint32_t loc, comps; pg_spv_scalar s; } want[] = {
        {"color", 0, 4, PG_SPV_FLOAT},
        {"weight", 1, 1, PG_SPV_FLOAT},
        {"ids", 2, 2, PG_SPV_UINT},
        {"cell", 3, 3, PG_SPV_INT},
    };
    for (uint32_t i = 0; i < 4 && i < r.n_outputs; i++)
        CHECK_MSG(!strcmp(r.outputs[i].name, want[i].name) && r.outputs[i].location == want[i].loc &&
                      r.outputs[i].components == want[i].comps && r.outputs[i].scalar == want[i].s,
                  "output %u: %s at %u, %u x %d; want %s at %u, %u x %d", i, r.outputs[i].name, r.outputs[i].location,
                  r.outputs[i].components, r.outputs[i].scalar, want[i].name, want[i].loc, want[i].comps, want[i].s);
    CHECK_MSG(r.n_bindings == 5, "%u bindings, want 5", r.n_bindings);
    check_binding(&r, 0, 0, "tex", "", PG_SPV_COMBINED_IMAGE_SAMPLER, 1, false, false);
    check_binding(&r, 0, 1, "env", "", PG_SPV_SAMPLED_IMAGE, 1, false, false);
    check_image(&r, 0, 1, 3, false, false, 0);
    check_binding(&r, 0, 2, "samp", "", PG_SPV_SAMPLER, 1, false, false);
    check_binding(&r, 0, 3, "frame", "Frame", PG_SPV_UNIFORM_BUFFER, 1, false, false);
    check_binding(&r, 1, 0, "many", "", PG_SPV_COMBINED_IMAGE_SAMPLER, 6, false, false);
    CHECK(pg_spv_find_name(&r, "Frame") == pg_spv_find_binding(&r, 0, 3));
    /* std140: tint 0 (16), mat3 at 16: 3 columns of stride 16 (48), float[3] at 64 with stride 16 -> 112 */
    const pg_spv_binding *f = pg_spv_find_binding(&r, 0, 3);
    CHECK_MSG(f && f->block_size == 112, "Frame: block size %u, want 112", f ? f->block_size : 0);
    CHECK(r.has_push && !strcmp(r.push_name, "P") && r.n_push == 1);
    check_member(&r, 0, "scale", 16, 8, PG_SPV_FLOAT, 2, 1);
    CHECK_MSG(r.push_size == 24, "push size %u, want 24", r.push_size);
    free(w);
}

/* A vertex shader: gl_PerVertex (gl_Position) is no output; a located one is. */
static void test_vertex(void)
{
    const char *src = "#version 460\n"
                      "layout(location = 0) in vec3 pos;\n"
                      "layout(location = 1) out vec2 uv_out;\n"
                      "void main() { gl_Position = vec4(pos, 1.0); gl_PointSize = 1.0; uv_out = pos.xy; }\n";
    size_t n = 0;
    uint32_t *w = compile("reflect_test.vert", src, VK_SHADER_STAGE_VERTEX_BIT, &n);
    pg_spv_reflection r;
    if (w && reflect_ok("vertex", w, n, &r)) {
        CHECK_MSG(r.execution_model == 0, "execution model %u, want 0 (Vertex)", r.execution_model);
        CHECK_MSG(r.n_outputs == 1 && !strcmp(r.outputs[0].name, "uv_out") && r.outputs[0].location == 1 &&
                      r.outputs[0].components == 2,
                  "%u outputs (first %s)", r.n_outputs, r.n_outputs ? r.outputs[0].name : "-");
        CHECK(r.n_bindings == 0 && !r.has_push);
    }
    free(w);
}

/* local_size_x_id: LocalSizeId on an OpSpecConstant whose default is the local_size_x value. */
static void test_spec_local_size(void)
{
    const char *src = "#version 460\n"
                      "layout(local_size_x_id = 3, local_size_x = 32, local_size_y = 4) in;\n"
                      "layout(set = 0, binding = 0, std430) buffer B { uint v[]; } b;\n"
                      "void main() { b.v[gl_GlobalInvocationID.x] = gl_WorkGroupSize.x; }\n";
    size_t n = 0;
    uint32_t *w = compile("reflect_spec.comp", src, VK_SHADER_STAGE_COMPUTE_BIT, &n);
    pg_spv_reflection r;
    if (w && reflect_ok("spec local size", w, n, &r)) {
        CHECK_MSG(r.local_size[0] == 32 && r.local_size[1] == 4 && r.local_size[2] == 1,
                  "local size %u %u %u, want 32 4 1", r.local_size[0], r.local_size[1], r.local_size[2]);
        const pg_spv_binding *b = pg_spv_find_name(&r, "b");
        CHECK(b && b->kind == PG_SPV_STORAGE_BUFFER && b->block_size == 0 && !b->non_writable);
    }
    free(w);
}

/* ---- modules assembled here ---- */
typedef struct asm_buf {
    uint32_t w[512];
    size_t n;
} asm_buf;

static void inst(asm_buf *a, uint32_t opcode, const uint32_t *ops, uint32_t n_ops)
{
    a->w[a->n++] = (n_ops + 1) << 16 | opcode;
    for (uint32_t i = 0; i < n_ops; i++) a->w[a->n++] = ops[i];
}
#define INST(a, opcode, ...)                                    \
    do {                                                        \
        const uint32_t o_[] = {__VA_ARGS__};                    \
        inst(a, opcode, o_, (uint32_t)(sizeof o_ / sizeof o_[0])); \
    } while (0)

/* An instruction of n_pre operand words and then a literal string. */
static void inst_str(asm_buf *a, uint32_t opcode, const uint32_t *pre, uint32_t n_pre, const char *s)
{
    uint32_t ops[40] = {0};
    memcpy(ops, pre, n_pre * sizeof *pre);
    size_t len = strlen(s) + 1;
    for (size_t i = 0; i < len; i++) ops[n_pre + i / 4] |= (uint32_t)(unsigned char)s[i] << (8 * (i % 4));
    inst(a, opcode, ops, n_pre + (uint32_t)((len + 3) / 4));
}

/* A SPIR-V 1.0 compute module: LocalSize 8 4 2 (OpExecutionMode), a Uniform-class BufferBlock
 * struct S { vec4 a; } (readonly member) at set 3, binding 7; with workgroup, a constant
 * composite (64, 1, 1) decorated BuiltIn WorkgroupSize; var_name is the variable's OpName. */
static void assemble(asm_buf *a, bool workgroup, const char *var_name, bool buffer_block)
{
    a->n = 0;
    const uint32_t header[] = {0x07230203u, 0x00010000u, 0, 16, 0};
    memcpy(a->w, header, sizeof header);
    a->n = 5;
    INST(a, 17, 1);    /* OpCapability Shader */
    INST(a, 14, 0, 1); /* OpMemoryModel Logical GLSL450 */
    inst_str(a, 15, (const uint32_t[]){5, 8}, 2, "main");
    INST(a, 16, 8, 17, 8, 4, 2); /* OpExecutionMode %8 LocalSize 8 4 2 */
    inst_str(a, 5, (const uint32_t[]){7}, 1, var_name);
    inst_str(a, 5, (const uint32_t[]){5}, 1, "S");
    inst_str(a, 6, (const uint32_t[]){5, 0}, 2, "a");
    INST(a, 71, 5, buffer_block ? 3 : 2); /* BufferBlock (or Block) */
    INST(a, 72, 5, 0, 35, 0);             /* Offset 0 */
    INST(a, 72, 5, 0, 24);                /* NonWritable */
    INST(a, 71, 7, 34, 3);                /* DescriptorSet 3 */
    INST(a, 71, 7, 33, 7);                /* Binding 7 */
    if (workgroup) INST(a, 71, 15, 11, 25); /* BuiltIn WorkgroupSize */
    INST(a, 19, 1);                       /* void */
    INST(a, 33, 2, 1);                    /* function type */
    INST(a, 22, 3, 32);                   /* float */
    INST(a, 23, 4, 3, 4);                 /* vec4 */
    INST(a, 30, 5, 4);                    /* struct S { vec4 } */
    INST(a, 32, 6, 2, 5);                 /* pointer Uniform S */
    INST(a, 59, 6, 7, 2);                 /* variable */
    INST(a, 21, 10, 32, 0);               /* uint */
    INST(a, 43, 10, 11, 64);
    INST(a, 43, 10, 12, 1);
    INST(a, 43, 10, 13, 2);
    INST(a, 23, 14, 10, 3);               /* uvec3 */
    INST(a, 44, 14, 15, 11, 12, 12);      /* (64, 1, 1) */
    INST(a, 54, 1, 8, 0, 2);              /* OpFunction */
    INST(a, 248, 9);                      /* OpLabel */
    INST(a, 253);                         /* OpReturn */
    INST(a, 56);                          /* OpFunctionEnd */
}

static void test_assembled(void)
{
    asm_buf a;
    pg_spv_reflection r;
    pg_error err = {0};
    assemble(&a, false, "buf", true);
    if (reflect_ok("assembled", a.w, a.n, &r)) {
        CHECK_MSG(r.version == 0x10000 && r.execution_model == 5, "version 0x%x model %u", r.version, r.execution_model);
        CHECK_MSG(r.local_size[0] == 8 && r.local_size[1] == 4 && r.local_size[2] == 2, "LocalSize %u %u %u, want 8 4 2",
                  r.local_size[0], r.local_size[1], r.local_size[2]);
        CHECK(r.n_bindings == 1);
        check_binding(&r, 3, 7, "buf", "S", PG_SPV_STORAGE_BUFFER, 1, true, false);
        CHECK(r.n_bindings == 1 && r.bindings[0].block_size == 16);
    }
    assemble(&a, true, "buf", true);
    if (reflect_ok("assembled with WorkgroupSize", a.w, a.n, &r))
        CHECK_MSG(r.local_size[0] == 64 && r.local_size[1] == 1 && r.local_size[2] == 1,
                  "WorkgroupSize %u %u %u, want 64 1 1", r.local_size[0], r.local_size[1], r.local_size[2]);
    assemble(&a, false, "", true); /* an instance-less block: the type's name */
    if (reflect_ok("assembled instance-less", a.w, a.n, &r))
        check_binding(&r, 3, 7, "S", "S", PG_SPV_STORAGE_BUFFER, 1, true, false);
    assemble(&a, false, "buf", false); /* Block in the Uniform class: a uniform buffer */
    if (reflect_ok("assembled Block", a.w, a.n, &r))
        check_binding(&r, 3, 7, "buf", "S", PG_SPV_UNIFORM_BUFFER, 1, true, false);
    /* a name of 65 bytes: over the limit */
    assemble(&a, false, "a_name_of_sixty_four_bytes_is_one_more_than_the_63_the_reader_has", true);
    pg_result res = pg_spirv_reflect(a.w, a.n, &r, &err);
    CHECK_MSG(res == PG_ERR_LIMIT && strstr(err.msg, "63"), "long name: %s %s", pg_result_name(res), err.msg);
    /* a bound far past anything real */
    assemble(&a, false, "buf", true);
    a.w[3] = 0xfffffff0u;
    res = pg_spirv_reflect(a.w, a.n, &r, &err);
    CHECK_MSG(res == PG_ERR_SHADER && strstr(err.msg, "bound"), "huge bound: %s %s", pg_result_name(res), err.msg);
    /* the struct's member type made the struct itself */
    assemble(&a, false, "buf", true);
    for (size_t i = 5; i < a.n; i += a.w[i] >> 16)
        if (a.w[i] == (3u << 16 | 30u)) a.w[i + 2] = 5;
    res = pg_spirv_reflect(a.w, a.n, &r, &err);
    CHECK_MSG(res == PG_ERR_SHADER && strstr(err.msg, "itself"), "self-containing struct: %s %s", pg_result_name(res),
              err.msg);
}

/* More bindings or push members than the limits: PG_ERR_LIMIT naming the limit. */
static void test_limits(void)
{
    char src[8192];
    int len = snprintf(src, sizeof src, "#version 460\nlayout(local_size_x = 64) in;\n");
    for (int i = 0; i < 33; i++)
        len += snprintf(src + len, sizeof src - (size_t)len, "layout(set = 0, binding = %d) uniform sampler2D t%d;\n",
                        i, i);
    len += snprintf(src + len, sizeof src - (size_t)len,
                    "layout(set = 1, binding = 0) buffer O { vec4 o; };\nvoid main() {\n    o = vec4(0.0)");
    for (int i = 0; i < 33; i++)
        len += snprintf(src + len, sizeof src - (size_t)len, " + textureLod(t%d, vec2(0.5), 0.0)", i);
    snprintf(src + len, sizeof src - (size_t)len, ";\n}\n");
    size_t n = 0;
    uint32_t *w = compile("reflect_many.comp", src, VK_SHADER_STAGE_COMPUTE_BIT, &n);
    pg_spv_reflection r;
    pg_error err = {0};
    pg_result res = w ? pg_spirv_reflect(w, n, &r, &err) : PG_OK;
    CHECK_MSG(w && res == PG_ERR_LIMIT && strstr(err.msg, "PG_SPV_MAX_BINDINGS"), "34 bindings: %s %s",
              pg_result_name(res), err.msg);
    free(w);

    len = snprintf(src, sizeof src, "#version 460\nlayout(local_size_x = 64) in;\nlayout(push_constant) uniform P {");
    for (int i = 0; i < 25; i++) len += snprintf(src + len, sizeof src - (size_t)len, " float m%d;", i);
    len += snprintf(src + len, sizeof src - (size_t)len,
                    " } p;\nlayout(set = 0, binding = 0) buffer O { float o; };\nvoid main() {\n    o = 0.0");
    for (int i = 0; i < 25; i++) len += snprintf(src + len, sizeof src - (size_t)len, " + p.m%d", i);
    snprintf(src + len, sizeof src - (size_t)len, ";\n}\n");
    w = compile("reflect_push.comp", src, VK_SHADER_STAGE_COMPUTE_BIT, &n);
    res = w ? pg_spirv_reflect(w, n, &r, &err) : PG_OK;
    CHECK_MSG(w && res == PG_ERR_LIMIT && strstr(err.msg, "PG_SPV_MAX_MEMBERS"), "25 push members: %s %s",
              pg_result_name(res), err.msg);
    free(w);
}

static void test_names(void)
{
    CHECK(!strcmp(pg_spv_image_format_name(0), "unknown"));
    CHECK(!strcmp(pg_spv_image_format_name(1), "rgba32f"));
    CHECK(!strcmp(pg_spv_image_format_name(2), "rgba16f"));
    CHECK(!strcmp(pg_spv_image_format_name(3), "r32f"));
    CHECK(!strcmp(pg_spv_image_format_name(4), "rgba8"));
    CHECK(!strcmp(pg_spv_image_format_name(5), "rgba8_snorm"));
    CHECK(!strcmp(pg_spv_image_format_name(8), "r11f_g11f_b10f"));
    CHECK(!strcmp(pg_spv_image_format_name(11), "rgb10_a2"));
    CHECK(!strcmp(pg_spv_image_format_name(15), "r8"));
    CHECK(!strcmp(pg_spv_image_format_name(20), "r8_snorm"));
    CHECK(!strcmp(pg_spv_image_format_name(21), "rgba32i"));
    CHECK(!strcmp(pg_spv_image_format_name(29), "r8i"));
    CHECK(!strcmp(pg_spv_image_format_name(30), "rgba32ui"));
    CHECK(!strcmp(pg_spv_image_format_name(33), "r32ui"));
    CHECK(!strcmp(pg_spv_image_format_name(34), "rgb10_a2ui"));
    CHECK(!strcmp(pg_spv_image_format_name(39), "r8ui"));
    CHECK(!strcmp(pg_spv_image_format_name(1000), "?"));
    CHECK(!strcmp(pg_spv_kind_name(PG_SPV_COMBINED_IMAGE_SAMPLER), "combined image sampler"));
    CHECK(!strcmp(pg_spv_kind_name(PG_SPV_STORAGE_IMAGE), "storage image"));
    CHECK(!strcmp(pg_spv_kind_name(PG_SPV_STORAGE_BUFFER), "storage buffer"));
    CHECK(!strcmp(pg_spv_kind_name((pg_spv_kind)99), "?"));
}

/* ---- robustness ---- */
/* Reflects a heap copy of exactly n words (ASan sees an overread); an error must carry a message. */
static pg_result reflect_copy(const uint32_t *w, size_t n, pg_spv_reflection *r, pg_error *err)
{
    uint32_t *c = malloc(n ? n * sizeof *c : 1);
    if (!c) return PG_ERR_OOM;
    if (n) memcpy(c, w, n * sizeof *c);
    err->code = PG_OK;
    err->msg[0] = 0;
    pg_result res = pg_spirv_reflect(c, n, r, err);
    free(c);
    return res;
}

static bool sane(const pg_spv_reflection *r)
{
    bool ok = r->n_bindings <= PG_SPV_MAX_BINDINGS && r->n_push <= PG_SPV_MAX_MEMBERS && r->n_outputs <= PG_SPV_MAX_OUTPUTS;
    for (uint32_t i = 0; ok && i < r->n_bindings; i++)
        ok = memchr(r->bindings[i].name, 0, 64) && memchr(r->bindings[i].type_name, 0, 64);
    return ok && memchr(r->push_name, 0, 64) && memchr(r->entry_point, 0, 64);
}

static void test_bad_input(const uint32_t *w, size_t n)
{
    pg_spv_reflection r;
    pg_error err = {0};
    CHECK(pg_spirv_reflect(NULL, 10, &r, &err) == PG_ERR_INVALID_ARG && err.msg[0]);
    CHECK(pg_spirv_reflect(w, n, NULL, &err) == PG_ERR_INVALID_ARG);
    CHECK(pg_spirv_reflect(w, 0, &r, NULL) == PG_ERR_SHADER); /* err may be NULL */
    CHECK(reflect_copy(w, 4, &r, &err) == PG_ERR_SHADER && strstr(err.msg, "header"));
    uint32_t bad[8] = {0xdeadbeefu, 0x10600, 0, 10, 0, 0, 0, 0};
    CHECK(reflect_copy(bad, 8, &r, &err) == PG_ERR_SHADER && strstr(err.msg, "magic"));
    bad[0] = 0x03022307u;
    CHECK(reflect_copy(bad, 8, &r, &err) == PG_ERR_SHADER && strstr(err.msg, "byte order"));
    bad[0] = 0x07230203u; /* header and zero words: a word count of 0 */
    CHECK(reflect_copy(bad, 8, &r, &err) == PG_ERR_SHADER && strstr(err.msg, "word count of 0"));
    CHECK(reflect_copy(bad, 5, &r, &err) == PG_ERR_SHADER && strstr(err.msg, "OpEntryPoint"));
    /* every prefix: a cut inside an instruction is "truncated"; one between instructions is a shorter
     * module (an error or a result) */
    int cuts = 0, truncated = 0;
    size_t next = 5;
    for (size_t k = 0; k <= n; k++) {
        while (next < k && next < n) next += w[next] >> 16;
        pg_result res = reflect_copy(w, k, &r, &err);
        if (k > 5 && k < next) {
            cuts++;
            truncated += res == PG_ERR_SHADER && strstr(err.msg, "truncated") != NULL;
        }
        CHECK_MSG(res == PG_OK ? k == n || sane(&r) : err.msg[0] != 0, "prefix of %zu words: %s with no message", k,
                  pg_result_name(res));
    }
    CHECK_MSG(cuts > 0 && truncated == cuts, "%d of %d cuts inside an instruction reported as truncated", truncated,
              cuts);
    CHECK(reflect_copy(w, n, &r, &err) == PG_OK);
}

/* Copies of w with 1..4 words replaced (a random value, a flipped bit, a small number or a
 * changed word count), from a fixed seed. */
static void test_random_words(const uint32_t *w, size_t n, uint32_t trials)
{
    uint64_t s = 0x9e3779b97f4a7c15ull;
    uint32_t *c = malloc(n * sizeof *c);
    if (!c) return;
    int ok = 0, failed = 0, silent = 0;
    for (uint32_t t = 0; t < trials; t++) {
        memcpy(c, w, n * sizeof *c);
        uint32_t changes = 1 + (uint32_t)(s % 4);
        for (uint32_t k = 0; k < changes; k++) {
            s ^= s << 13, s ^= s >> 7, s ^= s << 17;
            size_t at = (size_t)(s % n);
            uint32_t v = (uint32_t)(s >> 32);
            switch ((s >> 20) % 4) {
            case 0: c[at] = v; break;
            case 1: c[at] ^= 1u << (v % 32); break;
            case 2: c[at] = v % 64; break;
            default: c[at] = (c[at] & 0xffffu) | (v % 12) << 16; break;
            }
        }
        pg_spv_reflection r;
        pg_error err = {0};
        pg_result res = reflect_copy(c, n, &r, &err);
        if (res == PG_OK) {
            ok++;
            if (!sane(&r)) silent++;
        } else {
            failed++;
            if (!err.msg[0] || (res != PG_ERR_SHADER && res != PG_ERR_LIMIT)) silent++;
        }
    }
    printf("random words: %u trials, %d read, %d refused\n", trials, ok, failed);
    CHECK_MSG(silent == 0, "%d trials gave an error without a message, another code or an insane result", silent);
    CHECK_MSG(failed > 0 && ok > 0, "%d read, %d refused: the changes should do both", ok, failed);
    free(c);
}

/* Shared memory (the sum of the Workgroup variables' scalars, bool 4 bytes, no padding) and the
 * Depth operand of a shadow sampler. */
static void test_shared_and_depth(void)
{
    static const char *const src =
        "#version 460\n"
        "layout(local_size_x = 64) in;\n"
        "struct S { vec3 a; float b; bool c; mat2 m; };\n" /* 12 + 4 + 4 + 16 = 36 bytes */
        "shared S items[4];\n"                              /* 144 */
        "shared uint counts[10];\n"                         /* 40 */
        "layout(set = 0, binding = 0) uniform sampler2DShadow shadow_map;\n"
        "layout(set = 0, binding = 1) uniform sampler2D plain;\n"
        "layout(set = 0, binding = 2, std430) buffer O { float o[]; };\n"
        "void main() {\n"
        "    uint i = gl_LocalInvocationIndex;\n"
        "    items[i % 4u].a = vec3(float(i)); items[i % 4u].b = 1.0; items[i % 4u].c = i > 3u;\n"
        "    items[i % 4u].m = mat2(float(i)); counts[i % 10u] = i;\n"
        "    barrier();\n"
        "    o[i] = texture(shadow_map, vec3(0.5)) + texture(plain, vec2(0.5)).x + items[1].a.y + items[2].b\n"
        "         + (items[3].c ? 1.0 : 0.0) + items[0].m[1][1] + float(counts[9]);\n"
        "}\n";
    size_t n = 0;
    uint32_t *w = compile("reflect_shared.comp", src, VK_SHADER_STAGE_COMPUTE_BIT, &n);
    pg_spv_reflection r;
    if (!w || !reflect_ok("shared", w, n, &r)) {
        free(w);
        return;
    }
    CHECK_MSG(r.shared_bytes == 184, "shared bytes %u, want 184", r.shared_bytes);
    const pg_spv_binding *sh = pg_spv_find_binding(&r, 0, 0), *pl = pg_spv_find_binding(&r, 0, 1);
    CHECK_MSG(sh && sh->depth && sh->dim == 1 && sh->kind == PG_SPV_COMBINED_IMAGE_SAMPLER, "shadow_map: not a 2D depth sampler");
    CHECK_MSG(pl && !pl->depth, "plain: a depth image");
    free(w);
    /* no shared variable: 0 */
    w = compile("reflect_test.comp", COMPUTE_SRC, VK_SHADER_STAGE_COMPUTE_BIT, &n);
    if (w && reflect_ok("compute", w, n, &r)) CHECK_MSG(r.shared_bytes == 0, "shared bytes %u, want 0", r.shared_bytes);
    free(w);
}

int main(void)
{
    test_shared_and_depth();
    test_names();
    test_compute();
    test_fragment();
    test_vertex();
    test_spec_local_size();
    test_assembled();
    test_limits();
    size_t n = 0;
    uint32_t *w = compile("reflect_test.comp", COMPUTE_SRC, VK_SHADER_STAGE_COMPUTE_BIT, &n);
    if (w) {
        test_bad_input(w, n);
        test_random_words(w, n, 4000);
        free(w);
    }
    asm_buf a;
    assemble(&a, true, "buf", true);
    test_random_words(a.w, a.n, 2000);
    return pg_test_finish("test_spirv_reflect");
}
