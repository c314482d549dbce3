/* spirv_reflect.c - the interface of a SPIR-V module read from its words (spirv_reflect.h).
 *
 * Written from the SPIR-V specification: a module is a 5-word header (magic 0x07230203, version,
 * generator, id bound, schema) and instructions, each starting with a word of (word count << 16 |
 * opcode). Two walks: the first checks every instruction's word count against the words left and
 * against the least that its opcode needs, then records where each id of interest is defined
 * (types, constants, variables), its OpName and OpDecorate values, and where the OpMemberName /
 * OpMemberDecorate instructions are; the second reads the entry point's execution modes and the
 * module-scope variables. Every operand that names an id is checked against the bound and the
 * opcode of its definition before it is followed, type chains are walked with a depth limit and
 * struct sizes are memoised (a struct that contains itself is an error), so garbage words give an
 * error message and never a read out of bounds or an endless walk.
 */
#include "spirv_reflect.h"

#include <stdlib.h>
#include <string.h>

/* ---- the numbers of the specification this reader uses (SPIR-V 1.6, section 3) ---- */
#define SPV_MAGIC 0x07230203u
#define SPV_MAGIC_SWAPPED 0x03022307u
#define SPV_HEADER_WORDS 5u

enum {
    OP_NAME = 5, OP_MEMBER_NAME = 6, OP_ENTRY_POINT = 15, OP_EXECUTION_MODE = 16,
    OP_TYPE_VOID = 19, OP_TYPE_BOOL = 20, OP_TYPE_INT = 21, OP_TYPE_FLOAT = 22, OP_TYPE_VECTOR = 23,
    OP_TYPE_MATRIX = 24, OP_TYPE_IMAGE = 25, OP_TYPE_SAMPLER = 26, OP_TYPE_SAMPLED_IMAGE = 27,
    OP_TYPE_ARRAY = 28, OP_TYPE_RUNTIME_ARRAY = 29, OP_TYPE_STRUCT = 30, OP_TYPE_POINTER = 32,
    OP_TYPE_FORWARD_POINTER = 39, OP_CONSTANT_TRUE = 41, OP_CONSTANT_FALSE = 42, OP_CONSTANT = 43,
    OP_CONSTANT_COMPOSITE = 44, OP_SPEC_CONSTANT = 50, OP_SPEC_CONSTANT_COMPOSITE = 51,
    OP_VARIABLE = 59, OP_DECORATE = 71, OP_MEMBER_DECORATE = 72, OP_EXECUTION_MODE_ID = 331,
    OP_TYPE_ACCELERATION_STRUCTURE = 5341,
};
enum {
    SC_UNIFORM_CONSTANT = 0, SC_UNIFORM = 2, SC_OUTPUT = 3, SC_WORKGROUP = 4, SC_PUSH_CONSTANT = 9,
    SC_STORAGE_BUFFER = 12,
};
enum {
    DEC_BLOCK = 2, DEC_BUFFER_BLOCK = 3, DEC_ROW_MAJOR = 4, DEC_ARRAY_STRIDE = 6, DEC_MATRIX_STRIDE = 7,
    DEC_BUILTIN = 11, DEC_NON_WRITABLE = 24, DEC_NON_READABLE = 25, DEC_LOCATION = 30, DEC_BINDING = 33,
    DEC_DESCRIPTOR_SET = 34, DEC_OFFSET = 35,
};
enum { MODE_LOCAL_SIZE = 17, MODE_LOCAL_SIZE_ID = 38, BUILTIN_WORKGROUP_SIZE = 25, DIM_SUBPASS_DATA = 6 };

/* ---- the reader's own limits ---- */
#define ID_BOUND_MAX (1u << 20) /* ids of a module (a large shader has a few thousand) */
#define TYPE_DEPTH_MAX 32       /* types nested in each other */
#define NAME_BYTES 64

/* flags of an id */
enum {
    F_SET = 1 << 0, F_BINDING = 1 << 1, F_LOCATION = 1 << 2, F_ARRAY_STRIDE = 1 << 3, F_BLOCK = 1 << 4,
    F_BUFFER_BLOCK = 1 << 5, F_NON_WRITABLE = 1 << 6, F_NON_READABLE = 1 << 7, F_BUILTIN = 1 << 8,
};
enum { MEMO_NONE, MEMO_BUSY, MEMO_DONE };

typedef struct spv_id {
    uint32_t def;  /* word index of the instruction defining the id (0: none recorded) */
    uint32_t name; /* word index of its OpName (0: none) */
    uint32_t set, binding, location, array_stride;
    uint32_t struct_size; /* memoised size of a struct type */
    uint16_t flags;
    uint8_t memo;
} spv_id;

/* what OpMemberDecorate says of one member of a struct */
enum { M_OFFSET = 1 << 0, M_ROW_MAJOR = 1 << 1, M_NON_WRITABLE = 1 << 2, M_NON_READABLE = 1 << 3, M_BUILTIN = 1 << 4 };
typedef struct spv_member_info {
    uint32_t offset, matrix_stride;
    uint32_t name; /* word index of its OpMemberName (0: none) */
    uint32_t flags;
} spv_member_info;

typedef struct spv_ctx {
    const uint32_t *w;
    size_t n;
    uint32_t bound;
    spv_id *ids;
    uint32_t *mdec; /* word indices of OpMemberName and OpMemberDecorate */
    uint32_t n_mdec;
    uint32_t entry;           /* word index of the first OpEntryPoint (0: none) */
    uint32_t workgroup_size;  /* id decorated BuiltIn WorkgroupSize (0: none) */
    pg_error *err;
} spv_ctx;

const char *pg_spv_kind_name(pg_spv_kind k)
{
    switch (k) {
    case PG_SPV_COMBINED_IMAGE_SAMPLER: return "combined image sampler";
    case PG_SPV_SAMPLED_IMAGE: return "sampled image";
    case PG_SPV_SAMPLER: return "sampler";
    case PG_SPV_STORAGE_IMAGE: return "storage image";
    case PG_SPV_UNIFORM_BUFFER: return "uniform buffer";
    case PG_SPV_STORAGE_BUFFER: return "storage buffer";
    case PG_SPV_INPUT_ATTACHMENT: return "input attachment";
    case PG_SPV_ACCELERATION_STRUCTURE: return "acceleration structure";
    }
    return "?";
}

const char *pg_spv_image_format_name(uint32_t fmt)
{
    /* the Image Format table (section 3.11) in its order, as GLSL layout qualifiers */
    static const char *const names[] = {
        "unknown", "rgba32f", "rgba16f", "r32f", "rgba8", "rgba8_snorm", "rg32f", "rg16f", "r11f_g11f_b10f",
        "r16f", "rgba16", "rgb10_a2", "rg16", "rg8", "r16", "r8", "rgba16_snorm", "rg16_snorm", "rg8_snorm",
        "r16_snorm", "r8_snorm", "rgba32i", "rgba16i", "rgba8i", "r32i", "rg32i", "rg16i", "rg8i", "r16i",
        "r8i", "rgba32ui", "rgba16ui", "rgba8ui", "r32ui", "rgb10_a2ui", "rg32ui", "rg16ui", "rg8ui", "r16ui",
        "r8ui", "r64ui", "r64i",
    };
    return fmt < sizeof names / sizeof names[0] ? names[fmt] : "?";
}

/* The least word count an instruction of opcode op needs for the operands this reader reads
 * without a further check (1 for opcodes it does not read). */
static uint32_t min_words(uint32_t op)
{
    switch (op) {
    case OP_NAME: return 3;
    case OP_MEMBER_NAME: return 4;
    case OP_ENTRY_POINT: return 4;
    case OP_EXECUTION_MODE: case OP_EXECUTION_MODE_ID: return 3;
    case OP_TYPE_VOID: case OP_TYPE_BOOL: case OP_TYPE_SAMPLER: case OP_TYPE_STRUCT: return 2;
    case OP_TYPE_ACCELERATION_STRUCTURE: return 2;
    case OP_TYPE_INT: case OP_TYPE_VECTOR: case OP_TYPE_MATRIX: case OP_TYPE_ARRAY: return 4;
    case OP_TYPE_FLOAT: case OP_TYPE_SAMPLED_IMAGE: case OP_TYPE_RUNTIME_ARRAY: return 3;
    case OP_TYPE_IMAGE: return 9;
    case OP_TYPE_POINTER: return 4;
    case OP_CONSTANT_TRUE: case OP_CONSTANT_FALSE: case OP_CONSTANT_COMPOSITE: return 3;
    case OP_SPEC_CONSTANT_COMPOSITE: return 3;
    case OP_CONSTANT: case OP_SPEC_CONSTANT: case OP_VARIABLE: return 4;
    case OP_DECORATE: return 3;
    case OP_MEMBER_DECORATE: return 4;
    default: return 1;
    }
}

/* Which word of an instruction of opcode op holds the id it defines: 1 for types, 2 for the
 * constants and variables; 0 for opcodes whose results this reader does not need. */
static uint32_t result_word(uint32_t op)
{
    if ((op >= OP_TYPE_VOID && op < OP_TYPE_FORWARD_POINTER) || op == OP_TYPE_ACCELERATION_STRUCTURE) return 1;
    if ((op >= OP_CONSTANT_TRUE && op <= OP_CONSTANT_COMPOSITE) || op == OP_SPEC_CONSTANT ||
        op == OP_SPEC_CONSTANT_COMPOSITE || op == OP_VARIABLE)
        return 2;
    return 0;
}

static uint32_t opcode_at(const spv_ctx *c, uint32_t at)
{
    return c->w[at] & 0xffffu;
}

static uint32_t words_at(const spv_ctx *c, uint32_t at)
{
    return c->w[at] >> 16;
}

static pg_result check_id(spv_ctx *c, uint32_t at, uint32_t id)
{
    if (id == 0 || id >= c->bound)
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V word %u (opcode %u): id %u outside the bound %u", at,
                       opcode_at(c, at), id, c->bound);
    return PG_OK;
}

/* The instruction defining id, if it has opcode op (any recorded opcode when op is 0), else NULL. */
static const uint32_t *def_of(const spv_ctx *c, uint32_t id, uint32_t op)
{
    if (id == 0 || id >= c->bound || !c->ids[id].def) return NULL;
    const uint32_t *d = c->w + c->ids[id].def;
    return op == 0 || (d[0] & 0xffffu) == op ? d : NULL;
}

/* Copies the literal string starting at word `first` of the instruction at word `at` (UTF-8, four
 * bytes a word, the first byte in the lowest bits, NUL-terminated) into dst[NAME_BYTES]. at == 0
 * gives "". */
static pg_result copy_string(spv_ctx *c, uint32_t at, uint32_t first, char *dst)
{
    dst[0] = 0;
    if (!at) return PG_OK;
    uint32_t len = words_at(c, at);
    size_t k = 0;
    for (uint32_t i = first; i < len; i++)
        for (int b = 0; b < 4; b++) {
            char ch = (char)((c->w[at + i] >> (8 * b)) & 0xffu);
            if (ch == 0) {
                dst[k] = 0;
                return PG_OK;
            }
            if (k + 1 >= NAME_BYTES) {
                dst[k] = 0;
                return pg_fail(c->err, PG_ERR_LIMIT, "SPIR-V name \"%s...\" is longer than %d bytes", dst,
                               NAME_BYTES - 1);
            }
            dst[k++] = ch;
        }
    dst[k] = 0;
    return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V word %u (opcode %u): string \"%s\" not terminated", at,
                   opcode_at(c, at), dst);
}

static pg_result id_name(spv_ctx *c, uint32_t id, char *dst)
{
    return copy_string(c, c->ids[id].name, 2, dst);
}

/* Records one OpDecorate of the first walk. */
static pg_result record_decoration(spv_ctx *c, uint32_t at)
{
    const uint32_t *d = c->w + at;
    uint32_t len = words_at(c, at), id = d[1], dec = d[2];
    pg_result r = check_id(c, at, id);
    if (r) return r;
    spv_id *e = &c->ids[id];
    bool valued = dec == DEC_ARRAY_STRIDE || dec == DEC_BUILTIN || dec == DEC_LOCATION || dec == DEC_BINDING ||
                  dec == DEC_DESCRIPTOR_SET;
    if (valued && len < 4)
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V word %u: decoration %u of id %u has no value", at, dec, id);
    switch (dec) {
    case DEC_BLOCK: e->flags |= F_BLOCK; break;
    case DEC_BUFFER_BLOCK: e->flags |= F_BUFFER_BLOCK; break;
    case DEC_NON_WRITABLE: e->flags |= F_NON_WRITABLE; break;
    case DEC_NON_READABLE: e->flags |= F_NON_READABLE; break;
    case DEC_ARRAY_STRIDE: e->flags |= F_ARRAY_STRIDE, e->array_stride = d[3]; break;
    case DEC_LOCATION: e->flags |= F_LOCATION, e->location = d[3]; break;
    case DEC_BINDING: e->flags |= F_BINDING, e->binding = d[3]; break;
    case DEC_DESCRIPTOR_SET: e->flags |= F_SET, e->set = d[3]; break;
    case DEC_BUILTIN:
        e->flags |= F_BUILTIN;
        if (d[3] == BUILTIN_WORKGROUP_SIZE) c->workgroup_size = id;
        break;
    default: break;
    }
    return PG_OK;
}

/* Records what the second walk and the type walks need of the instruction at word `at`. */
static pg_result record(spv_ctx *c, uint32_t at, uint32_t op)
{
    const uint32_t *d = c->w + at;
    pg_result r = PG_OK;
    uint32_t rw = result_word(op);
    if (rw) {
        if (words_at(c, at) <= rw)
            return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V word %u: opcode %u without its result id", at, op);
        if ((r = check_id(c, at, d[rw]))) return r;
        if (c->ids[d[rw]].def)
            return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V word %u: id %u defined twice (first at word %u)", at,
                           d[rw], c->ids[d[rw]].def);
        c->ids[d[rw]].def = at;
        return PG_OK;
    }
    switch (op) {
    case OP_NAME:
        if ((r = check_id(c, at, d[1]))) return r;
        c->ids[d[1]].name = at;
        break;
    case OP_MEMBER_NAME:
    case OP_MEMBER_DECORATE:
        if ((r = check_id(c, at, d[1]))) return r;
        c->mdec[c->n_mdec++] = at;
        break;
    case OP_ENTRY_POINT:
        if (!c->entry) c->entry = at;
        break;
    case OP_DECORATE: return record_decoration(c, at);
    default: break;
    }
    return PG_OK;
}

/* The header and the first walk over the instructions. */
static pg_result scan(spv_ctx *c)
{
    const uint32_t *w = c->w;
    if (c->n < SPV_HEADER_WORDS)
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V module of %zu words is shorter than its %u-word header",
                       c->n, SPV_HEADER_WORDS);
    if (w[0] == SPV_MAGIC_SWAPPED)
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V module in the other byte order (magic 0x%08x)", w[0]);
    if (w[0] != SPV_MAGIC)
        return pg_fail(c->err, PG_ERR_SHADER, "not a SPIR-V module (magic 0x%08x, expected 0x%08x)", w[0], SPV_MAGIC);
    if (c->n > UINT32_MAX) return pg_fail(c->err, PG_ERR_LIMIT, "SPIR-V module of %zu words is too long", c->n);
    c->bound = w[3];
    if (c->bound == 0 || c->bound > ID_BOUND_MAX)
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V id bound %u is not in 1..%u", c->bound, ID_BOUND_MAX);
    c->ids = calloc(c->bound, sizeof *c->ids);
    c->mdec = malloc((c->n / 4 + 1) * sizeof *c->mdec); /* each OpMember* has 4 words or more */
    if (!c->ids || !c->mdec) return pg_fail(c->err, PG_ERR_OOM, "out of memory reading a SPIR-V module");
    for (size_t i = SPV_HEADER_WORDS; i < c->n;) {
        uint32_t op = w[i] & 0xffffu, len = w[i] >> 16;
        if (len == 0)
            return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V word %zu: instruction (opcode %u) with a word count of 0",
                           i, op);
        if (len > c->n - i)
            return pg_fail(c->err, PG_ERR_SHADER,
                           "SPIR-V module truncated: the instruction at word %zu (opcode %u) has %u words, %zu are left",
                           i, op, len, c->n - i);
        if (len < min_words(op))
            return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V word %zu: opcode %u with %u words (needs %u)", i, op, len,
                           min_words(op));
        pg_result r = record(c, (uint32_t)i, op);
        if (r) return r;
        i += len;
    }
    if (!c->entry) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V module without an OpEntryPoint");
    return PG_OK;
}

/* The value of a 32-bit scalar constant (OpConstant, or an OpSpecConstant's default). */
static pg_result const_u32(spv_ctx *c, uint32_t id, uint32_t *v)
{
    const uint32_t *d = def_of(c, id, 0);
    if (!d || ((d[0] & 0xffffu) != OP_CONSTANT && (d[0] & 0xffffu) != OP_SPEC_CONSTANT))
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V id %u is not an integer constant", id);
    *v = d[3];
    return PG_OK;
}

/* Strips OpTypeArray / OpTypeRuntimeArray from *type; *count is the product of the lengths (1 for
 * no array, 0 when one is a runtime array). */
static pg_result unwrap_arrays(spv_ctx *c, uint32_t *type, uint32_t *count)
{
    uint64_t n = 1;
    for (int depth = 0;; depth++) {
        const uint32_t *d = def_of(c, *type, 0);
        if (!d) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V id %u is not a type", *type);
        uint32_t op = d[0] & 0xffffu;
        if (op != OP_TYPE_ARRAY && op != OP_TYPE_RUNTIME_ARRAY) break;
        if (depth >= TYPE_DEPTH_MAX)
            return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V arrays nested deeper than %d", TYPE_DEPTH_MAX);
        uint32_t len = 0;
        if (op == OP_TYPE_ARRAY) {
            pg_result r = const_u32(c, d[3], &len);
            if (r) return r;
        }
        n *= len;
        if (n > UINT32_MAX) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V array of more than 2^32 elements");
        *type = d[2];
    }
    *count = (uint32_t)n;
    return PG_OK;
}

/* One struct's member decorations and names; *out is malloc'd (free it). */
static pg_result struct_members(spv_ctx *c, uint32_t sid, uint32_t n_members, spv_member_info **out)
{
    spv_member_info *m = calloc(n_members ? n_members : 1, sizeof *m);
    if (!m) return pg_fail(c->err, PG_ERR_OOM, "out of memory reading a SPIR-V module");
    for (uint32_t k = 0; k < c->n_mdec; k++) {
        uint32_t at = c->mdec[k];
        const uint32_t *d = c->w + at;
        if (d[1] != sid || d[2] >= n_members) continue;
        spv_member_info *e = &m[d[2]];
        if (opcode_at(c, at) == OP_MEMBER_NAME) {
            e->name = at;
            continue;
        }
        uint32_t dec = d[3];
        bool valued = dec == DEC_OFFSET || dec == DEC_MATRIX_STRIDE || dec == DEC_BUILTIN;
        if (valued && words_at(c, at) < 5) {
            free(m);
            return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V word %u: member decoration %u has no value", at, dec);
        }
        switch (dec) {
        case DEC_OFFSET: e->flags |= M_OFFSET, e->offset = d[4]; break;
        case DEC_MATRIX_STRIDE: e->matrix_stride = d[4]; break;
        case DEC_ROW_MAJOR: e->flags |= M_ROW_MAJOR; break;
        case DEC_NON_WRITABLE: e->flags |= M_NON_WRITABLE; break;
        case DEC_NON_READABLE: e->flags |= M_NON_READABLE; break;
        case DEC_BUILTIN: e->flags |= M_BUILTIN; break;
        default: break;
        }
    }
    *out = m;
    return PG_OK;
}

static pg_result struct_size(spv_ctx *c, uint32_t sid, int depth, uint32_t *size);

/* Bytes of a value of type tid inside a block; mi (may be NULL) gives the matrix stride and
 * order of the member it is in. A runtime array is 0 bytes. */
static pg_result type_size(spv_ctx *c, uint32_t tid, const spv_member_info *mi, int depth, uint64_t *size)
{
    const uint32_t *d = def_of(c, tid, 0);
    if (!d) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V id %u is not a type", tid);
    if (depth > TYPE_DEPTH_MAX)
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V types nested deeper than %d", TYPE_DEPTH_MAX);
    uint64_t inner = 0;
    uint32_t n = 0, s32 = 0;
    pg_result r = PG_OK;
    switch (d[0] & 0xffffu) {
    case OP_TYPE_BOOL: *size = 4; return PG_OK;
    case OP_TYPE_INT: case OP_TYPE_FLOAT: *size = d[2] / 8; return PG_OK;
    case OP_TYPE_POINTER: *size = 8; return PG_OK; /* a buffer reference */
    case OP_TYPE_RUNTIME_ARRAY: *size = 0; return PG_OK;
    case OP_TYPE_VECTOR:
        if ((r = type_size(c, d[2], NULL, depth + 1, &inner))) return r;
        *size = inner * d[3];
        return PG_OK;
    case OP_TYPE_MATRIX: {
        const uint32_t *col = def_of(c, d[2], OP_TYPE_VECTOR);
        if (!col) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V matrix type %u: column type is not a vector", tid);
        if (mi && mi->matrix_stride) {
            *size = (uint64_t)mi->matrix_stride * ((mi->flags & M_ROW_MAJOR) ? col[3] : d[3]);
            return PG_OK;
        }
        if ((r = type_size(c, d[2], NULL, depth + 1, &inner))) return r;
        *size = inner * d[3];
        return PG_OK;
    }
    case OP_TYPE_ARRAY:
        if ((r = const_u32(c, d[3], &n))) return r;
        if (c->ids[tid].flags & F_ARRAY_STRIDE) {
            *size = (uint64_t)n * c->ids[tid].array_stride;
        } else {
            if ((r = type_size(c, d[2], mi, depth + 1, &inner))) return r;
            *size = inner * n;
        }
        return PG_OK;
    case OP_TYPE_STRUCT:
        if ((r = struct_size(c, tid, depth + 1, &s32))) return r;
        *size = s32;
        return PG_OK;
    default:
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V type %u (opcode %u) has no size in a block", tid,
                       d[0] & 0xffffu);
    }
}

/* The size of one member of struct sid (d: its OpTypeStruct) and where it ends. */
static pg_result member_end(spv_ctx *c, uint32_t sid, const uint32_t *d, uint32_t k, const spv_member_info *mi,
                            int depth, uint64_t *size, uint64_t *end)
{
    if (!(mi->flags & M_OFFSET)) {
        char name[NAME_BYTES];
        if (id_name(c, sid, name)) name[0] = 0;
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V struct %u \"%s\": member %u has no Offset decoration", sid,
                       name, k);
    }
    pg_result r = type_size(c, d[2 + k], mi, depth, size);
    if (r) return r;
    *end = *size + mi->offset;
    if (*end > UINT32_MAX) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V struct %u is larger than 4 GiB", sid);
    return PG_OK;
}

/* Bytes of struct sid up to the end of its last member (memoised; a struct in itself is an error). */
static pg_result struct_size(spv_ctx *c, uint32_t sid, int depth, uint32_t *size)
{
    spv_id *e = &c->ids[sid];
    if (e->memo == MEMO_DONE) {
        *size = e->struct_size;
        return PG_OK;
    }
    if (e->memo == MEMO_BUSY) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V struct %u contains itself", sid);
    const uint32_t *d = def_of(c, sid, OP_TYPE_STRUCT);
    if (!d) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V id %u is not a struct", sid);
    uint32_t n_members = words_at(c, e->def) - 2;
    spv_member_info *mi = NULL;
    pg_result r = struct_members(c, sid, n_members, &mi);
    if (r) return r;
    e->memo = MEMO_BUSY;
    uint64_t max_end = 0;
    for (uint32_t k = 0; k < n_members && !r; k++) {
        uint64_t sz = 0, end = 0;
        r = member_end(c, sid, d, k, &mi[k], depth, &sz, &end);
        if (end > max_end) max_end = end;
    }
    free(mi);
    if (r) return r; /* memo stays BUSY: the module is refused anyway */
    e->memo = MEMO_DONE;
    e->struct_size = (uint32_t)max_end;
    *size = e->struct_size;
    return PG_OK;
}

/* Bytes of a value of type tid in Workgroup storage, which has no explicit layout: the sum of its
 * scalars (bool 4 bytes), no padding, so never more than a layout the driver picks. */
static pg_result natural_size(spv_ctx *c, uint32_t tid, int depth, uint64_t *size)
{
    const uint32_t *d = def_of(c, tid, 0);
    if (!d) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V id %u is not a type", tid);
    if (depth > TYPE_DEPTH_MAX) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V types nested deeper than %d", TYPE_DEPTH_MAX);
    uint64_t inner = 0;
    uint32_t n = 0;
    pg_result r = PG_OK;
    switch (d[0] & 0xffffu) {
    case OP_TYPE_BOOL: *size = 4; return PG_OK;
    case OP_TYPE_INT: case OP_TYPE_FLOAT: *size = d[2] / 8; return PG_OK;
    case OP_TYPE_VECTOR: case OP_TYPE_MATRIX: case OP_TYPE_ARRAY: /* d[3]: components, columns, length id */
        n = d[3];
        if ((d[0] & 0xffffu) == OP_TYPE_ARRAY && (r = const_u32(c, d[3], &n))) return r;
        if ((r = natural_size(c, d[2], depth + 1, &inner))) return r;
        *size = inner * n;
        return PG_OK;
    case OP_TYPE_STRUCT: {
        uint64_t sum = 0;
        for (uint32_t k = 0; k + 2 < words_at(c, c->ids[tid].def) && !r; k++) {
            r = natural_size(c, d[2 + k], depth + 1, &inner);
            sum += inner;
        }
        *size = sum;
        return r;
    }
    default:
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V type %u (opcode %u) in shared memory has no size", tid,
                       d[0] & 0xffffu);
    }
}

/* The scalar kind, component count and width of a scalar, vector or matrix type (PG_SPV_OTHER, 0, 0
 * else; bits may be NULL). */
static void scalar_bits_of(const spv_ctx *c, uint32_t tid, pg_spv_scalar *scalar, uint32_t *components, uint32_t *bits)
{
    const uint32_t *d = def_of(c, tid, 0);
    uint32_t count = 1;
    *scalar = PG_SPV_OTHER;
    *components = 0;
    if (bits) *bits = 0;
    if (d && (d[0] & 0xffffu) == OP_TYPE_MATRIX) {
        count = d[3];
        d = def_of(c, d[2], OP_TYPE_VECTOR);
    }
    if (d && (d[0] & 0xffffu) == OP_TYPE_VECTOR) {
        count *= d[3];
        d = def_of(c, d[2], 0);
    }
    if (!d) return;
    switch (d[0] & 0xffffu) {
    case OP_TYPE_FLOAT: *scalar = PG_SPV_FLOAT; break;
    case OP_TYPE_INT: *scalar = d[3] ? PG_SPV_INT : PG_SPV_UINT; break;
    case OP_TYPE_BOOL: *scalar = PG_SPV_BOOL; break;
    default: return;
    }
    *components = count;
    if (bits) *bits = (d[0] & 0xffffu) == OP_TYPE_BOOL ? 32 : d[2]; /* OpTypeFloat/OpTypeInt: their width */
}

/* The scalar kind and component count of a scalar, vector or matrix type (PG_SPV_OTHER, 0 else). */
static void scalar_of(const spv_ctx *c, uint32_t tid, pg_spv_scalar *scalar, uint32_t *components)
{
    scalar_bits_of(c, tid, scalar, components, NULL);
}

/* The type a variable's pointer type points to, and the variable's name. */
static pg_result variable_type(spv_ctx *c, const uint32_t *var, uint32_t *pointee, char *name)
{
    const uint32_t *p = def_of(c, var[1], OP_TYPE_POINTER);
    if (!p) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V variable %u: its type %u is not a pointer", var[2], var[1]);
    *pointee = p[3];
    return id_name(c, var[2], name);
}

/* Sampled type, dimension, depth, arrayed, multisampled and format of the OpTypeImage img into b. */
static void image_fields(const spv_ctx *c, const uint32_t *img, pg_spv_binding *b)
{
    uint32_t components;
    scalar_of(c, img[2], &b->sampled_type, &components);
    b->dim = img[3];
    b->arrayed = img[5] != 0;
    b->depth = img[4] == 1;
    b->multisampled = img[6] != 0;
    b->image_format = img[8];
}

/* A UniformConstant variable: image, sampler, combined image sampler or acceleration structure. */
static pg_result opaque_binding(spv_ctx *c, uint32_t type, pg_spv_binding *b)
{
    pg_result r = unwrap_arrays(c, &type, &b->array_size);
    if (r) return r;
    const uint32_t *d = def_of(c, type, 0), *img = NULL;
    switch (d[0] & 0xffffu) {
    case OP_TYPE_SAMPLED_IMAGE:
        if (!(img = def_of(c, d[2], OP_TYPE_IMAGE)))
            return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V sampled image type %u: %u is not an image type", type, d[2]);
        b->kind = PG_SPV_COMBINED_IMAGE_SAMPLER;
        image_fields(c, img, b);
        break;
    case OP_TYPE_IMAGE:
        b->kind = d[3] == DIM_SUBPASS_DATA ? PG_SPV_INPUT_ATTACHMENT
                  : d[7] == 2              ? PG_SPV_STORAGE_IMAGE
                                           : PG_SPV_SAMPLED_IMAGE;
        image_fields(c, d, b);
        break;
    case OP_TYPE_SAMPLER: b->kind = PG_SPV_SAMPLER; break;
    case OP_TYPE_ACCELERATION_STRUCTURE: b->kind = PG_SPV_ACCELERATION_STRUCTURE; break;
    default:
        return pg_fail(c->err, PG_ERR_SHADER,
                       "SPIR-V variable \"%s\": a UniformConstant of type opcode %u (no image, sampler or "
                       "acceleration structure)",
                       b->name, d[0] & 0xffffu);
    }
    return PG_OK;
}

/* A Uniform or StorageBuffer variable: a uniform or storage block. */
static pg_result block_binding(spv_ctx *c, uint32_t storage, uint32_t type, pg_spv_binding *b)
{
    pg_result r = unwrap_arrays(c, &type, &b->array_size);
    if (r) return r;
    const uint32_t *d = def_of(c, type, OP_TYPE_STRUCT);
    if (!d) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V block variable \"%s\": its type is not a struct", b->name);
    uint16_t flags = c->ids[type].flags;
    if (storage == SC_STORAGE_BUFFER || (flags & F_BUFFER_BLOCK))
        b->kind = PG_SPV_STORAGE_BUFFER;
    else if (flags & F_BLOCK)
        b->kind = PG_SPV_UNIFORM_BUFFER;
    else
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V uniform variable \"%s\": struct without Block or BufferBlock",
                       b->name);
    if ((r = id_name(c, type, b->type_name))) return r;
    if (!b->name[0]) memcpy(b->name, b->type_name, sizeof b->name);
    if ((r = struct_size(c, type, 0, &b->block_size))) return r;
    uint32_t n_members = words_at(c, c->ids[type].def) - 2;
    spv_member_info *mi = NULL;
    if ((r = struct_members(c, type, n_members, &mi))) return r;
    bool all_nw = n_members > 0, all_nr = n_members > 0;
    for (uint32_t k = 0; k < n_members; k++) {
        all_nw = all_nw && (mi[k].flags & M_NON_WRITABLE);
        all_nr = all_nr && (mi[k].flags & M_NON_READABLE);
    }
    free(mi);
    b->non_writable = b->non_writable || all_nw;
    b->non_readable = b->non_readable || all_nr;
    return PG_OK;
}

/* A descriptor variable (UniformConstant, Uniform, StorageBuffer) into out->bindings. */
static pg_result add_binding(spv_ctx *c, const uint32_t *var, pg_spv_reflection *out)
{
    pg_spv_binding b;
    memset(&b, 0, sizeof b);
    uint32_t type = 0, storage = var[3];
    pg_result r = variable_type(c, var, &type, b.name);
    if (r) return r;
    const spv_id *v = &c->ids[var[2]];
    if ((v->flags & (F_SET | F_BINDING)) != (F_SET | F_BINDING))
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V variable \"%s\" (id %u) without DescriptorSet and Binding",
                       b.name, var[2]);
    b.set = v->set;
    b.binding = v->binding;
    b.non_writable = (v->flags & F_NON_WRITABLE) != 0;
    b.non_readable = (v->flags & F_NON_READABLE) != 0;
    r = storage == SC_UNIFORM_CONSTANT ? opaque_binding(c, type, &b) : block_binding(c, storage, type, &b);
    if (r) return r;
    if (out->n_bindings >= PG_SPV_MAX_BINDINGS)
        return pg_fail(c->err, PG_ERR_LIMIT, "SPIR-V module with more than PG_SPV_MAX_BINDINGS (%d) bindings (at \"%s\")",
                       PG_SPV_MAX_BINDINGS, b.name);
    /* insertion in (set, binding) order, after equal keys */
    uint32_t i = out->n_bindings;
    while (i > 0 && (out->bindings[i - 1].set > b.set ||
                     (out->bindings[i - 1].set == b.set && out->bindings[i - 1].binding > b.binding))) {
        out->bindings[i] = out->bindings[i - 1];
        i--;
    }
    out->bindings[i] = b;
    out->n_bindings++;
    return PG_OK;
}

/* One member of the push-constant block. */
static pg_result push_member(spv_ctx *c, uint32_t sid, const uint32_t *d, uint32_t k, const spv_member_info *mi,
                             pg_spv_member *m)
{
    uint64_t size = 0, end = 0;
    pg_result r = member_end(c, sid, d, k, mi, 0, &size, &end);
    if (r) return r;
    if ((r = copy_string(c, mi->name, 3, m->name))) return r;
    m->offset = mi->offset;
    m->size = (uint32_t)size;
    uint32_t type = d[2 + k];
    if ((r = unwrap_arrays(c, &type, &m->array_size))) return r;
    if (type != d[2 + k]) {
        m->scalar = PG_SPV_OTHER; /* an array */
        m->components = 0;
    } else {
        scalar_bits_of(c, type, &m->scalar, &m->components, &m->bits);
    }
    return PG_OK;
}

/* The PushConstant variable: its block's name, size and members. */
static pg_result add_push(spv_ctx *c, const uint32_t *var, pg_spv_reflection *out)
{
    char name[NAME_BYTES];
    uint32_t type = 0;
    pg_result r = variable_type(c, var, &type, name);
    if (r) return r;
    if (out->has_push)
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V module with two push-constant blocks (%s and %s)",
                       out->push_name, name);
    const uint32_t *d = def_of(c, type, OP_TYPE_STRUCT);
    if (!d) return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V push-constant variable \"%s\": its type is not a struct", name);
    out->has_push = true;
    if ((r = id_name(c, type, out->push_name))) return r;
    if ((r = struct_size(c, type, 0, &out->push_size))) return r;
    uint32_t n_members = words_at(c, c->ids[type].def) - 2;
    if (n_members > PG_SPV_MAX_MEMBERS)
        return pg_fail(c->err, PG_ERR_LIMIT, "SPIR-V push-constant block \"%s\" has %u members (PG_SPV_MAX_MEMBERS %d)",
                       out->push_name, n_members, PG_SPV_MAX_MEMBERS);
    spv_member_info *mi = NULL;
    if ((r = struct_members(c, type, n_members, &mi))) return r;
    for (uint32_t k = 0; k < n_members && !r; k++) r = push_member(c, type, d, k, &mi[k], &out->push[k]);
    free(mi);
    out->n_push = r ? 0 : n_members;
    return r;
}

/* An Output variable with a Location that is no built-in (fragment outputs), in location order. */
static pg_result add_output(spv_ctx *c, const uint32_t *var, pg_spv_reflection *out)
{
    const spv_id *v = &c->ids[var[2]];
    if ((v->flags & F_BUILTIN) || !(v->flags & F_LOCATION)) return PG_OK;
    pg_spv_output o;
    memset(&o, 0, sizeof o);
    uint32_t type = 0, count = 0;
    pg_result r = variable_type(c, var, &type, o.name);
    if (r || (r = unwrap_arrays(c, &type, &count))) return r;
    if (def_of(c, type, OP_TYPE_STRUCT)) return PG_OK; /* an output block (gl_PerVertex or other) */
    o.location = v->location;
    scalar_of(c, type, &o.scalar, &o.components);
    if (out->n_outputs >= PG_SPV_MAX_OUTPUTS)
        return pg_fail(c->err, PG_ERR_LIMIT, "SPIR-V module with more than PG_SPV_MAX_OUTPUTS (%d) outputs (at \"%s\")",
                       PG_SPV_MAX_OUTPUTS, o.name);
    uint32_t i = out->n_outputs;
    while (i > 0 && out->outputs[i - 1].location > o.location) {
        out->outputs[i] = out->outputs[i - 1];
        i--;
    }
    out->outputs[i] = o;
    out->n_outputs++;
    return PG_OK;
}

/* A Workgroup variable (GLSL shared): its bytes into out->shared_bytes. */
static pg_result add_workgroup(spv_ctx *c, const uint32_t *var, pg_spv_reflection *out)
{
    char name[NAME_BYTES];
    uint32_t type = 0;
    uint64_t size = 0;
    pg_result r = variable_type(c, var, &type, name);
    if (!r) r = natural_size(c, type, 0, &size);
    if (r) return r;
    out->shared_bytes = out->shared_bytes + size > UINT32_MAX ? UINT32_MAX : (uint32_t)(out->shared_bytes + size);
    return PG_OK;
}

/* LocalSize / LocalSizeId of the entry point's execution modes (at: the OpExecutionMode(Id)). */
static pg_result execution_mode(spv_ctx *c, uint32_t at, pg_spv_reflection *out)
{
    const uint32_t *d = c->w + at;
    uint32_t op = opcode_at(c, at), mode = d[2];
    if (d[1] != c->w[c->entry + 2]) return PG_OK; /* another entry point's */
    bool by_value = op == OP_EXECUTION_MODE && mode == MODE_LOCAL_SIZE;
    bool by_id = op == OP_EXECUTION_MODE_ID && mode == MODE_LOCAL_SIZE_ID;
    if (!by_value && !by_id) return PG_OK;
    if (words_at(c, at) < 6)
        return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V word %u: LocalSize with fewer than 3 operands", at);
    for (int k = 0; k < 3; k++) {
        if (by_value) {
            out->local_size[k] = d[3 + k];
        } else {
            pg_result r = const_u32(c, d[3 + k], &out->local_size[k]);
            if (r) return r;
        }
    }
    return PG_OK;
}

/* The second walk: execution modes and module-scope variables. */
static pg_result read_interface(spv_ctx *c, pg_spv_reflection *out)
{
    for (size_t i = SPV_HEADER_WORDS; i < c->n; i += words_at(c, (uint32_t)i)) {
        uint32_t at = (uint32_t)i, op = opcode_at(c, at);
        const uint32_t *d = c->w + at;
        pg_result r = PG_OK;
        if (op == OP_EXECUTION_MODE || op == OP_EXECUTION_MODE_ID) {
            r = execution_mode(c, at, out);
        } else if (op == OP_VARIABLE) {
            switch (d[3]) {
            case SC_UNIFORM_CONSTANT: case SC_UNIFORM: case SC_STORAGE_BUFFER: r = add_binding(c, d, out); break;
            case SC_PUSH_CONSTANT: r = add_push(c, d, out); break;
            case SC_OUTPUT: r = add_output(c, d, out); break;
            case SC_WORKGROUP: r = add_workgroup(c, d, out); break;
            default: break;
            }
        }
        if (r) return r;
    }
    if (c->workgroup_size) { /* takes precedence over LocalSize(Id) */
        const uint32_t *d = def_of(c, c->workgroup_size, 0);
        uint32_t op = d ? d[0] & 0xffffu : 0;
        if ((op != OP_CONSTANT_COMPOSITE && op != OP_SPEC_CONSTANT_COMPOSITE) || (d[0] >> 16) < 6)
            return pg_fail(c->err, PG_ERR_SHADER, "SPIR-V WorkgroupSize id %u is not a 3-component constant",
                           c->workgroup_size);
        for (int k = 0; k < 3; k++) {
            pg_result r = const_u32(c, d[3 + k], &out->local_size[k]);
            if (r) return r;
        }
    }
    return PG_OK;
}

pg_result pg_spirv_reflect(const uint32_t *words, size_t n_words, pg_spv_reflection *out, pg_error *err)
{
    if (!out) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_spirv_reflect: no output");
    memset(out, 0, sizeof *out);
    if (!words) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_spirv_reflect: no SPIR-V words");
    spv_ctx c = {.w = words, .n = n_words, .err = err};
    pg_result r = scan(&c);
    if (!r) {
        out->version = words[1];
        out->execution_model = words[c.entry + 1];
        r = copy_string(&c, c.entry, 3, out->entry_point);
    }
    if (!r) r = read_interface(&c, out);
    free(c.ids);
    free(c.mdec);
    if (r) {
        memset(out, 0, sizeof *out);
        return r;
    }
    return PG_OK;
}

const pg_spv_binding *pg_spv_find_binding(const pg_spv_reflection *r, uint32_t set, uint32_t binding)
{
    for (uint32_t i = 0; r && i < r->n_bindings && i < PG_SPV_MAX_BINDINGS; i++)
        if (r->bindings[i].set == set && r->bindings[i].binding == binding) return &r->bindings[i];
    return NULL;
}

const pg_spv_binding *pg_spv_find_name(const pg_spv_reflection *r, const char *name)
{
    for (uint32_t i = 0; r && name && i < r->n_bindings && i < PG_SPV_MAX_BINDINGS; i++)
        if (!strcmp(r->bindings[i].name, name) || (r->bindings[i].type_name[0] && !strcmp(r->bindings[i].type_name, name)))
            return &r->bindings[i];
    return NULL;
}
