/* test_gpu_surface.c - glTF surface features on the GPU: vertex colours (COLOR_0 float
 * vec3, unorm8 vec4, unorm16 vec4 times the base colour factor), sampler wrap modes (REPEAT,
 * CLAMP_TO_EDGE, MIRRORED_REPEAT, mixed), NEAREST vs LINEAR magnification, minFilter without
 * mipmaps (level 0 only) vs with, textures read through TEXCOORD_1, and KHR_texture_transform
 * (offset, scale, rotation, all three, texCoord override); textured boxes whose transform or
 * TEXCOORD_1 selects the same UVs render bit-identically in every pipeline. The files come from
 * tests/corpus/gltf/features/gen_features.py: a quad [-1,1]^2 at z = 0 facing +Z, seen straight on
 * from (0,0,3) (fov 45, 64x64), rendered with forward_plus and deferred_oct16 in the albedo debug
 * view on lavapipe with validation and synchronization validation on (zero messages).
 * Each pixel inside the quad is compared with a CPU reference: the UV of the pixel centre
 * (affine on this quad, which is parallel to the image plane), the spec's T * R * S transform,
 * the wrap mode on texel indices (Vulkan's rules) and the nearest texel of level 0 (sRGB decoded;
 * the textures hold only 0 and 255, so linear 0 or 1); pixels within 0.12 texel of a texel edge
 * are skipped. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_harness.h"
#include "pass_list.h"
#include "scenario.h"
#include "test_util.h"

#define W 64
#define H 64
#define CAM_D 3.0
#define FOV_DEG 45.0

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;
static const char *k_pipelines[] = {"pipelines/forward_plus.json", "pipelines/deferred_oct16.json"};

typedef struct loaded {
    pg_scene *sc;
    pg_scene_gpu *sg;
} loaded;

static bool open_feature(const char *file, loaded *l)
{
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/corpus/gltf/features/%s", PG_TEST_DIR, file);
    pg_error err = {0};
    memset(l, 0, sizeof *l);
    if (pg_scene_load(path, &l->sc, &err) || pg_scene_gpu_create(g_gpu, l->sc, &l->sg, &err)) {
        CHECK_MSG(0, "%s: %s", file, err.msg);
        pg_scene_free(l->sc);
        l->sc = NULL;
        return false;
    }
    return true;
}

static void close_feature(loaded *l)
{
    pg_scene_gpu_destroy(g_gpu, l->sg);
    pg_scene_free(l->sc);
    memset(l, 0, sizeof *l);
}

/* The albedo (scene-linear HDR) image of the quad seen straight on. */
static bool render_albedo(const loaded *l, const char *pipeline, pg_th_frame *out)
{
    pg_frame_info fi = {.time = 0, .width = W, .height = H};
    fi.camera = (pg_camera){.position = {0, 0, (float)CAM_D}, .target = {0, 0, 0}, .up = {0, 1, 0},
                            .fov_y_deg = (float)FOV_DEG, .near_z = 0.5f, .far_z = 10.0f, .aspect = (float)W / H};
    fi.lights = pg_light_setup_object(l->sc, 8, 1);
    pg_param_override albedo = {"view", "albedo"};
    return pg_th_render(g_gpu, &g_reg, l->sg, pipeline, &albedo, 1, &fi, 1, false, out);
}

/* Pixel centre -> quad coordinates (s right, t down, both 0..1 over the quad); false outside
 * (with a margin of `m`). */
static bool quad_st(uint32_t px, uint32_t py, double m, double *s, double *t)
{
    double half = CAM_D * tan(FOV_DEG * M_PI / 360.0);
    double x = ((px + 0.5) / W * 2 - 1) * half * ((double)W / H);
    double y = -((py + 0.5) / H * 2 - 1) * half; /* y_ndc -1 is the top of the image */
    *s = (x + 1) / 2;
    *t = (1 - y) / 2;
    return *s > m && *s < 1 - m && *t > m && *t < 1 - m;
}

static const float *pixel(const pg_th_frame *f, uint32_t x, uint32_t y) { return f->hdr + ((size_t)y * f->w + x) * 4; }

static double srgb_to_linear(uint8_t c)
{
    double x = c / 255.0;
    return x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4);
}

/* ---- vertex colours -------------------------------------------------------------------------- */

static void check_vertex_colors(const char *file, const float factor[3])
{
    loaded l;
    if (!open_feature(file, &l)) return;
    CHECK_MSG(l.sg->colors.buffer != VK_NULL_HANDLE && l.sg->uv1.buffer == VK_NULL_HANDLE, "%s: streams", file);
    for (int p = 0; p < 2; p++) {
        pg_th_frame f;
        if (!render_albedo(&l, k_pipelines[p], &f)) {
            CHECK_MSG(0, "%s: %s render", file, k_pipelines[p]);
            continue;
        }
        uint32_t n = 0, bad = 0;
        double worst = 0;
        for (uint32_t y = 0; y < H; y++)
            for (uint32_t x = 0; x < W; x++) {
                double s, t;
                if (!quad_st(x, y, 0.03, &s, &t) || fabs(s - 0.5) < 0.03 || fabs(t - 0.5) < 0.03) continue;
                int k = (t >= 0.5) * 2 + (s >= 0.5); /* sub-quad TL, TR, BL, BR = vertices 4k.. */
                const float *c = l.sc->colors[4 * k];
                const float *g = pixel(&f, x, y);
                n++;
                double e = 0;
                for (int ch = 0; ch < 3; ch++) e = fmax(e, fabs(g[ch] - c[ch] * factor[ch]));
                worst = fmax(worst, e);
                if (e > 0.01) bad++;
            }
        printf("%s %s: %u quad pixels, %u off the vertex colour x factor by > 0.01 (max %.4f)\n", file,
               k_pipelines[p], n, bad, worst);
        CHECK_MSG(n > 1500 && bad == 0, "%s %s: %u of %u pixels off (max %.4f)", file, k_pipelines[p], bad, n, worst);
        pg_th_release(&f);
    }
    close_feature(&l);
}

/* ---- textured quads against a CPU reference ------------------------------------------------- */

typedef struct tex_ref {
    float uv[2][4][2];     /* per set: TL, TR, BL, BR */
    int set;               /* which TEXCOORD the texture reads */
    double m[6];           /* KHR_texture_transform, row-major 2x3 (identity when none) */
    pg_wrap wrap_s, wrap_t;
} tex_ref;

/* The spec's matrices: T (offset), R (rotation, counter-clockwise in UV space), S (scale);
 * M = T * R * S, the top two rows. */
static void spec_transform(double ox, double oy, double rot, double sx, double sy, double m[6])
{
    double T[9] = {1, 0, ox, 0, 1, oy, 0, 0, 1};
    double R[9] = {cos(rot), sin(rot), 0, -sin(rot), cos(rot), 0, 0, 0, 1};
    double S[9] = {sx, 0, 0, 0, sy, 0, 0, 0, 1};
    double TR[9], M[9];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            TR[r * 3 + c] = 0;
            for (int k = 0; k < 3; k++) TR[r * 3 + c] += T[r * 3 + k] * R[k * 3 + c];
        }
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            M[r * 3 + c] = 0;
            for (int k = 0; k < 3; k++) M[r * 3 + c] += TR[r * 3 + k] * S[k * 3 + c];
        }
    memcpy(m, M, 6 * sizeof(double));
}

/* Vulkan's wrap of a texel index (repeat, clamp to edge, mirrored repeat). */
static int wrap_index(int i, int n, pg_wrap w)
{
    if (w == PG_WRAP_CLAMP) return i < 0 ? 0 : i >= n ? n - 1 : i;
    if (w == PG_WRAP_MIRROR) {
        int t = ((i % (2 * n)) + 2 * n) % (2 * n);
        return t >= n ? 2 * n - 1 - t : t;
    }
    return ((i % n) + n) % n;
}

/* The nearest texel (linear RGB) the reference expects at quad point (s, t); false when the
 * sample point lies within `edge` texel of a texel boundary (either answer would be right). */
static bool reference_texel(const tex_ref *r, const pg_texture *tex, double s, double t, double edge, double out[3])
{
    const float(*c)[2] = r->uv[r->set];
    double u = c[0][0] + s * (c[1][0] - c[0][0]) + t * (c[2][0] - c[0][0]);
    double v = c[0][1] + s * (c[1][1] - c[0][1]) + t * (c[2][1] - c[0][1]);
    double u2 = r->m[0] * u + r->m[1] * v + r->m[2], v2 = r->m[3] * u + r->m[4] * v + r->m[5];
    const pg_mip *m0 = &tex->mips[0];
    double x = u2 * m0->width, y = v2 * m0->height;
    double fx = x - floor(x), fy = y - floor(y);
    if (fx < edge || fx > 1 - edge || fy < edge || fy > 1 - edge) return false;
    int ix = wrap_index((int)floor(x), (int)m0->width, r->wrap_s), iy = wrap_index((int)floor(y), (int)m0->height, r->wrap_t);
    const uint8_t *p = m0->rgba + ((size_t)iy * m0->width + ix) * 4;
    for (int k = 0; k < 3; k++) out[k] = srgb_to_linear(p[k]);
    return true;
}

static tex_ref plain_ref(float u0, float v0, float u1, float v1, pg_wrap ws, pg_wrap wt)
{
    tex_ref r;
    memset(&r, 0, sizeof r);
    const float c[4][2] = {{u0, v0}, {u1, v0}, {u0, v1}, {u1, v1}};
    memcpy(r.uv[0], c, sizeof c);
    memcpy(r.uv[1], c, sizeof c);
    r.m[0] = r.m[4] = 1;
    r.wrap_s = ws;
    r.wrap_t = wt;
    return r;
}

/* Renders `file` with both pipelines and compares every quad pixel with the reference. Returns
 * the forward_plus albedo image in *keep when keep is not NULL (caller frees). */
static void check_textured(const char *file, const tex_ref *r, float **keep)
{
    loaded l;
    if (keep) *keep = NULL;
    if (!open_feature(file, &l)) return;
    const pg_texture *tex = NULL;
    if (l.sc->n_materials && l.sc->materials[0].base_color_tex >= 0)
        tex = &l.sc->textures[l.sc->materials[0].base_color_tex];
    CHECK_MSG(tex != NULL, "%s: no base colour texture", file);
    /* one sampler per distinct state: the white texture's default + this texture's */
    bool default_state = tex && tex->sampler.wrap_s == PG_WRAP_REPEAT && tex->sampler.wrap_t == PG_WRAP_REPEAT &&
                         !tex->sampler.mag_nearest && !tex->sampler.min_nearest && tex->sampler.mip == PG_MIP_LINEAR;
    CHECK_MSG(l.sg->n_samplers == (default_state ? 1u : 2u), "%s: %u samplers", file, l.sg->n_samplers);
    for (int p = 0; p < 2 && tex; p++) {
        pg_th_frame f;
        if (!render_albedo(&l, k_pipelines[p], &f)) {
            CHECK_MSG(0, "%s: %s render", file, k_pipelines[p]);
            continue;
        }
        uint32_t n = 0, bad = 0;
        for (uint32_t y = 0; y < H; y++)
            for (uint32_t x = 0; x < W; x++) {
                double s, t, want[3];
                if (!quad_st(x, y, 0.02, &s, &t) || !reference_texel(r, tex, s, t, 0.12, want)) continue;
                const float *g = pixel(&f, x, y);
                n++;
                bool off = false;
                for (int k = 0; k < 3; k++) off = off || fabs(g[k] - want[k]) > 0.02;
                if (off && bad++ < 4)
                    printf("  %s %s: pixel %u,%u (s %.3f t %.3f): %.3f %.3f %.3f, want %.0f %.0f %.0f\n", file,
                           k_pipelines[p], x, y, s, t, g[0], g[1], g[2], want[0], want[1], want[2]);
            }
        printf("%s %s: %u pixels compared with the CPU reference, %u differ\n", file, k_pipelines[p], n, bad);
        CHECK_MSG(n > 800 && bad == 0, "%s %s: %u of %u pixels differ from the reference", file, k_pipelines[p], bad, n);
        if (keep && p == 0) {
            *keep = malloc((size_t)W * H * 4 * sizeof(float));
            if (*keep) memcpy(*keep, f.hdr, (size_t)W * H * 4 * sizeof(float));
        }
        pg_th_release(&f);
    }
    close_feature(&l);
}

/* The albedo at the pixel nearest to quad point (s, t), from an image kept by check_textured. */
static const float *at_st(const float *img, double s, double t)
{
    double half = CAM_D * tan(FOV_DEG * M_PI / 360.0);
    double x = s * 2 - 1, y = 1 - 2 * t;
    int px = (int)floor((x / (half * W / H) + 1) / 2 * W), py = (int)floor((-y / half + 1) / 2 * H);
    return img + ((size_t)py * W + px) * 4;
}

static bool is_rgb(const float *p, float r, float g, float b)
{
    return fabsf(p[0] - r) < 0.02f && fabsf(p[1] - g) < 0.02f && fabsf(p[2] - b) < 0.02f;
}

static void check_wrap(void)
{
    const struct {
        const char *file;
        pg_wrap s, t;
    } cases[] = {{"wrap_repeat.gltf", PG_WRAP_REPEAT, PG_WRAP_REPEAT},
                 {"wrap_clamp.gltf", PG_WRAP_CLAMP, PG_WRAP_CLAMP},
                 {"wrap_mirror.gltf", PG_WRAP_MIRROR, PG_WRAP_MIRROR},
                 {"wrap_clamp_mirror.gltf", PG_WRAP_CLAMP, PG_WRAP_MIRROR}};
    float *img[4];
    for (int i = 0; i < 4; i++) {
        tex_ref r = plain_ref(-1, -1, 2, 2, cases[i].s, cases[i].t);
        check_textured(cases[i].file, &r, &img[i]);
    }
    if (img[0] && img[1] && img[2] && img[3]) {
        /* the centre period (u, v in 0..1) is the texture itself in every mode; the periods
         * around it: repeat = a copy, clamp = the edge texels, mirror = the mirror image. Texture
         * (3x2): R G B / Y M W. Quad s = (u + 1) / 3. */
        for (int i = 0; i < 4; i++)
            CHECK_MSG(is_rgb(at_st(img[i], (0.5 / 3 + 1) / 3, (0.25 + 1) / 3), 1, 0, 0), "%s: centre period, texel (0,0)",
                      cases[i].file);
        double s_left = (-0.5 / 3 + 1) / 3, t_top = (0.25 + 1) / 3; /* u = -1/6 (left period, its last texel) */
        CHECK(is_rgb(at_st(img[0], s_left, t_top), 0, 0, 1));       /* repeat: texel 2 = blue */
        CHECK(is_rgb(at_st(img[1], s_left, t_top), 1, 0, 0));       /* clamp: texel 0 = red */
        CHECK(is_rgb(at_st(img[2], s_left, t_top), 1, 0, 0));       /* mirror: texel 0 = red */
        double s_far = (-2.5 / 3 + 1) / 3;                          /* u = -5/6: first texel of the left period */
        CHECK(is_rgb(at_st(img[0], s_far, t_top), 1, 0, 0));        /* repeat: texel 0 */
        CHECK(is_rgb(at_st(img[1], s_far, t_top), 1, 0, 0));       /* clamp: texel 0 */
        CHECK(is_rgb(at_st(img[2], s_far, t_top), 0, 0, 1));       /* mirror: texel 2 */
        /* mixed: S clamps like wrap_clamp, T mirrors like wrap_mirror (v = -1/4: row 0 mirrored = 0) */
        CHECK(is_rgb(at_st(img[3], s_left, (-0.25 + 1) / 3), 1, 0, 0));
        CHECK(is_rgb(at_st(img[3], s_left, (-0.75 + 1) / 3), 1, 1, 0)); /* v = -3/4: row 1 = yellow */
        CHECK(memcmp(img[0], img[1], (size_t)W * H * 16) != 0 && memcmp(img[1], img[2], (size_t)W * H * 16) != 0);
    }
    for (int i = 0; i < 4; i++) free(img[i]);
}

/* magnification: a 2x2 checker (black white / white black) over the quad */
static void check_mag(void)
{
    tex_ref r = plain_ref(0, 0, 1, 1, PG_WRAP_CLAMP, PG_WRAP_CLAMP);
    float *nearest = NULL;
    check_textured("mag_nearest.gltf", &r, &nearest);
    loaded l;
    if (!open_feature("mag_linear.gltf", &l)) {
        free(nearest);
        return;
    }
    for (int p = 0; p < 2; p++) {
        pg_th_frame f;
        if (!render_albedo(&l, k_pipelines[p], &f)) {
            CHECK_MSG(0, "mag_linear: %s render", k_pipelines[p]);
            continue;
        }
        uint32_t n = 0, mid = 0, mid_nearest = 0;
        for (uint32_t y = 0; y < H; y++)
            for (uint32_t x = 0; x < W; x++) {
                double s, t;
                if (!quad_st(x, y, 0.02, &s, &t)) continue;
                n++;
                float g = pixel(&f, x, y)[0];
                mid += g > 0.1f && g < 0.9f;
                if (nearest) {
                    float gn = nearest[((size_t)y * W + x) * 4];
                    mid_nearest += gn > 0.1f && gn < 0.9f;
                }
            }
        /* bilinear: the texel centres keep their value, the middle of the quad is their mean */
        const float *c = at_st(f.hdr, 0.5, 0.5), *tl = at_st(f.hdr, 0.25, 0.25), *tr = at_st(f.hdr, 0.75, 0.25);
        printf("mag_linear %s: %u of %u pixels between the texel values (nearest: %u); centre %.3f, texel centres %.3f "
               "%.3f\n",
               k_pipelines[p], mid, n, mid_nearest, c[0], tl[0], tr[0]);
        CHECK_MSG(mid > n / 3 && mid_nearest == 0, "linear %u / nearest %u intermediate pixels of %u", mid, mid_nearest, n);
        CHECK_MSG(fabsf(c[0] - 0.5f) < 0.06f, "linear centre %.3f", c[0]);
        CHECK_MSG(tl[0] < 0.1f && tr[0] > 0.9f, "linear texel centres %.3f %.3f", tl[0], tr[0]);
        pg_th_release(&f);
    }
    close_feature(&l);
    free(nearest);
}

/* minification (2x2 checker repeated 128 times): minFilter NEAREST samples level 0 only, so every
 * pixel is black or white; NEAREST_MIPMAP_NEAREST reaches the 1x1 level (linear mean 0.5) */
static void check_min(void)
{
    const char *files[2] = {"min_nearest.gltf", "min_nearest_mipmap.gltf"};
    for (int i = 0; i < 2; i++) {
        loaded l;
        if (!open_feature(files[i], &l)) continue;
        for (int p = 0; p < 2; p++) {
            pg_th_frame f;
            if (!render_albedo(&l, k_pipelines[p], &f)) {
                CHECK_MSG(0, "%s: %s render", files[i], k_pipelines[p]);
                continue;
            }
            uint32_t n = 0, binary = 0, grey = 0;
            for (uint32_t y = 0; y < H; y++)
                for (uint32_t x = 0; x < W; x++) {
                    double s, t;
                    if (!quad_st(x, y, 0.03, &s, &t)) continue;
                    float g = pixel(&f, x, y)[0];
                    n++;
                    binary += g < 0.02f || g > 0.98f;
                    grey += fabsf(g - 0.5f) < 0.05f;
                }
            printf("%s %s: %u pixels, %u black/white, %u grey\n", files[i], k_pipelines[p], n, binary, grey);
            if (i == 0) CHECK_MSG(n > 1500 && binary == n, "%s: %u of %u pixels black or white", files[i], binary, n);
            else CHECK_MSG(n > 1500 && grey == n, "%s: %u of %u pixels grey", files[i], grey, n);
            pg_th_release(&f);
        }
        close_feature(&l);
    }
}

static void check_texcoord1(void)
{
    /* TEXCOORD_0 covers the red texel, TEXCOORD_1 the blue one (2x1 texture) */
    tex_ref r = plain_ref(0.05f, 0.1f, 0.45f, 0.9f, PG_WRAP_REPEAT, PG_WRAP_REPEAT);
    const float c1[4][2] = {{0.55f, 0.1f}, {0.95f, 0.1f}, {0.55f, 0.9f}, {0.95f, 0.9f}};
    memcpy(r.uv[1], c1, sizeof c1);
    float *img = NULL;
    r.set = 1;
    check_textured("texcoord1.gltf", &r, &img);
    if (img) CHECK_MSG(is_rgb(at_st(img, 0.5, 0.5), 0, 0, 1), "texcoord1: not blue");
    free(img);
    check_textured("xform_texcoord.gltf", &r, &img); /* the transform's texCoord 1 */
    if (img) CHECK_MSG(is_rgb(at_st(img, 0.5, 0.5), 0, 0, 1), "xform_texcoord: not blue");
    free(img);
    r.set = 0;
    check_textured("texcoord0.gltf", &r, &img);
    if (img) CHECK_MSG(is_rgb(at_st(img, 0.5, 0.5), 1, 0, 0), "texcoord0: not red");
    free(img);
    loaded l;
    if (open_feature("texcoord0.gltf", &l)) { /* TEXCOORD_1 present, read by no texture: no stream */
        CHECK(l.sg->uv1.buffer == VK_NULL_HANDLE && l.sg->colors.buffer == VK_NULL_HANDLE);
        close_feature(&l);
    }
}

static void check_transform(void)
{
    /* texture 2x2: red green / blue white, REPEAT, NEAREST; UV 0..1 */
    const double q = M_PI / 2;
    const struct {
        const char *file;
        double ox, oy, rot, sx, sy;
        float quad[4][3]; /* the colour at the centres of the quad's TL, TR, BL, BR quarters */
    } cases[] = {
        {"xform_offset.gltf", 0.5, 0, 0, 1, 1, {{0, 1, 0}, {1, 0, 0}, {1, 1, 1}, {0, 0, 1}}},
        {"xform_scale.gltf", 0, 0, 0, 0.5, 0.5, {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}}},
        /* rotation 90 degrees counter-clockwise in UV space: (u, v) -> (v, -u): the picture turns
         * clockwise on screen (red to the top right, blue to the top left) */
        {"xform_rotation.gltf", 0, 0, q, 1, 1, {{0, 0, 1}, {1, 0, 0}, {1, 1, 1}, {0, 1, 0}}},
        /* T * R * S (scale first): (u, v) -> (v, 1 - u / 2): top blue, bottom white */
        {"xform_all.gltf", 0, 1, q, 0.5, 1, {{0, 0, 1}, {0, 0, 1}, {1, 1, 1}, {1, 1, 1}}},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        tex_ref r = plain_ref(0, 0, 1, 1, PG_WRAP_REPEAT, PG_WRAP_REPEAT);
        spec_transform(cases[i].ox, cases[i].oy, cases[i].rot, cases[i].sx, cases[i].sy, r.m);
        float *img = NULL;
        check_textured(cases[i].file, &r, &img);
        if (!img) continue;
        const double st[4][2] = {{0.25, 0.25}, {0.75, 0.25}, {0.25, 0.75}, {0.75, 0.75}};
        for (int k = 0; k < 4; k++) {
            const float *p = at_st(img, st[k][0], st[k][1]);
            CHECK_MSG(is_rgb(p, cases[i].quad[k][0], cases[i].quad[k][1], cases[i].quad[k][2]),
                      "%s: quarter %d is %.2f %.2f %.2f", cases[i].file, k, p[0], p[1], p[2]);
        }
        free(img);
    }
}

/* ---- textured boxes: transform and TEXCOORD_1 change nothing when they select the same UVs ----
 * box_plain / box_xform (identity KHR_texture_transform) / box_uv1 (the texture on TEXCOORD_1,
 * TEXCOORD_0 scrambled), fully shaded from an oblique camera (three faces, mip transitions,
 * triangle edges): every pipeline's HDR image of box_xform and box_uv1 must be bit-identical to
 * its box_plain image. Sampling with implicit derivatives of a coordinate computed inside the
 * material's branches gave lavapipe seams and noise along triangle edges here (175 pixels off
 * by up to 104 display steps with naive). */
static void check_boxes(void)
{
    static const char *const files[] = {"box_plain.gltf", "box_xform.gltf", "box_uv1.gltf"};
    static const char *const pipes[] = {"pipelines/naive.json",          "pipelines/forward_plus.json",
                                        "pipelines/deferred.json",       "pipelines/deferred_packed.json",
                                        "pipelines/deferred_oct16.json", "pipelines/visibility.json",
                                        "pipelines/reference.json"};
    enum { NP = sizeof pipes / sizeof pipes[0] };
    pg_th_frame plain[NP];
    memset(plain, 0, sizeof plain);
    for (int fi_ = 0; fi_ < 3; fi_++) {
        loaded l;
        if (!open_feature(files[fi_], &l)) return;
        pg_frame_info fi = {.time = 0, .width = W, .height = H};
        fi.camera = (pg_camera){.position = {2.6f, 2.0f, 3.4f}, .target = {0, 0, 0}, .up = {0, 1, 0},
                                .fov_y_deg = (float)FOV_DEG, .near_z = 0.5f, .far_z = 20.0f, .aspect = (float)W / H};
        fi.lights = pg_light_setup_object(l.sc, 8, 1);
        for (int p = 0; p < NP; p++) {
            pg_th_frame f;
            if (!pg_th_render(g_gpu, &g_reg, l.sg, pipes[p], NULL, 0, &fi, 1, false, &f)) {
                CHECK_MSG(0, "%s: %s render", files[fi_], pipes[p]);
                continue;
            }
            if (fi_ == 0) {
                plain[p] = f;
                continue;
            }
            if (plain[p].hdr) {
                uint32_t d = pg_th_differ_pixels(&f, &plain[p]);
                double peak = 0, m = pg_th_max_abs(&f, &plain[p], &peak);
                printf("%s vs box_plain, %s: %u pixels differ (max %.4g, peak %.4g)\n", files[fi_], pipes[p], d, m, peak);
                CHECK_MSG(pg_th_hdr_identical(&f, &plain[p]), "%s %s: %u pixels differ from box_plain (max %.4g)",
                          files[fi_], pipes[p], d, m);
            }
            pg_th_release(&f);
        }
        close_feature(&l);
    }
    for (int p = 0; p < NP; p++) pg_th_release(&plain[p]);
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_surface", "PG_TEST_NO_GPU set");
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_surface: %s\n", err.msg);
        return 1;
    }
    const float white[3] = {1, 1, 1}, half_green[3] = {1, 0.5f, 1};
    check_vertex_colors("vcolor_float3.gltf", white);
    check_vertex_colors("vcolor_unorm8.gltf", white);
    check_vertex_colors("vcolor_unorm16.gltf", half_green);
    check_wrap();
    check_mag();
    check_min();
    check_texcoord1();
    check_transform();
    check_boxes();
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_surface");
}
