/* ocio_shim.cpp - the C interface of core/color/ocio.h over OpenColorIO 2.1 (Debian libopencolorio-dev).
 *
 * Thin on purpose: every entry point is a try/catch around a few OCIO calls; no exception leaves
 * this file. The GPU shader is OCIO's own GLSL 4.0 text with each `uniform samplerND name;`
 * rewritten to `layout(set = S, binding = B) uniform samplerND name;` (Vulkan GLSL has no
 * default-block uniforms) and global `const` arrays made plain (private) globals; a processor that
 * needs other uniforms (dynamic properties) is refused.
 */
#include "ocio.h"
#include "pg_file.h"

#include <OpenColorIO/OpenColorIO.h>

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <sstream>
#include <string>
#include <vector>


namespace OCIO = OCIO_NAMESPACE;

struct pg_ocio_config {
    OCIO::ConstConfigRcPtr config;
    std::string path;
};

struct pg_ocio_cpu {
    OCIO::ConstCPUProcessorRcPtr cpu;
};

extern "C" void pg_ocio_resolve_path(const char *setting, char *buf, size_t size)
{
    const char *env = getenv("OCIO");
    if (setting && setting[0]) snprintf(buf, size, "%s", setting);
    else if (env && env[0]) snprintf(buf, size, "%s", env);
    else pg_data_path(buf, size, PG_OCIO_SHIPPED_CONFIG);
}

extern "C" const char *pg_ocio_version(void)
{
    return OCIO::GetVersion();
}

/* The LUT files a transform names (FileTransform, also inside groups), resolved through the
 * config's search path and stat-checked like the config before OCIO reads them. A file OCIO
 * cannot find is left to OCIO's own error. */
static pg_result check_transform_files(const OCIO::ConstConfigRcPtr &cfg, const OCIO::ConstTransformRcPtr &t,
                                       const char *config_path, pg_error *err, int depth)
{
    if (!t || depth > 16) return PG_OK;
    if (auto g = OCIO::DynamicPtrCast<const OCIO::GroupTransform>(t)) {
        for (int i = 0; i < g->getNumTransforms(); i++) {
            pg_result r = check_transform_files(cfg, g->getTransform(i), config_path, err, depth + 1);
            if (r) return r;
        }
        return PG_OK;
    }
    auto f = OCIO::DynamicPtrCast<const OCIO::FileTransform>(t);
    if (!f || !f->getSrc() || !f->getSrc()[0]) return PG_OK;
    std::string resolved;
    try {
        resolved = cfg->getCurrentContext()->resolveFileLocation(f->getSrc());
    } catch (...) {
        return PG_OK;
    }
    pg_result r = pg_file_check(resolved.c_str(), "OCIO LUT", PG_FILE_CAP_OCIO, nullptr, err);
    if (r) pg_error_prefix(err, "%s", config_path);
    return r;
}

static pg_result check_luts(const OCIO::ConstConfigRcPtr &cfg, const char *config_path, pg_error *err)
{
    const OCIO::ColorSpaceDirection dirs[2] = {OCIO::COLORSPACE_DIR_TO_REFERENCE,
                                               OCIO::COLORSPACE_DIR_FROM_REFERENCE};
    for (int i = 0; i < cfg->getNumColorSpaces(OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ALL); i++) {
        const char *name = cfg->getColorSpaceNameByIndex(OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ALL, i);
        OCIO::ConstColorSpaceRcPtr cs = name ? cfg->getColorSpace(name) : nullptr;
        if (!cs) continue;
        for (auto d : dirs) {
            pg_result r = check_transform_files(cfg, cs->getTransform(d), config_path, err, 0);
            if (r) return r;
        }
    }
    for (int i = 0; i < cfg->getNumLooks(); i++) {
        OCIO::ConstLookRcPtr lk = cfg->getLook(cfg->getLookNameByIndex(i));
        if (!lk) continue;
        pg_result r = check_transform_files(cfg, lk->getTransform(), config_path, err, 0);
        if (!r) r = check_transform_files(cfg, lk->getInverseTransform(), config_path, err, 0);
        if (r) return r;
    }
    for (int i = 0; i < cfg->getNumViewTransforms(); i++) {
        OCIO::ConstViewTransformRcPtr vt = cfg->getViewTransform(cfg->getViewTransformNameByIndex(i));
        if (!vt) continue;
        for (auto d : {OCIO::VIEWTRANSFORM_DIR_TO_REFERENCE, OCIO::VIEWTRANSFORM_DIR_FROM_REFERENCE}) {
            pg_result r = check_transform_files(cfg, vt->getTransform(d), config_path, err, 0);
            if (r) return r;
        }
    }
    return PG_OK;
}

extern "C" pg_result pg_ocio_open(const char *path, pg_ocio_config **out, pg_error *err)
{
    *out = nullptr;
    char resolved[PG_PATH_MAX];
    if (!path || !path[0]) {
        pg_ocio_resolve_path(nullptr, resolved, sizeof resolved);
        path = resolved;
    }
    /* stat before OCIO opens it: a FIFO, a device or a directory is refused by name (OCIO would
     * block on a FIFO), a file over the cap before a byte is read, a missing one with the OS
     * reason (OCIO's own message does not say why) */
    pg_result cr = pg_file_check(path, "OCIO config", PG_FILE_CAP_OCIO, nullptr, err);
    if (cr) return cr;
    try {
        pg_ocio_config *c = new pg_ocio_config;
        c->path = path;
        try {
            c->config = OCIO::Config::CreateFromFile(path);
        } catch (const std::exception &e) {
            delete c;
            return pg_fail(err, PG_ERR_PARSE, "%s: OCIO config error: %s", path, e.what());
        }
        try {
            c->config->validate();
        } catch (const std::exception &e) {
            delete c;
            return pg_fail(err, PG_ERR_SCHEMA, "%s: invalid OCIO config: %s", path, e.what());
        }
        pg_result lr = check_luts(c->config, path, err);
        if (lr) {
            delete c;
            return lr;
        }
        if (!c->config->hasRole(OCIO::ROLE_SCENE_LINEAR)) {
            delete c;
            return pg_fail(err, PG_ERR_SCHEMA, "%s: the OCIO config defines no 'scene_linear' role (the colour space "
                           "passgraph renders in)", path);
        }
        if (c->config->getNumDisplays() < 1) {
            delete c;
            return pg_fail(err, PG_ERR_SCHEMA, "%s: the OCIO config defines no display", path);
        }
        *out = c;
        return PG_OK;
    } catch (const std::bad_alloc &) {
        return pg_fail(err, PG_ERR_OOM, "%s: out of memory loading the OCIO config", path);
    } catch (const std::exception &e) {
        return pg_fail(err, PG_ERR_PARSE, "%s: OCIO config error: %s", path, e.what());
    } catch (...) {
        return pg_fail(err, PG_ERR_PARSE, "%s: OCIO config error (unknown exception)", path);
    }
}

extern "C" void pg_ocio_close(pg_ocio_config *cfg)
{
    delete cfg;
}

extern "C" const char *pg_ocio_config_path(const pg_ocio_config *cfg)
{
    return cfg ? cfg->path.c_str() : "";
}

extern "C" uint32_t pg_ocio_num_displays(const pg_ocio_config *cfg)
{
    try {
        int n = cfg->config->getNumDisplays();
        return n > 0 ? (uint32_t)n : 0;
    } catch (...) {
        return 0;
    }
}

extern "C" const char *pg_ocio_display(const pg_ocio_config *cfg, uint32_t index)
{
    try {
        if (index >= pg_ocio_num_displays(cfg)) return nullptr;
        const char *d = cfg->config->getDisplay((int)index);
        return d && d[0] ? d : nullptr;
    } catch (...) {
        return nullptr;
    }
}

extern "C" const char *pg_ocio_default_display(const pg_ocio_config *cfg)
{
    try {
        const char *d = cfg->config->getDefaultDisplay();
        return d && d[0] ? d : pg_ocio_display(cfg, 0);
    } catch (...) {
        return nullptr;
    }
}

static bool has_display(const pg_ocio_config *cfg, const char *display)
{
    for (uint32_t i = 0, n = pg_ocio_num_displays(cfg); i < n; i++) {
        const char *d = pg_ocio_display(cfg, i);
        if (d && !strcmp(d, display)) return true;
    }
    return false;
}

extern "C" uint32_t pg_ocio_num_views(const pg_ocio_config *cfg, const char *display)
{
    try {
        if (!display || !has_display(cfg, display)) return 0;
        int n = cfg->config->getNumViews(display);
        return n > 0 ? (uint32_t)n : 0;
    } catch (...) {
        return 0;
    }
}

extern "C" const char *pg_ocio_view(const pg_ocio_config *cfg, const char *display, uint32_t index)
{
    try {
        if (index >= pg_ocio_num_views(cfg, display)) return nullptr;
        const char *v = cfg->config->getView(display, (int)index);
        return v && v[0] ? v : nullptr;
    } catch (...) {
        return nullptr;
    }
}

extern "C" const char *pg_ocio_default_view(const pg_ocio_config *cfg, const char *display)
{
    try {
        if (!display || !has_display(cfg, display)) return nullptr;
        const char *v = cfg->config->getDefaultView(display);
        return v && v[0] ? v : pg_ocio_view(cfg, display, 0);
    } catch (...) {
        return nullptr;
    }
}

extern "C" bool pg_ocio_has_view(const pg_ocio_config *cfg, const char *display, const char *name)
{
    if (!display || !display[0]) display = pg_ocio_default_display(cfg);
    if (!display || !name) return false;
    for (uint32_t i = 0, n = pg_ocio_num_views(cfg, display); i < n; i++) {
        const char *v = pg_ocio_view(cfg, display, i);
        if (v && !strcmp(v, name)) return true;
    }
    return false;
}

/* "a, b, c" of the displays or of a display's views */
static std::string name_list(const pg_ocio_config *cfg, const char *display)
{
    std::string s;
    uint32_t n = display ? pg_ocio_num_views(cfg, display) : pg_ocio_num_displays(cfg);
    for (uint32_t i = 0; i < n; i++) {
        const char *x = display ? pg_ocio_view(cfg, display, i) : pg_ocio_display(cfg, i);
        if (!x) continue;
        if (!s.empty()) s += ", ";
        s += x;
    }
    return s;
}

extern "C" pg_result pg_ocio_resolve(const pg_ocio_config *cfg, const char *display, const char *view,
                                     char *display_out, size_t display_size, char *view_out, size_t view_size,
                                     pg_error *err)
{
    try {
        const char *d = display && display[0] ? display : pg_ocio_default_display(cfg);
        if (!d || !has_display(cfg, d))
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s: unknown display '%s' (displays: %s)", cfg->path.c_str(),
                           d ? d : "", name_list(cfg, nullptr).c_str());
        const char *v = view && view[0] ? view : pg_ocio_default_view(cfg, d);
        if (!v || !pg_ocio_has_view(cfg, d, v))
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s: unknown view '%s' of display '%s' (views: %s)",
                           cfg->path.c_str(), v ? v : "", d, name_list(cfg, d).c_str());
        /* a name that does not fit was cut, and the cut name could be another display or view of
           the config (drawn instead): refused */
        if ((display_out && display_size && strlen(d) >= display_size) || (view_out && view_size && strlen(v) >= view_size))
            return pg_fail(err, PG_ERR_LIMIT, "%s: display '%.60s...' or view '%.60s...': a name longer than %zu bytes",
                           cfg->path.c_str(), d, v, (display_size < view_size ? display_size : view_size) - 1);
        if (display_out && display_size) snprintf(display_out, display_size, "%s", d);
        if (view_out && view_size) snprintf(view_out, view_size, "%s", v);
        return PG_OK;
    } catch (...) {
        return pg_fail(err, PG_ERR_OOM, "%s: out of memory", cfg->path.c_str());
    }
}

/* The processor scene_linear -> (display, view). Throws. */
static OCIO::ConstProcessorRcPtr display_processor(const pg_ocio_config *cfg, const char *display, const char *view)
{
    OCIO::DisplayViewTransformRcPtr t = OCIO::DisplayViewTransform::Create();
    t->setSrc(OCIO::ROLE_SCENE_LINEAR);
    t->setDisplay(display);
    t->setView(view);
    return cfg->config->getProcessor(t);
}

namespace {
struct ShaderOwner { /* frees a half-built pg_ocio_shader on any early return */
    pg_ocio_shader *s = nullptr;
    ~ShaderOwner() { pg_ocio_shader_free(s); }
};
} // namespace

/* texture i of the shader description (3D LUTs first, then 1D/2D ones): its shape, channels,
 * sampler name, interpolation and values */
static void describe_texture(const OCIO::GpuShaderDescRcPtr &sd, uint32_t i, uint32_t n3, pg_ocio_texture *t,
                             const char *&sampler, const float *&values, OCIO::Interpolation &interp)
{
    const char *tex_name = nullptr;
    if (i < n3) {
        unsigned edge = 0;
        sd->get3DTexture(i, tex_name, sampler, edge, interp);
        sd->get3DTextureValues(i, values);
        t->dim = PG_OCIO_TEX_3D;
        t->width = t->height = t->depth = edge;
        t->channels = 3;
    } else {
        unsigned w = 0, h = 0;
        OCIO::GpuShaderDesc::TextureType ch = OCIO::GpuShaderDesc::TEXTURE_RGB_CHANNEL;
        sd->getTexture(i - n3, tex_name, sampler, w, h, ch, interp);
        sd->getTextureValues(i - n3, values);
        t->dim = h > 1 ? PG_OCIO_TEX_2D : PG_OCIO_TEX_1D;
        t->width = w;
        t->height = h ? h : 1;
        t->depth = 1;
        t->channels = ch == OCIO::GpuShaderDesc::TEXTURE_RED_CHANNEL ? 1 : 3;
    }
}

/* the LUT textures copied out of OCIO, bound from desc->first_binding on (throws bad_alloc) */
static pg_result copy_textures(const OCIO::GpuShaderDescRcPtr &sd, const pg_ocio_shader_desc *desc, const char *path,
                               pg_ocio_shader *s, pg_error *err)
{
    uint32_t n3 = sd->getNum3DTextures(), n12 = sd->getNumTextures();
    s->n_textures = n3 + n12;
    if (s->n_textures) {
        s->textures = (pg_ocio_texture *)calloc(s->n_textures, sizeof(pg_ocio_texture));
        if (!s->textures) throw std::bad_alloc();
    }
    for (uint32_t i = 0; i < s->n_textures; i++) {
        pg_ocio_texture *t = &s->textures[i];
        const char *sampler = nullptr;
        const float *values = nullptr;
        OCIO::Interpolation interp = OCIO::INTERP_LINEAR;
        describe_texture(sd, i, n3, t, sampler, values, interp);
        if (!sampler || !values || !t->width || strlen(sampler) >= sizeof t->sampler)
            return pg_fail(err, PG_ERR_SCHEMA, "%s: display '%s', view '%s': OCIO gave an unusable LUT texture",
                           path, s->display, s->view);
        snprintf(t->sampler, sizeof t->sampler, "%s", sampler);
        /* OCIO computes tetrahedral / nearest interpolation itself from exact texel fetches */
        t->linear = interp != OCIO::INTERP_NEAREST && interp != OCIO::INTERP_TETRAHEDRAL;
        t->binding = desc->first_binding + i;
        size_t n = (size_t)t->width * t->height * t->depth * t->channels;
        float *copy = (float *)malloc(n * sizeof(float));
        if (!copy) throw std::bad_alloc();
        memcpy(copy, values, n * sizeof(float));
        t->values = copy;
    }
    return PG_OK;
}

/* a "uniform TYPE NAME;" line of OCIO's shader (from column p): one of the textures' samplers,
 * given its set and binding; its dimension taken from the declaration */
static pg_result bind_sampler(const std::string &line, size_t p, const pg_ocio_shader_desc *desc, const char *path,
                              pg_ocio_shader *s, std::string &glsl, pg_error *err)
{
    std::istringstream words(line.substr(p + 8));
    std::string type, name;
    words >> type >> name;
    if (!name.empty() && name.back() == ';') name.pop_back();
    const pg_ocio_texture *t = nullptr;
    for (uint32_t i = 0; i < s->n_textures; i++)
        if (name == s->textures[i].sampler) t = &s->textures[i];
    if (type.compare(0, 7, "sampler") != 0 || !t)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: display '%s', view '%s': OCIO's shader declares "
                       "'%s', which passgraph cannot bind", path, s->display, s->view, line.c_str() + p);
    pg_ocio_texture *tm = &s->textures[t - s->textures];
    if (type == "sampler1D") tm->dim = PG_OCIO_TEX_1D;
    else if (type == "sampler2D") tm->dim = PG_OCIO_TEX_2D;
    else if (type == "sampler3D") tm->dim = PG_OCIO_TEX_3D;
    else
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: OCIO sampler type '%s' is not supported", path,
                       type.c_str());
    if (tm->dim == PG_OCIO_TEX_1D && tm->height != 1)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: OCIO declares '%s' 1D but gives %ux%u texels", path,
                       tm->sampler, tm->width, tm->height);
    char decl[256];
    snprintf(decl, sizeof decl, "layout(set = %u, binding = %u) uniform %s %s;", desc->set, tm->binding,
             type.c_str(), tm->sampler);
    glsl += decl;
    return PG_OK;
}

/* GLSL 4.0 -> Vulkan GLSL: bind every sampler; any other default-block uniform is refused */
static pg_result vulkan_glsl(const char *text, const pg_ocio_shader_desc *desc, const char *path, pg_ocio_shader *s,
                             std::string &glsl, pg_error *err)
{
    std::istringstream in(text);
    std::string line;
    pg_result r;
    while (std::getline(in, line)) {
        size_t p = line.find_first_not_of(" \t");
        if (p != std::string::npos && line.compare(p, 8, "uniform ") == 0) {
            if ((r = bind_sampler(line, p, desc, path, s, glsl, err))) return r;
        } else if (line.compare(0, 6, "const ") == 0 && line.find('[') < line.find('=')) {
            /* a global constant array (GradingRGBCurve knots, ...): glslang copies a const
             * array into a temporary at every dynamically indexed read; a private global
             * is indexed in place (Filmic (ACES) at 320x180 on lavapipe: 2100 ms -> 2.7 ms) */
            glsl += line.substr(6);
        } else {
            glsl += line;
        }
        glsl += '\n';
    }
    return PG_OK;
}

/* OCIO's GPU shader sequence: the display/view resolved, its processor, the shader description,
 * the LUT textures, the shader text made Vulkan GLSL; each step checked */
extern "C" pg_result pg_ocio_shader_create(const pg_ocio_config *cfg, const pg_ocio_shader_desc *desc,
                                           pg_ocio_shader **out, pg_error *err)
{
    *out = nullptr;
    const char *path = cfg->path.c_str();
    ShaderOwner own;
    pg_result r;
    try {
        own.s = (pg_ocio_shader *)calloc(1, sizeof(pg_ocio_shader));
        if (!own.s) throw std::bad_alloc();
        pg_ocio_shader *s = own.s;
        if ((r = pg_ocio_resolve(cfg, desc->display, desc->view, s->display, sizeof s->display, s->view,
                                 sizeof s->view, err)))
            return r;
        OCIO::ConstProcessorRcPtr proc;
        try {
            proc = display_processor(cfg, s->display, s->view);
        } catch (const std::exception &e) {
            return pg_fail(err, PG_ERR_SCHEMA, "%s: display '%s', view '%s': %s", path, s->display, s->view, e.what());
        }
        OCIO::ConstGPUProcessorRcPtr gpu = proc->getDefaultGPUProcessor();
        OCIO::GpuShaderDescRcPtr sd = OCIO::GpuShaderDesc::CreateShaderDesc();
        sd->setLanguage(OCIO::GPU_LANGUAGE_GLSL_4_0);
        sd->setFunctionName(desc->function_name && desc->function_name[0] ? desc->function_name : "ocio_display");
        sd->setResourcePrefix("ocio");
        gpu->extractGpuShaderInfo(sd);
        if (sd->getNumUniforms() > 0)
            return pg_fail(err, PG_ERR_INVALID_ARG,
                           "%s: display '%s', view '%s' needs %u shader uniform(s) (OCIO dynamic properties), which "
                           "passgraph's display pass does not support", path, s->display, s->view,
                           sd->getNumUniforms());
        if ((r = copy_textures(sd, desc, path, s, err))) return r;
        std::string glsl;
        if ((r = vulkan_glsl(sd->getShaderText(), desc, path, s, glsl, err))) return r;
        s->glsl = (char *)malloc(glsl.size() + 1);
        if (!s->glsl) throw std::bad_alloc();
        memcpy(s->glsl, glsl.c_str(), glsl.size() + 1);
        *out = own.s;
        own.s = nullptr;
        return PG_OK;
    } catch (const std::bad_alloc &) {
        return pg_fail(err, PG_ERR_OOM, "%s: out of memory building the OCIO shader", path);
    } catch (const std::exception &e) {
        return pg_fail(err, PG_ERR_SCHEMA, "%s: OCIO: %s", path, e.what());
    } catch (...) {
        return pg_fail(err, PG_ERR_SCHEMA, "%s: OCIO: unknown exception", path);
    }
}

extern "C" void pg_ocio_shader_free(pg_ocio_shader *s)
{
    if (!s) return;
    for (uint32_t i = 0; s->textures && i < s->n_textures; i++) free((void *)s->textures[i].values);
    free(s->textures);
    free(s->glsl);
    free(s);
}

extern "C" pg_result pg_ocio_cpu_create(const pg_ocio_config *cfg, const char *display, const char *view,
                                        pg_ocio_cpu **out, pg_error *err)
{
    *out = nullptr;
    const char *path = cfg->path.c_str();
    char d[PG_NAME_MAX * 2], v[PG_NAME_MAX * 2];
    pg_result r = pg_ocio_resolve(cfg, display, view, d, sizeof d, v, sizeof v, err);
    if (r) return r;
    try {
        OCIO::ConstProcessorRcPtr proc = display_processor(cfg, d, v);
        pg_ocio_cpu *p = new pg_ocio_cpu;
        try {
            p->cpu = proc->getDefaultCPUProcessor();
        } catch (...) {
            delete p;
            throw;
        }
        *out = p;
        return PG_OK;
    } catch (const std::bad_alloc &) {
        return pg_fail(err, PG_ERR_OOM, "%s: out of memory", path);
    } catch (const std::exception &e) {
        return pg_fail(err, PG_ERR_SCHEMA, "%s: display '%s', view '%s': %s", path, d, v, e.what());
    } catch (...) {
        return pg_fail(err, PG_ERR_SCHEMA, "%s: display '%s', view '%s': unknown OCIO exception", path, d, v);
    }
}

extern "C" void pg_ocio_cpu_apply(const pg_ocio_cpu *p, float *pixels, size_t n, uint32_t channels)
{
    if (!p || !pixels || !n || (channels != 3 && channels != 4)) return;
    try {
        OCIO::PackedImageDesc img(pixels, (long)n, 1, (long)channels);
        p->cpu->apply(img);
    } catch (...) {
        /* cannot happen for float RGB(A) buffers; leave the pixels as they are */
    }
}

extern "C" void pg_ocio_cpu_free(pg_ocio_cpu *p)
{
    delete p;
}
