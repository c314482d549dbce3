/* test_gpu_light_terms.c - the light sums of shaders/lighting.glsl on the Vulkan device (lavapipe,
 * validation and synchronization validation on: zero messages), on inputs the end-to-end tests
 * cannot reach: tests/gpu/shaders/light_terms.comp sums two lights a case three ways (the tiled
 * loop's select form, the per-pixel loops' early-return form, and the Lambert pairs where the model
 * has them), for each light model (Lambert with the CIS 565 window, Lambert with the glTF window,
 * Blinn-Phong, the glTF pbr BRDF). For every case:
 *  - the early-return form equals the select form bit for bit, and so do the pairs (Lambert);
 *  - each sum (added to a prior sum, so that the order of the terms shows) is within REL |expected| +
 *    ABS x its scale + 2 ulp of the prior (Blinn-Phong's specular: REL + 2n ulp for its exponent n,
 *    1..128) of the model evaluated here in double on the
 *    same float offsets (light - P rounded as the shader rounds it), the pbr model through the C
 *    twin's BRDF (renderer/common/brdf.c pg_brdf_pbr); the scale is the light's colour x
 *    min(1/d^2, 1/dmin^2) (x the pbr lobe's bound 0.5 / a^3);
 * over random lights (in range, out of range, behind the point, no window, a window shorter than
 * the range) and hostile ones: a light exactly on the point (d = 0: taken head-on, L = N, att =
 * 1/dmin^2), in either light of a pair or both; d exactly R (adds 0); R = 0 on the point (adds 0);
 * NaN and infinite positions (add 0). No scene can put a light exactly on a shaded point, so the
 * head-on case is tested here only. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "brdf.h"
#include "render_session.h"
#include "scenario.h"
#include "shader.h"
#include "test_util.h"
#include "vk_pipeline.h"

#define CASES 4096
#define REL 4e-6  /* of the expected sum: float rounding (pow and the BRDF's divisions the largest) */
#define ABS 4e-7  /* of the scale: the window's and N.L's cancellation near 0 */

typedef struct lt_case {
    float P[4], N[4], V[4], albedo[4], mat[4];
    float a[2][4], b[2][4]; /* stored a0, b0, a1, b1 in the shader's order: see pack() */
} lt_case;

typedef struct lt_model {
    const char *name;
    const char *defs[1];
    uint32_t n_defs;
    bool gltf, blinn_phong, pbr, pairs;
} lt_model;

static const lt_model k_models[] = {
    {"lambert", {NULL}, 0, false, false, false, true},
    {"lambert gltf falloff", {"PG_GLTF_FALLOFF"}, 1, true, false, false, true},
    {"blinn_phong", {"PG_BLINN_PHONG"}, 1, false, true, false, false},
    {"pbr", {"PG_PBR"}, 1, false, false, true, false},
};

static pg_gpu *g_gpu;
static uint64_t g_rng = 0x9e3779b97f4a7c15ull;

static double rnd(void) /* [0, 1) */
{
    g_rng = g_rng * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(g_rng >> 11) / 9007199254740992.0;
}

static double rnd_range(double a, double b)
{
    return a + (b - a) * rnd();
}

static void rnd_unit(double u[3])
{
    double l;
    do {
        for (int k = 0; k < 3; k++) u[k] = rnd_range(-1, 1);
        l = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    } while (l < 0.1 || l > 1);
    for (int k = 0; k < 3; k++) u[k] /= l;
}

static float inv_r2(float R) /* pg_light_inv_r2(R * R) */
{
    float r2 = R * R;
    float v = 1.0f / r2;
    return v < FLT_MAX ? v : FLT_MAX;
}

/* Light j of case c: centre pos, cut-off R, falloff range Rf, colour. */
static void set_light(lt_case *c, int j, const float pos[3], float R, float Rf, const float col[3])
{
    for (int k = 0; k < 3; k++) {
        c->a[j][k] = pos[k];
        c->b[j][k] = col[k];
    }
    c->a[j][3] = inv_r2(Rf);
    c->b[j][3] = R * R;
}

static void random_light(lt_case *c, int j)
{
    float R = (float)exp(rnd_range(log(0.05), log(30.0)));
    double s = rnd() < 0.8 ? rnd_range(0.0, 0.97) : rnd_range(1.03, 1.6);
    double u[3];
    rnd_unit(u);
    float pos[3];
    for (int k = 0; k < 3; k++) pos[k] = (float)(c->P[k] + u[k] * s * R);
    double w = rnd();
    float Rf = w < 0.7 ? R : (w < 0.85 ? 0.5f * R : 3e38f); /* the window: the range, shorter, none */
    float col[3] = {(float)rnd_range(0, 10), (float)rnd_range(0, 10), (float)rnd_range(0, 10)};
    set_light(c, j, pos, R, Rf, col);
}

static void make_case(lt_case *c, uint32_t i, float inv_md2)
{
    memset(c, 0, sizeof *c);
    double span = i % 2 ? 40.0 : 1.0;
    for (int k = 0; k < 3; k++) c->P[k] = (float)rnd_range(-span, span);
    double N[3], T[3];
    rnd_unit(N);
    do {
        rnd_unit(T);
    } while (fabs(N[0] * T[0] + N[1] * T[1] + N[2] * T[2]) > 0.9);
    double tn = N[0] * T[0] + N[1] * T[1] + N[2] * T[2];
    for (int k = 0; k < 3; k++) T[k] -= tn * N[k];
    double tl = sqrt(T[0] * T[0] + T[1] * T[1] + T[2] * T[2]);
    double nv = rnd_range(0.15, 1.0), tv = sqrt(1 - nv * nv);
    for (int k = 0; k < 3; k++) {
        c->N[k] = (float)N[k];
        c->V[k] = (float)(N[k] * nv + T[k] / tl * tv);
        c->albedo[k] = (float)rnd_range(0.05, 1.0);
    }
    c->mat[0] = (float)rnd();               /* metallic */
    c->mat[1] = (float)rnd_range(0.1, 1.0); /* roughness */
    c->albedo[3] = (float)rnd_range(1.0, 128.0); /* Blinn-Phong's exponent */
    c->mat[2] = i % 4 < 2 ? 0.0f : (float)rnd_range(0, 1e3); /* the diffuse sum before the two lights */
    c->mat[3] = inv_md2;
    random_light(c, 0);
    random_light(c, 1);
    float col[3] = {2.0f, 0.5f, 1.0f};
    uint32_t kind = i % 16;
    if (kind == 3 || kind == 5) set_light(c, 0, c->P, 1.5f, 1.5f, col); /* on the point: head-on */
    if (kind == 4 || kind == 5) set_light(c, 1, c->P, 0.2f, 3e38f, col);
    if (kind == 6) {                                                     /* d exactly R: adds 0 */
        memset(c->P, 0, sizeof c->P);
        float pos[3] = {2.5f, 0, 0};
        set_light(c, 1, pos, 2.5f, 2.5f, col);
    }
    if (kind == 7) set_light(c, 0, c->P, 0.0f, 0.0f, col); /* R = 0 on the point: adds 0 */
    if (kind == 8) c->a[1][i % 3] = NAN;
    if (kind == 9) c->a[0][i % 3] = i % 2 ? INFINITY : -INFINITY;
}

/* The model in double on the shader's float offsets: diffuse and specular sums, and the scale. */
static void expect(const lt_model *m, const lt_case *c, double diff[3], double spec[3], double *scale, bool *edge)
{
    const double dmin2 = 1.0 / c->mat[3];
    double N[3] = {c->N[0], c->N[1], c->N[2]}, V[3] = {c->V[0], c->V[1], c->V[2]};
    double a = pg_pbr_alpha(c->mat[1]);
    *scale = 0;
    *edge = false;
    for (int k = 0; k < 3; k++) diff[k] = spec[k] = 0;
    for (int j = 0; j < 2; j++) {
        double Ld[3], d2 = 0;
        for (int k = 0; k < 3; k++) {
            Ld[k] = (float)(c->a[j][k] - c->P[k]); /* one float subtraction, as the shader */
            d2 += Ld[k] * Ld[k];
        }
        double R2 = c->b[j][3];
        if (fabs(d2 - R2) <= 1e-5 * R2 && d2 != R2) *edge = true; /* float d^2 may round across R^2 */
        if (!(d2 < R2)) continue;
        double t = d2 * c->a[j][3], fo = fmin(fmax(1 - t * t, 0), 1);
        if (m->gltf) fo *= fo;
        double att = fo / fmax(d2, dmin2), L[3];
        for (int k = 0; k < 3; k++) L[k] = d2 > 0 ? Ld[k] / sqrt(d2) : N[k];
        double nl = N[0] * L[0] + N[1] * L[1] + N[2] * L[2], ndl = fmax(nl, 0);
        double cmax = fmax(c->b[j][0], fmax(c->b[j][1], c->b[j][2]));
        *scale += cmax / fmax(d2, dmin2) * (m->pbr ? 1 + 0.5 / (a * a * a) : 1);
        if (m->pbr) {
            if (ndl * att > 0)
                for (int k = 0; k < 3; k++)
                    diff[k] += c->b[j][k] * M_PI * pg_brdf_pbr(L, V, N, c->albedo[k], c->mat[0], c->mat[1]) * ndl * att;
            continue;
        }
        for (int k = 0; k < 3; k++) diff[k] += c->b[j][k] * ndl * att;
        if (m->blinn_phong && nl > 0) {
            double H[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
            double hl = sqrt(H[0] * H[0] + H[1] * H[1] + H[2] * H[2]);
            double nh = fmax((N[0] * H[0] + N[1] * H[1] + N[2] * H[2]) / hl, 0);
            *scale += cmax / fmax(d2, dmin2);
            for (int k = 0; k < 3; k++) spec[k] += c->b[j][k] * pow(nh, c->albedo[3]) * att * nl;
        }
    }
}

typedef struct lt_gpu {
    VkDescriptorSetLayout dsl;
    VkDescriptorPool pool;
    VkDescriptorSet set;
    VkPipelineLayout layout;
    VkPipeline pipe;
    VkShaderModule cs;
    pg_buffer in, out;
} lt_gpu;

static void lt_gpu_free(lt_gpu *g)
{
    VkDevice d = g_gpu->device;
    if (g->pipe) vkDestroyPipeline(d, g->pipe, NULL);
    if (g->layout) vkDestroyPipelineLayout(d, g->layout, NULL);
    if (g->cs) vkDestroyShaderModule(d, g->cs, NULL);
    if (g->pool) vkDestroyDescriptorPool(d, g->pool, NULL);
    if (g->dsl) vkDestroyDescriptorSetLayout(d, g->dsl, NULL);
    pg_buffer_destroy(g_gpu, &g->in);
    pg_buffer_destroy(g_gpu, &g->out);
}

/* Compiles the probe with the model's defines and sets up its descriptors over two host buffers. */
static bool lt_gpu_init(const lt_model *m, lt_gpu *g, pg_error *err)
{
    VkDevice d = g_gpu->device;
    char path[512];
    snprintf(path, sizeof path, "%s/gpu/shaders/light_terms.comp", PG_TEST_DIR);
    uint32_t *code = NULL;
    size_t words = 0;
    if (pg_shader_compile_user(path, VK_SHADER_STAGE_COMPUTE_BIT, m->defs, m->n_defs, g_gpu->vulkan12, &code, &words,
                               err) ||
        pg_shader_module_words(g_gpu, "light_terms", code, words, &g->cs, err)) {
        free(code);
        return false;
    }
    free(code);
    VkDescriptorSetLayoutBinding b[2] = {
        {.binding = 0, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = 1,
         .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
        {.binding = 1, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = 1,
         .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT}};
    VkDescriptorSetLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                          .bindingCount = 2, .pBindings = b};
    VkDescriptorPoolSize ps = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2};
    VkDescriptorPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1,
                                     .poolSizeCount = 1, .pPoolSizes = &ps};
    if (vkCreateDescriptorSetLayout(d, &li, NULL, &g->dsl) || vkCreateDescriptorPool(d, &pi, NULL, &g->pool)) {
        snprintf(err->msg, sizeof err->msg, "descriptor set layout or pool");
        return false;
    }
    VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                      .descriptorPool = g->pool, .descriptorSetCount = 1, .pSetLayouts = &g->dsl};
    if (vkAllocateDescriptorSets(d, &ai, &g->set)) {
        snprintf(err->msg, sizeof err->msg, "descriptor set");
        return false;
    }
    if (pg_pipeline_layout_create(g_gpu, 1, &g->dsl, 4, &g->layout, err) ||
        pg_compute_pipeline_create(g_gpu, g->layout, g->cs, "light_terms", &g->pipe, err) ||
        pg_buffer_create(g_gpu, CASES * sizeof(lt_case), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, "light_terms.cases",
                         &g->in, err) ||
        pg_buffer_create(g_gpu, CASES * 6 * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, "light_terms.sums", &g->out,
                         err))
        return false;
    VkDescriptorBufferInfo bi[2] = {{g->in.buffer, 0, VK_WHOLE_SIZE}, {g->out.buffer, 0, VK_WHOLE_SIZE}};
    VkWriteDescriptorSet w[2];
    for (int k = 0; k < 2; k++)
        w[k] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = g->set,
                                      .dstBinding = (uint32_t)k, .descriptorCount = 1,
                                      .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &bi[k]};
    vkUpdateDescriptorSets(d, 2, w, 0, NULL);
    return true;
}

static bool lt_gpu_run(lt_gpu *g, uint32_t count, pg_error *err)
{
    VkCommandBuffer cmd;
    if (pg_gpu_begin_once(g_gpu, &cmd, err)) return false;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, g->pipe);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, g->layout, 0, 1, &g->set, 0, NULL);
    vkCmdPushConstants(cmd, g->layout, PG_PUSH_STAGES, 0, 4, &count);
    vkCmdDispatch(cmd, (count + 63) / 64, 1, 1);
    pg_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    return pg_gpu_end_once(g_gpu, cmd, err) == PG_OK;
}

/* The shader's Case: P, N, V, albedo, mat, a0, b0, a1, b1 (9 vec4). */
static void pack(const lt_case *c, float *dst)
{
    const float *src[9] = {c->P, c->N, c->V, c->albedo, c->mat, c->a[0], c->b[0], c->a[1], c->b[1]};
    for (int k = 0; k < 9; k++) memcpy(dst + 4 * k, src[k], 16);
}

static bool same_bits(const float *x, const float *y)
{
    return memcmp(x, y, 3 * sizeof(float)) == 0;
}

static void check_model(const lt_model *m, const lt_case *cases)
{
    lt_gpu g = {0};
    pg_error err = {0};
    bool ok = lt_gpu_init(m, &g, &err);
    if (ok) {
        for (uint32_t i = 0; i < CASES; i++) pack(&cases[i], (float *)g.in.mapped + 36 * i);
        ok = lt_gpu_run(&g, CASES, &err);
    }
    CHECK_MSG(ok, "%s: %s", m->name, err.msg);
    if (!ok) {
        lt_gpu_free(&g);
        return;
    }
    const float *sums = g.out.mapped;
    uint32_t not_same = 0, pairs_differ = 0, off = 0, checked = 0, head_on = 0, no_pairs = 0;
    double worst = 0, worst_head_on = 0;
    for (uint32_t i = 0; i < CASES; i++) {
        const float *o = sums + 24 * i; /* select diffuse, specular; early return; pairs (w: has them) */
        if (!same_bits(o, o + 8) || !same_bits(o + 4, o + 12)) not_same++;
        if (m->pairs && o[23] != 1.0f) no_pairs++;
        if (m->pairs && !same_bits(o, o + 16)) pairs_differ++;
        double diff[3], spec[3], scale;
        bool edge;
        expect(m, &cases[i], diff, spec, &scale, &edge);
        if (edge) continue;
        checked++;
        bool on_point = !memcmp(cases[i].a[0], cases[i].P, 12) || !memcmp(cases[i].a[1], cases[i].P, 12);
        head_on += on_point;
        for (int k = 0; k < 3; k++) {
            double prior = cases[i].mat[2]; /* the sum before the lights: two more roundings of it */
            /* Blinn-Phong's (N.H)^n multiplies the rounding of N.H by n: 2 ulp of it per unit of n */
            double spec_rel = REL + (m->blinn_phong ? cases[i].albedo[3] * 0x1p-22 : 0);
            double u = fmax(fabs(o[k] - (prior + diff[k])) /
                                (REL * fabs(diff[k]) + ABS * scale + 0x1p-22 * (prior + diff[k]) + 1e-30),
                            fabs(o[4 + k] - spec[k]) / (spec_rel * fabs(spec[k]) + ABS * scale + 1e-30));
            if (!(u <= 1)) {
                if (off++ < 5)
                    fprintf(stderr, "%s case %u channel %d: diffuse %.9g specular %.9g, expected %.9g %.9g\n",
                            m->name, i, k, o[k], o[4 + k], prior + diff[k], spec[k]);
            }
            if (!(u <= worst)) worst = u;
            if (on_point && !(u <= worst_head_on)) worst_head_on = u;
        }
    }
    printf("%s: %u cases (%u checked against double, %u with a light on the point): worst bound usage %.3g (on the "
           "point %.3g); the early-return form and the pairs differ from the select form in %u and %u\n",
           m->name, CASES, checked, head_on, worst, worst_head_on, not_same, m->pairs ? pairs_differ : 0u);
    CHECK_MSG(off == 0, "%s: %u channels outside %g |expected| + %g scale", m->name, off, REL, ABS);
    CHECK_MSG(checked > CASES * 9 / 10 && head_on > CASES / 8, "%s: %u checked, %u on the point", m->name, checked,
              head_on);
    CHECK_MSG(not_same == 0, "%s: the early-return form differs from the select form in %u cases", m->name, not_same);
    CHECK_MSG(no_pairs == 0 && pairs_differ == 0, "%s: pairs missing (%u) or not bit-identical (%u)", m->name,
              no_pairs, pairs_differ);
    lt_gpu_free(&g);
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_light_terms", "PG_TEST_NO_GPU set");
    pg_gpu_desc gd = {.validation = true, .device_index = -1};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_light_terms: %s\n", err.msg);
        return 1;
    }
    lt_case *cases = malloc(CASES * sizeof *cases);
    CHECK(cases != NULL);
    if (cases) {
        const float inv_md2 = 1.0f / (PG_LIGHT_MIN_DISTANCE * PG_LIGHT_MIN_DISTANCE);
        for (uint32_t i = 0; i < CASES; i++) make_case(&cases[i], i, inv_md2);
        for (size_t k = 0; k < sizeof k_models / sizeof k_models[0]; k++) check_model(&k_models[k], cases);
    }
    free(cases);
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_light_terms");
}
