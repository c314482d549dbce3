/* test_shader_cache.c - the on-disk caches (core/base/pg_cache.h), in a temporary cache folder and a
 * temporary shaders folder:
 *  - SPIR-V: a cold compile runs glslang and writes one .spv; the same variant again is a memory
 *    hit; after pg_shader_cache_forget ("a new process") it is a disk hit that runs no glslang and
 *    gives the same words; another define, another stage, or a changed #include file is a new key
 *    (compiled); a .spv with a flipped byte or cut short is rejected and compiled again (and
 *    rewritten); with the caches off everything is compiled and nothing read or written; an
 *    unwritable cache folder still compiles.
 *  - pipeline cache (GPU, validation on): the first device starts cold and saves a file named by
 *    vendor/device/driver/UUID; the next device loads it; a corrupt file, and a well-formed file
 *    whose data names another vendor, are ignored (loaded 0 bytes); a compute pipeline is created
 *    through the loaded cache with no validation message. */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pg_cache.h"
#include "shader.h"
#include "test_util.h"
#include "vk_context.h"
#include "pass_set.h"
#include "vk_pipeline.h"

static char g_root[256], g_cache[320], g_shaders[320];

static void write_text(const char *rel, const char *text)
{
    char p[512];
    snprintf(p, sizeof p, "%s/%s", g_shaders, rel);
    FILE *f = fopen(p, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static pg_shader_cache_stats stats(void)
{
    pg_shader_cache_stats s;
    pg_shader_cache_stats_get(&s);
    return s;
}

static bool compile(const char *def, VkShaderStageFlagBits stage, uint32_t **w, size_t *n)
{
    const char *defs[1] = {def};
    pg_error err = {0};
    pg_result r = pg_shader_compile(stage == VK_SHADER_STAGE_COMPUTE_BIT ? "t.comp" : "t.frag", stage, defs, 1, w, n,
                                    &err);
    if (r) fprintf(stderr, "compile: %s\n", err.msg);
    return r == PG_OK;
}

/* The only .spv file in the cache (path into buf); false unless exactly one. */
static int spv_files(char *buf, size_t size)
{
    char dir[400];
    snprintf(dir, sizeof dir, "%s/spirv", g_cache);
    DIR *d = opendir(dir);
    if (!d) return 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        size_t l = strlen(e->d_name);
        if (l > 4 && !strcmp(e->d_name + l - 4, ".spv")) {
            n++;
            if (buf) snprintf(buf, size, "%s/%s", dir, e->d_name);
        }
    }
    closedir(d);
    return n;
}

static void test_spirv(void)
{
    uint32_t *w0 = NULL, *w = NULL;
    size_t n0 = 0, n = 0;
    pg_shader_cache_forget();
    CHECK(compile("K=1", VK_SHADER_STAGE_COMPUTE_BIT, &w0, &n0));
    pg_shader_cache_stats s = stats();
    CHECK_MSG(s.compiled == 1 && s.disk_writes == 1 && s.disk_hits == 0, "cold: %u compiled %u written", s.compiled,
              s.disk_writes);
    CHECK(spv_files(NULL, 0) == 1);

    CHECK(compile("K=1", VK_SHADER_STAGE_COMPUTE_BIT, &w, &n));
    s = stats();
    CHECK_MSG(s.compiled == 1 && s.memory_hits == 1, "memory: %u compiled %u hits", s.compiled, s.memory_hits);
    CHECK(n == n0 && w && !memcmp(w, w0, n * 4));
    free(w);

    pg_shader_cache_forget();
    CHECK(compile("K=1", VK_SHADER_STAGE_COMPUTE_BIT, &w, &n));
    s = stats();
    CHECK_MSG(s.compiled == 0 && s.disk_hits == 1, "warm: %u compiled %u disk hits", s.compiled, s.disk_hits);
    CHECK(n == n0 && w && !memcmp(w, w0, n * 4));
    free(w);

    /* another define, another stage: new keys */
    pg_shader_cache_forget();
    CHECK(compile("K=2", VK_SHADER_STAGE_COMPUTE_BIT, &w, &n));
    free(w);
    CHECK(compile("K=1", VK_SHADER_STAGE_FRAGMENT_BIT, &w, &n));
    free(w);
    s = stats();
    CHECK_MSG(s.compiled == 2 && s.disk_hits == 0, "defines/stage: %u compiled", s.compiled);
    CHECK(spv_files(NULL, 0) == 3);

    /* a changed include invalidates; changing it back finds the first file again */
    write_text("inc.glsl", "float inc_value() { return 7.0; }\n");
    pg_shader_cache_forget();
    CHECK(compile("K=1", VK_SHADER_STAGE_COMPUTE_BIT, &w, &n));
    s = stats();
    CHECK_MSG(s.compiled == 1 && s.disk_hits == 0, "changed include: %u compiled %u disk hits", s.compiled,
              s.disk_hits);
    CHECK(!(n == n0 && !memcmp(w, w0, n * 4)));
    free(w);
    write_text("inc.glsl", "float inc_value() { return 3.0; }\n");
    pg_shader_cache_forget();
    CHECK(compile("K=1", VK_SHADER_STAGE_COMPUTE_BIT, &w, &n));
    s = stats();
    CHECK(s.compiled == 0 && s.disk_hits == 1);
    CHECK(n == n0 && !memcmp(w, w0, n * 4));
    free(w);

    /* corrupt files: one flipped byte of SPIR-V, then a file cut short: rejected, recompiled, rewritten */
    char path[600];
    for (int k = 0; k < 2; k++) {
        /* start from an empty cache holding only the K=1 compute variant */
        char dir[400];
        snprintf(dir, sizeof dir, "%s/spirv", g_cache);
        DIR *d = opendir(dir);
        struct dirent *e;
        while (d && (e = readdir(d)))
            if (e->d_name[0] != '.') {
                char f[700];
                snprintf(f, sizeof f, "%s/%s", dir, e->d_name);
                unlink(f);
            }
        if (d) closedir(d);
        pg_shader_cache_forget();
        CHECK(compile("K=1", VK_SHADER_STAGE_COMPUTE_BIT, &w, &n));
        free(w);
        CHECK(spv_files(path, sizeof path) == 1);
        size_t bytes;
        unsigned char *data = pg_cache_read(path, &bytes);
        CHECK(data && bytes > 100);
        if (!data) return;
        if (k == 0) data[bytes - 9] ^= 0x10;
        FILE *f = fopen(path, "wb");
        if (f) {
            fwrite(data, 1, k == 0 ? bytes : bytes - 6, f);
            fclose(f);
        }
        free(data);
        pg_shader_cache_forget();
        CHECK(compile("K=1", VK_SHADER_STAGE_COMPUTE_BIT, &w, &n));
        s = stats();
        CHECK_MSG(s.rejected == 1 && s.compiled == 1 && s.disk_hits == 0 && s.disk_writes == 1,
                  "corrupt %d: %u rejected %u compiled", k, s.rejected, s.compiled);
        CHECK(n == n0 && !memcmp(w, w0, n * 4));
        free(w);
        pg_shader_cache_forget();
        CHECK(compile("K=1", VK_SHADER_STAGE_COMPUTE_BIT, &w, &n));
        free(w);
        CHECK(stats().disk_hits == 1);
    }

    /* caches off */
    pg_cache_set_enabled(false);
    pg_shader_cache_forget();
    CHECK(compile("K=1", VK_SHADER_STAGE_COMPUTE_BIT, &w, &n));
    free(w);
    CHECK(compile("K=1", VK_SHADER_STAGE_COMPUTE_BIT, &w, &n));
    free(w);
    s = stats();
    CHECK_MSG(s.compiled == 2 && s.memory_hits == 0 && s.disk_hits == 0 && s.disk_writes == 0, "off: %u compiled",
              s.compiled);
    pg_cache_set_enabled(true);

    /* an unwritable cache folder: a note, the compile still succeeds */
    char old[400];
    snprintf(old, sizeof old, "%s", g_cache);
    setenv("PASSGRAPH_CACHE_DIR", "/proc/passgraph-no-such-dir", 1);
    pg_shader_cache_forget();
    CHECK(compile("K=9", VK_SHADER_STAGE_COMPUTE_BIT, &w, &n));
    free(w);
    s = stats();
    CHECK(s.compiled == 1 && s.disk_writes == 0);
    setenv("PASSGRAPH_CACHE_DIR", old, 1);
    free(w0);
}

static char *pipeline_file(char *buf, size_t size)
{
    char dir[400];
    snprintf(dir, sizeof dir, "%s/pipelines", g_cache);
    DIR *d = opendir(dir);
    if (!d) return NULL;
    struct dirent *e;
    char *found = NULL;
    while ((e = readdir(d)))
        if (strstr(e->d_name, ".bin") && !strstr(e->d_name, ".tmp")) {
            snprintf(buf, size, "%s/%s", dir, e->d_name);
            found = buf;
        }
    closedir(d);
    return found;
}

static pg_gpu *make_gpu(void)
{
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    pg_gpu *gpu = NULL;
    if (pg_gpu_create(&gd, &gpu, &err)) fprintf(stderr, "gpu: %s\n", err.msg);
    return gpu;
}

static uint32_t g_messages;

static void close_gpu(pg_gpu *gpu)
{
    g_messages += gpu->validation_messages;
    pg_gpu_destroy(gpu);
}

static void test_pipeline_cache(void)
{
    char path[600];
    pg_gpu *gpu = make_gpu();
    CHECK(gpu);
    if (!gpu) return;
    CHECK(gpu->pipeline_cache != VK_NULL_HANDLE);
    CHECK(gpu->pipeline_cache_loaded == 0);
    char name[64];
    snprintf(name, sizeof name, "%04x-%04x-%08x-", gpu->props.vendorID, gpu->props.deviceID,
             gpu->props.driverVersion);
    close_gpu(gpu);
    CHECK(pipeline_file(path, sizeof path) != NULL);
    CHECK_MSG(strstr(path, name) != NULL, "%s does not name %s", path, name);

    gpu = make_gpu();
    CHECK(gpu);
    if (!gpu) return;
    CHECK_MSG(gpu->pipeline_cache_loaded >= sizeof(VkPipelineCacheHeaderVersionOne), "loaded %zu bytes",
              gpu->pipeline_cache_loaded);
    /* a pipeline through the loaded cache */
    VkShaderModule cs = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipe = VK_NULL_HANDLE;
    const char *defs[1] = {"K=1"};
    pg_error err = {0};
    CHECK(pg_shader_module(gpu, "t.comp", VK_SHADER_STAGE_COMPUTE_BIT, defs, 1, &cs, &err) == PG_OK);
    CHECK(pg_pipeline_layout_create(gpu, 0, NULL, 0, &layout, &err) == PG_OK);
    CHECK(pg_compute_pipeline_create(gpu, layout, cs, "t", &pipe, &err) == PG_OK);
    if (pipe) vkDestroyPipeline(gpu->device, pipe, NULL);
    if (layout) vkDestroyPipelineLayout(gpu->device, layout, NULL);
    if (cs) vkDestroyShaderModule(gpu->device, cs, NULL);
    close_gpu(gpu);

    /* corrupt: one byte of the data flipped */
    size_t bytes;
    unsigned char *data = pg_cache_read(path, &bytes);
    CHECK(data && bytes > 40);
    if (!data) return;
    data[bytes - 1] ^= 0x01;
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(data, 1, bytes, f);
        fclose(f);
    }
    gpu = make_gpu();
    if (gpu) {
        CHECK_MSG(gpu->pipeline_cache_loaded == 0, "corrupt file loaded (%zu bytes)", gpu->pipeline_cache_loaded);
        CHECK(gpu->pipeline_cache != VK_NULL_HANDLE);
        close_gpu(gpu);
    }
    /* the corrupt file was replaced on close: loads again */
    gpu = make_gpu();
    if (gpu) {
        CHECK(gpu->pipeline_cache_loaded > 0);
        close_gpu(gpu);
    }

    /* well-formed wrapper, data for another vendor */
    free(data);
    data = pg_cache_read(path, &bytes);
    CHECK(data && bytes > 40);
    if (!data) return;
    unsigned char *vk = data + 32; /* after pc_file_head (core/vk/pipeline_cache.c): magic, size, hash */
    VkPipelineCacheHeaderVersionOne h;
    memcpy(&h, vk, sizeof h);
    h.vendorID ^= 0x5a5a;
    memcpy(vk, &h, sizeof h);
    pg_hash128 sum = pg_hash128_init();
    pg_hash128_add(&sum, vk, bytes - 32);
    memcpy(data + 16, &sum.a, 8);
    memcpy(data + 24, &sum.b, 8);
    f = fopen(path, "wb");
    if (f) {
        fwrite(data, 1, bytes, f);
        fclose(f);
    }
    free(data);
    gpu = make_gpu();
    if (gpu) {
        CHECK_MSG(gpu->pipeline_cache_loaded == 0, "other vendor's data loaded (%zu bytes)",
                  gpu->pipeline_cache_loaded);
        close_gpu(gpu);
    }

    /* caches off: no pipeline cache object */
    pg_cache_set_enabled(false);
    gpu = make_gpu();
    if (gpu) {
        CHECK(gpu->pipeline_cache == VK_NULL_HANDLE && gpu->pipeline_cache_loaded == 0);
        close_gpu(gpu);
    }
    pg_cache_set_enabled(true);
    printf("validation messages: %u\n", g_messages);
    CHECK_MSG(g_messages == 0, "%u validation message(s)", g_messages);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    snprintf(g_root, sizeof g_root, "/tmp/pg_shader_cache_XXXXXX");
    if (!mkdtemp(g_root)) return pg_test_skip("test_shader_cache", "no temporary folder");
    snprintf(g_cache, sizeof g_cache, "%s/cache", g_root);
    snprintf(g_shaders, sizeof g_shaders, "%s/shaders", g_root);
    mkdir(g_shaders, 0755);
    write_text("common.glsl", "// marks the data folder\n");
    write_text("inc.glsl", "float inc_value() { return 3.0; }\n");
    write_text("t.comp", "#version 460\n#include \"inc.glsl\"\nlayout(local_size_x = 1) in;\n"
                         "shared float s;\n"
                         "void main() { s = inc_value() * float(K); }\n");
    write_text("t.frag", "#version 460\n#include \"inc.glsl\"\nlayout(location = 0) out vec4 c;\n"
                         "void main() { c = vec4(inc_value() * float(K)); }\n");
    setenv("PASSGRAPH_DATA_DIR", g_root, 1);
    setenv("PASSGRAPH_CACHE_DIR", g_cache, 1);
    unsetenv("PASSGRAPH_NO_SHADER_CACHE");
    pg_cache_set_enabled(true);
    test_spirv();
    if (!getenv("PG_TEST_NO_GPU")) test_pipeline_cache();
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_root);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", g_root);
    return pg_test_finish("test_shader_cache");
}
