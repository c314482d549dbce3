/* test_gpu_pbr.c - the glTF metallic-roughness light model (shading "pbr": the default for a glTF
 * file's materials, shaders/lighting.glsl) on the Vulkan device with the validation layer and
 * synchronization validation on (zero messages), 160x90, the scenes of tests/corpus/gltf/pbr/
 * (gen_pbr.py) with their own point lights:
 *  1. patches.gltf (a floor of four patches: rough and glossy dielectrics, rough and glossy metals;
 *     two lights without a range): the reference (rgba32f, reach infinite) equals the BRDF of the
 *     glTF 2.0 specification evaluated in double on the CPU (renderer/common/brdf.c pg_brdf_pbr, the
 *     terms as the specification writes them) at the floor point under each pixel centre, plus the
 *     ambient term, within PBR_CPU_REL (2e-5) relative; the reference split over one dispatch per light
 *     (one running sum) is bit-identical to one dispatch; every deterministic pipeline is within
 *     its documented per-pixel bound of the reference (accuracy_bounds.h; the lightcut its stated
 *     2%; these two, whose surface is the pixel's ray, against the reference with surface=ray: on
 *     an NVIDIA GPU the raster reference's interpolated normal moves the glossy spheres' glints by
 *     twice visibility's bound) plus the rgba16f rounding and the two unranged lights' cut-off; forward_plus is
 *     bit-identical to naive, and so is the reference written in rgba16f.
 *  2. spheres.gltf (5 x 5 spheres, metallic 0..1 by row, roughness 0.1..0.9 by column): in every
 *     row the glossiest sphere's brightest pixel is more than twice the roughest one's; the rows
 *     differ in the highlight's colour (roughness 0.1 and 0.3: blue / red of the brightest pixel > 0.5
 *     for the dielectric, whose highlight is the white light's, < 0.35 for the metal, whose F0 is
 *     its base colour, 0.28); the pipelines within their bounds as in 1.
 *  3. textured.gltf: with no light and ambient 0.5, every floor pixel is (c_diff + F0) x 0.5 x
 *     occlusion of its texels (metallicRoughnessTexture B: metallic, occlusionTexture R) within
 *     1e-6 relative (float rounding); with its light, the unlit box (KHR_materials_unlit) is its base colour exactly in the
 *     reference, in every model (pbr, lambert, blinn_phong). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accuracy_bounds.h"
#include "brdf.h"
#include "default_view.h"
#include "gpu_harness.h"
#include "pass_list.h"
#include "test_util.h"

#define W 160
#define H 90
#define AMBIENT 0.02      /* the object view's ambient (pg_scene_default_view) */
#define DMIN2 1e-4        /* PG_LIGHT_MIN_DISTANCE^2 */
/* the reference vs the CPU's double evaluation, relative, per channel (measured 6.8e-6 on lavapipe) */
#define PBR_CPU_REL 2e-5

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

typedef pg_th_scene loaded;

static bool load(const char *file, loaded *out)
{
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", "pbr", file);
    if (!pg_th_file_open(g_gpu, path, W, H, -1, out)) return false;
    CHECK_MSG(out->scene->features.auto_shading == PG_SHADING_PBR, "%s: a glTF file's default model is not pbr", file);
    return true;
}

static void unload(loaded *l)
{
    pg_th_scene_close(g_gpu, l);
}

/* the ray through pixel (x, y)'s centre: origin o (on the near plane) and direction d (unnormalized) */
static void pixel_ray(const pg_frame_info *fi, uint32_t x, uint32_t y, double o[3], double d[3])
{
    double b[3];
    pg_th_pixel_ray(fi, x, y, o, b);
    for (int k = 0; k < 3; k++) d[k] = b[k] - o[k];
}

/* the floor point (y = 0) under the pixel; false when the ray misses it */
static bool floor_point(const pg_frame_info *fi, uint32_t x, uint32_t y, double p[3])
{
    double o[3], d[3];
    pixel_ray(fi, x, y, o, d);
    if (!(fabs(d[1]) > 1e-12)) return false;
    double t = -o[1] / d[1];
    for (int k = 0; k < 3; k++) p[k] = o[k] + t * d[k];
    return t > 0;
}

/* the glTF BRDF of material m at floor point p (normal +Y) under the scene's point lights, plus the
 * ambient term (c_diff + F0) x ambient */
static void cpu_shade(const loaded *l, const pg_material *m, const double p[3], double ambient, double out[3])
{
    const double N[3] = {0, 1, 0};
    double V[3] = {l->fi.camera.position[0] - p[0], l->fi.camera.position[1] - p[1], l->fi.camera.position[2] - p[2]};
    double vl = sqrt(V[0] * V[0] + V[1] * V[1] + V[2] * V[2]);
    for (int k = 0; k < 3; k++) V[k] /= vl;
    for (int c = 0; c < 3; c++) {
        double b = m->base_color[c], f0 = 0.04 + (b - 0.04) * m->metallic, cdiff = b * (1 - m->metallic);
        out[c] = (cdiff + f0) * ambient;
    }
    for (uint32_t i = 0; i < l->scene->n_lights; i++) {
        const pg_scene_light *L = &l->scene->lights[i];
        double d[3] = {L->position[0] - p[0], L->position[1] - p[1], L->position[2] - p[2]};
        double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], dl = sqrt(d2), Ld[3] = {d[0] / dl, d[1] / dl, d[2] / dl};
        double ndl = Ld[1];
        if (ndl <= 0) continue;
        for (int c = 0; c < 3; c++)
            out[c] += pg_brdf_pbr(Ld, V, N, m->base_color[c], m->metallic, m->roughness) * ndl * L->intensity *
                      L->color[c] / fmax(d2, DMIN2);
    }
}

static bool render(const loaded *l, const char *pipe, const pg_param_override *sets, uint32_t n, pg_th_frame *f)
{
    bool ok = pg_th_render(g_gpu, &g_reg, l->sg, pipe, sets, n, &l->fi, 1, false, f);
    CHECK_MSG(ok, "%s: render failed", pipe);
    return ok;
}

/* every deterministic pipeline against the reference (pg_th_pipelines_vs_ref, with the cut-off of the
 * unranged lights: n x light_cutoff 1e-4; visibility and the lightcut against the reference with
 * surface=ray), and the reference written in rgba16f bit-identical to naive */
static void pipelines_vs_ref(const char *label, const loaded *l, const pg_th_frame *ref)
{
    pg_param_override ray = {"surface", "ray"};
    pg_th_frame ray_ref;
    if (!render(l, "pipelines/reference.json", &ray, 1, &ray_ref)) return;
    pg_th_pipelines_vs_ref(g_gpu, &g_reg, l->sg, &l->fi, ref, &ray_ref, label, l->scene->n_lights * 1e-4);
    pg_th_release(&ray_ref);
    pg_param_override half = {"hdr_format", "rgba16f"};
    pg_th_frame naive, r16;
    if (render(l, "pipelines/naive.json", NULL, 0, &naive)) {
        if (render(l, "pipelines/reference.json", &half, 1, &r16)) {
            CHECK_MSG(pg_th_hdr_identical(&r16, &naive), "%s: the reference in rgba16f is not bit-identical to naive",
                      label);
            pg_th_release(&r16);
        }
        pg_th_release(&naive);
    }
}

static void patches(const loaded *l)
{
    pg_th_frame ref;
    if (!render(l, "pipelines/reference.json", NULL, 0, &ref)) return;
    uint32_t n = 0, bad = 0, per_patch[4] = {0, 0, 0, 0};
    double worst = 0;
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            double p[3], e[3];
            if (!floor_point(&l->fi, x, y, p) || fabs(p[0]) > 4.9 || fabs(p[2]) > 4.9) continue;
            if (fabs(p[0]) < 0.05 || fabs(p[2]) < 0.05) continue; /* a patch seam */
            int patch = (p[0] > 0 ? 1 : 0) + (p[2] > 0 ? 2 : 0);  /* gen_pbr.py: materials 0..3 */
            cpu_shade(l, &l->scene->materials[patch], p, AMBIENT, e);
            const float *g = ref.hdr + ((size_t)y * W + x) * 4;
            n++;
            per_patch[patch]++;
            for (int c = 0; c < 3; c++) {
                double rel = fabs(g[c] - e[c]) / fmax(e[c], 1e-6);
                worst = fmax(worst, rel);
                if (rel > PBR_CPU_REL) bad++;
            }
        }
    printf("patches: reference vs the glTF BRDF in double: %u floor pixels (%u %u %u %u a patch), worst relative "
           "%.3g (bound %.0e)\n",
           n, per_patch[0], per_patch[1], per_patch[2], per_patch[3], worst, PBR_CPU_REL);
    CHECK_MSG(per_patch[0] > 100 && per_patch[1] > 100 && per_patch[2] > 100 && per_patch[3] > 100 && bad == 0,
              "patches: %u of %u channels off by > %g (worst %.3g)", bad, 3 * n, PBR_CPU_REL, worst);
    /* one dispatch per light: the three running sums between dispatches give the same bits */
    pg_param_override split = {"lights_per_dispatch", "1"};
    pg_th_frame r1;
    if (render(l, "pipelines/reference.json", &split, 1, &r1)) {
        CHECK_MSG(pg_th_hdr_identical(&r1, &ref), "patches: the reference over 2 dispatches differs from 1");
        pg_th_release(&r1);
    }
    pipelines_vs_ref("patches", l, &ref);
    pg_th_release(&ref);
}

/* which sphere of spheres.gltf the pixel's ray meets first (row * 5 + col), -1 none or near a silhouette */
static int sphere_at(const loaded *l, uint32_t x, uint32_t y)
{
    double o[3], d[3];
    pixel_ray(&l->fi, x, y, o, d);
    double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    int best = -1;
    double best_t = 1e300;
    for (int s = 0; s < 25; s++) {
        double c[3] = {s % 5 - 2.0, s / 5 - 2.0, 0}, oc[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
        double t = (oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2]) / dl; /* closest approach along the unit ray */
        double m2 = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - t * t;
        if (m2 < 0.33 * 0.33 && t < best_t) best = s, best_t = t; /* well inside the silhouette (radius 0.4) */
    }
    return best;
}

static void spheres(const loaded *l)
{
    pg_th_frame ref;
    if (!render(l, "pipelines/reference.json", NULL, 0, &ref)) return;
    double peak[25] = {0}, sum[25] = {0}, peak_br[25] = {0}; /* peak_br: blue / red of the brightest pixel */
    uint32_t cnt[25] = {0};
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            int s = sphere_at(l, x, y);
            if (s < 0) continue;
            const float *g = ref.hdr + ((size_t)y * W + x) * 4;
            double lum = 0.2126 * g[0] + 0.7152 * g[1] + 0.0722 * g[2];
            if (lum > peak[s]) peak_br[s] = g[2] / fmax(g[0], 1e-30);
            peak[s] = fmax(peak[s], lum);
            sum[s] += lum;
            cnt[s]++;
        }
    for (int row = 0; row < 5; row++) {
        printf("spheres: metallic %.2f: peak", row / 4.0);
        for (int col = 0; col < 5; col++) printf(" %.4f", peak[row * 5 + col]);
        printf("; mean");
        for (int col = 0; col < 5; col++) printf(" %.4f", cnt[row * 5 + col] ? sum[row * 5 + col] / cnt[row * 5 + col] : 0);
        printf("\n");
        CHECK_MSG(cnt[row * 5] > 20 && cnt[row * 5 + 4] > 20 && peak[row * 5] > 2 * peak[row * 5 + 4],
                  "spheres: metallic %.2f: roughness 0.1 peak %.4f vs 0.9 peak %.4f", row / 4.0, peak[row * 5],
                  peak[row * 5 + 4]);
    }
    /* the rows differ in the highlight's colour: a dielectric's is the light's (white, F0 = 0.04, over
     * the orange diffuse), a metal's is its base colour's (blue / red 0.25 / 0.9) */
    for (int col = 0; col < 2; col++) {
        printf("spheres: roughness %.1f: highlight blue / red, metallic 0: %.3f, metallic 1: %.3f\n", 0.1 + 0.2 * col,
               peak_br[col], peak_br[20 + col]);
        CHECK_MSG(peak_br[col] > 0.5 && peak_br[20 + col] < 0.35, "spheres: roughness %.1f: highlight blue/red %.3f "
                  "(dielectric) %.3f (metal)", 0.1 + 0.2 * col, peak_br[col], peak_br[20 + col]);
    }
    pipelines_vs_ref("spheres", l, &ref);
    pg_th_release(&ref);
}

/* true when the pixel's ray meets the unlit box (-0.25..0.25, 0..0.5, -0.25..0.25) well inside a face
 * (grow 0), or comes near it (grow > 0: the box grown by that) */
static bool on_box(const loaded *l, uint32_t x, uint32_t y, double grow)
{
    double o[3], d[3];
    pixel_ray(&l->fi, x, y, o, d);
    const double lo[3] = {-0.23 - grow, 0.02 - grow, -0.23 - grow}, hi[3] = {0.23 + grow, 0.48 + grow, 0.23 + grow};
    double s0 = 0, s1 = 1;
    for (int k = 0; k < 3; k++) {
        if (fabs(d[k]) < 1e-300) {
            if (o[k] < lo[k] || o[k] > hi[k]) return false;
            continue;
        }
        double u = (lo[k] - o[k]) / d[k], v = (hi[k] - o[k]) / d[k];
        s0 = fmax(s0, fmin(u, v));
        s1 = fmin(s1, fmax(u, v));
    }
    return s0 < s1;
}

static void textured(loaded *l)
{
    /* 1. ambient alone: (c_diff + F0) x ambient x occlusion per texel quadrant */
    pg_frame_info lit = l->fi;
    l->fi.lights.count = l->fi.lights.file_count = 0;
    l->fi.lights.ambient = 0.5f;
    pg_th_frame f;
    if (render(l, "pipelines/reference.json", NULL, 0, &f)) {
        uint32_t n = 0, bad = 0, quads[4] = {0, 0, 0, 0};
        double worst = 0;
        for (uint32_t y = 0; y < H; y++)
            for (uint32_t x = 0; x < W; x++) {
                double p[3];
                if (!floor_point(&l->fi, x, y, p) || fabs(p[0]) > 1.95 || fabs(p[2]) > 1.95) continue;
                if (fabs(p[0]) < 0.05 || fabs(p[2]) < 0.05 || on_box(l, x, y, 0.05)) continue; /* seams, the box */
                bool metal = p[0] > 0, dark = p[2] > 0; /* u > 0.5: metal texel; v > 0.5: occlusion 64/255 */
                double occ = dark ? 64.0 / 255.0 : 1.0, e = 0.5 * occ * (metal ? 0.8 : 0.8 + 0.04);
                const float *g = f.hdr + ((size_t)y * W + x) * 4;
                quads[(metal ? 1 : 0) + (dark ? 2 : 0)]++;
                n++;
                for (int c = 0; c < 3; c++) {
                    double rel = fabs(g[c] - e) / e;
                    worst = fmax(worst, rel);
                    if (rel > 1e-6) bad++; /* exact up to float rounding (measured 4e-8) */
                }
            }
        printf("textured: ambient 0.5 alone: %u floor pixels (%u %u %u %u a quadrant) vs (c_diff + F0) x 0.5 x "
               "occlusion: worst relative %.3g\n",
               n, quads[0], quads[1], quads[2], quads[3], worst);
        CHECK_MSG(quads[0] > 50 && quads[1] > 50 && quads[2] > 50 && quads[3] > 50 && bad == 0,
                  "textured: %u of %u channels off (worst %.3g)", bad, 3 * n, worst);
        pg_th_release(&f);
    }
    /* 2. the unlit box is its base colour under the light, in every model */
    l->fi = lit;
    static const char *const models[] = {"pbr", "lambert", "blinn_phong"};
    for (int m = 0; m < 3; m++) {
        pg_param_override set = {"shading", models[m]};
        if (!render(l, "pipelines/reference.json", &set, 1, &f)) continue;
        uint32_t n = 0, bad = 0;
        const float want[3] = {0.2f, 0.9f, 0.3f};
        for (uint32_t y = 0; y < H; y++)
            for (uint32_t x = 0; x < W; x++) {
                if (!on_box(l, x, y, 0.0)) continue;
                const float *g = f.hdr + ((size_t)y * W + x) * 4;
                n++;
                if (g[0] != want[0] || g[1] != want[1] || g[2] != want[2]) bad++;
            }
        printf("textured: shading %s: %u unlit-box pixels, %u not exactly the base colour\n", models[m], n, bad);
        CHECK_MSG(n > 20 && bad == 0, "textured: %s: %u of %u unlit pixels off", models[m], bad, n);
        pg_th_release(&f);
    }
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_pbr", "PG_TEST_NO_GPU is set");
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_pbr: %s\n", err.msg);
        return 1;
    }
    loaded a, b, c;
    if (load("patches.gltf", &a)) patches(&a);
    unload(&a);
    if (load("spheres.gltf", &b)) spheres(&b);
    unload(&b);
    if (load("textured.gltf", &c)) textured(&c);
    unload(&c);
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_pbr");
}
