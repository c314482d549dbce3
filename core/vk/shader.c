/* shader.c - glslang C interface wrapper with textual #include expansion. */
#include "shader.h"

#include <glslang/Include/glslang_c_interface.h>
#include <glslang/Public/resource_limits_c.h>
#include <glslang/build_info.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "pg_cache.h"
#include "vk_context.h"

/* ---- textual include expansion ---- */
typedef struct strbuf {
    char *data;
    size_t len, cap;
} strbuf;

static bool sb_append(strbuf *sb, const char *s, size_t n)
{
    if (sb->len + n + 1 > sb->cap) {
        size_t cap = sb->cap ? sb->cap * 2 : 4096;
        while (cap < sb->len + n + 1) cap *= 2;
        char *d = realloc(sb->data, cap);
        if (!d) return false;
        sb->data = d;
        sb->cap = cap;
    }
    memcpy(sb->data + sb->len, s, n);
    sb->len += n;
    sb->data[sb->len] = 0;
    return true;
}

typedef struct gen_sources {
    const pg_shader_source *v;
    uint32_t n;
    /* a user shader (pg_shader_compile_user): the top-level file's path and folder; its includes
     * are looked up in that folder first (names without ".." or a leading '/'), then in the
     * shaders folder (the library); every file boundary gets a `#line N "file"` so glslang's
     * messages name the user's file and line */
    const char *user_path;
    const char *user_dir;
} gen_sources;

/* The file an include or top-level name reads: a generated source, the user's folder, or the
 * shaders folder. *text is malloc'd; path names it for messages. */
static pg_result open_source(const char *name, int depth, const gen_sources *gen, char *path, size_t path_size,
                             char **text, pg_error *err)
{
    *text = NULL;
    for (uint32_t i = 0; gen && i < gen->n && !*text; i++) {
        if (!gen->v[i].name || strcmp(gen->v[i].name, name)) continue;
        snprintf(path, path_size, "<generated %s>", name);
        size_t len = gen->v[i].text ? strlen(gen->v[i].text) : 0;
        *text = malloc(len + 1);
        if (!*text) return pg_fail(err, PG_ERR_OOM, "out of memory expanding %s", path);
        if (len) memcpy(*text, gen->v[i].text, len);
        (*text)[len] = 0;
        return PG_OK;
    }
    if (gen->user_path && depth == 0) {
        snprintf(path, path_size, "%s", gen->user_path);
        return pg_read_file(path, text, NULL, err);
    }
    if (gen->user_dir) { /* include_name_ok: relative, no ".." */
        if (snprintf(path, path_size, "%s/%s", gen->user_dir, name) >= (int)path_size)
            return pg_fail(err, PG_ERR_SHADER, "%s/%s: path too long", gen->user_dir, name);
        if (access(path, R_OK) == 0) return pg_read_file(path, text, NULL, err);
    }
    snprintf(path, path_size, "%s/shaders/%s", pg_data_dir(), name);
    return pg_read_file(path, text, NULL, err);
}

/* an #include's name stays inside the folders it is looked up in: relative, no ".." component
 * (the library's own includes are plain names; a user's may name a subfolder) */
static bool include_name_ok(const char *name)
{
    if (!name[0] || name[0] == '/') return false;
    for (const char *p = name; *p; p++) {
        if ((unsigned char)*p < ' ') return false;
        const bool start = p == name || p[-1] == '/';
        if (start && p[0] == '.' && p[1] == '.' && (p[2] == '/' || p[2] == 0)) return false;
    }
    return true;
}

static bool line_directive(strbuf *out, int line, const char *path)
{
    char buf[PG_PATH_MAX + 96];
    int n = snprintf(buf, sizeof buf, "#line %d \"%s\"\n", line, path);
    return n > 0 && (size_t)n < sizeof buf && sb_append(out, buf, (size_t)n);
}

static pg_result expand(const char *name, int depth, const gen_sources *gen, strbuf *out, pg_error *err)
{
    if (depth > 8) return pg_fail(err, PG_ERR_SHADER, "shaders/%s: #include nested too deep", name);
    char path[PG_PATH_MAX + 64];
    char *text = NULL;
    pg_result r = open_source(name, depth, gen, path, sizeof path, &text, err);
    if (r) return r;
    const bool lines = gen->user_path != NULL;
    if (lines && depth > 0 && !line_directive(out, 1, path)) goto oom;
    const char *p = text;
    int line = 1;
    while (*p) {
        const char *eol = strchr(p, '\n');
        size_t n = eol ? (size_t)(eol - p + 1) : strlen(p);
        const char *q = p;
        while (*q == ' ' || *q == '\t') q++;
        if (strncmp(q, "#include", 8) == 0) {
            const char *a = strchr(q, '"');
            const char *b = a ? strchr(a + 1, '"') : NULL;
            if (!a || !b || b > p + n) {
                free(text);
                return pg_fail(err, PG_ERR_SHADER, "%s:%d: malformed #include", path, line);
            }
            char inc[PG_NAME_MAX * 2];
            size_t il = (size_t)(b - a - 1);
            if (il >= sizeof inc) { /* cut, it named another file (which was read) */
                free(text);
                return pg_fail(err, PG_ERR_SHADER, "%s:%d: #include name longer than %d bytes", path, line,
                               (int)sizeof inc - 1);
            }
            memcpy(inc, a + 1, il);
            inc[il] = 0;
            r = include_name_ok(inc) ? expand(inc, depth + 1, gen, out, err)
                                     : pg_fail(err, PG_ERR_SHADER, "#include names a file outside the allowed folders "
                                                                   "(no absolute path, no '..' component)");
            if (r) {
                char why[sizeof err->msg];
                snprintf(why, sizeof why, "%s", err->msg);
                pg_fail(err, r, "%s:%d: #include \"%s\" (looked up in %s%s%s/shaders): %s", path, line, inc,
                        gen->user_dir ? gen->user_dir : "", gen->user_dir ? " then " : "", pg_data_dir(), why);
                free(text);
                return r;
            }
            if (!sb_append(out, "\n", 1)) goto oom;
            if (lines && !line_directive(out, line + 1, path)) goto oom;
        } else if (!sb_append(out, p, n)) {
            goto oom;
        }
        p += n;
        line++;
    }
    free(text);
    return PG_OK;
oom:
    free(text);
    return pg_fail(err, PG_ERR_OOM, "out of memory expanding %s", path);
}

/* The #version a Vulkan shader can have: 150 or later, or 310 es or later (below that glslang's
 * Vulkan built-ins do not parse, and it printed thousands of lines of them on stdout) */
static pg_result check_version(const char *ver, const char *shown, const char *name, pg_error *err)
{
    const char *p = ver + 8;
    while (*p == ' ' || *p == '\t') p++;
    char *end = NULL;
    const long v = strtol(p, &end, 10);
    if (end == p)
        return pg_fail(err, PG_ERR_SHADER, "%s%s: #version without a number", shown, name);
    while (*end == ' ' || *end == '\t') end++;
    const bool es = strncmp(end, "es", 2) == 0;
    if (es ? v < 310 : v < 150)
        return pg_fail(err, PG_ERR_SHADER,
                       "%s%s: #version %ld%s: Vulkan GLSL needs #version 150 or later (450 recommended), or 310 es",
                       shown, name, v, es ? " es" : "");
    return PG_OK;
}

/* 1-based line number of position at in text */
static int line_of(const char *text, const char *at)
{
    int line = 1;
    for (const char *p = text; p < at; p++) line += *p == '\n';
    return line;
}

static pthread_mutex_t g_glslang_lock = PTHREAD_MUTEX_INITIALIZER;
static bool g_glslang_ready;

/* ---- SPIR-V cache: in memory for the process, on disk in <cache dir>/spirv/<key>.spv ----
 * The key hashes the expanded source (every included file's content and the generated sources
 * spliced in, the defines inserted after #version), the stage, the glslang version and the
 * client / target versions glslang is asked for. A .spv file is a spv_file_head and the words. */
/* the glslang client / SPIR-V target: Vulkan 1.3 / SPIR-V 1.6, or 1.2 / 1.5 for a Vulkan 1.2 device
 * (gpu->vulkan12) */
#define SPV_CLIENT(v12) ((v12) ? GLSLANG_TARGET_VULKAN_1_2 : GLSLANG_TARGET_VULKAN_1_3)
#define SPV_TARGET(v12) ((v12) ? GLSLANG_TARGET_SPV_1_5 : GLSLANG_TARGET_SPV_1_6)
#define SPV_MAGIC "PGSPV01\n"
#define SPV_MEMORY_MAX 512

typedef struct spv_file_head {
    char magic[8];
    uint64_t key_a, key_b;
    uint64_t n_words;
    uint64_t sum_a, sum_b; /* pg_hash128 of the words */
} spv_file_head;

typedef struct spv_entry {
    pg_hash128 key;
    uint32_t *words;
    size_t n;
} spv_entry;

static pthread_mutex_t g_cache_lock = PTHREAD_MUTEX_INITIALIZER;
static spv_entry g_mem[SPV_MEMORY_MAX];
static uint32_t g_n_mem;
static pg_shader_cache_stats g_stats;

static double now_ms(void)
{
    return pg_time_s() * 1e3;
}

static void add_ms(double *acc, double ms)
{
    pthread_mutex_lock(&g_cache_lock);
    *acc += ms;
    pthread_mutex_unlock(&g_cache_lock);
}

static pg_hash128 spirv_key(const char *src, VkShaderStageFlagBits stage, bool vulkan12)
{
    pg_hash128 h = pg_hash128_init();
    char ver[160];
    snprintf(ver, sizeof ver, "passgraph-spirv-1 glslang %d.%d.%d%s client %d target %d stage %d", GLSLANG_VERSION_MAJOR,
             GLSLANG_VERSION_MINOR, GLSLANG_VERSION_PATCH, GLSLANG_VERSION_FLAVOR, (int)SPV_CLIENT(vulkan12), (int)SPV_TARGET(vulkan12),
             (int)stage);
    pg_hash128_add(&h, ver, strlen(ver) + 1);
    pg_hash128_add(&h, src, strlen(src));
    return h;
}

static bool spirv_path(pg_hash128 key, char *buf, size_t size, bool make_dir)
{
    char dir[PG_PATH_MAX];
    if (!pg_cache_dir(dir, sizeof dir)) return false;
    size_t l = strlen(dir);
    if (l + 8 >= sizeof dir) return false;
    memcpy(dir + l, "/spirv", 7);
    if (make_dir && !pg_cache_mkdirs(dir)) {
        static bool noted; /* once per process, not once per variant */
        if (!noted) pg_cache_note("shader cache folder %s cannot be made; SPIR-V not saved", dir);
        noted = true;
        return false;
    }
    return snprintf(buf, size, "%s/%016llx%016llx.spv", dir, (unsigned long long)key.a, (unsigned long long)key.b) <
           (int)size;
}

static bool dup_words(const uint32_t *w, size_t n, uint32_t **out, size_t *n_out)
{
    uint32_t *c = malloc(n * sizeof *c);
    if (!c) return false;
    memcpy(c, w, n * sizeof *c);
    *out = c;
    *n_out = n;
    return true;
}

static void memory_put(pg_hash128 key, const uint32_t *w, size_t n)
{
    if (g_n_mem >= SPV_MEMORY_MAX) return;
    spv_entry *e = &g_mem[g_n_mem];
    if (dup_words(w, n, &e->words, &e->n)) {
        e->key = key;
        g_n_mem++;
    }
}

static bool spirv_cache_get(pg_hash128 key, uint32_t **out, size_t *n_out)
{
    bool hit = false;
    pthread_mutex_lock(&g_cache_lock);
    for (uint32_t i = 0; i < g_n_mem && !hit; i++)
        if (g_mem[i].key.a == key.a && g_mem[i].key.b == key.b) {
            hit = dup_words(g_mem[i].words, g_mem[i].n, out, n_out);
            if (hit) g_stats.memory_hits++;
        }
    char path[PG_PATH_MAX + 64];
    if (!hit && spirv_path(key, path, sizeof path, false)) {
        size_t bytes;
        unsigned char *data = pg_cache_read(path, &bytes);
        if (data) {
            spv_file_head h;
            bool ok = bytes >= sizeof h;
            if (ok) memcpy(&h, data, sizeof h);
            ok = ok && !memcmp(h.magic, SPV_MAGIC, 8) && h.key_a == key.a && h.key_b == key.b && h.n_words > 5 &&
                 h.n_words <= (bytes - sizeof h) / 4 && bytes == sizeof h + h.n_words * 4;
            uint32_t *w = ok ? malloc(h.n_words * 4) : NULL;
            if (w) {
                memcpy(w, data + sizeof h, h.n_words * 4);
                pg_hash128 sum = pg_hash128_init();
                pg_hash128_add(&sum, w, h.n_words * 4);
                ok = sum.a == h.sum_a && sum.b == h.sum_b && w[0] == 0x07230203u;
            }
            if (ok && w) {
                *out = w;
                *n_out = h.n_words;
                hit = true;
                g_stats.disk_hits++;
                memory_put(key, w, h.n_words);
            } else {
                free(w);
                g_stats.rejected++;
                pg_cache_note("shader cache file %s is corrupt; ignored, compiling again", path);
            }
            free(data);
        }
    }
    pthread_mutex_unlock(&g_cache_lock);
    return hit;
}

static void spirv_cache_put(pg_hash128 key, const uint32_t *w, size_t n)
{
    pthread_mutex_lock(&g_cache_lock);
    memory_put(key, w, n);
    char path[PG_PATH_MAX + 64];
    if (spirv_path(key, path, sizeof path, true)) {
        spv_file_head h = {.key_a = key.a, .key_b = key.b, .n_words = n};
        memcpy(h.magic, SPV_MAGIC, 8);
        pg_hash128 sum = pg_hash128_init();
        pg_hash128_add(&sum, w, n * 4);
        h.sum_a = sum.a;
        h.sum_b = sum.b;
        if (pg_cache_write(path, &h, sizeof h, w, n * 4)) g_stats.disk_writes++;
    }
    pthread_mutex_unlock(&g_cache_lock);
}

void pg_shader_cache_stats_get(pg_shader_cache_stats *out)
{
    pthread_mutex_lock(&g_cache_lock);
    *out = g_stats;
    pthread_mutex_unlock(&g_cache_lock);
}

void pg_shader_cache_forget(void)
{
    pthread_mutex_lock(&g_cache_lock);
    for (uint32_t i = 0; i < g_n_mem; i++) free(g_mem[i].words);
    g_n_mem = 0;
    memset(&g_stats, 0, sizeof g_stats);
    pthread_mutex_unlock(&g_cache_lock);
}

static glslang_stage_t to_glslang_stage(VkShaderStageFlagBits s)
{
    switch (s) {
    case VK_SHADER_STAGE_VERTEX_BIT: return GLSLANG_STAGE_VERTEX;
    case VK_SHADER_STAGE_FRAGMENT_BIT: return GLSLANG_STAGE_FRAGMENT;
    default: return GLSLANG_STAGE_COMPUTE;
    }
}

pg_result pg_shader_compile(const char *name, VkShaderStageFlagBits stage,
                            const char *const *defines, uint32_t n_defines, uint32_t **spirv,
                            size_t *n_words, pg_error *err)
{
    return pg_shader_compile_ex(name, stage, defines, n_defines, NULL, 0, spirv, n_words, err);
}

static pg_result compile_for(const char *name, VkShaderStageFlagBits stage, const char *const *defines,
                             uint32_t n_defines, const gen_sources *gen, bool vulkan12, uint32_t **spirv,
                             size_t *n_words, pg_error *err);

pg_result pg_shader_compile_ex(const char *name, VkShaderStageFlagBits stage, const char *const *defines,
                               uint32_t n_defines, const pg_shader_source *sources, uint32_t n_sources,
                               uint32_t **spirv, size_t *n_words, pg_error *err)
{
    const gen_sources gen = {sources, n_sources, NULL, NULL};
    return compile_for(name, stage, defines, n_defines, &gen, false, spirv, n_words, err);
}

/* the folder of path ("." for a bare name) */
static void dir_of(const char *path, char *out, size_t size)
{
    const char *slash = strrchr(path, '/');
    if (!slash) snprintf(out, size, ".");
    else if (slash == path) snprintf(out, size, "/");
    else snprintf(out, size, "%.*s", (int)(slash - path), path);
}

pg_result pg_shader_compile_user(const char *path, VkShaderStageFlagBits stage, const char *const *defines,
                                 uint32_t n_defines, bool vulkan12, uint32_t **spirv, size_t *n_words, pg_error *err)
{
    char dir[PG_PATH_MAX];
    dir_of(path, dir, sizeof dir);
    const gen_sources gen = {NULL, 0, path, dir};
    return compile_for(path, stage, defines, n_defines, &gen, vulkan12, spirv, n_words, err);
}

pg_result pg_shader_module_words(struct pg_gpu *gpu, const char *name, const uint32_t *code, size_t words,
                                 VkShaderModule *out, pg_error *err)
{
    VkShaderModuleCreateInfo ci = {
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = words * sizeof(uint32_t),
        .pCode = code,
    };
    VkResult vr = vkCreateShaderModule(gpu->device, &ci, NULL, out);
    if (vr != VK_SUCCESS)
        return pg_fail(err, PG_ERR_VULKAN, "vkCreateShaderModule(%s) failed: %s", name, pg_vk_result_name(vr));
    pg_gpu_name(gpu, VK_OBJECT_TYPE_SHADER_MODULE, (uint64_t)*out, "%s", name);
    return PG_OK;
}

/* vulkan12: target Vulkan 1.2 / SPIR-V 1.5 (the most a 1.2 device accepts) instead of 1.3 / 1.6 */
/* "#define NAME VALUE" lines for defines (NAME or NAME=VALUE), and for a built-in shader with
 * PASSGRAPH_KEEP_NAN=1 in the environment PG_HDR_KEEP_NAN: it stores a NaN it computes instead of 0
 * (common.glsl pg_hdr_sanitize), for the tools' nonfinite count; part of the source, so of the key */
static bool append_defines(strbuf *src, const char *const *defines, uint32_t n_defines, bool builtin)
{
    bool ok = true;
    for (uint32_t i = 0; ok && i < n_defines; i++) {
        char line[PG_NAME_MAX + 32];
        const char *eq = strchr(defines[i], '=');
        if (eq)
            snprintf(line, sizeof line, "#define %.*s %s\n", (int)(eq - defines[i]), defines[i], eq + 1);
        else
            snprintf(line, sizeof line, "#define %s 1\n", defines[i]);
        ok = sb_append(src, line, strlen(line));
    }
    const char *keep = getenv("PASSGRAPH_KEEP_NAN");
    if (ok && builtin && keep && !strcmp(keep, "1")) {
        static const char k_keep[] = "#define PG_HDR_KEEP_NAN 1\n";
        ok = sb_append(src, k_keep, sizeof k_keep - 1);
    }
    return ok;
}

static pg_result compile_for(const char *name, VkShaderStageFlagBits stage, const char *const *defines,
                             uint32_t n_defines, const gen_sources *gen, bool vulkan12, uint32_t **spirv,
                             size_t *n_words, pg_error *err)
{
    *spirv = NULL;
    *n_words = 0;
    strbuf body = {0};
    const char *shown = gen->user_path ? "" : "shaders/"; /* messages: the user's path as given */
    for (const char *c = gen->user_path ? name : ""; *c; c++) /* the #line directives carry the name */
        if (*c == '"' || *c == '\\' || (unsigned char)*c < ' ')
            return pg_fail(err, PG_ERR_SHADER, "%s: a shader file name with a '\"', '\\' or control character cannot "
                                               "be named by GLSL's #line; rename the file", name);
    pg_result r = expand(name, 0, gen, &body, err);
    if (r) {
        free(body.data);
        return r;
    }
    /* put the defines right after the #version line */
    strbuf src = {0};
    if (!body.data || !body.data[0]) { /* an empty file (or one an editor is about to write) */
        free(body.data);
        return pg_fail(err, PG_ERR_SHADER, "%s%s: empty file (no #version line)", shown, name);
    }
    char *ver = strstr(body.data, "#version");
    char *ver_end = ver ? strchr(ver, '\n') : NULL;
    if (!ver || !ver_end) {
        free(body.data);
        return pg_fail(err, PG_ERR_SHADER, "%s%s: no #version line", shown, name);
    }
    if ((r = check_version(ver, shown, name, err))) {
        free(body.data);
        return r;
    }
    bool ok = sb_append(&src, body.data, (size_t)(ver_end - body.data + 1)) &&
              append_defines(&src, defines, n_defines, !gen->user_path);
    char lineinfo[PG_PATH_MAX + 96];
    if (gen->user_path)
        snprintf(lineinfo, sizeof lineinfo, "#extension GL_GOOGLE_cpp_style_line_directive : require\n#line %d \"%s\"\n",
                 line_of(body.data, ver_end) + 1, name);
    else
        snprintf(lineinfo, sizeof lineinfo, "#line 2\n");
    ok = ok && sb_append(&src, lineinfo, strlen(lineinfo)) &&
         sb_append(&src, ver_end + 1, strlen(ver_end + 1));
    free(body.data);
    if (!ok) {
        free(src.data);
        return pg_fail(err, PG_ERR_OOM, "out of memory");
    }

    pg_hash128 key = spirv_key(src.data, stage, vulkan12);
    double t0 = now_ms();
    bool hit = pg_cache_enabled() && spirv_cache_get(key, spirv, n_words);
    add_ms(&g_stats.lookup_ms, now_ms() - t0);
    if (hit) {
        free(src.data);
        return PG_OK;
    }

    pthread_mutex_lock(&g_glslang_lock);
    if (!g_glslang_ready) {
        glslang_initialize_process();
        g_glslang_ready = true;
    }
    glslang_input_t input = {
        .language = GLSLANG_SOURCE_GLSL,
        .stage = to_glslang_stage(stage),
        .client = GLSLANG_CLIENT_VULKAN,
        .client_version = SPV_CLIENT(vulkan12),
        .target_language = GLSLANG_TARGET_SPV,
        .target_language_version = SPV_TARGET(vulkan12),
        .code = src.data,
        .default_version = 460,
        .default_profile = GLSLANG_NO_PROFILE,
        .messages = GLSLANG_MSG_DEFAULT_BIT | GLSLANG_MSG_SPV_RULES_BIT | GLSLANG_MSG_VULKAN_RULES_BIT,
        .resource = glslang_default_resource(),
    };
    t0 = now_ms();
    glslang_shader_t *sh = glslang_shader_create(&input);
    glslang_program_t *prog = NULL;
    if (!sh) {
        r = pg_fail(err, PG_ERR_SHADER, "%s%s: glslang_shader_create failed", shown, name);
        goto done;
    }
    if (!glslang_shader_preprocess(sh, &input) || !glslang_shader_parse(sh, &input)) {
        r = pg_fail(err, PG_ERR_SHADER, "%s%s: compile failed:\n%s", shown, name, glslang_shader_get_info_log(sh));
        goto done;
    }
    prog = glslang_program_create();
    glslang_program_add_shader(prog, sh);
    if (!glslang_program_link(prog, GLSLANG_MSG_SPV_RULES_BIT | GLSLANG_MSG_VULKAN_RULES_BIT)) {
        r = pg_fail(err, PG_ERR_SHADER, "%s%s: link failed:\n%s", shown, name, glslang_program_get_info_log(prog));
        goto done;
    }
    glslang_program_SPIRV_generate(prog, input.stage);
    size_t words = glslang_program_SPIRV_get_size(prog);
    uint32_t *code = malloc(words * sizeof(uint32_t));
    if (!code) {
        r = pg_fail(err, PG_ERR_OOM, "out of memory");
        goto done;
    }
    glslang_program_SPIRV_get(prog, code);
    *spirv = code;
    *n_words = words;
    r = PG_OK;
    __atomic_fetch_add(&g_stats.compiled, 1, __ATOMIC_RELAXED);
    add_ms(&g_stats.compile_ms, now_ms() - t0);
    if (pg_cache_enabled()) spirv_cache_put(key, code, words);
done:
    if (prog) glslang_program_delete(prog);
    if (sh) glslang_shader_delete(sh);
    pthread_mutex_unlock(&g_glslang_lock);
    free(src.data);
    return r;
}

pg_result pg_shader_module(pg_gpu *gpu, const char *name, VkShaderStageFlagBits stage,
                           const char *const *defines, uint32_t n_defines, VkShaderModule *out,
                           pg_error *err)
{
    return pg_shader_module_ex(gpu, name, stage, defines, n_defines, NULL, 0, out, err);
}

pg_result pg_shader_module_ex(pg_gpu *gpu, const char *name, VkShaderStageFlagBits stage,
                              const char *const *defines, uint32_t n_defines, const pg_shader_source *sources,
                              uint32_t n_sources, VkShaderModule *out, pg_error *err)
{
    uint32_t *code;
    size_t words;
    const gen_sources gen = {sources, n_sources, NULL, NULL};
    pg_result r = compile_for(name, stage, defines, n_defines, &gen, gpu->vulkan12, &code, &words, err);
    if (r) return r;
    r = pg_shader_module_words(gpu, name, code, words, out, err);
    free(code);
    return r;
}

const char *pg_spirv_missing_capability(const uint32_t *code, size_t words, bool int64, bool int64_atomics)
{
    static const struct {
        uint32_t cap;
        const char *what;
    } off[] = {
        {9, "Float16 (16-bit floats in shaders)"},      {10, "Float64 (64-bit floats, double)"},
        {22, "Int16 (16-bit integers in shaders)"},     {39, "Int8 (8-bit integers in shaders)"},
        {4433, "StorageBuffer16BitAccess"},             {4434, "UniformAndStorageBuffer16BitAccess"},
        {4435, "StoragePushConstant16"},                {4436, "StorageInputOutput16"},
        {4448, "StorageBuffer8BitAccess"},              {4449, "UniformAndStorageBuffer8BitAccess"},
        {4450, "StoragePushConstant8"},
    };
    for (size_t w = 5; w < words;) {
        const uint32_t n = code[w] >> 16, op = code[w] & 0xffffu;
        if (n == 0) break;
        if (op == 17 && w + 1 < words) { /* OpCapability */
            const uint32_t cap = code[w + 1];
            if (cap == 11 && !int64) return "Int64 (64-bit integers; shaderInt64)";
            if (cap == 12 && !int64_atomics) return "Int64Atomics (64-bit atomics; shaderBufferInt64Atomics)";
            for (size_t k = 0; k < sizeof off / sizeof off[0]; k++)
                if (off[k].cap == cap) return off[k].what;
        } else if (op != 10 && op != 11 && op != 14) { /* past OpExtension, OpExtInstImport, OpMemoryModel */
            break;
        }
        w += n;
    }
    return NULL;
}
