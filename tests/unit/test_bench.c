/* test_bench.c - the benchmark's building blocks, CPU only: sample statistics (tools/stats/bench_stats.c),
 * the Pareto front of (time, error) points, the SVG chart writer (tools/stats/svg_plot.c): tick
 * placement, labels, escaping and a well-formed document; and which overrides each side of a
 * comparison takes (tools/sides.c, shared by compare and bench: --set, --pipeline-set,
 * --reference-set, the debug view, swept values). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_stats.h"
#include "sides.h"
#include "svg_plot.h"
#include "test_util.h"

static bool near(double a, double b)
{
    return fabs(a - b) <= 1e-12 * (1.0 + fabs(b));
}

static void test_stats(void)
{
    pg_sample_stats s;
    /* odd count, unsorted input left untouched */
    double odd[] = {5, 1, 4, 2, 3};
    CHECK(pg_sample_stats_compute(odd, 5, &s, NULL) == PG_OK);
    CHECK(s.n == 5 && near(s.median, 3) && near(s.mean, 3) && near(s.min, 1) && near(s.max, 5));
    CHECK_MSG(near(s.p95, 5), "p95 of 5 samples = rank ceil(4.75) = 5th = 5, got %g", s.p95);
    CHECK(odd[0] == 5 && odd[1] == 1);
    /* even count: mean of the two middle samples */
    double even[] = {10, 2, 8, 4};
    CHECK(pg_sample_stats_compute(even, 4, &s, NULL) == PG_OK);
    CHECK_MSG(near(s.median, 6), "median of 2,4,8,10 = 6, got %g", s.median);
    CHECK(near(s.mean, 6) && near(s.min, 2) && near(s.max, 10) && near(s.p95, 10));
    /* one sample */
    double one[] = {7.5};
    CHECK(pg_sample_stats_compute(one, 1, &s, NULL) == PG_OK);
    CHECK(s.n == 1 && near(s.median, 7.5) && near(s.mean, 7.5) && near(s.min, 7.5) && near(s.max, 7.5) &&
          near(s.p95, 7.5));
    /* p95 by nearest rank: 1..20 -> rank 19 -> 19; 1..100 -> 95; 1..21 -> rank ceil(19.95) = 20 */
    double v[100];
    for (int i = 0; i < 100; i++) v[i] = 100 - i; /* descending: the function sorts */
    CHECK(pg_sample_stats_compute(v + 80, 20, &s, NULL) == PG_OK);
    CHECK_MSG(near(s.p95, 19), "p95 of 1..20 = 19, got %g", s.p95);
    CHECK(near(s.median, 10.5));
    CHECK(pg_sample_stats_compute(v, 100, &s, NULL) == PG_OK);
    CHECK_MSG(near(s.p95, 95), "p95 of 1..100 = 95, got %g", s.p95);
    CHECK(pg_sample_stats_compute(v + 79, 21, &s, NULL) == PG_OK);
    CHECK_MSG(near(s.p95, 20), "p95 of 1..21 = 20, got %g", s.p95);
    CHECK(pg_nearest_rank_pct(95, 20) == 19 && pg_nearest_rank_pct(95, 1) == 1 && pg_nearest_rank_pct(95, 0) == 0);
    CHECK(pg_nearest_rank_pct(50, 4) == 2 && pg_nearest_rank_pct(100, 7) == 7);
    /* non-finite samples are left out */
    double mixed[] = {NAN, 3, INFINITY, 1};
    CHECK(pg_sample_stats_compute(mixed, 4, &s, NULL) == PG_OK);
    CHECK(s.n == 2 && near(s.median, 2) && near(s.max, 3));
    /* nothing to summarise: n = 0, NaN, not an error */
    CHECK(pg_sample_stats_compute(NULL, 0, &s, NULL) == PG_OK);
    CHECK(s.n == 0 && isnan(s.median) && isnan(s.p95));
    double nans[] = {NAN, NAN};
    CHECK(pg_sample_stats_compute(nans, 2, &s, NULL) == PG_OK && s.n == 0 && isnan(s.mean));
    pg_error err = {0};
    CHECK(pg_sample_stats_compute(NULL, 3, &s, &err) == PG_ERR_INVALID_ARG && err.msg[0]);
}

static void test_pareto(void)
{
    bool f[8];
    uint32_t order[8];
    /* x = time, y = error; point 2 is dominated by 1, point 4 by 3 (same time, more error) */
    double x[] = {1, 2, 3, 5, 5, 8};
    double y[] = {10, 4, 6, 1, 2, 1};
    uint32_t n = pg_pareto_front(x, y, 6, f, order);
    CHECK_MSG(n == 3, "front of 6 points: want 3, got %u", n);
    CHECK(f[0] && f[1] && !f[2] && f[3] && !f[4] && !f[5]);
    CHECK(order[0] == 0 && order[1] == 1 && order[2] == 3);
    /* single point */
    double x1[] = {4}, y1[] = {0.5};
    CHECK(pg_pareto_front(x1, y1, 1, f, order) == 1 && f[0] && order[0] == 0);
    /* exact ties: identical points are all on the front, in index order */
    double xt[] = {2, 1, 2, 3};
    double yt[] = {1, 5, 1, 0};
    n = pg_pareto_front(xt, yt, 4, f, order);
    CHECK_MSG(n == 4, "ties: want 4, got %u", n);
    CHECK(order[0] == 1 && order[1] == 0 && order[2] == 2 && order[3] == 3);
    /* tie in one coordinate only: the other decides */
    double xs[] = {1, 1}, ys[] = {2, 3};
    CHECK(pg_pareto_front(xs, ys, 2, f, NULL) == 1 && f[0] && !f[1]);
    /* a point better in both dominates everything */
    double xd[] = {5, 1, 3}, yd[] = {5, 0, 2};
    CHECK(pg_pareto_front(xd, yd, 3, f, order) == 1 && f[1] && order[0] == 1);
    /* non-finite points are never on the front and dominate nothing; zero error is fine */
    double xn[] = {NAN, 2, 1}, yn[] = {0, 0, INFINITY};
    CHECK(pg_pareto_front(xn, yn, 3, f, NULL) == 1 && !f[0] && f[1] && !f[2]);
    CHECK(pg_pareto_front(NULL, NULL, 0, NULL, NULL) == 0);
}

/* A minimal XML check: every element opened is closed in order, attributes are quoted,
 * no raw '&' outside an entity. Returns false with a reason. */
static bool xml_balanced(const char *s, char *why, size_t why_size)
{
    char stack[64][32];
    int depth = 0;
    for (const char *p = s; *p; p++) {
        if (*p == '&') {
            const char *ents[] = {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"};
            bool ok = false;
            for (int k = 0; k < 5; k++) ok |= !strncmp(p, ents[k], strlen(ents[k]));
            if (!ok) {
                snprintf(why, why_size, "raw '&' at offset %ld", (long)(p - s));
                return false;
            }
            continue;
        }
        if (*p != '<') continue;
        const char *q = strchr(p, '>');
        if (!q) {
            snprintf(why, why_size, "unterminated tag at offset %ld", (long)(p - s));
            return false;
        }
        bool closing = p[1] == '/', self = q[-1] == '/';
        const char *n = p + (closing ? 2 : 1);
        size_t len = strcspn(n, " \t\n/>");
        if (len == 0 || len >= 32) {
            snprintf(why, why_size, "bad tag name at offset %ld", (long)(p - s));
            return false;
        }
        /* quotes inside the tag must pair up */
        int quotes = 0;
        for (const char *c = p; c < q; c++) quotes += *c == '"';
        if (quotes % 2) {
            snprintf(why, why_size, "odd quotes in tag at offset %ld", (long)(p - s));
            return false;
        }
        if (closing) {
            if (depth == 0 || strncmp(stack[depth - 1], n, len) || stack[depth - 1][len]) {
                snprintf(why, why_size, "</%.*s> does not close <%s>", (int)len, n, depth ? stack[depth - 1] : "");
                return false;
            }
            depth--;
        } else if (!self) {
            if (depth >= 64) {
                snprintf(why, why_size, "too deep");
                return false;
            }
            memcpy(stack[depth], n, len);
            stack[depth][len] = 0;
            depth++;
        }
        p = q;
    }
    if (depth) {
        snprintf(why, why_size, "<%s> never closed", stack[depth - 1]);
        return false;
    }
    return true;
}

static void test_ticks(void)
{
    pg_plot_tick t[64];
    /* log axis over 4 decades: labelled ticks exactly at the powers of ten */
    uint32_t n = pg_plot_ticks(PG_PLOT_LOG10, 1, 10000, t, 64);
    uint32_t majors = 0;
    bool pow10 = true;
    for (uint32_t i = 0; i < n; i++) {
        if (!t[i].major) continue;
        majors++;
        double e = log10(t[i].value);
        pow10 &= fabs(e - round(e)) < 1e-9;
    }
    CHECK_MSG(majors == 5 && pow10, "log ticks 1..1e4: want the 5 powers of ten labelled, got %u (pow10 %d)", majors,
              pow10);
    CHECK(n > majors); /* minor ticks 2..9 */
    /* tiny values, many decades */
    n = pg_plot_ticks(PG_PLOT_LOG10, 1e-7, 1e-1, t, 64);
    majors = 0;
    for (uint32_t i = 0; i < n; i++) majors += t[i].major;
    CHECK(majors == 7 && n >= 7);
    /* narrow log range: 1, 2, 5 labelled */
    n = pg_plot_ticks(PG_PLOT_LOG10, 10, 200, t, 64);
    bool has2 = false, has5 = false, has3 = false;
    for (uint32_t i = 0; i < n; i++) {
        if (!t[i].major) continue;
        has2 |= near(t[i].value, 20);
        has5 |= near(t[i].value, 50);
        has3 |= near(t[i].value, 30);
    }
    CHECK(has2 && has5 && !has3);
    /* nice ranges */
    double lo, hi;
    pg_plot_nice_range(PG_PLOT_LOG10, 30, 80, &lo, &hi);
    CHECK_MSG(near(lo, 20) && near(hi, 100), "log range of 30..80: %g..%g", lo, hi);
    pg_plot_nice_range(PG_PLOT_LOG10, 1e-6, 3e-3, &lo, &hi);
    CHECK(near(lo, 1e-6) && near(hi, 5e-3));
    pg_plot_nice_range(PG_PLOT_LINEAR, 0, 47, &lo, &hi);
    CHECK_MSG(near(lo, 0) && near(hi, 50), "linear range 0..47: %g..%g", lo, hi);
    pg_plot_nice_range(PG_PLOT_LINEAR, 5, 5, &lo, &hi);
    CHECK(lo < 5 && hi > 5);
    n = pg_plot_ticks(PG_PLOT_LINEAR, 0, 50, t, 64);
    CHECK(n == 6 && near(t[0].value, 0) && near(t[5].value, 50));
    /* labels */
    char b[64];
    pg_plot_format_tick(PG_PLOT_LOG10, 1000, 0, b, sizeof b);
    CHECK_MSG(!strcmp(b, "1000"), "got '%s'", b);
    pg_plot_format_tick(PG_PLOT_LOG10, 1e6, 0, b, sizeof b);
    CHECK_MSG(!strcmp(b, "1M"), "got '%s'", b);
    pg_plot_format_tick(PG_PLOT_LOG10, 100000, 0, b, sizeof b);
    CHECK_MSG(!strcmp(b, "100k"), "got '%s'", b);
    pg_plot_format_tick(PG_PLOT_LOG10, 0.01, 0, b, sizeof b);
    CHECK_MSG(!strcmp(b, "0.01"), "got '%s'", b);
    pg_plot_format_tick(PG_PLOT_LOG10, 1e-6, 0, b, sizeof b);
    CHECK_MSG(!strcmp(b, "10^-6"), "got '%s'", b);
    pg_plot_format_tick(PG_PLOT_LINEAR, 0.25, 0.25, b, sizeof b);
    CHECK_MSG(!strcmp(b, "0.25"), "got '%s'", b);
    pg_plot_format_tick(PG_PLOT_LINEAR, 40, 10, b, sizeof b);
    CHECK_MSG(!strcmp(b, "40"), "got '%s'", b);
    pg_svg_escape("a<b & \"c\" 'd'>", b, sizeof b);
    CHECK_MSG(!strcmp(b, "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;"), "got '%s'", b);
    pg_svg_escape("&&&&&&", b, 12);
    CHECK_MSG(!strcmp(b, "&amp;&amp;"), "truncation keeps whole entities: got '%s'", b);
    CHECK(strcmp(pg_plot_color(0), pg_plot_color(1)) && !strcmp(pg_plot_color(0), pg_plot_color(PG_PLOT_PALETTE_SIZE)));
    /* the palette's colours all differ (two stacked passes of one bar shared one with 10 colours) */
    for (int i = 0; i < PG_PLOT_PALETTE_SIZE; i++)
        for (int j = i + 1; j < PG_PLOT_PALETTE_SIZE; j++)
            CHECK_MSG(strcmp(pg_plot_color(i), pg_plot_color(j)), "colours %d and %d are both %s", i, j, pg_plot_color(i));
}

static void test_svg(void)
{
    double lx[] = {0, 100, 1000, 10000}, ly[] = {1.5, 3, 20, 180};
    double sx[] = {12}, sy[] = {0}, s2x[] = {8}, s2y[] = {2e-5};
    const char *labels[] = {"fast & <exact>"};
    pg_plot_series ser[] = {
        {.name = "naive <ref> & \"co\"", .x = lx, .y = ly, .n = 4, .color = 0, .marker = PG_MARKER_CIRCLE, .line = true},
        {.name = "forward+", .x = sx, .y = sy, .n = 1, .labels = labels, .color = 1, .marker = PG_MARKER_SQUARE},
        {.name = "deferred", .x = s2x, .y = s2y, .n = 1, .color = 2, .marker = PG_MARKER_TRIANGLE, .dasharray = "2,2"},
    };
    pg_plot plots[2] = {
        {.title = "time & lights <log>", .subtitle = "sub 'x'",
         .x = {.label = "lights", .scale = PG_PLOT_LOG10, .zero_label = "0"},
         .y = {.label = "ms", .scale = PG_PLOT_LOG10, .zero_label = "0 (exact)"}, .series = ser, .n_series = 3},
    };
    const char *bl[] = {"a", "b"}, *sn[] = {"shade", "display"};
    double bv[] = {3, 2, 2, NAN};
    const uint32_t order[] = {1, 0, 0, 1}; /* bar a draws display first */
    pg_plot_bars bars = {.n_bars = 2, .n_stack = 2, .bar_labels = bl, .stack_names = sn, .values = bv,
                         .order = order, .show_totals = true, .total_unit = " ms"};
    plots[1] = (pg_plot){.title = "bars", .x = {.label = "ms"}, .bars = &bars};
    char *svg = NULL;
    size_t len = 0;
    pg_error err = {0};
    pg_svg_doc_desc d = {.title = "doc <1>", .subtitle = "s & t"};
    CHECK(pg_svg_render(plots, 2, &d, &svg, &len, &err) == PG_OK);
    CHECK(svg && len == strlen(svg));
    if (svg) {
        CHECK_MSG(!strncmp(svg, "<svg ", 5), "document starts with '%.20s'", svg);
        CHECK(strstr(svg, "xmlns=\"http://www.w3.org/2000/svg\"") != NULL);
        char why[128] = "";
        CHECK_MSG(xml_balanced(svg, why, sizeof why), "not well-formed: %s", why);
        CHECK(strstr(svg, "time &amp; lights &lt;log&gt;") != NULL);
        CHECK(strstr(svg, "naive &lt;ref&gt; &amp; &quot;co&quot;") != NULL);
        CHECK(strstr(svg, "doc &lt;1&gt;") != NULL);
        CHECK(strstr(svg, "fast &amp; &lt;exact&gt;") != NULL);
        CHECK(strstr(svg, "<time") == NULL && strstr(svg, "<ref>") == NULL);
        /* log x ticks at powers of ten: 100, 1000, 10000 labelled; the zero band labelled "0" */
        CHECK(strstr(svg, ">100<") != NULL && strstr(svg, ">1000<") != NULL && strstr(svg, ">10000<") != NULL);
        CHECK(strstr(svg, ">0 (exact)<") != NULL);
        /* 2e-5 on a log y axis reaching below 0.001: superscript exponents */
        CHECK(strstr(svg, "<tspan") != NULL);
        CHECK(strstr(svg, "stroke-dasharray=\"2,2\"") == NULL); /* no line for the scatter series */
        CHECK(strstr(svg, "5 ms") != NULL && strstr(svg, "2 ms") != NULL); /* bar totals; NaN counts as 0 */
        const char *disp = strstr(svg, "<title>display: "), *shade = strstr(svg, "<title>shade: ");
        CHECK_MSG(disp && shade && disp < shade, "bar segments follow the given order");
        CHECK(strstr(svg, "<polyline") != NULL && strstr(svg, "<rect") != NULL && strstr(svg, "<circle") != NULL);
        size_t l = strlen(svg);
        CHECK(l > 7 && !strcmp(svg + l - 7, "</svg>\n"));
    }
    free(svg);
    /* an empty panel: a message, still well-formed */
    pg_plot empty = {.title = "nothing", .x = {.scale = PG_PLOT_LOG10}, .y = {.scale = PG_PLOT_LOG10},
                     .empty_message = "naive skipped above 5000 lights"};
    CHECK(pg_svg_render(&empty, 1, NULL, &svg, &len, &err) == PG_OK);
    if (svg) {
        char why[128] = "";
        CHECK_MSG(xml_balanced(svg, why, sizeof why), "empty panel not well-formed: %s", why);
        CHECK(strstr(svg, "naive skipped above 5000 lights") != NULL);
    }
    free(svg);
    /* bad input */
    pg_plot_series bad = {.name = "x", .n = 3};
    pg_plot bp = {.series = &bad, .n_series = 1};
    svg = NULL;
    CHECK(pg_svg_render(&bp, 1, NULL, &svg, &len, &err) == PG_ERR_INVALID_ARG && !svg && err.msg[0]);
    CHECK(pg_svg_write("/nonexistent-dir/x.svg", &empty, 1, NULL, &err) == PG_ERR_IO && strstr(err.msg, "x.svg"));
}

/* ---------------------------------------------------------------- sides: what each side takes */

/* A pipeline under test (shading, view, max_lights) and a reference (shading, view, exposure). */
#define SIDES_PIPE(name, params)                                                                   \
    "{\"name\": \"" name "\", \"parameters\": {" params "},"                                      \
    " \"resources\": [{\"name\": \"out\", \"type\": \"image\", \"format\": \"rgba8\"}],"            \
    " \"passes\": [{\"name\": \"p\", \"type\": \"t\", \"writes\": [\"out\"]}], \"output\": \"out\"}"
#define P_SHADING "\"shading\": {\"type\": \"enum\", \"values\": [\"lambert\", \"blinn_phong\"], \"default\": \"lambert\"}"
#define P_VIEW "\"view\": {\"type\": \"enum\", \"values\": [\"none\", \"albedo\"], \"default\": \"none\"}"
static const char *const k_sides_pipe =
    SIDES_PIPE("fwd", P_SHADING ", " P_VIEW ", \"max_lights\": {\"type\": \"int\", \"default\": 64, \"min\": 1, \"max\": 1024}");
static const char *const k_sides_ref =
    SIDES_PIPE("ref", P_SHADING ", " P_VIEW ", \"exposure\": {\"type\": \"float\", \"default\": 1, \"min\": 0, \"max\": 100}");

/* "k=v;k=v" of a list, for compact checks */
static const char *fmt_ov(const pg_ov_list *l)
{
    static char buf[512];
    pg_ov_list_format(l, buf, sizeof buf);
    return buf;
}

static void test_sides(void)
{
    pg_error err = {0};
    pg_pipeline *pl = NULL, *ref = NULL;
    CHECK_MSG(pg_pipeline_load_string(k_sides_pipe, "fwd.json", NULL, 0, &pl, &err) == PG_OK, "%s", err.msg);
    CHECK_MSG(pg_pipeline_load_string(k_sides_ref, "ref.json", NULL, 0, &ref, &err) == PG_OK, "%s", err.msg);
    if (!pl || !ref) {
        pg_pipeline_free(pl);
        pg_pipeline_free(ref);
        return;
    }
    static pg_side_sets ss;
    static pg_ov_list po, ro;
    /* the command line: --set shading=blinn_phong --set max_lights=8 --debug-view albedo, where the
     * common parser keeps the debug view among the sets as 'view' (pointer identity marks it) */
    pg_cli_common c;
    memset(&c, 0, sizeof c);
    static char dv[] = "albedo";
    c.sets[c.n_sets++] = (pg_param_override){"shading", "blinn_phong"};
    c.sets[c.n_sets++] = (pg_param_override){"view", dv};
    c.sets[c.n_sets++] = (pg_param_override){"max_lights", "8"};
    c.debug_view = dv;
    memset(&ss, 0, sizeof ss);
    CHECK(pg_sides_from_common(&ss, &c));
    CHECK_MSG(!strcmp(fmt_ov(&ss.set), "shading=blinn_phong;max_lights=8"), "--set list: %s", fmt_ov(&ss.set));
    CHECK_MSG(!strcmp(fmt_ov(&ss.pipeline), "view=albedo") && !strcmp(ss.pipeline.from[0], "--debug-view"),
              "the debug view is the pipeline's: %s", fmt_ov(&ss.pipeline));
    /* compare: the pipeline takes everything; the reference the --set keys it declares, no debug view */
    pg_sides_pipeline(&ss, NULL, NULL, 0, &po);
    pg_sides_reference(&ss, ref, NULL, 0, &ro);
    CHECK_MSG(!strcmp(fmt_ov(&po), "shading=blinn_phong;max_lights=8;view=albedo"), "pipeline: %s", fmt_ov(&po));
    CHECK_MSG(!strcmp(fmt_ov(&ro), "shading=blinn_phong"), "reference: %s", fmt_ov(&ro));
    CHECK(!strcmp(ro.from[0], "--set"));
    /* a reference that did not load takes no --set value */
    pg_sides_reference(&ss, NULL, NULL, 0, &ro);
    CHECK(ro.n == 0);
    /* --set view=albedo (not the debug view) goes to both sides */
    memset(&c, 0, sizeof c);
    c.sets[c.n_sets++] = (pg_param_override){"view", "albedo"};
    memset(&ss, 0, sizeof ss);
    CHECK(pg_sides_from_common(&ss, &c));
    pg_sides_reference(&ss, ref, NULL, 0, &ro);
    CHECK_MSG(!strcmp(fmt_ov(&ro), "view=albedo"), "--set view=albedo on the reference: %s", fmt_ov(&ro));

    /* --pipeline-set and --reference-set: parsed in place, each wins over --set on its side */
    memset(&ss, 0, sizeof ss);
    pg_ov_list_put(&ss.set, "shading", "blinn_phong", "--set");
    char a0[] = "--pipeline-set", a1[] = "shading=lambert", a2[] = "--reference-set", a3[] = "exposure=2",
         a4[] = "--reference-set", a5[] = "shading=lambert", a6[] = "--bogus";
    char *argv[] = {a0, a1, a2, a3, a4, a5, a6};
    int argc = 7;
    for (int i = 0; i < argc; i++) {
        bool used = false;
        pg_result r = pg_sides_parse(&ss, argc, argv, &i, &used, &err);
        CHECK_MSG(r == PG_OK, "%s", err.msg);
        CHECK_MSG(used == (i < 6), "argv[%d] used=%d", i, used);
    }
    CHECK_MSG(!strcmp(fmt_ov(&ss.pipeline), "shading=lambert"), "%s", fmt_ov(&ss.pipeline));
    CHECK_MSG(!strcmp(fmt_ov(&ss.reference), "exposure=2;shading=lambert"), "%s", fmt_ov(&ss.reference));
    pg_sides_pipeline(&ss, pl, NULL, 0, &po);
    pg_sides_reference(&ss, ref, NULL, 0, &ro);
    CHECK_MSG(!strcmp(fmt_ov(&po), "shading=lambert") && !strcmp(po.from[0], "--pipeline-set"), "pipeline: %s",
              fmt_ov(&po));
    CHECK_MSG(!strcmp(fmt_ov(&ro), "shading=lambert;exposure=2") && !strcmp(ro.from[0], "--reference-set"),
              "reference: %s", fmt_ov(&ro));

    /* bench: a pipeline takes the keys it declares; swept values go to the reference when it declares
     * the key, unless --reference-set pins it */
    memset(&ss, 0, sizeof ss);
    pg_ov_list_put(&ss.set, "exposure", "4", "--set"); /* the reference's only */
    pg_ov_list_put(&ss.pipeline, "max_lights", "16", "--pipeline-set");
    pg_param_override swept[] = {{"shading", "blinn_phong"}, {"max_lights", "32"}};
    pg_sides_pipeline(&ss, pl, swept, 1, &po);
    pg_sides_reference(&ss, ref, swept, 2, &ro);
    CHECK_MSG(!strcmp(fmt_ov(&po), "shading=blinn_phong;max_lights=16"), "bench pipeline: %s", fmt_ov(&po));
    CHECK_MSG(!strcmp(fmt_ov(&ro), "exposure=4;shading=blinn_phong") && !strcmp(ro.from[1], "--sweep"),
              "bench reference follows the sweep: %s", fmt_ov(&ro));
    pg_ov_list_put(&ss.reference, "shading", "lambert", "--reference-set");
    pg_sides_reference(&ss, ref, swept, 1, &ro);
    CHECK_MSG(!strcmp(fmt_ov(&ro), "exposure=4;shading=lambert"), "--reference-set pins it: %s", fmt_ov(&ro));

    /* keys a side does not declare: an option error naming the option, the key and the side */
    memset(&ro, 0, sizeof ro);
    pg_ov_list_put(&ro, "max_lights", "8", "--reference-set");
    CHECK(pg_sides_check_keys(&ro, ref, "reference", &err) == PG_ERR_INVALID_ARG);
    CHECK_MSG(strstr(err.msg, "--reference-set max_lights=8") && strstr(err.msg, "reference ref") &&
                  strstr(err.msg, "declared: shading, view, exposure"),
              "%s", err.msg);
    memset(&po, 0, sizeof po);
    pg_ov_list_put(&po, "view", "albedo", "--debug-view");
    CHECK(pg_sides_check_keys(&po, pl, "pipeline", &err) == PG_OK);
    CHECK(pg_sides_check_keys(&po, ref, "reference", &err) == PG_OK);
    pg_ov_list_put(&po, "exposure", "1", "--pipeline-set");
    CHECK(pg_sides_check_keys(&po, pl, "pipeline", &err) == PG_ERR_INVALID_ARG && strstr(err.msg, "--pipeline-set exposure=1"));

    /* values a side refuses: the option that gave it, not the loader's '--set' */
    char path[] = "/tmp/passgraph_test_sides_XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd >= 0) {
        size_t n = strlen(k_sides_ref);
        CHECK(write(fd, k_sides_ref, n) == (ssize_t)n);
        close(fd);
        memset(&ro, 0, sizeof ro);
        pg_ov_list_put(&ro, "exposure", "2", "--set");
        CHECK_MSG(pg_sides_check_values(path, &ro, "reference", &err) == PG_OK, "%s", err.msg);
        pg_ov_list_put(&ro, "shading", "toon", "--reference-set");
        CHECK(pg_sides_check_values(path, &ro, "reference", &err) == PG_ERR_INVALID_ARG);
        CHECK_MSG(!strncmp(err.msg, "--reference-set shading=toon: reference ", 40) && strstr(err.msg, "not one of") &&
                      !strstr(err.msg, "--set "),
                  "%s", err.msg);
        memset(&ro, 0, sizeof ro);
        pg_ov_list_put(&ro, "shading", "toon", "--sweep");
        CHECK(pg_sides_check_values(path, &ro, "reference", &err) == PG_ERR_INVALID_ARG);
        CHECK_MSG(!strncmp(err.msg, "--sweep shading=toon: ", 22) && strstr(err.msg, "--reference-set shading=VALUE"),
                  "a shared value says how to give the reference its own: %s", err.msg);
        unlink(path);
    }
    /* parse errors name the option */
    memset(&ss, 0, sizeof ss);
    char b0[] = "--reference-set", b1[] = "shading";
    char *bargv[] = {b0, b1};
    int i = 0;
    bool used;
    CHECK(pg_sides_parse(&ss, 2, bargv, &i, &used, &err) == PG_ERR_INVALID_ARG && strstr(err.msg, "--reference-set shading: expected KEY=VALUE"));
    i = 0;
    CHECK(pg_sides_parse(&ss, 1, bargv, &i, &used, &err) == PG_ERR_INVALID_ARG && strstr(err.msg, "missing value"));
    pg_pipeline_free(pl);
    pg_pipeline_free(ref);
}

int main(void)
{
    test_stats();
    test_pareto();
    test_ticks();
    test_svg();
    test_sides();
    return pg_test_finish("test_bench");
}
