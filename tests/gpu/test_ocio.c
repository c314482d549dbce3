/* test_ocio.c - colour management: the shipped OpenColorIO config, the C shim (core/color/ocio.h), the
 * display_ocio pass against OCIO's own CPU processor, and OpenEXR output (core/image/exr.h).
 *
 * (a) CPU only: the shipped config loads; its displays and views; the default display/view;
 *     unknown display / view errors list the available names; a missing, broken or incomplete
 *     config is an error naming the file; the CPU processor's values for each view (Standard is
 *     the sRGB curve of the clamped value, Raw the identity, Filmic a monotonic roll-off); the
 *     generated GLSL binds every sampler; a config with 1D / 2D / 3D LUTs yields those textures;
 *     EXR write + read round trips (float exact, half to the nearest half).
 * (b) GPU (lavapipe, validation + synchronization validation; any message fails): a grid of
 *     scene-linear values (0, 1e-6, ..., 0.18, 1, 1e3, 6e4 in every RGB combination) is written
 *     into the hdr image by the test's own pass type and displayed by display_ocio for EVERY view
 *     of every display of the shipped config, and for LUT-based views; the 8-bit result must be
 *     within 1 step of OCIO's CPU processor quantized to 8 bits (bound stated below), and the
 *     pass's two stages (compute, the default, and the full-screen fragment pass) give
 *     byte-identical images. Also:
 *     exposure, pass options vs. settings, errors at create, the EXR of the read-back HDR, and
 *     the default pipeline's Standard view against the display_tonemap clamp on the atrium.
 *
 * PG_TEST_NO_GPU=1 runs part (a) only (the valgrind run does).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "exr.h"
#include "graph_execute.h"
#include "image_util.h"
#include "ocio.h"
#include "pass_api.h"
#include "pass_list.h"
#include "render_session.h"
#include "scenario.h"
#include "shader.h"
#include "test_util.h"

/* GPU vs CPU bound: at most this many 8-bit steps on any channel of any grid pixel */
#define MAX_STEPS 1

static char g_tmp[PG_PATH_MAX];

static bool contains(const char *hay, const char *needle)
{
    return hay && needle && strstr(hay, needle) != NULL;
}

static void tmp_path(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "%s/%s", g_tmp, name);
}

static bool write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f) return false;
    bool ok = fputs(text, f) >= 0;
    return fclose(f) == 0 && ok;
}

static float srgb_oetf(float x)
{
    x = x < 0 ? 0 : x > 1 ? 1 : x;
    return x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1.0f / 2.4f) - 0.055f;
}

static int quantize(float x)
{
    if (!(x > 0)) return 0; /* NaN too */
    if (x >= 1) return 255;
    return (int)floorf(x * 255.0f + 0.5f);
}

static const char *const k_views[3] = {"Standard", "Filmic (ACES)", "Raw"};
static const char *const k_displays[2] = {"sRGB", "Rec.1886"};

/* ------------------------------------------------------------------ (a) CPU */

static void test_shipped_config(void)
{
    char path[PG_PATH_MAX];
    pg_data_path(path, sizeof path, PG_OCIO_SHIPPED_CONFIG);
    pg_ocio_config *cfg = NULL;
    pg_error err = {0};
    CHECK_MSG(pg_ocio_open(path, &cfg, &err) == PG_OK, "%s", err.msg);
    if (!cfg) return;
    printf("ocio: OpenColorIO %s, %s\n", pg_ocio_version(), pg_ocio_config_path(cfg));
    CHECK(pg_ocio_num_displays(cfg) == 2);
    for (uint32_t d = 0; d < 2; d++) {
        const char *dn = pg_ocio_display(cfg, d);
        CHECK_MSG(dn && !strcmp(dn, k_displays[d]), "display %u is '%s'", d, dn ? dn : "(null)");
        CHECK(pg_ocio_num_views(cfg, k_displays[d]) == 3);
        for (uint32_t v = 0; v < 3; v++) {
            const char *vn = pg_ocio_view(cfg, k_displays[d], v);
            CHECK_MSG(vn && !strcmp(vn, k_views[v]), "%s view %u is '%s'", k_displays[d], v, vn ? vn : "(null)");
        }
        const char *dv = pg_ocio_default_view(cfg, k_displays[d]);
        CHECK(dv && !strcmp(dv, "Standard"));
    }
    CHECK(pg_ocio_display(cfg, 2) == NULL);
    CHECK(pg_ocio_view(cfg, "sRGB", 3) == NULL);
    CHECK(pg_ocio_num_views(cfg, "Nope") == 0);
    const char *dd = pg_ocio_default_display(cfg);
    CHECK(dd && !strcmp(dd, "sRGB"));
    CHECK(pg_ocio_has_view(cfg, NULL, "Filmic (ACES)"));
    CHECK(pg_ocio_has_view(cfg, "Rec.1886", "Raw"));
    CHECK(!pg_ocio_has_view(cfg, NULL, "cluster_heat"));
    CHECK(!pg_ocio_has_view(cfg, "Nope", "Raw"));

    char d[128], v[128];
    CHECK(pg_ocio_resolve(cfg, NULL, "", d, sizeof d, v, sizeof v, &err) == PG_OK && !strcmp(d, "sRGB") &&
          !strcmp(v, "Standard"));
    CHECK(pg_ocio_resolve(cfg, "Rec.1886", "Raw", d, sizeof d, v, sizeof v, &err) == PG_OK &&
          !strcmp(d, "Rec.1886") && !strcmp(v, "Raw"));
    /* a name its buffer cannot hold is refused: cut, it could name another view of the config */
    err = (pg_error){0};
    CHECK(pg_ocio_resolve(cfg, "sRGB", "Filmic (ACES)", d, sizeof d, v, 8, &err) == PG_ERR_LIMIT);
    CHECK_MSG(contains(err.msg, "a name longer than 7 bytes"), "%s", err.msg);
    err = (pg_error){0};
    CHECK(pg_ocio_resolve(cfg, "sRGB", "Nope", NULL, 0, NULL, 0, &err) == PG_ERR_INVALID_ARG);
    CHECK_MSG(contains(err.msg, path) && contains(err.msg, "unknown view 'Nope' of display 'sRGB'") &&
                  contains(err.msg, "(views: Standard, Filmic (ACES), Raw)"),
              "%s", err.msg);
    printf("ocio: unknown view: %s\n", err.msg);
    err = (pg_error){0};
    CHECK(pg_ocio_resolve(cfg, "Nope", NULL, NULL, 0, NULL, 0, &err) == PG_ERR_INVALID_ARG);
    CHECK_MSG(contains(err.msg, "unknown display 'Nope'") && contains(err.msg, "(displays: sRGB, Rec.1886)"), "%s",
              err.msg);
    pg_ocio_cpu *bad = NULL;
    err = (pg_error){0};
    CHECK(pg_ocio_cpu_create(cfg, NULL, "Filmic", &bad, &err) == PG_ERR_INVALID_ARG && !bad);
    CHECK_MSG(contains(err.msg, "unknown view 'Filmic'"), "%s", err.msg);

    /* CPU values */
    static const float grays[] = {0, 1e-6f, 1e-3f, 0.01f, 0.18f, 0.5f, 0.9f, 1, 1.5f, 16, 1e3f, 6e4f};
    const size_t ng = sizeof grays / sizeof grays[0];
    for (uint32_t di = 0; di < 2; di++) {
        for (uint32_t vi = 0; vi < 3; vi++) {
            pg_ocio_cpu *p = NULL;
            CHECK_MSG(pg_ocio_cpu_create(cfg, k_displays[di], k_views[vi], &p, &err) == PG_OK, "%s", err.msg);
            if (!p) continue;
            float px[sizeof grays / sizeof grays[0] * 4];
            for (size_t i = 0; i < ng; i++) px[i * 4] = px[i * 4 + 1] = px[i * 4 + 2] = grays[i], px[i * 4 + 3] = 1;
            pg_ocio_cpu_apply(p, px, ng, 4);
            double max_err = 0;
            int max_steps = 0;
            bool monotonic = true;
            for (size_t i = 0; i < ng; i++) {
                float g = grays[i], o = px[i * 4 + 1];
                CHECK_MSG(fabsf(px[i * 4] - o) < 1e-4f && fabsf(px[i * 4 + 2] - o) < 1e-4f,
                          "%s/%s: grey %g is not grey: %g %g %g", k_displays[di], k_views[vi], g, px[i * 4], o,
                          px[i * 4 + 2]);
                if (i && o + 1e-6f < px[(i - 1) * 4 + 1]) monotonic = false;
                float want = g;
                if (vi == 0) want = di == 0 ? srgb_oetf(g) : powf(fminf(g, 1.0f), 1.0f / 2.4f);
                if (vi != 1) {
                    double e = fabs((double)o - want);
                    if (e > max_err) max_err = e;
                    int st = abs(quantize(o) - quantize(want));
                    if (st > max_steps) max_steps = st;
                }
            }
            CHECK_MSG(monotonic, "%s/%s: not monotonic on greys", k_displays[di], k_views[vi]);
            if (vi == 0) { /* Standard: the display curve of the clamped value (sRGB: display_tonemap's clamp) */
                printf("ocio: CPU %s/Standard vs the analytic %s curve: max abs %.2g, max %d 8-bit step(s)\n",
                       k_displays[di], di ? "gamma 1/2.4" : "sRGB", max_err, max_steps);
                CHECK_MSG(max_err < 2e-3 && max_steps <= 1, "%s/Standard: max err %g", k_displays[di], max_err);
            } else if (vi == 2) { /* Raw: untouched, not even clamped */
                CHECK_MSG(max_err == 0, "%s/Raw is not the identity (max err %g)", k_displays[di], max_err);
            } else { /* Filmic: black stays black, mid grey lifted, highlights roll off below 1 */
                float g18 = px[4 * 4 + 1], g1 = px[7 * 4 + 1], g1e3 = px[10 * 4 + 1], g6e4 = px[11 * 4 + 1];
                printf("ocio: CPU %s/Filmic (ACES): 0 -> %.4f, 0.18 -> %.4f, 1 -> %.4f, 1e3 -> %.4f, 6e4 -> %.4f\n",
                       k_displays[di], px[1], g18, g1, g1e3, g6e4);
                CHECK(px[1] < 0.01f && g18 > 0.3f && g18 < 0.55f && g1 > 0.7f && g1 < 0.95f && g1e3 > 0.95f &&
                      g6e4 <= 1.0f);
            }
            pg_ocio_cpu_free(p);
        }
    }
    /* the generated shader: every uniform is a bound sampler; the shipped config needs no LUT */
    pg_ocio_shader *sh = NULL;
    pg_ocio_shader_desc sd = {.display = "sRGB", .view = "Filmic (ACES)", .set = 1, .first_binding = 1};
    CHECK_MSG(pg_ocio_shader_create(cfg, &sd, &sh, &err) == PG_OK, "%s", err.msg);
    if (sh) {
        CHECK(contains(sh->glsl, "vec4 ocio_display(vec4"));
        CHECK(sh->n_textures == 0);
        CHECK(!strcmp(sh->display, "sRGB") && !strcmp(sh->view, "Filmic (ACES)"));
        for (const char *l = sh->glsl; l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) {
            const char *e = strchr(l, '\n');
            size_t n = e ? (size_t)(e - l) : strlen(l);
            char line[512];
            snprintf(line, sizeof line, "%.*s", (int)(n < 511 ? n : 511), l);
            CHECK_MSG(!contains(line, "uniform ") || contains(line, "layout(set = 1"), "unbound: %s", line);
        }
    }
    pg_ocio_shader_free(sh);
    pg_ocio_close(cfg);
}

static void test_bad_configs(void)
{
    pg_error err = {0};
    pg_ocio_config *cfg = NULL;
    char path[PG_PATH_MAX];
    tmp_path(path, sizeof path, "missing.ocio");
    CHECK(pg_ocio_open(path, &cfg, &err) == PG_ERR_IO && !cfg);
    CHECK_MSG(contains(err.msg, path) && contains(err.msg, "OCIO config '") && contains(err.msg, "cannot open: No such file"), "%s", err.msg);
    printf("ocio: missing config: %s\n", err.msg);

    tmp_path(path, sizeof path, "broken.ocio");
    write_text(path, "ocio_profile_version: 2\nroles: [\n  scene_linear: x\n");
    err = (pg_error){0};
    CHECK(pg_ocio_open(path, &cfg, &err) != PG_OK && !cfg);
    CHECK_MSG(contains(err.msg, path) && contains(err.msg, "OCIO config error"), "%s", err.msg);
    printf("ocio: broken config: %s\n", err.msg);

    tmp_path(path, sizeof path, "no_scene_linear.ocio");
    write_text(path, "ocio_profile_version: 2\n"
                     "roles:\n  default: raw\n"
                     "displays:\n  d:\n    - !<View> {name: v, colorspace: raw}\n"
                     "colorspaces:\n  - !<ColorSpace> {name: raw, isdata: true}\n");
    err = (pg_error){0};
    CHECK(pg_ocio_open(path, &cfg, &err) != PG_OK && !cfg);
    CHECK_MSG(contains(err.msg, path) && contains(err.msg, "scene_linear"), "%s", err.msg);

    tmp_path(path, sizeof path, "not_a_config.ocio");
    write_text(path, "this is not yaml: [\n");
    err = (pg_error){0};
    CHECK(pg_ocio_open(path, &cfg, &err) != PG_OK && !cfg);
    CHECK_MSG(contains(err.msg, path), "%s", err.msg);

    /* which file: setting > $OCIO > shipped */
    char buf[PG_PATH_MAX], shipped[PG_PATH_MAX];
    pg_data_path(shipped, sizeof shipped, PG_OCIO_SHIPPED_CONFIG);
    const char *old = getenv("OCIO");
    char saved[PG_PATH_MAX] = "";
    if (old) pg_strlcpy(saved, old, sizeof saved);
    unsetenv("OCIO");
    pg_ocio_resolve_path(NULL, buf, sizeof buf);
    CHECK(!strcmp(buf, shipped));
    pg_ocio_resolve_path("mine.ocio", buf, sizeof buf);
    CHECK(!strcmp(buf, "mine.ocio"));
    setenv("OCIO", "/env/config.ocio", 1);
    pg_ocio_resolve_path("", buf, sizeof buf);
    CHECK(!strcmp(buf, "/env/config.ocio"));
    pg_ocio_resolve_path("mine.ocio", buf, sizeof buf);
    CHECK(!strcmp(buf, "mine.ocio"));
    if (saved[0]) setenv("OCIO", saved, 1);
    else unsetenv("OCIO");
}

/* A config whose views are LUTs: a 64-entry RGB 1D LUT (sampler1D), an 8192-entry 1D LUT (wrapped
 * into a sampler2D), a 17^3 3D LUT with tetrahedral and with trilinear interpolation. */
static bool write_lut_config(char *cfg_path, size_t n)
{
    char p[PG_PATH_MAX];
    tmp_path(p, sizeof p, "rgb64.spi1d");
    FILE *f = fopen(p, "wb");
    if (!f) return false;
    fprintf(f, "Version 1\nFrom 0.0 1.0\nLength 64\nComponents 3\n{\n");
    for (int i = 0; i < 64; i++) {
        double x = i / 63.0;
        fprintf(f, "  %.7f %.7f %.7f\n", pow(x, 1 / 2.2), pow(x, 1 / 1.6), 0.2 + 0.6 * x * x);
    }
    fprintf(f, "}\n");
    fclose(f);
    tmp_path(p, sizeof p, "grey8192.spi1d");
    if (!(f = fopen(p, "wb"))) return false;
    fprintf(f, "Version 1\nFrom 0.0 1.0\nLength 8192\nComponents 1\n{\n");
    for (int i = 0; i < 8192; i++) fprintf(f, "  %.7f\n", pow(i / 8191.0, 1 / 2.4));
    fprintf(f, "}\n");
    fclose(f);
    tmp_path(p, sizeof p, "twist17.cube");
    if (!(f = fopen(p, "wb"))) return false;
    fprintf(f, "TITLE \"passgraph test twist\"\nLUT_3D_SIZE 17\n");
    for (int b = 0; b < 17; b++)
        for (int g = 0; g < 17; g++)
            for (int r = 0; r < 17; r++) {
                double R = r / 16.0, G = g / 16.0, B = b / 16.0;
                fprintf(f, "%.7f %.7f %.7f\n", pow(0.8 * R + 0.2 * G, 1 / 2.2), pow(0.9 * G + 0.1 * B, 1 / 2.2),
                        pow(0.7 * B + 0.3 * R, 1 / 2.2));
            }
    fclose(f);
    snprintf(cfg_path, n, "%s/luts.ocio", g_tmp);
    return write_text(cfg_path,
                      "ocio_profile_version: 2\n"
                      "search_path: \".\"\n"
                      "roles:\n  default: linear\n  scene_linear: linear\n"
                      "displays:\n  LUT:\n"
                      "    - !<View> {name: 1D RGB, colorspace: lut1d_rgb}\n"
                      "    - !<View> {name: 1D long, colorspace: lut1d_long}\n"
                      "    - !<View> {name: 3D tetrahedral, colorspace: lut3d_tet}\n"
                      "    - !<View> {name: 3D linear, colorspace: lut3d_lin}\n"
                      "colorspaces:\n"
                      "  - !<ColorSpace> {name: linear, isdata: false}\n"
                      "  - !<ColorSpace>\n    name: lut1d_rgb\n"
                      "    from_scene_reference: !<FileTransform> {src: rgb64.spi1d, interpolation: linear}\n"
                      "  - !<ColorSpace>\n    name: lut1d_long\n"
                      "    from_scene_reference: !<FileTransform> {src: grey8192.spi1d, interpolation: linear}\n"
                      "  - !<ColorSpace>\n    name: lut3d_tet\n"
                      "    from_scene_reference: !<FileTransform> {src: twist17.cube, interpolation: tetrahedral}\n"
                      "  - !<ColorSpace>\n    name: lut3d_lin\n"
                      "    from_scene_reference: !<FileTransform> {src: twist17.cube, interpolation: linear}\n");
}

static const char *const k_lut_views[4] = {"1D RGB", "1D long", "3D tetrahedral", "3D linear"};

static void test_lut_config(const char *path)
{
    pg_ocio_config *cfg = NULL;
    pg_error err = {0};
    CHECK_MSG(pg_ocio_open(path, &cfg, &err) == PG_OK, "%s", err.msg);
    if (!cfg) return;
    /* expected textures: dimension and channels */
    static const struct {
        pg_ocio_tex_dim dim;
        uint32_t channels, w, h, d;
        bool linear;
    } want[4] = {{PG_OCIO_TEX_1D, 3, 64, 1, 1, true},
                 {PG_OCIO_TEX_2D, 1, 4096, 3, 1, true},
                 {PG_OCIO_TEX_3D, 3, 17, 17, 17, false},
                 {PG_OCIO_TEX_3D, 3, 17, 17, 17, true}};
    for (int i = 0; i < 4; i++) {
        pg_ocio_shader *sh = NULL;
        pg_ocio_shader_desc sd = {.view = k_lut_views[i], .set = 1, .first_binding = 1};
        CHECK_MSG(pg_ocio_shader_create(cfg, &sd, &sh, &err) == PG_OK, "%s", err.msg);
        if (!sh) continue;
        CHECK_MSG(sh->n_textures == 1, "%s: %u textures", k_lut_views[i], sh->n_textures);
        if (sh->n_textures == 1) {
            const pg_ocio_texture *t = &sh->textures[0];
            printf("ocio: LUT view '%s': %uD texture %ux%ux%u, %u channel(s), %s\n", k_lut_views[i], (unsigned)t->dim,
                   t->width, t->height, t->depth, t->channels, t->linear ? "linear" : "nearest");
            CHECK_MSG(t->dim == want[i].dim && t->channels == want[i].channels && t->width == want[i].w &&
                          t->height == want[i].h && t->depth == want[i].d && t->linear == want[i].linear &&
                          t->binding == 1 && t->values,
                      "%s: unexpected texture", k_lut_views[i]);
            char decl[128];
            snprintf(decl, sizeof decl, "layout(set = 1, binding = 1) uniform sampler%dD %s;", (int)t->dim, t->sampler);
            CHECK_MSG(contains(sh->glsl, decl), "%s: no '%s' in the GLSL", k_lut_views[i], decl);
        }
        pg_ocio_shader_free(sh);
    }
    pg_ocio_close(cfg);
}

static void test_exr_cpu(void)
{
    enum { W = 7, H = 5 };
    float px[W * H * 4];
    for (int i = 0; i < W * H * 4; i++) px[i] = (i % 4 == 3) ? 1.0f : (float)(i * 0.37 - 3.1) * (float)(i % 5) * 17.0f;
    px[0] = 65504.0f;
    px[1] = 1e-6f; /* subnormal as half */
    px[2] = -0.0f;
    char path[PG_PATH_MAX];
    pg_error err = {0};
    for (int half = 0; half < 2; half++) {
        tmp_path(path, sizeof path, half ? "cpu_half.exr" : "cpu_float.exr");
        CHECK_MSG(pg_exr_write_rgba(path, px, W, H, half, &err) == PG_OK, "%s", err.msg);
        float *back = NULL;
        uint32_t w = 0, h = 0;
        CHECK_MSG(pg_exr_read_rgba(path, &back, &w, &h, &err) == PG_OK, "%s", err.msg);
        if (back) {
            CHECK(w == W && h == H);
            int bad = 0;
            for (int i = 0; i < W * H * 4; i++) {
                float want = half ? pg_half_to_float(pg_float_to_half(px[i])) : px[i];
                if (memcmp(&want, &back[i], 4)) bad++;
            }
            CHECK_MSG(bad == 0, "%s EXR round trip: %d values differ", half ? "half" : "float", bad);
        }
        free(back);
    }
    tmp_path(path, sizeof path, "missing.exr");
    float *none = NULL;
    uint32_t w, h;
    err = (pg_error){0};
    CHECK(pg_exr_read_rgba(path, &none, &w, &h, &err) != PG_OK && !none);
    CHECK_MSG(contains(err.msg, path), "%s", err.msg);
    { /* a file cut after its header: refused as truncated, before its pixels are allocated (the
       * header of a 16384 x 8192 image in 377 bytes took 2 GiB) */
        enum { TW = 16, TH = 4096 }; /* ZIP: 16 lines a chunk, 256 chunks, a table of 2 KiB */
        float *tall = calloc((size_t)TW * TH * 4, sizeof(float));
        tmp_path(path, sizeof path, "cut.exr");
        CHECK_MSG(tall && pg_exr_write_rgba(path, tall, TW, TH, true, &err) == PG_OK, "%s", err.msg);
        free(tall);
        CHECK(truncate(path, 1024) == 0);
        err = (pg_error){0};
        CHECK(pg_exr_read_rgba(path, &none, &w, &h, &err) == PG_ERR_PARSE && !none);
        CHECK_MSG(contains(err.msg, "truncated: its header announces 16x4096 pixels in 256 chunks") &&
                      contains(err.msg, "the file has 1024"),
                  "%s", err.msg);
    }
    { /* pg_exr_read_rgba_within refuses a side past its limit from the header, before the pixels
       * (an environment of 65536 x 32768 announced by a small file asked for 32 GiB) */
        enum { WW = 64, WH = 2 };
        float wide[WW * WH * 4] = {0};
        tmp_path(path, sizeof path, "wide.exr");
        CHECK_MSG(pg_exr_write_rgba(path, wide, WW, WH, true, &err) == PG_OK, "%s", err.msg);
        err = (pg_error){0};
        CHECK(pg_exr_read_rgba_within(path, 63, &none, &w, &h, &err) == PG_ERR_LIMIT && !none);
        CHECK_MSG(contains(err.msg, "64 x 2: wider or taller than 63"), "%s", err.msg);
        CHECK(pg_exr_read_rgba_within(path, 64, &none, &w, &h, &err) == PG_OK && none && w == WW && h == WH);
        free(none);
        none = NULL;
    }
    { /* a required attribute missing (its name changed in place, so the offsets stay valid) is
       * named: OpenEXRCore's default (ZIP, a 64 x 64 window) gave "Unable to decompress" or
       * "truncated ... 64x64" */
        static const char *const attrs[] = {"compression", "dataWindow", "channels"};
        for (int a = 0; a < 3; a++) {
            tmp_path(path, sizeof path, "renamed.exr");
            CHECK_MSG(pg_exr_write_rgba(path, px, W, H, false, &err) == PG_OK, "%s", err.msg);
            FILE *f = fopen(path, "r+b");
            unsigned char buf[4096];
            size_t n = f ? fread(buf, 1, sizeof buf, f) : 0;
            size_t len = strlen(attrs[a]), at = 0;
            while (at + len + 1 < n && memcmp(buf + at, attrs[a], len + 1)) at++; /* the name and its 0 */
            CHECK_MSG(at + len + 1 < n, "no %s attribute in the written header", attrs[a]);
            if (f && at + len + 1 < n) {
                fseek(f, (long)(at + len - 1), SEEK_SET);
                fputc('X', f);
            }
            if (f) fclose(f);
            err = (pg_error){0};
            CHECK(pg_exr_read_rgba(path, &none, &w, &h, &err) != PG_OK && !none);
            char want[64];
            snprintf(want, sizeof want, "'%s' attribute not found", attrs[a]);
            CHECK_MSG(contains(err.msg, path) && contains(err.msg, want), "%s", err.msg);
        }
    }
    { /* chunks whose ZIP data is exactly as long as their raw data: OpenEXRCore 3.1.5 kept the
       * compressed bytes and read them back as raw (noise). Images of 1 x 16 (one chunk of 16 lines)
       * with 0..16 noisy pixels and the rest flat, float and half: every one reads back exactly */
        int mismatched = 0, files = 0;
        uint32_t state = 12345u;
        for (int seed = 0; seed < 24; seed++)
            for (int noisy = 0; noisy <= 16; noisy++)
                for (int hf = 0; hf < 2; hf++) {
                    float img[16 * 4];
                    for (int i = 0; i < 16 * 4; i++) {
                        state = state * 1664525u + 1013904223u;
                        img[i] = i / 4 < noisy ? (float)(state >> 8) / 16777216.0f * 4.0f : 0.5f;
                    }
                    tmp_path(path, sizeof path, "chunk.exr");
                    float *back = NULL;
                    err = (pg_error){0};
                    if (pg_exr_write_rgba(path, img, 1, 16, hf, &err) != PG_OK ||
                        pg_exr_read_rgba(path, &back, &w, &h, &err) != PG_OK) {
                        CHECK_MSG(0, "%s", err.msg);
                        continue;
                    }
                    files++;
                    for (int i = 0; i < 16 * 4; i++) {
                        float want = hf ? pg_half_to_float(pg_float_to_half(img[i])) : img[i];
                        if (memcmp(&want, &back[i], 4)) {
                            mismatched++;
                            break;
                        }
                    }
                    free(back);
                }
        CHECK_MSG(files == 24 * 17 * 2 && mismatched == 0, "%d of %d one-chunk EXR files read back wrong",
                  mismatched, files);
    }
    tmp_path(path, sizeof path, "no/such/dir/x.exr");
    err = (pg_error){0};
    CHECK(pg_exr_write_rgba(path, px, W, H, false, &err) != PG_OK);
    CHECK_MSG(contains(err.msg, path), "%s", err.msg);
    /* half conversion: round to nearest even, overflow, subnormals, NaN */
    CHECK(pg_float_to_half(1.0f) == 0x3c00 && pg_float_to_half(-2.0f) == 0xc000);
    CHECK(pg_float_to_half(65504.0f) == 0x7bff && pg_float_to_half(65520.0f) == 0x7c00);
    CHECK(pg_float_to_half(5.9604645e-8f) == 0x0001 && pg_float_to_half(2e-8f) == 0);
    CHECK(pg_float_to_half(1.0f + 1.0f / 2048) == 0x3c00); /* tie -> even */
    CHECK(pg_float_to_half(1.0f + 3.0f / 2048) == 0x3c02);
    CHECK((pg_float_to_half(NAN) & 0x7c00) == 0x7c00 && (pg_float_to_half(NAN) & 0x3ff));
}

/* ------------------------------------------------------------------ (b) GPU */

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;
static float *g_grid; /* GW*GH*4 */
#define GW 64
#define GH 53

typedef struct test_grid {
    pg_buffer buf;
} test_grid;

static pg_result tg_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    (void)in;
    (void)err;
    pg_decl_write(out, "hdr", PG_RES_IMAGE, PG_ACCESS_TRANSFER_DST, 0, PG_FMTCLASS_FLOAT);
    return PG_OK;
}

static pg_result tg_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    test_grid *p = self;
    const pg_phys_resource *hdr = ctx->slots[0];
    if (hdr->format != VK_FORMAT_R32G32B32A32_SFLOAT || hdr->width != GW || hdr->height != GH)
        return pg_fail(err, PG_ERR_FORMAT, "test_grid: hdr must be rgba32f %ux%u", GW, GH);
    pg_result r = pg_buffer_create(ctx->gpu, (VkDeviceSize)GW * GH * 16, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true,
                                   "test_grid", &p->buf, err);
    if (r) return r;
    memcpy(p->buf.mapped, g_grid, (size_t)GW * GH * 16);
    return PG_OK;
}

static void tg_record(void *self, const pg_pass_record_ctx *ctx)
{
    test_grid *p = self;
    VkBufferImageCopy c = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {GW, GH, 1}};
    vkCmdCopyBufferToImage(ctx->cmd, p->buf.buffer, ctx->slots[0]->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &c);
}

static void tg_destroy(void *self, pg_gpu *gpu)
{
    test_grid *p = self;
    pg_buffer_destroy(gpu, &p->buf);
}

static const pg_pass_type k_test_grid = {
    .name = "test_grid",
    .summary = "test: copies a grid of HDR values into its image",
    .instance_size = sizeof(test_grid),
    .declare = tg_declare,
    .create = tg_create,
    .record = tg_record,
    .destroy = tg_destroy,
};

static void make_grid(void)
{
    static const float v[] = {0,    1e-6f, 1e-4f, 1e-3f, 0.01f, 0.05f, 0.18f, 0.3f,
                              0.5f, 1,     2,     16,    100,   1e3f,  6e4f};
    const int n = (int)(sizeof v / sizeof v[0]);
    g_grid = malloc((size_t)GW * GH * 16);
    for (int i = 0; i < GW * GH; i++) {
        int k = i % (n * n * n);
        g_grid[i * 4 + 0] = v[k % n];
        g_grid[i * 4 + 1] = v[(k / n) % n];
        g_grid[i * 4 + 2] = v[k / (n * n)];
        g_grid[i * 4 + 3] = 1;
    }
}

/* Renders the grid pipeline; *ldr and *hdr (may be NULL) are malloc'd copies. */
static bool render_grid(const char *pipeline, const pg_param_override *sets, uint32_t n_sets,
                        const pg_param_override *settings, uint32_t n_settings, uint8_t **ldr, float **hdr,
                        pg_error *err)
{
    *ldr = NULL;
    if (hdr) *hdr = NULL;
    pg_session_desc sd = {.pipeline_path = pipeline, .registry = &g_reg, .overrides = sets, .n_overrides = n_sets,
                          .settings = settings, .n_settings = n_settings};
    pg_session *s = NULL;
    if (pg_session_create(g_gpu, NULL, &sd, &s, err)) return false;
    pg_frame_info fi = {.camera = {.position = {0, 0, 5}, .up = {0, 1, 0}, .fov_y_deg = 60, .near_z = 0.1f,
                                   .far_z = 100, .aspect = (float)GW / GH},
                        .width = GW, .height = GH};
    pg_frame_stats st;
    bool ok = !pg_session_render(s, &fi, true, &st, err);
    uint32_t w, h;
    pg_format f;
    const void *p = ok ? pg_runtime_output(s->runtime, 0, &w, &h, &f) : NULL;
    if (ok && (!p || w != GW || h != GH || f != PG_FMT_RGBA8_UNORM)) {
        pg_fail(err, PG_ERR_FORMAT, "unexpected output");
        ok = false;
    }
    if (ok) {
        *ldr = malloc((size_t)GW * GH * 4);
        memcpy(*ldr, p, (size_t)GW * GH * 4);
    }
    if (ok && hdr) {
        const void *hp = pg_runtime_output(s->runtime, 1, &w, &h, &f);
        *hdr = malloc((size_t)GW * GH * 16);
        if (hp && f == PG_FMT_RGBA32F) memcpy(*hdr, hp, (size_t)GW * GH * 16);
        else ok = !pg_fail(err, PG_ERR_FORMAT, "unexpected hdr output");
    }
    pg_session_destroy(s);
    return ok;
}

/* Max 8-bit difference between the GPU image and OCIO's CPU processor (scene value x exposure). */
static int compare_cpu(const char *cfg_path, const char *display, const char *view, float exposure,
                       const uint8_t *ldr, int *n_diff)
{
    pg_ocio_config *cfg = NULL;
    pg_ocio_cpu *p = NULL;
    pg_error err = {0};
    if (pg_ocio_open(cfg_path, &cfg, &err) || pg_ocio_cpu_create(cfg, display, view, &p, &err)) {
        CHECK_MSG(0, "%s", err.msg);
        pg_ocio_close(cfg);
        return 256;
    }
    float *px = malloc((size_t)GW * GH * 3 * sizeof(float));
    for (int i = 0; i < GW * GH; i++)
        for (int c = 0; c < 3; c++) px[i * 3 + c] = g_grid[i * 4 + c] * exposure;
    pg_ocio_cpu_apply(p, px, (size_t)GW * GH, 3);
    int worst = 0, worst_i = 0;
    *n_diff = 0;
    for (int i = 0; i < GW * GH; i++) {
        int pix = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs((int)ldr[i * 4 + c] - quantize(px[i * 3 + c]));
            if (d > pix) pix = d;
        }
        if (pix) (*n_diff)++;
        if (pix > worst) worst = pix, worst_i = i;
    }
    if (worst > MAX_STEPS) {
        int i = worst_i;
        printf("  worst pixel: scene (%g, %g, %g) -> GPU (%d, %d, %d), CPU (%.5f, %.5f, %.5f)\n", g_grid[i * 4],
               g_grid[i * 4 + 1], g_grid[i * 4 + 2], ldr[i * 4], ldr[i * 4 + 1], ldr[i * 4 + 2], px[i * 3],
               px[i * 3 + 1], px[i * 3 + 2]);
    }
    free(px);
    pg_ocio_cpu_free(p);
    pg_ocio_close(cfg);
    return worst;
}

static void gpu_view(const char *grid, const char *cfg_path, const char *display, const char *view, float exposure)
{
    pg_param_override settings[3] = {{"ocio.config", cfg_path}, {"ocio.display", display}, {"ocio.view", view}};
    char ev[32];
    snprintf(ev, sizeof ev, "%.9g", exposure);
    pg_param_override sets[1] = {{"exposure", ev}};
    uint8_t *ldr = NULL;
    pg_error err = {0};
    bool ok = render_grid(grid, sets, 1, settings, 3, &ldr, NULL, &err);
    CHECK_MSG(ok, "%s/%s: %s", display, view, err.msg);
    if (!ok) return;
    int n_diff = 0;
    int worst = compare_cpu(cfg_path, display, view, exposure, ldr, &n_diff);
    printf("ocio: GPU vs CPU %-9s / %-15s exposure %-5g: max %d 8-bit step(s), %d of %d pixels differ\n", display,
           view, exposure, worst, n_diff, GW * GH);
    CHECK_MSG(worst <= MAX_STEPS, "%s/%s: GPU differs from OCIO's CPU processor by %d steps", display, view, worst);
    /* the full-screen fragment pass writes the same bytes as the compute pass */
    pg_param_override frag_sets[2] = {{"exposure", ev}, {"stage", "fragment"}};
    uint8_t *frag = NULL;
    ok = render_grid(grid, frag_sets, 2, settings, 3, &frag, NULL, &err);
    CHECK_MSG(ok, "%s/%s stage fragment: %s", display, view, err.msg);
    if (ok) {
        bool same = !memcmp(ldr, frag, (size_t)GW * GH * 4);
        CHECK_MSG(same, "%s/%s: stage compute and fragment differ", display, view);
        if (!same) printf("ocio: %s / %s: stage compute and fragment DIFFER\n", display, view);
    }
    free(frag);
    free(ldr);
}

static void gpu_tests(const char *lut_cfg)
{
    char grid[PG_PATH_MAX], shipped[PG_PATH_MAX];
    snprintf(grid, sizeof grid, "%s/ocio/grid.json", PG_TEST_DIR);
    pg_data_path(shipped, sizeof shipped, PG_OCIO_SHIPPED_CONFIG);
    make_grid();
    /* every view of every display of the shipped config */
    for (int d = 0; d < 2; d++)
        for (int v = 0; v < 3; v++) gpu_view(grid, shipped, k_displays[d], k_views[v], 1.0f);
    /* exposure is a scene-linear multiply before the view */
    gpu_view(grid, shipped, "sRGB", "Standard", 0.25f);
    gpu_view(grid, shipped, "sRGB", "Filmic (ACES)", 8.0f);
    /* LUT views: 1D (sampler1D), 1D wrapped into a sampler2D, 3D tetrahedral and trilinear */
    if (lut_cfg)
        for (int v = 0; v < 4; v++) gpu_view(grid, lut_cfg, "LUT", k_lut_views[v], 1.0f);

    /* pass options, and settings over options */
    char opt_pipe[PG_PATH_MAX], text[2048];
    tmp_path(opt_pipe, sizeof opt_pipe, "grid_options.json");
    snprintf(text, sizeof text,
             "{\"name\": \"grid_options\", \"resources\": [{\"name\": \"hdr\", \"type\": \"image\", \"format\": "
             "\"rgba32f\"}, {\"name\": \"ldr\", \"type\": \"image\", \"format\": \"rgba8\"}], \"passes\": [{\"name\": "
             "\"grid\", \"type\": \"test_grid\", \"writes\": [\"hdr\"]}, {\"name\": \"display\", \"type\": "
             "\"display_ocio\", \"reads\": [\"hdr\"], \"writes\": [\"ldr\"], \"options\": {\"display\": \"Rec.1886\", "
             "\"view\": \"Filmic (ACES)\", \"exposure\": 2}}], \"output\": \"ldr\", \"hdr_output\": \"hdr\"}");
    write_text(opt_pipe, text);
    uint8_t *ldr = NULL;
    float *hdr = NULL;
    pg_error err = {0};
    int n_diff;
    if (render_grid(opt_pipe, NULL, 0, NULL, 0, &ldr, &hdr, &err)) {
        int worst = compare_cpu(shipped, "Rec.1886", "Filmic (ACES)", 2.0f, ldr, &n_diff);
        printf("ocio: pass options display/view/exposure: max %d step(s)\n", worst);
        CHECK(worst <= MAX_STEPS);
    } else {
        CHECK_MSG(0, "options pipeline: %s", err.msg);
    }
    /* the linear HDR image as EXR (float: bit exact; half: each value to its nearest half) */
    if (hdr) {
        char path[PG_PATH_MAX];
        for (int half = 0; half < 2; half++) {
            tmp_path(path, sizeof path, half ? "grid_half.exr" : "grid_float.exr");
            CHECK_MSG(!pg_exr_write_rgba(path, hdr, GW, GH, half, &err), "%s", err.msg);
            float *back = NULL;
            uint32_t w = 0, h = 0;
            CHECK_MSG(!pg_exr_read_rgba(path, &back, &w, &h, &err), "%s", err.msg);
            int bad = 0;
            for (int i = 0; back && w == GW && h == GH && i < GW * GH * 4; i++) {
                float want = half ? pg_half_to_float(pg_float_to_half(hdr[i])) : hdr[i];
                bad += memcmp(&want, &back[i], 4) != 0;
                if (!half) bad += memcmp(&g_grid[i], &back[i], 4) != 0; /* the grid survived the GPU */
            }
            CHECK_MSG(back && w == GW && h == GH && bad == 0, "EXR (%s) of the read-back HDR: %d values differ",
                      half ? "half" : "float", bad);
            free(back);
        }
    }
    free(ldr);
    free(hdr);
    pg_param_override raw[1] = {{"ocio.view", "Raw"}};
    if (render_grid(opt_pipe, NULL, 0, raw, 1, &ldr, NULL, &err)) {
        int worst = compare_cpu(shipped, "Rec.1886", "Raw", 2.0f, ldr, &n_diff);
        printf("ocio: setting ocio.view=Raw over the option: max %d step(s)\n", worst);
        CHECK(worst <= MAX_STEPS);
        free(ldr);
    } else {
        CHECK_MSG(0, "settings over options: %s", err.msg);
    }

    /* errors at create name the file and list what exists */
    pg_param_override bad_view[1] = {{"ocio.view", "Nope"}};
    err = (pg_error){0};
    CHECK(!render_grid(grid, NULL, 0, bad_view, 1, &ldr, NULL, &err));
    CHECK_MSG(contains(err.msg, "pass 'display' (display_ocio)") && contains(err.msg, "unknown view 'Nope'") &&
                  contains(err.msg, "Standard, Filmic (ACES), Raw"),
              "%s", err.msg);
    printf("ocio: bad view at create: %s\n", err.msg);
    char missing[PG_PATH_MAX];
    tmp_path(missing, sizeof missing, "missing.ocio");
    pg_param_override bad_cfg[1] = {{"ocio.config", missing}};
    err = (pg_error){0};
    CHECK(!render_grid(grid, NULL, 0, bad_cfg, 1, &ldr, NULL, &err));
    CHECK_MSG(contains(err.msg, missing), "%s", err.msg);
    /* rgba8_srgb would encode twice: refused at compile time */
    char srgb_pipe[PG_PATH_MAX];
    tmp_path(srgb_pipe, sizeof srgb_pipe, "grid_srgb.json");
    char *at = strstr(text, "\"rgba8\"");
    if (at) {
        char t2[2100];
        snprintf(t2, sizeof t2, "%.*s\"rgba8_srgb\"%s", (int)(at - text), text, at + 7);
        write_text(srgb_pipe, t2);
        err = (pg_error){0};
        CHECK(!render_grid(srgb_pipe, NULL, 0, NULL, 0, &ldr, NULL, &err));
        CHECK_MSG(contains(err.msg, "rgba8_srgb") && contains(err.msg, "display-encoded"), "%s", err.msg);
    }
    free(g_grid);
    g_grid = NULL;
}

/* The default pipeline's OCIO Standard view against the display_tonemap clamp it replaces, on the
 * built-in atrium. */
static void gpu_default_scene(void)
{
    pg_error err = {0};
    pg_scene *scene = NULL;
    pg_scene_gpu *sg = NULL;
    if (pg_scene_create_default(&scene, &err) || pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        CHECK_MSG(0, "%s", err.msg);
        pg_scene_free(scene);
        return;
    }
    uint8_t *img[2] = {NULL, NULL};
    const char *names[2] = {"ocio Standard", "tonemap=clamp"};
    for (int k = 0; k < 2; k++) {
        char path[PG_PATH_MAX];
        pg_data_path(path, sizeof path, "pipelines/naive.json");
        pg_param_override set = {"tonemap", "clamp"};
        pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg, .overrides = &set, .n_overrides = k};
        pg_session *s = NULL;
        pg_frame_info fi = {.camera = pg_camera_default_for_scene(scene, 160.0f / 90),
                            .lights = pg_light_setup_default(scene, 64, 3), .time = 1, .width = 160, .height = 90};
        pg_frame_stats st;
        if (pg_session_create(g_gpu, sg, &sd, &s, &err) || pg_session_render(s, &fi, true, &st, &err)) {
            CHECK_MSG(0, "%s: %s", names[k], err.msg);
        } else {
            uint32_t w, h;
            pg_format f;
            const uint8_t *p = pg_runtime_output(s->runtime, 0, &w, &h, &f);
            img[k] = malloc((size_t)w * h * 4);
            memcpy(img[k], p, (size_t)w * h * 4);
            CHECK(f == PG_FMT_RGBA8_UNORM);
        }
        pg_session_destroy(s);
    }
    if (img[0] && img[1]) {
        int worst = 0, n = 0;
        for (int i = 0; i < 160 * 90 * 4; i++) {
            if (i % 4 == 3) continue;
            int d = abs(img[0][i] - img[1][i]);
            if (d > worst) worst = d;
            n += d > 0;
        }
        printf("ocio: atrium, OCIO Standard vs display_tonemap clamp: max %d 8-bit step(s), %d channel values differ\n",
               worst, n);
        CHECK_MSG(worst <= 1, "Standard view differs from the clamp tonemap by %d steps", worst);
    }
    free(img[0]);
    free(img[1]);
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
}

int main(void)
{
    snprintf(g_tmp, sizeof g_tmp, "/tmp/pg_test_ocio_XXXXXX");
    if (!mkdtemp(g_tmp)) {
        fprintf(stderr, "test_ocio: cannot create a temporary folder\n");
        return 1;
    }
    test_shipped_config();
    test_bad_configs();
    char lut_cfg[PG_PATH_MAX];
    bool have_luts = write_lut_config(lut_cfg, sizeof lut_cfg);
    CHECK(have_luts);
    if (have_luts) test_lut_config(lut_cfg);
    test_exr_cpu();

    if (getenv("PG_TEST_NO_GPU")) {
        printf("test_ocio: GPU part skipped (PG_TEST_NO_GPU)\n");
    } else {
        pg_register_builtin_passes(&g_reg);
        pg_error err = {0};
        CHECK(pg_registry_add(&g_reg, &k_test_grid, &err) == PG_OK);
        pg_gpu_desc gd = {.validation = true, .device_index = -1};
        if (pg_gpu_create(&gd, &g_gpu, &err)) {
            fprintf(stderr, "test_ocio: %s\n", err.msg);
            CHECK_MSG(0, "no GPU: %s", err.msg);
        } else {
            gpu_tests(have_luts ? lut_cfg : NULL);
            gpu_default_scene();
            printf("validation messages: %u\n", g_gpu->validation_messages);
            CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
            pg_gpu_destroy(g_gpu);
        }
    }
    char cmd[PG_PATH_MAX + 16];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_tmp);
    if (system(cmd) != 0) fprintf(stderr, "test_ocio: could not remove %s\n", g_tmp);
    return pg_test_finish("test_ocio");
}
