/* test_gpu_user_passes.c - the example user passes written only in JSON + GLSL (pipelines/examples/,
 * the `shader` pass type, docs/user-passes.md) on the Vulkan device with the validation layer and
 * synchronization validation on (zero messages), 160x90:
 *  1. tonemap (fullscreen): every pixel of the 8-bit output equals the CPU evaluation of
 *     tonemap.frag (exposure, extended Reinhard on luminance with white 4, sRGB) of the HDR image
 *     read back, within one 8-bit step; a second exposure moves the image as the formula says; the
 *     same curve as a compute pass (tonemap_stage=compute) gives the same bytes.
 *  2. bloom (compute: 3 downsamples, 2 upsample-adds, a composite): against the same pipeline with
 *     bloom_strength 0, the image's energy (sum of RGB) is kept within 2%, the brightest pixel
 *     loses energy and the ring 3-8 pixels around it gains some.
 *  3. ssao (compute on the deferred G-buffer; sun.gltf: a unit box on a flat floor): the occlusion
 *     term (ao_only, radius 1) averages below 0.85 on the floor within 0.25 of the box's foot and above 0.97
 *     on the floor farther than 1.5 from it.
 *  4. user_lighting (compute over the cluster lists; rgb_points.gltf: three point lights over a
 *     flat floor), both loops (per pixel; tiled, the lists culled per tile in shared memory):
 *     every floor pixel equals the CPU evaluation of the model (Lambert, (1 - (d/R)^2)^2 / (1 + d^2),
 *     R the range or the cut-off reach) within 2e-3 relative (the rgba16f target) + 1e-5.
 *  5. normals (the draw form: the scene's draws, passgraph's material code, the user's fragment
 *     shader): the HDR image is bit-identical to the naive pipeline's debug view "normal".
 *  6. vis_surface (a compute pass with "surface": "visibility": the surface rebuilt from the
 *     visibility buffer with visibility_surface.glsl): bit-identical to the visibility pipeline's
 *     debug views "normal" and "albedo". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_harness.h"
#include "pass_list.h"
#include "scene_gpu.h"
#include "test_util.h"

#define W 160
#define H 90

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

static bool render(const pg_th_scene *s, const char *pipe, const pg_param_override *sets, uint32_t n, pg_th_frame *f)
{
    bool ok = pg_th_render(g_gpu, &g_reg, s->sg, pipe, sets, n, &s->fi, 1, false, f);
    CHECK_MSG(ok, "%s: render failed", pipe);
    return ok;
}

static double srgb(double c)
{
    c = fmin(fmax(c, 0.0), 1.0);
    return c > 0.0031308 ? 1.055 * pow(c, 1.0 / 2.4) - 0.055 : c * 12.92;
}

/* tonemap.frag on the CPU: the worst difference in 8-bit steps over every pixel */
static double tonemap_worst(const pg_th_frame *f, double exposure, double white)
{
    double worst = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        double c[3], L;
        for (int k = 0; k < 3; k++) c[k] = fmin(fmax((double)f->hdr[i * 4 + k], 0.0), 65000.0) * exposure;
        L = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        double s = L > 0 ? (1 + L / (white * white)) / (1 + L) : 1;
        for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(srgb(c[k] * s) * 255.0 - f->ldr[i * 4 + k]));
    }
    return worst;
}

static void tonemap(const pg_th_scene *s)
{
    static const char *pipe = "pipelines/examples/tonemap/tonemap.json";
    pg_th_frame f;
    if (!render(s, pipe, NULL, 0, &f)) return;
    double worst = tonemap_worst(&f, 1.0, 4.0);
    printf("tonemap: 8-bit output vs the CPU curve: worst %.3f steps\n", worst);
    CHECK_MSG(worst <= 1.0, "tonemap: worst %.3f 8-bit steps from the CPU curve (bound 1)", worst);
    CHECK_MSG(tonemap_worst(&f, 2.0, 4.0) > 2.0, "tonemap: the check cannot tell exposure 2 from 1");
    pg_th_frame c;
    pg_param_override cs = {"tonemap_stage", "compute"};
    if (render(s, pipe, &cs, 1, &c)) {
        CHECK_MSG(!memcmp(c.ldr, f.ldr, (size_t)W * H * 4), "tonemap: the compute pass's image differs from the fullscreen one's");
        pg_th_release(&c);
    }
    pg_th_release(&f);
    pg_param_override e[2] = {{"exposure", "2"}, {"white", "1.5"}};
    if (!render(s, pipe, e, 2, &f)) return;
    worst = tonemap_worst(&f, 2.0, 1.5);
    CHECK_MSG(worst <= 1.0, "tonemap exposure 2, white 1.5: worst %.3f 8-bit steps (bound 1)", worst);
    pg_th_release(&f);
}

static double pixel_energy(const pg_th_frame *f, uint32_t x, uint32_t y)
{
    const float *p = f->hdr + ((size_t)y * W + x) * 4;
    return (double)p[0] + p[1] + p[2];
}

static void bloom(const pg_th_scene *s)
{
    static const char *pipe = "pipelines/examples/bloom/bloom.json";
    pg_param_override off = {"bloom_strength", "0"}, on = {"bloom_strength", "0.5"};
    pg_th_frame a, b;
    if (!render(s, pipe, &off, 1, &a)) return;
    if (!render(s, pipe, &on, 1, &b)) {
        pg_th_release(&a);
        return;
    }
    double ea = 0, eb = 0, peak = -1;
    uint32_t px = 0, py = 0;
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            double e = pixel_energy(&a, x, y);
            ea += e;
            eb += pixel_energy(&b, x, y);
            if (e > peak) peak = e, px = x, py = y;
        }
    double ring_a = 0, ring_b = 0;
    for (int dy = -8; dy <= 8; dy++)
        for (int dx = -8; dx <= 8; dx++) {
            int x = (int)px + dx, y = (int)py + dy;
            double r = sqrt((double)(dx * dx + dy * dy));
            if (x < 0 || y < 0 || x >= W || y >= H || r < 3 || r > 8) continue;
            ring_a += pixel_energy(&a, (uint32_t)x, (uint32_t)y);
            ring_b += pixel_energy(&b, (uint32_t)x, (uint32_t)y);
        }
    printf("bloom: energy %.4g -> %.4g (ratio %.4f); brightest pixel (%u, %u) %.4g -> %.4g; ring 3-8 px %.4g -> %.4g\n",
           ea, eb, eb / ea, px, py, peak, pixel_energy(&b, px, py), ring_a, ring_b);
    CHECK_MSG(fabs(eb / ea - 1) < 0.02, "bloom: energy ratio %.4f (bound 1 +- 0.02)", eb / ea);
    CHECK_MSG(pixel_energy(&b, px, py) < peak, "bloom: the brightest pixel did not lose energy");
    CHECK_MSG(ring_b > ring_a, "bloom: the ring around the brightest pixel gained no energy");
    pg_th_release(&a);
    pg_th_release(&b);
}

/* the floor point under pixel (x, y) the unit box of sun.gltf does not hide (pg_th_floor_point);
 * *edge gets its distance to the box's foot */
static bool floor_point(const pg_frame_info *fi, uint32_t x, uint32_t y, double p[3], double *edge)
{
    if (!pg_th_floor_point(fi, x, y, true, p)) return false;
    double dx = fmax(fabs(p[0]) - 0.5, 0.0), dz = fmax(fabs(p[2]) - 0.5, 0.0);
    *edge = sqrt(dx * dx + dz * dz);
    return true;
}

static void ssao(const pg_th_scene *s)
{
    pg_param_override o[2] = {{"ao_only", "true"}, {"ao_radius", "1"}};
    pg_th_frame f;
    if (!render(s, "pipelines/examples/ssao/ssao.json", o, 2, &f)) return;
    double near_sum = 0, far_sum = 0;
    uint32_t n_near = 0, n_far = 0;
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            double p[3], edge;
            if (!floor_point(&s->fi, x, y, p, &edge)) continue;
            double ao = f.hdr[((size_t)y * W + x) * 4];
            if (edge > 0.01 && edge < 0.25) near_sum += ao, n_near++;
            if (edge > 1.5) far_sum += ao, n_far++;
        }
    double an = n_near ? near_sum / n_near : 1, af = n_far ? far_sum / n_far : 0;
    printf("ssao: mean occlusion term %.3f on %u floor pixels at the box's foot, %.3f on %u open floor pixels\n", an,
           n_near, af, n_far);
    CHECK_MSG(n_near >= 20 && n_far >= 200, "ssao: too few floor pixels (%u near, %u far)", n_near, n_far);
    CHECK_MSG(an < 0.85, "ssao: the crease is not darker (%.3f, bound < 0.85)", an);
    CHECK_MSG(af > 0.97, "ssao: the open floor is occluded (%.3f, bound > 0.97)", af);
    pg_th_release(&f);
}

/* lighting.comp's model at a floor point (normal +Y), albedo 0.8, the object ambient 0.02 */
static void cpu_light(const pg_scene *sc, const double p[3], double out[3])
{
    double sum[3] = {0.02, 0.02, 0.02};
    for (uint32_t i = 0; i < sc->n_lights; i++) {
        pg_gpu_file_light g;
        pg_gpu_file_light_from(&sc->lights[i], &g);
        const double c[3] = {g.color_type[0], g.color_type[1], g.color_type[2]};
        double range = sc->lights[i].range;
        double R = range > 0 ? range : sqrt(fmax(c[0], fmax(c[1], c[2])) / 1e-4); /* light_animate.comp's reach */
        double d[3] = {sc->lights[i].position[0] - p[0], sc->lights[i].position[1] - p[1],
                       sc->lights[i].position[2] - p[2]};
        double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(dist < R) || dist <= 0) continue;
        double w = 1 - (dist / R) * (dist / R), f = w * w / (1 + dist * dist) * fmax(d[1] / dist, 0.0);
        for (int k = 0; k < 3; k++) sum[k] += c[k] * f;
    }
    for (int k = 0; k < 3; k++) out[k] = 0.8 * sum[k];
}

static void user_lighting(const pg_th_scene *s, const char *loop)
{
    pg_th_frame f;
    pg_param_override o = {"loop", loop};
    if (!render(s, "pipelines/examples/lighting/lighting.json", &o, 1, &f)) return;
    uint32_t n = 0, bad = 0;
    double worst = 0;
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            double p[3], e[3], edge;
            if (!floor_point(&s->fi, x, y, p, &edge)) continue;
            cpu_light(s->scene, p, e);
            const float *g = f.hdr + ((size_t)y * W + x) * 4;
            n++;
            for (int k = 0; k < 3; k++) {
                double u = fabs(g[k] - e[k]) / (2e-3 * e[k] + 1e-5);
                worst = fmax(worst, u);
                bad += u > 1;
            }
        }
    printf("user_lighting loop=%s: %u floor pixels vs the CPU model: worst bound usage %.3f\n", loop, n, worst);
    CHECK_MSG(n > W * H / 4 && bad == 0,
              "user_lighting loop=%s: %u of %u channels outside 2e-3 |cpu| + 1e-5 (worst usage %.3f)", loop, bad, 3 * n,
              worst);
    pg_th_release(&f);
}

static void normals(const pg_th_scene *s)
{
    pg_param_override v = {"view", "normal"};
    pg_th_frame a, b;
    if (!render(s, "pipelines/examples/normals/normals.json", NULL, 0, &a)) return;
    if (render(s, "pipelines/naive.json", &v, 1, &b)) {
        CHECK_MSG(pg_th_hdr_identical(&a, &b), "normals: the draw form differs from naive's view=normal in %u pixels",
                  pg_th_differ_pixels(&a, &b));
        pg_th_release(&b);
    }
    pg_th_release(&a);
}

static void vis_surface(const pg_th_scene *s)
{
    static const char *const views[] = {"normal", "albedo"};
    for (int k = 0; k < 2; k++) {
        pg_param_override v = {"view", views[k]}, a = {"albedo", k ? "true" : "false"};
        pg_th_frame f, ref;
        if (!render(s, "pipelines/examples/vis_surface/vis_surface.json", &a, 1, &f)) return;
        if (render(s, "pipelines/visibility.json", &v, 1, &ref)) {
            CHECK_MSG(pg_th_hdr_identical(&f, &ref), "vis_surface: %s differs from visibility's view=%s in %u pixels",
                      views[k], views[k], pg_th_differ_pixels(&f, &ref));
            pg_th_release(&ref);
        }
        pg_th_release(&f);
    }
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_user_passes", "PG_TEST_NO_GPU is set");
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_user_passes: %s\n", err.msg);
        return 1;
    }
    pg_th_scene atrium, sun, rgb;
    if (pg_th_scene_open(g_gpu, "atrium", "default", NULL, W, H, 256, &atrium)) {
        tonemap(&atrium);
        bloom(&atrium);
        normals(&atrium);
        vis_surface(&atrium);
        pg_th_scene_close(g_gpu, &atrium);
    }
    if (pg_th_file_open(g_gpu, "lights/sun.gltf", W, H, PG_SHADING_LAMBERT, &sun)) {
        ssao(&sun);
        pg_th_scene_close(g_gpu, &sun);
    }
    if (pg_th_file_open(g_gpu, "lights/rgb_points.gltf", W, H, PG_SHADING_LAMBERT, &rgb)) {
        user_lighting(&rgb, "pixel");
        user_lighting(&rgb, "tiled");
        pg_th_scene_close(g_gpu, &rgb);
    }
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_user_passes");
}
