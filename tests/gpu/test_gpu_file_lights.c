/* test_gpu_file_lights.c - a scene file's own KHR_lights_punctual lights light it
 * (tests/corpus/gltf/lights/, gen_lights.py), on the Vulkan device with the validation layer and
 * synchronization validation on (zero messages), 160x90, the default object view (the floor is
 * flat: seen from above), Lambert shading (the scene's "auto" model set so; the pbr BRDF under
 * these lights is test_gpu_pbr's):
 *  1. rgb_points.gltf: three coloured point lights (red with range 4, green and blue without).
 *     The reference (rgba32f, reach infinite) equals a CPU evaluation of the extension's model at
 *     the floor point under each pixel centre (colour x intensity / pi, x N.L, x the window
 *     clamp(1 - (d/range)^4, 0, 1)^2 for the ranged light, / max(d^2, dmin^2), + the object
 *     ambient 0.02, times albedo 0.8) within 1e-4 relative (float rounding); the pixel under
 *     each lamp is dominated (3x) by the lamp's colour.
 *  2. naive, forward_plus, deferred and visibility (light_cutoff 1e-4: the unranged lights stop
 *     where they add < 1e-4) are within 2e-3 |ref| + 2 x 1e-4 x 0.8 (the cut-off of the two
 *     unranged lights, albedo 0.8) + the rgba16f rounding; forward_plus is
 *     bit-identical to naive. A light_cutoff of 0.05 is a measurably worse approximation (the
 *     knob works), still within 2 x 0.05 x 0.8 of the reference.
 *  3. sun.gltf: a directional light of 2 lux lights every floor pixel the box does not hide alike:
 *     0.8 x (2 / pi x cos 30 deg + 0.02) within 1e-4 relative.
 *  4. spot.gltf: a spot light (inner 0.3, outer 0.5 rad) pointing down: the reference equals the CPU
 *     model with the extension's cone (clamp(cos x scale + offset, 0, 1)^2) within 1e-4 relative;
 *     more than half of the floor is outside the cone and gets the ambient term alone; every
 *     deterministic pipeline (naive, forward_plus, the three deferred, visibility, the lightcut)
 *     is within its documented per-pixel bound of the reference plus the cut-off and rgba16f terms
 *     of 2; mixed.gltf (a point light, a spot, a sun) likewise; in both, visibility and
 *     deferred_oct16 are byte-identical with tile_lights=false (the tiled loop leaves out the spot
 *     lights whose cone misses a tile: they add exactly 0).
 *  5. spots.gltf: 96 spot lights of every orientation, outer cones 0.02 rad to pi/2, three of them
 *     unranged: the cluster lists leave out a spot light where its cone misses a cluster
 *     (cluster_light.glsl pg_cone_reaches_sphere), so forward_plus stays bit-identical to naive
 *     only if that test never drops a light from a cluster where it lights a pixel; every
 *     pipeline within its bound of the reference (cut-off of three unranged lights), the tiled
 *     loops byte-identical to the per-pixel ones; and again through an orthographic camera. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accuracy_bounds.h"
#include "default_view.h"
#include "gpu_harness.h"
#include "pass_list.h"
#include "test_util.h"

#define W 160
#define H 90
#define ALBEDO 0.8
#define AMBIENT 0.02

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

typedef pg_th_scene loaded;

static bool load(const char *file, loaded *out)
{
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", "lights", file);
    /* the extension's light model with Lambert's BRDF (pbr: test_gpu_pbr) */
    return pg_th_file_open(g_gpu, path, W, H, PG_SHADING_LAMBERT, out);
}

static void unload(loaded *l)
{
    pg_th_scene_close(g_gpu, l);
}

/* the extension's model at a floor point (normal +Y), infinite reach for unranged lights */
static void cpu_shade(const pg_scene *s, const double p[3], double out[3])
{
    double sum[3] = {AMBIENT, AMBIENT, AMBIENT};
    for (uint32_t i = 0; i < s->n_lights; i++) {
        const pg_scene_light *L = &s->lights[i];
        double k = L->intensity / 3.14159265358979, w = 0, ndl;
        if (L->type == PG_LIGHT_DIRECTIONAL) {
            ndl = fmax(-L->direction[1], 0.0);
            w = ndl;
        } else {
            double d[3] = {L->position[0] - p[0], L->position[1] - p[1], L->position[2] - p[2]};
            double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            ndl = fmax(d[1] / sqrt(d2), 0.0);
            double win = 1;
            if (L->range > 0) {
                double t = d2 / ((double)L->range * L->range);
                win = fmin(fmax(1 - t * t, 0.0), 1.0);
                win *= win;
            }
            w = ndl * win / fmax(d2, 1e-4);
            if (L->type == PG_LIGHT_SPOT) { /* the extension's cone: clamp(cd scale + offset, 0, 1)^2 */
                double cd = -(L->direction[0] * d[0] + L->direction[1] * d[1] + L->direction[2] * d[2]) / sqrt(d2);
                double ci = cos(L->inner_cone), co = cos(L->outer_cone), sc = 1.0 / fmax(ci - co, 1e-3);
                double t = fmin(fmax(cd * sc - co * sc, 0.0), 1.0);
                w *= t * t;
            }
        }
        for (int c = 0; c < 3; c++) sum[c] += L->color[c] * k * w;
    }
    for (int c = 0; c < 3; c++) out[c] = ALBEDO * sum[c];
}

static bool render(const loaded *l, const char *pipe, const pg_param_override *sets, uint32_t n, pg_th_frame *f)
{
    bool ok = pg_th_render(g_gpu, &g_reg, l->sg, pipe, sets, n, &l->fi, 1, false, f);
    CHECK_MSG(ok, "%s: render failed", pipe);
    return ok;
}

/* every floor pixel of the reference against the CPU model; returns the pixels compared */
static uint32_t ref_vs_cpu(const char *label, const loaded *l, const pg_th_frame *ref, uint32_t *unlit)
{
    uint32_t n = 0, bad = 0;
    double worst = 0;
    *unlit = 0;
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            double p[3], e[3];
            if (!pg_th_floor_point(&l->fi, x, y, false, p)) continue;
            cpu_shade(l->scene, p, e);
            const float *g = ref->hdr + ((size_t)y * W + x) * 4;
            n++;
            if (e[0] == ALBEDO * AMBIENT && e[1] == ALBEDO * AMBIENT && e[2] == ALBEDO * AMBIENT) (*unlit)++;
            for (int c = 0; c < 3; c++) {
                double rel = fabs(g[c] - e[c]) / fmax(e[c], 1e-6);
                worst = fmax(worst, rel);
                if (rel > 1e-4) bad++;
            }
        }
    printf("%s: reference vs the CPU model: %u floor pixels (%u outside every light), worst relative %.3g\n", label, n,
           *unlit, worst);
    CHECK_MSG(n > W * H / 4 && bad == 0, "%s: reference vs CPU: %u of %u channels off by > 1e-4 (worst %.3g)", label,
              bad, 3 * n, worst);
    return n;
}

/* every deterministic pipeline against the reference (pg_th_pipelines_vs_ref) with the cut-off of two
 * unranged lights (2 x 1e-4 x albedo) */
static void pipelines_vs_ref(const char *label, const loaded *l, const pg_th_frame *ref)
{
    pg_th_pipelines_vs_ref(g_gpu, &g_reg, l->sg, &l->fi, ref, NULL, label, 2 * 1e-4 * ALBEDO);
}

/* the tiled loop leaves out spot lights whose cone misses the tile (shading.glsl
 * pg_spot_reaches_sphere): visibility and deferred_oct16 give the same bytes with the per-pixel
 * loop (tile_lights=false), which evaluates every light of the cluster */
static void tile_cone_identical(const char *label, const loaded *l)
{
    static const char *const pipes[] = {"pipelines/visibility.json", "pipelines/deferred_oct16.json"};
    pg_param_override off = {"tile_lights", "false"};
    for (int k = 0; k < 2; k++) {
        pg_th_frame a, b;
        if (!render(l, pipes[k], NULL, 0, &a)) continue;
        if (render(l, pipes[k], &off, 1, &b)) {
            CHECK_MSG(pg_th_hdr_identical(&a, &b), "%s: %s: the tiled loop differs from the per-pixel loop", label,
                      pipes[k]);
            pg_th_release(&b);
        }
        pg_th_release(&a);
    }
}

static void spot(const loaded *l)
{
    pg_th_frame ref;
    if (!render(l, "pipelines/reference.json", NULL, 0, &ref)) return;
    uint32_t unlit = 0, n = ref_vs_cpu("spot", l, &ref, &unlit);
    /* the cone (outer 0.5 rad from 3 units up: radius 1.64) lights a disc: most of the floor is outside */
    CHECK_MSG(n > 0 && unlit > n / 2 && unlit < n, "spot: %u of %u floor pixels outside the cone", unlit, n);
    pipelines_vs_ref("spot", l, &ref);
    tile_cone_identical("spot", l);
    pg_th_release(&ref);
}

static void rgb_points(const loaded *l)
{
    pg_th_frame ref;
    if (!render(l, "pipelines/reference.json", NULL, 0, &ref)) return;
    /* 1. the reference against the CPU model, every floor pixel */
    uint32_t unlit = 0;
    ref_vs_cpu("rgb_points", l, &ref, &unlit);
    /* the pixel under each lamp is the lamp's colour */
    for (uint32_t i = 0; i < l->scene->n_lights; i++) {
        const pg_scene_light *L = &l->scene->lights[i];
        int dom = L->color[0] > 0 ? 0 : L->color[1] > 0 ? 1 : 2;
        uint32_t bx = 0, by = 0;
        double best = 1e30;
        for (uint32_t y = 0; y < H; y++)
            for (uint32_t x = 0; x < W; x++) {
                double p[3];
                if (!pg_th_floor_point(&l->fi, x, y, false, p)) continue;
                double d = hypot(p[0] - L->position[0], p[2] - L->position[2]);
                if (d < best) best = d, bx = x, by = y;
            }
        const float *g = ref.hdr + ((size_t)by * W + bx) * 4;
        bool ok = true;
        for (int c = 0; c < 3; c++)
            if (c != dom) ok = ok && g[dom] > 3 * g[c];
        CHECK_MSG(ok, "light %u (%s): pixel (%u,%u) = (%g,%g,%g) not dominated by channel %d", i, L->name, bx, by,
                  g[0], g[1], g[2], dom);
    }
    /* 2. the pipelines with the cut-off against the reference */
    static const char *const pipes[] = {"pipelines/naive.json", "pipelines/forward_plus.json",
                                        "pipelines/deferred.json", "pipelines/visibility.json"};
    pg_th_frame naive;
    memset(&naive, 0, sizeof naive);
    for (size_t k = 0; k < sizeof pipes / sizeof pipes[0]; k++) {
        pg_th_frame f;
        if (!render(l, pipes[k], NULL, 0, &f)) continue;
        double peak = 0, worst_abs = pg_th_max_abs(&f, &ref, &peak), over = 0;
        for (size_t i = 0; i < (size_t)W * H; i++)
            for (int c = 0; c < 3; c++) {
                double r = ref.hdr[i * 4 + c], d = fabs(f.hdr[i * 4 + c] - r);
                double bound = 2e-3 * fabs(r) + 2 * 1e-4 * ALBEDO + 1e-6;
                over = fmax(over, d / bound);
            }
        printf("rgb_points: %s vs reference: max |d| %.3g (peak %.3g), bound usage %.3f\n", pipes[k], worst_abs, peak,
               over);
        CHECK_MSG(over <= 1.0, "%s: %.3f of the cut-off bound", pipes[k], over);
        if (k == 0) naive = f;
        else {
            if (k == 1) CHECK_MSG(pg_th_hdr_identical(&f, &naive), "forward_plus is not bit-identical to naive");
            pg_th_release(&f);
        }
    }
    /* the knob: a coarse cut-off is measurably worse, within its own bound */
    pg_param_override coarse = {"light_cutoff", "0.05"};
    pg_th_frame f;
    if (render(l, "pipelines/naive.json", &coarse, 1, &f)) {
        double peak = 0, d = pg_th_max_abs(&f, &ref, &peak), d_fine = pg_th_max_abs(&naive, &ref, &peak);
        printf("rgb_points: light_cutoff 0.05: max |d| %.3g (1e-4: %.3g)\n", d, d_fine);
        CHECK_MSG(d > 10 * d_fine && d <= 2 * 0.05 * ALBEDO + 2e-3 * peak, "cutoff 0.05: %g (1e-4: %g)", d, d_fine);
        pg_th_release(&f);
    }
    pg_th_release(&naive);
    pg_th_release(&ref);
}

static void sun(const loaded *l)
{
    pg_th_frame ref;
    if (!render(l, "pipelines/reference.json", NULL, 0, &ref)) return;
    double e = ALBEDO * (2.0 / 3.14159265358979 * cos(30.0 * 3.14159265358979 / 180.0) + AMBIENT);
    uint32_t n = 0, bad = 0;
    double worst = 0;
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            double p[3];
            if (!pg_th_floor_point(&l->fi, x, y, true, p)) continue;
            const float *g = ref.hdr + ((size_t)y * W + x) * 4;
            n++;
            for (int c = 0; c < 3; c++) {
                double rel = fabs(g[c] - e) / e;
                worst = fmax(worst, rel);
                if (rel > 1e-4) bad++;
            }
        }
    printf("sun: %u floor pixels vs %.6f: worst relative %.3g\n", n, e, worst);
    CHECK_MSG(n > W * H / 4 && bad == 0, "sun: %u of %u channels off (worst %.3g)", bad, 3 * n, worst);
    pg_th_release(&ref);
}

/* An animated colour or intensity past what the loaders take (KHR_animation_pointer clamps each
 * to its own range only) is clamped when the light's record is made: colour x intensity at most
 * PG_LIGHT_MAX_LUX for a directional light, whose record the light pass multiplies by 1e30, and
 * PG_LIGHT_MAX_CANDELA for the others, so a few of them still sum to a float (docs/scenes.md) */
static void animated_clamp(void)
{
    const struct {
        pg_light_type type;
        float color, intensity;
        double most;
    } cases[] = {
        {PG_LIGHT_DIRECTIONAL, 3.4e38f, 1e30f, PG_LIGHT_MAX_LUX},
        {PG_LIGHT_DIRECTIONAL, 1.0f, 1e9f, PG_LIGHT_MAX_LUX},
        {PG_LIGHT_POINT, 3.4e38f, 1e30f, PG_LIGHT_MAX_CANDELA},
        {PG_LIGHT_SPOT, 1e20f, 1e20f, PG_LIGHT_MAX_CANDELA},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        pg_scene_light L;
        memset(&L, 0, sizeof L);
        L.type = cases[i].type;
        L.color[0] = cases[i].color, L.color[1] = 0.5f * cases[i].color, L.color[2] = 0.0f;
        L.intensity = cases[i].intensity;
        L.outer_cone = 0.5f;
        L.direction[1] = -1.0f;
        pg_gpu_file_light g;
        pg_gpu_file_light_from(&L, &g);
        const double peak = g.color_type[0] * 3.14159265358979;
        CHECK_MSG(isfinite(g.color_type[0]) && isfinite(g.color_type[1]) && peak <= cases[i].most * 1.0001 &&
                      peak >= cases[i].most * 0.9999 && fabs(g.color_type[1] / g.color_type[0] - 0.5) < 1e-5,
                  "case %zu: record colour (%g, %g, %g): peak x pi %g, want %g", i, g.color_type[0], g.color_type[1],
                  g.color_type[2], peak, cases[i].most);
    }
    /* within the limits nothing changes */
    pg_scene_light L;
    memset(&L, 0, sizeof L);
    L.type = PG_LIGHT_DIRECTIONAL;
    L.color[0] = L.color[1] = L.color[2] = 1.0f;
    L.intensity = 1.2e5f;
    pg_gpu_file_light g;
    pg_gpu_file_light_from(&L, &g);
    CHECK(g.color_type[0] == 1.2e5f / 3.14159265358979f);
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_file_lights", "PG_TEST_NO_GPU is set");
    animated_clamp();
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_file_lights: %s\n", err.msg);
        return 1;
    }
    loaded a, b;
    if (load("rgb_points.gltf", &a)) rgb_points(&a);
    unload(&a);
    if (load("sun.gltf", &b)) sun(&b);
    unload(&b);
    loaded c, d;
    if (load("spot.gltf", &c)) spot(&c);
    unload(&c);
    if (load("mixed.gltf", &d)) { /* a point light, a spot and a sun: every exact pipeline and the lightcut */
        pg_th_frame ref;
        if (render(&d, "pipelines/reference.json", NULL, 0, &ref)) {
            pipelines_vs_ref("mixed", &d, &ref);
            tile_cone_identical("mixed", &d);
            pg_th_release(&ref);
        }
    }
    unload(&d);
    loaded e;
    if (load("spots.gltf", &e)) { /* the cone tests of the light assignment on a hostile set */
        pg_th_frame ref;
        if (render(&e, "pipelines/reference.json", NULL, 0, &ref)) {
            pg_th_pipelines_vs_ref(g_gpu, &g_reg, e.sg, &e.fi, &ref, NULL, "spots", 3 * 1e-4 * ALBEDO);
            tile_cone_identical("spots", &e);
            pg_th_release(&ref);
        }
        /* the same view orthographic, 14 units high: the clusters are boxes of parallel rays */
        e.fi.camera.ortho_height = 14.0f;
        if (render(&e, "pipelines/reference.json", NULL, 0, &ref)) {
            pg_th_pipelines_vs_ref(g_gpu, &g_reg, e.sg, &e.fi, &ref, NULL, "spots orthographic", 3 * 1e-4 * ALBEDO);
            pg_th_release(&ref);
        }
    }
    unload(&e);
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_file_lights");
}
