/* shader_pass_declare.c - declare() of the `shader` pass type (docs/user-passes.md): reads the
 * pass's options, compiles the user's GLSL file (on the CPU, glslang; cached), reads its interface
 * from the SPIR-V (spirv_reflect.h) and checks it against the JSON: every set-2 binding named in
 * options.bindings and the reverse, the kind of each (combined sampler, storage image or buffer,
 * uniform buffer) against the resource's kind and the access asked, readonly / writeonly
 * qualifiers against the access, a storage image's format qualifier against the resource's
 * format, the push-constant members against options.params, the fragment outputs against
 * options.targets. Each refusal names the pipeline file, the JSON path, the shader file and the
 * binding. Then it declares the slots in the order of the pass's reads and writes. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cjson/cJSON.h>
#include <vulkan/vulkan.h>

#include "pipeline_paths.h"
#include "shader.h"
#include "shader_pass.h"
#include "shader_pass_declare.h"
#include "spirv_reflect.h"

static const char *const k_forms[] = {"compute", "fullscreen", "draw"};

/* The SPIR-V image format a storage image of this pipeline format declares (0: none matches). */
static uint32_t spv_format_of(pg_format f)
{
    switch (f) {
    case PG_FMT_RGBA8_UNORM: return 4;
    case PG_FMT_RGBA16F: return 2;
    case PG_FMT_RGBA32F: return 1;
    case PG_FMT_RG16F: return 7;
    case PG_FMT_RGBA16_UNORM: return 10;
    case PG_FMT_RG16_UNORM: return 12;
    case PG_FMT_RG16_SNORM: return 17;
    case PG_FMT_R32F: return 3;
    case PG_FMT_R32UI: return 33;
    case PG_FMT_RG32UI: return 35;
    case PG_FMT_RGBA32UI: return 30;
    case PG_FMT_R11G11B10F: return 8;
    default: return 0;
    }
}

/* options.form_key: which form, and the shader file resolved and confined into p->path. */
static pg_result read_form(sp_ctx *c)
{
    const cJSON *o = c->in->desc->options;
    int found = -1;
    for (int i = 0; i < 3; i++) {
        const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, k_forms[i]);
        if (!v) continue;
        if (found >= 0)
            return pg_sp_fail(c, PG_ERR_SCHEMA, k_forms[i], "give one of compute, fullscreen, draw (also has %s)",
                           k_forms[found]);
        if (!cJSON_IsString(v) || !v->valuestring[0])
            return pg_sp_fail(c, PG_ERR_SCHEMA, k_forms[i], "expected the shader's file name (a string)");
        found = i;
        c->rel = v->valuestring;
    }
    if (found < 0)
        return pg_sp_fail(c, PG_ERR_SCHEMA, NULL,
                       "a shader pass names its shader file under one of \"compute\", \"fullscreen\", \"draw\"");
    c->form_key = k_forms[found];
    c->p->form = (uint8_t)found;
    pg_error e;
    if (pg_pipeline_resolve_file(c->in->desc->file, c->in->pipeline ? c->in->pipeline->path : NULL, c->rel,
                                 c->p->path, sizeof c->p->path, &e))
        return pg_sp_fail(c, e.code, c->form_key, "shader %s", e.msg);
    struct stat st;
    if (stat(c->p->path, &st) != 0)
        return pg_sp_fail(c, PG_ERR_IO, c->form_key, "cannot open shader '%s' (%s)", c->rel, c->p->path);
    if (!S_ISREG(st.st_mode))
        return pg_sp_fail(c, PG_ERR_IO, c->form_key, "shader '%s' is not a regular file", c->rel);
    return PG_OK;
}

static bool is_identifier(const char *s)
{
    if (!s[0] || (s[0] >= '0' && s[0] <= '9')) return false;
    for (; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') || *s == '_'))
            return false;
    return true;
}

/* options.defines: {"NAME": number | true | false | "token"} -> NAME=VALUE defines (false: none). */
static pg_result read_defines(sp_ctx *c)
{
    const cJSON *defs = cJSON_GetObjectItemCaseSensitive(c->in->desc->options, "defines");
    if (!defs) return PG_OK;
    if (!cJSON_IsObject(defs)) return pg_sp_fail(c, PG_ERR_SCHEMA, "defines", "expected an object {\"NAME\": value}");
    const cJSON *it;
    cJSON_ArrayForEach(it, defs)
    {
        char sub[PG_NAME_MAX + 16];
        snprintf(sub, sizeof sub, "defines.%s", it->string);
        if (!is_identifier(it->string) || strlen(it->string) >= 40 || !strncmp(it->string, "PG_", 3))
            return pg_sp_fail(c, PG_ERR_SCHEMA, sub, "a define is a C identifier under 40 characters, not starting PG_");
        char d[PG_NAME_MAX];
        if (cJSON_IsBool(it)) {
            if (cJSON_IsFalse(it)) continue;
            snprintf(d, sizeof d, "%s", it->string);
        } else if (cJSON_IsNumber(it) && isfinite(it->valuedouble)) {
            double v = it->valuedouble;
            if (v == floor(v) && fabs(v) < 1e15) snprintf(d, sizeof d, "%s=%lld", it->string, (long long)v);
            else snprintf(d, sizeof d, "%s=%.9g", it->string, v);
        } else if (cJSON_IsString(it) && is_identifier(it->valuestring) && strlen(it->valuestring) < 20) {
            snprintf(d, sizeof d, "%s=%s", it->string, it->valuestring);
        } else {
            return pg_sp_fail(c, PG_ERR_SCHEMA, sub, "expected a finite number, true/false or an identifier");
        }
        if (c->out->n_defines >= PG_MAX_DEFINES) return pg_sp_fail(c, PG_ERR_LIMIT, sub, "more than %d defines", PG_MAX_DEFINES);
        pg_decl_define(c->out, d);
    }
    return PG_OK;
}

/* options.surface: "none" (default) or "visibility" (compute: rebuild surfaces from a visibility
 * buffer with visibility_surface.glsl; the pass binds the scene's streams and materials). */
static pg_result read_surface(sp_ctx *c)
{
    static const char *const k_surfaces[] = {"none", "visibility", NULL};
    int v = 0;
    pg_result r = pg_opt_enum(c->in->desc, "surface", k_surfaces, 0, &v, c->err);
    if (r) return r;
    if (v == 1 && c->p->form != SP_COMPUTE)
        return pg_sp_fail(c, PG_ERR_SCHEMA, "surface", "\"visibility\" is for a compute shader");
    c->p->vis_surface = v == 1;
    return PG_OK;
}

/* Compiles the shader with the declared defines and reads its interface. */
static pg_result compile_and_reflect(sp_ctx *c)
{
    const VkShaderStageFlagBits stage =
        c->p->form == SP_COMPUTE ? VK_SHADER_STAGE_COMPUTE_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
    const char *defs[PG_MAX_DEFINES + 8];
    /* a visibility surface is compiled without the alpha-mask variant (compute: no discard), as
     * pg_vis_geometry does at create */
    uint32_t n = c->p->vis_surface ? pg_scene_draw_define_list(c->out, &c->p->draw, defs, PG_MAX_DEFINES)
                                   : pg_decl_define_list(c->out, defs, PG_MAX_DEFINES);
    if (c->p->form == SP_DRAW) defs[n++] = "TEXTURE_COUNT=1"; /* the scene's count at create: same interface */
    if (c->p->vis_surface) { /* what pg_vis_geometry adds at create (placeholders of the same interface) */
        static const char *const vis[] = {"TEXTURE_COUNT=1", "PG_VIS_TRI_BITS=16", "PG_SURFACE_GRADS",
                                          "PG_SURFACE_NO_PUSH", "PG_SCENE_SET=3", "PG_VIS_SET=1", "PG_VIS_BINDING=0"};
        for (size_t i = 0; i < sizeof vis / sizeof vis[0]; i++) defs[n++] = vis[i];
    }
    uint32_t *words = NULL;
    size_t n_words = 0;
    pg_error e;
    if (pg_shader_compile_user(c->p->path, stage, defs, n, false, &words, &n_words, &e))
        return pg_sp_fail(c, PG_ERR_SHADER, c->form_key, "%s", e.msg);
    pg_result r = pg_spirv_reflect(words, n_words, &c->refl, &e);
    uint64_t h = 1469598103934665603ull; /* FNV-1a */
    for (size_t i = 0; i < n_words * 4; i++) h = (h ^ ((const unsigned char *)words)[i]) * 1099511628211ull;
    c->p->spirv_hash = h;
    free(words);
    if (r) return pg_sp_fail(c, r, c->form_key, "shader '%s': %s", c->rel, e.msg);
    return PG_OK;
}

/* Sets other than the frame (0), the scene (1, draw form) and the user's (2) are refused. */
static pg_result check_sets(sp_ctx *c)
{
    for (uint32_t i = 0; i < c->refl.n_bindings; i++) {
        const pg_spv_binding *b = &c->refl.bindings[i];
        if (b->set == SP_USER_SET) continue;
        if (b->set == 0 && b->binding == 0 && b->kind == PG_SPV_UNIFORM_BUFFER && !strcmp(b->type_name, "FrameUniforms"))
            continue;
        if (b->set == 1 && (c->p->form == SP_DRAW || c->p->vis_surface)) continue;
        if (b->set == SP_SCENE_SET && c->p->vis_surface) continue;
        return pg_sp_fail(c, PG_ERR_SHADER, c->form_key,
                       "shader '%s' binding '%s' (set %u, binding %u): a user shader's resources are in set %d "
                       "(set 0 is the frame block FRAME_UNIFORMS_BLOCK of common.glsl%s)",
                       c->rel, b->name, b->set, b->binding, SP_USER_SET,
                       c->p->form == SP_DRAW ? ", set 1 the scene's materials" : "");
    }
    return PG_OK;
}

/* The access a binding gets when the JSON gives only the resource. */
static pg_access inferred_access(const pg_spv_binding *b)
{
    switch (b->kind) {
    case PG_SPV_COMBINED_IMAGE_SAMPLER: return PG_ACCESS_SAMPLED;
    case PG_SPV_UNIFORM_BUFFER: return PG_ACCESS_UNIFORM;
    default:
        return b->non_writable ? PG_ACCESS_STORAGE_READ
                               : b->non_readable ? PG_ACCESS_STORAGE_WRITE : PG_ACCESS_STORAGE_RW;
    }
}

static bool access_from_name(const char *s, pg_access *out)
{
    static const struct {
        const char *name;
        pg_access a;
    } k[] = {{"sampled", PG_ACCESS_SAMPLED},           {"storage_read", PG_ACCESS_STORAGE_READ},
             {"storage_write", PG_ACCESS_STORAGE_WRITE}, {"storage_rw", PG_ACCESS_STORAGE_RW},
             {"uniform", PG_ACCESS_UNIFORM}};
    for (size_t i = 0; i < sizeof k / sizeof k[0]; i++)
        if (!strcmp(s, k[i].name)) {
            *out = k[i].a;
            return true;
        }
    return false;
}

/* A pipeline image is one 2D single-sampled colour or depth layer, sampled without comparison:
 * other dimensions, arrays, multisampling and shadow samplers are refused by name. */
static pg_result check_image_shape(sp_ctx *c, const char *sub, const pg_spv_binding *b)
{
    static const char *const dims[] = {"1D", "2D", "3D", "cube", "rectangle", "buffer", "subpass"};
    const char *what = NULL;
    char buf[48];
    if (b->dim != 1) {
        snprintf(buf, sizeof buf, "a %s image", b->dim < 7 ? dims[b->dim] : "?");
        what = buf;
    } else if (b->arrayed) {
        what = "an image array (layers)";
    } else if (b->multisampled) {
        what = "a multisampled image";
    } else if (b->depth) {
        what = "a shadow sampler (depth comparison; the pass's sampler compares nothing)";
    }
    if (!what) return PG_OK;
    return pg_sp_fail(c, PG_ERR_FORMAT, sub,
                      "shader '%s' binding '%s' (set %u, binding %u) is %s: a pipeline image is bound as one 2D "
                      "layer (sampler2D, image2D)",
                      c->rel, b->name, b->set, b->binding, what);
}

/* The shader's kind against the resource and the access; qualifiers and formats. */
static pg_result check_binding_kind(sp_ctx *c, const char *sub, const pg_spv_binding *b, const pg_resource_desc *rd,
                                    pg_access a)
{
    const bool image = rd->kind == PG_RES_IMAGE;
    const char *want = NULL;
    switch (b->kind) {
    case PG_SPV_COMBINED_IMAGE_SAMPLER:
        if (!image || a != PG_ACCESS_SAMPLED) want = "an image bound \"sampled\"";
        break;
    case PG_SPV_STORAGE_IMAGE:
        if (!image || a == PG_ACCESS_SAMPLED || a == PG_ACCESS_UNIFORM) want = "an image bound storage_read/write/rw";
        break;
    case PG_SPV_UNIFORM_BUFFER:
        if (image || a != PG_ACCESS_UNIFORM) want = "a buffer bound \"uniform\"";
        break;
    case PG_SPV_STORAGE_BUFFER:
        if (image || a == PG_ACCESS_SAMPLED || a == PG_ACCESS_UNIFORM) want = "a buffer bound storage_read/write/rw";
        break;
    default:
        return pg_sp_fail(c, PG_ERR_SHADER, sub,
                       "shader '%s' binding '%s' (set %u, binding %u) is a %s: use a combined sampler (sampler2D), "
                       "a storage image, a uniform or a storage buffer",
                       c->rel, b->name, b->set, b->binding, pg_spv_kind_name(b->kind));
    }
    if (want)
        return pg_sp_fail(c, PG_ERR_FORMAT, sub,
                       "shader '%s' binding '%s' (set %u, binding %u) is a %s: it needs %s, not %s '%s' bound %s",
                       c->rel, b->name, b->set, b->binding, pg_spv_kind_name(b->kind), want,
                       image ? "image" : "buffer", rd->name, pg_access_name(a));
    if (b->kind == PG_SPV_STORAGE_IMAGE || b->kind == PG_SPV_STORAGE_BUFFER) {
        if (b->non_writable && pg_sp_access_writes(a))
            return pg_sp_fail(c, PG_ERR_FORMAT, sub,
                           "shader '%s' binding '%s' (set %u, binding %u) is readonly but bound %s", c->rel, b->name,
                           b->set, b->binding, pg_access_name(a));
        if (!b->non_writable && a == PG_ACCESS_STORAGE_READ)
            return pg_sp_fail(c, PG_ERR_FORMAT, sub,
                           "shader '%s' binding '%s' (set %u, binding %u) is bound storage_read but the shader may "
                           "write it: declare it readonly",
                           c->rel, b->name, b->set, b->binding);
        if (b->non_readable && a != PG_ACCESS_STORAGE_WRITE)
            return pg_sp_fail(c, PG_ERR_FORMAT, sub,
                           "shader '%s' binding '%s' (set %u, binding %u) is writeonly but bound %s", c->rel, b->name,
                           b->set, b->binding, pg_access_name(a));
    }
    if (image && (b->kind == PG_SPV_COMBINED_IMAGE_SAMPLER || b->kind == PG_SPV_STORAGE_IMAGE)) {
        pg_result r = check_image_shape(c, sub, b);
        if (r) return r;
    }
    const bool uint_image = pg_format_get(rd->format)->fmt_class == PG_FMTCLASS_UINT;
    const bool uint_shader = b->sampled_type == PG_SPV_UINT || b->sampled_type == PG_SPV_INT;
    if (image && (b->kind == PG_SPV_COMBINED_IMAGE_SAMPLER || b->kind == PG_SPV_STORAGE_IMAGE) &&
        uint_image != uint_shader)
        return pg_sp_fail(c, PG_ERR_FORMAT, sub,
                          "shader '%s' binding '%s' (set %u, binding %u) reads %s texels but resource '%s' is %s: use "
                          "%s",
                          c->rel, b->name, b->set, b->binding, uint_shader ? "integer" : "float", rd->name,
                          pg_format_get(rd->format)->name,
                          uint_image ? "a usampler/uimage" : "a sampler/image of floats (sampler2D, image2D)");
    const cJSON *fo = cJSON_GetObjectItemCaseSensitive(c->in->desc->options, "filter"); /* read after the bindings */
    const bool linear = !cJSON_IsString(fo) || strcmp(fo->valuestring, "nearest") != 0;
    if (b->kind == PG_SPV_COMBINED_IMAGE_SAMPLER && uint_image && linear)
        return pg_sp_fail(c, PG_ERR_FORMAT, "filter",
                          "resource '%s' is %s, which cannot be filtered, and shader '%s' samples it (binding '%s') "
                          "with the pass's sampler, \"linear\" by default: set \"filter\": \"nearest\"",
                          rd->name, pg_format_get(rd->format)->name, c->rel, b->name);
    if (b->kind == PG_SPV_STORAGE_IMAGE && b->image_format == 0) /* SpvImageFormatUnknown */
        return pg_sp_fail(c, PG_ERR_FORMAT, sub,
                          "shader '%s' binding '%s' (set %u, binding %u) is a storage image without a format "
                          "qualifier (reading or writing one needs device features passgraph does not enable): "
                          "declare it layout(%s)",
                          c->rel, b->name, b->set, b->binding, pg_spv_image_format_name(spv_format_of(rd->format)));
    if (b->kind == PG_SPV_STORAGE_IMAGE && b->image_format != spv_format_of(rd->format))
        return pg_sp_fail(c, PG_ERR_FORMAT, sub,
                       "shader '%s' binding '%s' (set %u, binding %u) declares format %s but resource '%s' is %s",
                       c->rel, b->name, b->set, b->binding, pg_spv_image_format_name(b->image_format), rd->name,
                       pg_format_get(rd->format)->name);
    if (b->array_size != 1)
        return pg_sp_fail(c, PG_ERR_SHADER, sub, "shader '%s' binding '%s': arrays of resources are not bound by a "
                       "shader pass", c->rel, b->name);
    return PG_OK;
}

/* One entry of options.bindings: its resource, access and the pass slot it is. */
static pg_result read_binding(sp_ctx *c, const cJSON *it, uint32_t k)
{
    char sub[PG_NAME_MAX + 16];
    snprintf(sub, sizeof sub, "bindings.%s", it->string);
    const pg_spv_binding *b = NULL;
    for (uint32_t i = 0; i < c->refl.n_bindings && !b; i++)
        if (c->refl.bindings[i].set == SP_USER_SET && !strcmp(c->refl.bindings[i].name, it->string)) {
            b = &c->refl.bindings[i];
            c->binding_refl[k] = (int)i;
        }
    if (!b) return pg_sp_fail(c, PG_ERR_SHADER, sub, "shader '%s' has no binding '%s' in set %d", c->rel, it->string, SP_USER_SET);
    const char *res = NULL;
    pg_access a = inferred_access(b);
    if (cJSON_IsString(it)) {
        res = it->valuestring;
    } else if (cJSON_IsObject(it)) {
        const cJSON *r = cJSON_GetObjectItemCaseSensitive(it, "resource");
        const cJSON *ac = cJSON_GetObjectItemCaseSensitive(it, "access");
        for (const cJSON *key = it->child; key; key = key->next) /* a typo ("acess") was dropped silently */
            if (strcmp(key->string, "resource") && strcmp(key->string, "access"))
                return pg_sp_fail(c, PG_ERR_SCHEMA, sub, "unknown key '%s' (resource, access)", key->string);
        if (cJSON_IsString(r)) res = r->valuestring;
        if (ac && (!cJSON_IsString(ac) || !access_from_name(ac->valuestring, &a)))
            return pg_sp_fail(c, PG_ERR_SCHEMA, sub,
                           "access: expected sampled, storage_read, storage_write, storage_rw or uniform");
    }
    if (!res) return pg_sp_fail(c, PG_ERR_SCHEMA, sub, "expected a resource name or {\"resource\": R, \"access\": A}");
    const pg_resource_desc *rd = c->in->pipeline ? pg_pipeline_find_resource(c->in->pipeline, res) : NULL;
    if (!rd) return pg_sp_fail(c, PG_ERR_UNKNOWN_RESOURCE, sub, "no resource '%s' in the pipeline", res);
    pg_result r = check_binding_kind(c, sub, b, rd, a);
    if (r) return r;
    const pg_pass_desc *d = c->in->desc;
    const bool w = pg_sp_access_writes(a);
    int idx = w ? pg_sp_find_in(d->writes, d->n_writes, res) : pg_sp_find_in(d->reads, d->n_reads, res);
    if (idx < 0)
        return pg_sp_fail(c, PG_ERR_SCHEMA, sub, "resource '%s' is bound %s but is not in the pass's %s", res,
                       pg_access_name(a), w ? "writes" : "reads");
    int *use = w ? &c->write_use[idx] : &c->read_use[idx];
    if (*use != SP_USE_NONE)
        return pg_sp_fail(c, PG_ERR_SCHEMA, sub, "resource '%s' is bound twice (each entry of %s is one binding)", res,
                       w ? "writes" : "reads");
    *use = 1 + (int)k;
    c->binding_access[k] = a;
    c->p->bindings[k].number = (uint16_t)b->binding;
    c->p->bindings[k].block_size = b->block_size;
    c->p->bindings[k].type = (uint16_t)(b->kind == PG_SPV_COMBINED_IMAGE_SAMPLER ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
                                        : b->kind == PG_SPV_STORAGE_IMAGE     ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                        : b->kind == PG_SPV_UNIFORM_BUFFER    ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                                                                              : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    return PG_OK;
}

static pg_result read_bindings(sp_ctx *c)
{
    const cJSON *bs = cJSON_GetObjectItemCaseSensitive(c->in->desc->options, "bindings");
    if (bs && !cJSON_IsObject(bs)) return pg_sp_fail(c, PG_ERR_SCHEMA, "bindings", "expected an object {\"name\": resource}");
    uint32_t k = 0;
    const cJSON *it;
    cJSON_ArrayForEach(it, bs)
    {
        if (k >= SP_MAX_BINDINGS) return pg_sp_fail(c, PG_ERR_LIMIT, "bindings", "more than %d bindings", SP_MAX_BINDINGS);
        pg_result r = read_binding(c, it, k++);
        if (r) return r;
    }
    c->p->n_bindings = (uint8_t)k;
    for (uint32_t i = 0; i < c->refl.n_bindings; i++) {
        const pg_spv_binding *b = &c->refl.bindings[i];
        if (b->set == SP_USER_SET && !cJSON_GetObjectItemCaseSensitive(bs, b->name))
            return pg_sp_fail(c, PG_ERR_SHADER, "bindings",
                           "shader '%s' binding '%s' (set %u, binding %u, a %s) is not bound: add \"%s\": RESOURCE",
                           c->rel, b->name, b->set, b->binding, pg_spv_kind_name(b->kind), b->name);
    }
    return PG_OK;
}

pg_result pg_shader_pass_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    static const char *const known[] = {"compute", "fullscreen", "draw",    "bindings",    "params",
                                        "defines", "dispatch",   "targets", "blend",       "depth",
                                        "depth_test", "depth_clear", "filter", "address", "surface", NULL};
    sp_ctx *c = calloc(1, sizeof *c);
    if (!c) return pg_fail(err, PG_ERR_OOM, "out of memory");
    c->in = in;
    c->out = out;
    c->err = err;
    c->p = pg_decl_params(out, sizeof *c->p);
    pg_result r = c->p ? pg_opt_check_known(in->desc, known, err) : pg_fail(err, PG_ERR_LIMIT, "params block");
    if (!r) r = read_form(c);
    if (!r) r = read_surface(c);
    if (!r && (c->p->form == SP_DRAW || c->p->vis_surface)) pg_scene_draw_declare_features(in, out, &c->p->draw);
    if (!r) r = read_defines(c);
    if (!r) r = compile_and_reflect(c);
    if (!r) r = check_sets(c);
    if (!r) r = read_bindings(c);
    if (!r) r = pg_sp_read_params(c);
    if (!r) r = pg_sp_read_attachments(c);
    if (!r) r = pg_sp_declare_slots(c);
    if (!r) r = pg_sp_read_dispatch(c);
    if (!r) pg_sp_explain(c);
    free(c);
    return r;
}
