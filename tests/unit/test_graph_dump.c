/* test_graph_dump.c - `passgraph dump`'s views of a compiled graph (core/dump/graph_dump.c), no GPU.
 *
 * Hand-built pipelines (JSON strings + fake pass types) with known order, culls, omitted items,
 * lifetimes, blocks and barriers: the JSON dump parses back with exactly those facts and mirrors
 * every barrier of the plan; the DOT has every node, greys the culled ones and labels barrier
 * edges; the text dump has every section; the memory-timeline SVG is well-formed with one bar per
 * transient resource. Every shipped pipeline is dumped too, and its DOT is rendered by Graphviz's
 * `dot -Tsvg` when dot is installed (skipped with a printed reason otherwise). */
#include "graph.h"
#include "graph_dump.h"
#include "pass_list.h"
#include "fake_passes.h"
#include "scene_vars.h"
#include "test_util.h"

#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ------------------------------------------------------------------------------------------ */
/* fake pass types                                                                            */

#define IMG PG_RES_IMAGE
#define BUF PG_RES_BUFFER

/* reads a buffer (unused with 0 lights) and an image; explains what it left out */
static pg_result d_final(const pg_declare_in *in, pg_pass_decl *d, pg_error *e)
{
    (void)e;
    pg_slot buf = pg_decl_read(d, "buf", BUF, PG_ACCESS_STORAGE_READ, PG_STAGE_FRAGMENT, 0);
    pg_decl_read(d, "src", IMG, PG_ACCESS_SAMPLED, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    pg_decl_write(d, "color", IMG, PG_ACCESS_COLOR_WRITE, 0, PG_FMTCLASS_FLOAT);
    pg_decl_define(d, "FAKE_FINAL");
    if (pg_lights_of(in) == 0) pg_decl_mark_unused(d, buf, "0 lights");
    if (!pg_scene_features_of(in).has_alpha_mask) pg_decl_explain(d, "no alpha-mask materials: no discard");
    return PG_OK;
}

#define TYPE(n, fn, rs, ws) {.name = n, .summary = "test type", .declare = fn} /* rs, ws: the slots, for the reader */
static const pg_pass_type g_types[] = {
    TYPE("fake_color", pg_fake_color, "", "color"),
    TYPE("fake_blur", pg_fake_blur, "src", "dst"),
    TYPE("fake_fill", pg_fake_fill_buffer, "", "buf"),
    TYPE("fake_final", d_final, "buf, src", "color"),
};
static pg_pass_registry g_reg;

/* gen -> a -> blur -> b -> final -> out, fill -> buf -> final; 'junkp' writes 'junk' that nobody
 * reads (culled); 'dbg' and 'debugp' are dropped by their 'when'. At 100x50 with 100 lights:
 *   a, b rgba16f 40,000 B; out rgba8 20,000 B; buf 16 x 100 = 1,600 B
 *   order gen(0) blur(1) fill(2) final(3); a [0..1], b [1..3], buf [2..3], out [3..4 = end]
 *   blocks #0 image {a, out}, #1 image {b}, #2 buffer {buf}: 101,600 B -> 81,600 B */
static const char *const k_graph =
    "{\"name\": \"dumptest\", \"description\": \"a graph for the dump tests\",\n"
    " \"parameters\": {\"debug\": {\"type\": \"bool\", \"default\": false}},\n"
    " \"resources\": [\n"
    "  {\"name\": \"a\", \"type\": \"image\", \"format\": \"rgba16f\"},\n"
    "  {\"name\": \"b\", \"type\": \"image\", \"format\": \"rgba16f\"},\n"
    "  {\"name\": \"junk\", \"type\": \"image\", \"format\": \"rgba8\"},\n"
    "  {\"name\": \"buf\", \"type\": \"buffer\", \"stride\": 16, \"count\": [\"lights\"]},\n"
    "  {\"name\": \"out\", \"type\": \"image\", \"format\": \"rgba8\"},\n"
    "  {\"name\": \"dbg\", \"type\": \"image\", \"format\": \"rgba8\", \"when\": \"$debug == true\"}],\n"
    " \"passes\": [\n"
    "  {\"name\": \"gen\", \"type\": \"fake_color\", \"writes\": [\"a\"]},\n"
    "  {\"name\": \"blur\", \"type\": \"fake_blur\", \"reads\": [\"a\"], \"writes\": [\"b\"]},\n"
    "  {\"name\": \"junkp\", \"type\": \"fake_color\", \"writes\": [\"junk\"]},\n"
    "  {\"name\": \"fill\", \"type\": \"fake_fill\", \"writes\": [\"buf\"]},\n"
    "  {\"name\": \"final\", \"type\": \"fake_final\", \"reads\": [\"buf\", \"b\"], \"writes\": [\"out\"]},\n"
    "  {\"name\": \"debugp\", \"type\": \"fake_color\", \"writes\": [\"dbg\"], \"when\": \"$debug == true\"}],\n"
    " \"output\": \"out\"}\n";

static pg_pipeline *load(const char *json)
{
    pg_pipeline *pl = NULL;
    pg_error err = {0};
    pg_result r = pg_pipeline_load_string(json, "dumptest.json", NULL, 0, &pl, &err);
    CHECK_MSG(r == PG_OK, "load: %s", err.msg);
    return pl;
}

static pg_graph_plan *compile(const pg_pipeline *pl, const pg_pass_registry *reg, uint32_t lights, uint32_t w,
                              uint32_t h, bool features)
{
    pg_compile_desc d;
    memset(&d, 0, sizeof d);
    d.pipeline = pl;
    d.registry = reg;
    pg_scene_vars_set(&d.vars, &(pg_scene_features){.has_alpha_mask = features, .has_normal_maps = features,
                                                    .has_textures = features},
                      lights, NULL);
    d.output_width = w;
    d.output_height = h;
    pg_graph_plan *plan = NULL;
    pg_error err = {0};
    pg_result r = pg_graph_compile(&d, &plan, &err);
    CHECK_MSG(r == PG_OK, "compile %s: %s", pl ? pl->name : "?", err.msg);
    return plan;
}

/* whole output of a FILE writer as a malloc'd string */
typedef void (*writer_fn)(const pg_graph_plan *, const pg_pipeline *, FILE *);
static char *capture(writer_fn fn, const pg_graph_plan *plan, const pg_pipeline *pl)
{
    FILE *f = tmpfile();
    if (!f) return NULL;
    fn(plan, pl, f);
    long len = ftell(f);
    rewind(f);
    char *s = calloc(1, (size_t)(len > 0 ? len : 0) + 1);
    if (s && len > 0 && fread(s, 1, (size_t)len, f) != (size_t)len) s[0] = 0;
    fclose(f);
    return s;
}

#define HAS(text, frag) CHECK_MSG((text) && strstr((text), (frag)) != NULL, "'%s' missing", frag)
#define HASNT(text, frag) CHECK_MSG((text) && strstr((text), (frag)) == NULL, "'%s' present", frag)

static size_t count_of(const char *text, const char *needle)
{
    size_t n = 0;
    for (const char *p = text; p && (p = strstr(p, needle)); p += strlen(needle)) n++;
    return n;
}

static const char *jstr(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsString(v) ? v->valuestring : NULL;
}
static double jnum(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(v) ? v->valuedouble : -12345.0;
}
static bool jnull(const cJSON *o, const char *key)
{
    return cJSON_IsNull(cJSON_GetObjectItemCaseSensitive(o, key));
}
static bool jtrue(const cJSON *o, const char *key)
{
    return cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(o, key));
}
static const cJSON *jget(const cJSON *o, const char *key)
{
    return cJSON_GetObjectItemCaseSensitive(o, key);
}
static bool streq(const char *a, const char *b)
{
    return a && b && strcmp(a, b) == 0;
}

/* names joined by '|' ("none" for an empty array) equals want */
static bool names_are(const cJSON *arr, const char *want)
{
    char buf[512] = "";
    size_t len = 0;
    const cJSON *it;
    cJSON_ArrayForEach(it, arr)
    {
        if (!cJSON_IsString(it)) return false;
        len += (size_t)snprintf(buf + len, sizeof buf - len, "%s%s", len ? "|" : "", it->valuestring);
    }
    if (!len) pg_strlcpy(buf, "none", sizeof buf);
    return strcmp(buf, want) == 0;
}

/* the barrier object mirrors the plan's barrier exactly */
static void check_barrier(const pg_graph_plan *plan, const pg_barrier *b, const cJSON *o, const char *where)
{
    char buf[512];
    CHECK_MSG(streq(jstr(o, "resource"), plan->resources[b->resource].name), "%s: resource", where);
    CHECK_MSG(streq(jstr(o, "why"), b->why), "%s: why", where);
    pg_stage_names(b->src_stages, buf, sizeof buf);
    CHECK_MSG(names_are(jget(o, "src_stages"), buf), "%s: src_stages want %s", where, buf);
    pg_access_mask_names(b->src_access, buf, sizeof buf);
    CHECK_MSG(names_are(jget(o, "src_access"), buf), "%s: src_access want %s", where, buf);
    pg_stage_names(b->dst_stages, buf, sizeof buf);
    CHECK_MSG(names_are(jget(o, "dst_stages"), buf), "%s: dst_stages want %s", where, buf);
    pg_access_mask_names(b->dst_access, buf, sizeof buf);
    CHECK_MSG(names_are(jget(o, "dst_access"), buf), "%s: dst_access want %s", where, buf);
    if (b->is_image) {
        CHECK_MSG(streq(jstr(o, "old_layout"), pg_layout_name(b->old_layout)), "%s: old_layout", where);
        CHECK_MSG(streq(jstr(o, "new_layout"), pg_layout_name(b->new_layout)), "%s: new_layout", where);
    } else {
        CHECK_MSG(jnull(o, "old_layout") && jnull(o, "new_layout"), "%s: buffer layouts not null", where);
    }
    if (b->alias_prev >= 0)
        CHECK_MSG(streq(jstr(o, "after_alias_of"), plan->resources[b->alias_prev].name), "%s: alias", where);
    else
        CHECK_MSG(jnull(o, "after_alias_of"), "%s: after_alias_of not null", where);
    CHECK_MSG(cJSON_IsBool(jget(o, "wrap")) && (bool)cJSON_IsTrue(jget(o, "wrap")) == b->wrap, "%s: wrap", where);
    CHECK_MSG(cJSON_IsBool(jget(o, "first_frame")) && (bool)cJSON_IsTrue(jget(o, "first_frame")) == b->first_frame,
              "%s: first_frame", where);
}

/* Checks that a JSON dump states exactly what the plan says (any plan). */
static void check_json_mirrors_plan(const pg_graph_plan *plan, const pg_pipeline *pl, const cJSON *root,
                                    const char *what)
{
    CHECK_MSG(jnum(root, "format_version") == 1, "%s: format_version", what);
    const cJSON *order = jget(root, "order"), *passes = jget(root, "passes");
    CHECK_MSG(cJSON_GetArraySize(order) == (int)plan->n_order, "%s: order size", what);
    CHECK_MSG(cJSON_GetArraySize(passes) == (int)plan->n_order, "%s: passes size", what);
    uint32_t n_barriers = 0;
    for (uint32_t k = 0; k < plan->n_order && k < (uint32_t)cJSON_GetArraySize(passes); k++) {
        const pg_plan_pass *pp = &plan->passes[plan->order[k]];
        const cJSON *jp = cJSON_GetArrayItem(passes, (int)k);
        CHECK_MSG(streq(cJSON_GetArrayItem(order, (int)k)->valuestring, pp->name), "%s: order[%u]", what, k);
        CHECK_MSG(streq(jstr(jp, "name"), pp->name) && jnum(jp, "position") == k, "%s: passes[%u]", what, k);
        CHECK_MSG(streq(jstr(jp, "type"), pp->type->name), "%s: passes[%u].type", what, k);
        const cJSON *bs = jget(jp, "barriers");
        CHECK_MSG(cJSON_GetArraySize(bs) == (int)pp->n_barriers, "%s: %s: %d barriers, plan %u", what, pp->name,
                  cJSON_GetArraySize(bs), pp->n_barriers);
        for (uint32_t b = 0; b < pp->n_barriers && b < (uint32_t)cJSON_GetArraySize(bs); b++) {
            char where[160];
            snprintf(where, sizeof where, "%s: %s barrier %u", what, pp->name, b);
            check_barrier(plan, &pp->barriers[b], cJSON_GetArrayItem(bs, (int)b), where);
        }
        n_barriers += pp->n_barriers;
        uint32_t n_r = 0, n_w = 0;
        for (uint32_t s = 0; s < pp->n_slots; s++) pp->slots[s].is_write ? n_w++ : n_r++;
        CHECK_MSG(cJSON_GetArraySize(jget(jp, "reads")) == (int)n_r, "%s: %s reads", what, pp->name);
        CHECK_MSG(cJSON_GetArraySize(jget(jp, "writes")) == (int)n_w, "%s: %s writes", what, pp->name);
        CHECK_MSG(cJSON_GetArraySize(jget(jp, "defines")) == (int)pp->decl.n_defines, "%s: %s defines", what,
                  pp->name);
        CHECK_MSG(cJSON_GetArraySize(jget(jp, "left_out")) == (int)pp->decl.n_explain, "%s: %s left_out", what,
                  pp->name);
    }
    const cJSON *fb = jget(root, "final_barriers");
    CHECK_MSG(cJSON_GetArraySize(fb) == (int)plan->n_final_barriers, "%s: final barriers", what);
    for (uint32_t b = 0; b < plan->n_final_barriers && b < (uint32_t)cJSON_GetArraySize(fb); b++)
        check_barrier(plan, &plan->final_barriers[b], cJSON_GetArrayItem(fb, (int)b), "final");

    uint32_t n_culled = 0;
    for (uint32_t i = 0; i < plan->n_passes; i++) n_culled += plan->passes[i].culled;
    const cJSON *culled = jget(root, "culled_passes");
    CHECK_MSG(cJSON_GetArraySize(culled) == (int)n_culled, "%s: culled_passes", what);
    const cJSON *c;
    cJSON_ArrayForEach(c, culled)
    {
        bool found = false;
        for (uint32_t i = 0; i < plan->n_passes; i++)
            if (plan->passes[i].culled && streq(jstr(c, "name"), plan->passes[i].name))
                found = streq(jstr(c, "reason"), plan->passes[i].cull_reason);
        CHECK_MSG(found, "%s: culled pass %s with its reason", what, jstr(c, "name"));
    }
    CHECK_MSG(cJSON_GetArraySize(jget(root, "omitted")) == (int)(pl ? pl->n_omitted : 0), "%s: omitted", what);
    CHECK_MSG(cJSON_GetArraySize(jget(root, "explain")) == (int)plan->n_explain, "%s: explain", what);

    const cJSON *res = jget(root, "resources");
    CHECK_MSG(cJSON_GetArraySize(res) == (int)plan->n_resources, "%s: resources", what);
    for (uint32_t r = 0; r < plan->n_resources && r < (uint32_t)cJSON_GetArraySize(res); r++) {
        const pg_plan_resource *pr = &plan->resources[r];
        const cJSON *jr = cJSON_GetArrayItem(res, (int)r);
        CHECK_MSG(streq(jstr(jr, "name"), pr->name), "%s: resources[%u]", what, r);
        CHECK_MSG(jnum(jr, "size_bytes") == (double)pr->size_bytes, "%s: %s size", what, pr->name);
        CHECK_MSG(jtrue(jr, "culled") == pr->culled, "%s: %s culled", what, pr->name);
        if (pr->block >= 0)
            CHECK_MSG(jnum(jr, "block") == pr->block && jnum(jr, "offset") == (double)pr->block_offset,
                      "%s: %s block", what, pr->name);
        else
            CHECK_MSG(jnull(jr, "block") && jnull(jr, "offset"), "%s: %s block not null", what, pr->name);
        if (!pr->culled && pr->first_pass >= 0)
            CHECK_MSG(jnum(jr, "first_position") == pr->first_pass && jnum(jr, "last_position") == pr->last_pass,
                      "%s: %s lifetime", what, pr->name);
    }
    const cJSON *blocks = jget(root, "blocks");
    CHECK_MSG(cJSON_GetArraySize(blocks) == (int)plan->n_blocks, "%s: blocks", what);
    for (uint32_t b = 0; b < plan->n_blocks && b < (uint32_t)cJSON_GetArraySize(blocks); b++) {
        const cJSON *jb = cJSON_GetArrayItem(blocks, (int)b);
        const cJSON *mem = jget(jb, "members");
        CHECK_MSG(jnum(jb, "size_bytes") == (double)plan->blocks[b].size_bytes, "%s: block %u size", what, b);
        CHECK_MSG(cJSON_GetArraySize(mem) == (int)plan->blocks[b].n_members, "%s: block %u members", what, b);
        for (uint32_t m = 0; m < plan->blocks[b].n_members && m < (uint32_t)cJSON_GetArraySize(mem); m++)
            CHECK_MSG(streq(jstr(cJSON_GetArrayItem(mem, (int)m), "resource"),
                            plan->resources[plan->blocks[b].members[m]].name),
                      "%s: block %u member %u", what, b, m);
    }
    const cJSON *t = jget(root, "totals");
    CHECK_MSG(jnum(t, "passes_run") == plan->n_order, "%s: totals.passes_run", what);
    CHECK_MSG(jnum(t, "passes_culled") == n_culled, "%s: totals.passes_culled", what);
    CHECK_MSG(jnum(t, "barriers") == n_barriers, "%s: totals.barriers", what);
    CHECK_MSG(jnum(t, "final_barriers") == plan->n_final_barriers, "%s: totals.final_barriers", what);
    CHECK_MSG(jnum(t, "transient_bytes_unaliased") == (double)plan->transient_bytes_unaliased,
              "%s: totals unaliased", what);
    CHECK_MSG(jnum(t, "transient_bytes_aliased") == (double)plan->transient_bytes_aliased, "%s: totals aliased",
              what);
}

/* A small well-formedness check: every element closed in order, attribute quotes balanced, the
 * document is one <svg> element. */
static bool xml_balanced(const char *s, char *why, size_t why_size)
{
    char stack[64][32];
    int depth = 0, roots = 0;
    const char *p = s;
    while ((p = strchr(p, '<'))) {
        if (!strncmp(p, "<?", 2) || !strncmp(p, "<!", 2)) {
            p = strchr(p, '>');
            if (!p) break;
            continue;
        }
        const bool closing = p[1] == '/';
        const char *name = p + (closing ? 2 : 1);
        size_t n = strcspn(name, " \t\n/>");
        if (!n || n >= 32) {
            snprintf(why, why_size, "bad tag near '%.20s'", p);
            return false;
        }
        /* find the end of the tag, outside quotes */
        const char *q = name + n;
        char quote = 0;
        for (; *q && (quote || *q != '>'); q++)
            if (*q == '"' || *q == '\'') quote = quote == *q ? 0 : (quote ? quote : *q);
        if (!*q) {
            snprintf(why, why_size, "unterminated tag near '%.20s'", p);
            return false;
        }
        if (closing) {
            if (!depth || strncmp(stack[depth - 1], name, n) || stack[depth - 1][n]) {
                snprintf(why, why_size, "</%.*s> does not close <%s>", (int)n, name, depth ? stack[depth - 1] : "");
                return false;
            }
            depth--;
        } else if (q[-1] != '/') {
            if (depth == 0) roots++;
            if (depth >= 64) {
                snprintf(why, why_size, "too deep");
                return false;
            }
            memcpy(stack[depth], name, n);
            stack[depth][n] = 0;
            depth++;
        }
        p = q + 1;
    }
    if (depth || roots != 1) {
        snprintf(why, why_size, "depth %d at the end, %d root elements", depth, roots);
        return false;
    }
    return true;
}

static void check_timeline(const pg_graph_plan *plan, const pg_pipeline *pl, const char *what)
{
    char *svg = capture(pg_dump_timeline_svg, plan, pl);
    CHECK_MSG(svg && !strncmp(svg, "<svg", 4), "%s: timeline does not start with <svg", what);
    size_t len = svg ? strlen(svg) : 0;
    CHECK_MSG(len > 7 && !strcmp(svg + len - 7, "</svg>\n"), "%s: timeline does not end with </svg>", what);
    char why[160] = "";
    CHECK_MSG(svg && xml_balanced(svg, why, sizeof why), "%s: timeline SVG not well-formed: %s", what, why);
    uint32_t transients = 0;
    for (uint32_t r = 0; r < plan->n_resources; r++) {
        const pg_plan_resource *pr = &plan->resources[r];
        if (pr->block < 0) continue;
        transients++;
        char attr[PG_NAME_MAX + 32];
        snprintf(attr, sizeof attr, "data-resource=\"%s\"", pr->name);
        CHECK_MSG(count_of(svg, attr) == 1, "%s: timeline: one bar for %s", what, pr->name);
    }
    CHECK_MSG(count_of(svg, "class=\"bar\"") == transients, "%s: timeline: %zu bars, %u transient resources",
              what, count_of(svg, "class=\"bar\""), transients);
    free(svg);
}

/* ------------------------------------------------------------------------------------------ */
/* the hand-built graph                                                                       */

static void test_hand_graph_json(void)
{
    pg_pipeline *pl = load(k_graph);
    if (!pl) return;
    pg_graph_plan *plan = compile(pl, &g_reg, 100, 100, 50, false);
    if (!plan) {
        pg_pipeline_free(pl);
        return;
    }
    char *json = pg_dump_json(plan, pl);
    CHECK(json != NULL);
    cJSON *root = json ? cJSON_Parse(json) : NULL;
    CHECK_MSG(root != NULL, "JSON dump does not parse");
    if (root) {
        /* top-level keys, in this order */
        static const char *const keys[] = {"format_version", "pipeline", "output", "aliasing", "immediate", "order",
                                           "passes", "final_barriers", "culled_passes", "omitted", "explain",
                                           "resources", "blocks", "totals", NULL};
        const cJSON *it = root->child;
        for (int i = 0; keys[i]; i++, it = it ? it->next : NULL)
            CHECK_MSG(it && streq(it->string, keys[i]), "top-level key %d: want %s, got %s", i, keys[i],
                      it ? it->string : "(end)");
        CHECK_MSG(it == NULL, "extra top-level key %s", it ? it->string : "");

        const cJSON *jp = jget(root, "pipeline");
        CHECK(streq(jstr(jp, "name"), "dumptest"));
        CHECK(streq(jstr(jp, "description"), "a graph for the dump tests"));
        CHECK(cJSON_IsFalse(jget(jget(jp, "parameters"), "debug")));
        CHECK(cJSON_GetArraySize(jget(jp, "overridden")) == 0);
        const cJSON *out = jget(root, "output");
        CHECK(streq(jstr(out, "resource"), "out") && jnull(out, "hdr_resource"));
        CHECK(jnum(out, "width") == 100 && jnum(out, "height") == 50);
        CHECK(jtrue(root, "aliasing"));
        CHECK(cJSON_IsFalse(jget(root, "immediate")));

        /* order */
        const cJSON *order = jget(root, "order");
        CHECK(names_are(order, "gen|blur|fill|final"));
        const cJSON *passes = jget(root, "passes");
        const cJSON *final = cJSON_GetArrayItem(passes, 3);
        CHECK(streq(jstr(final, "name"), "final") && streq(jstr(final, "type"), "fake_final"));
        CHECK(jnum(final, "declared_index") == 4);
        CHECK(names_are(jget(final, "defines"), "FAKE_FINAL"));
        CHECK(cJSON_GetArraySize(jget(final, "left_out")) == 1 &&
              streq(cJSON_GetArrayItem(jget(final, "left_out"), 0)->valuestring, "no alpha-mask materials: no discard"));
        const cJSON *r0 = cJSON_GetArrayItem(jget(final, "reads"), 0);
        CHECK(streq(jstr(r0, "resource"), "buf") && streq(jstr(r0, "slot"), "buf") &&
              streq(jstr(r0, "access"), "storage_read") && !jtrue(r0, "unused") && jnull(r0, "layout"));
        CHECK(names_are(jget(r0, "stages"), "fragment_shader"));
        const cJSON *r1 = cJSON_GetArrayItem(jget(final, "reads"), 1);
        CHECK(streq(jstr(r1, "resource"), "b") && streq(jstr(r1, "access"), "sampled") &&
              streq(jstr(r1, "layout"), "shader_read_only"));
        const cJSON *w0 = cJSON_GetArrayItem(jget(final, "writes"), 0);
        CHECK(streq(jstr(w0, "resource"), "out") && streq(jstr(w0, "layout"), "color_attachment"));

        /* barriers placed at 'blur': a RAW+layout from the colour attachment to a sampled read,
         * and b's first use from UNDEFINED */
        const cJSON *blur_b = jget(cJSON_GetArrayItem(passes, 1), "barriers");
        CHECK(cJSON_GetArraySize(blur_b) == 2);
        const cJSON *ba = cJSON_GetArrayItem(blur_b, 0);
        CHECK(streq(jstr(ba, "resource"), "a") && streq(jstr(ba, "why"), "RAW+layout"));
        CHECK(names_are(jget(ba, "src_stages"), "color_output") && names_are(jget(ba, "src_access"), "color_write"));
        CHECK(names_are(jget(ba, "dst_stages"), "fragment_shader") &&
              names_are(jget(ba, "dst_access"), "sampled_read"));
        CHECK(streq(jstr(ba, "old_layout"), "color_attachment") && streq(jstr(ba, "new_layout"), "shader_read_only"));
        const cJSON *bb = cJSON_GetArrayItem(blur_b, 1);
        CHECK(streq(jstr(bb, "resource"), "b") && streq(jstr(bb, "old_layout"), "undefined") &&
              names_are(jget(bb, "src_access"), "none"));
        /* 'out' reuses a's memory at 'final': its first use waits for a's last reader */
        const cJSON *fin_b = jget(final, "barriers");
        bool alias_seen = false;
        cJSON_ArrayForEach(it, fin_b) if (streq(jstr(it, "resource"), "out"))
        {
            alias_seen = true;
            CHECK(streq(jstr(it, "after_alias_of"), "a") && streq(jstr(it, "old_layout"), "undefined") &&
                  names_are(jget(it, "src_stages"), "fragment_shader|color_output"));
        }
        CHECK(alias_seen);
        const cJSON *fb = jget(root, "final_barriers");
        CHECK(cJSON_GetArraySize(fb) == 1 && streq(jstr(cJSON_GetArrayItem(fb, 0), "resource"), "out") &&
              streq(jstr(cJSON_GetArrayItem(fb, 0), "new_layout"), "transfer_src"));

        /* culled and omitted, with reasons */
        const cJSON *culled = jget(root, "culled_passes");
        CHECK(cJSON_GetArraySize(culled) == 1);
        const cJSON *cp = cJSON_GetArrayItem(culled, 0);
        CHECK(streq(jstr(cp, "name"), "junkp") && streq(jstr(cp, "type"), "fake_color"));
        CHECK(jstr(cp, "reason") && strstr(jstr(cp, "reason"), "nothing reads its writes (junk)"));
        CHECK(names_are(jget(cp, "writes"), "junk") && names_are(jget(cp, "reads"), "none"));
        const cJSON *om = jget(root, "omitted");
        CHECK(cJSON_GetArraySize(om) == 2);
        CHECK(streq(jstr(cJSON_GetArrayItem(om, 0), "what"), "resource 'dbg'"));
        CHECK(streq(jstr(cJSON_GetArrayItem(om, 1), "what"), "pass 'debugp'"));
        CHECK(jstr(cJSON_GetArrayItem(om, 1), "why") && strstr(jstr(cJSON_GetArrayItem(om, 1), "why"), "$debug"));

        /* resources */
        const cJSON *res = jget(root, "resources");
        CHECK(cJSON_GetArraySize(res) == 5);
        const struct {
            const char *name, *kind, *format, *first, *last;
            double bytes;
            int block;
        } want[] = {
            {"a", "image", "rgba16f", "gen", "blur", 40000, 0},
            {"b", "image", "rgba16f", "blur", "final", 40000, 1},
            {"junk", "image", "rgba8", NULL, NULL, 20000, -1},
            {"buf", "buffer", NULL, "fill", "final", 1600, 2},
            {"out", "image", "rgba8", "final", "(end)", 20000, 0},
        };
        for (int i = 0; i < 5; i++) {
            const cJSON *jr = cJSON_GetArrayItem(res, i);
            CHECK_MSG(streq(jstr(jr, "name"), want[i].name), "resources[%d] %s", i, want[i].name);
            CHECK_MSG(streq(jstr(jr, "kind"), want[i].kind), "%s kind", want[i].name);
            CHECK_MSG(want[i].format ? streq(jstr(jr, "format"), want[i].format) : jnull(jr, "format"), "%s format",
                      want[i].name);
            CHECK_MSG(jnum(jr, "size_bytes") == want[i].bytes, "%s bytes %g", want[i].name, jnum(jr, "size_bytes"));
            CHECK_MSG(want[i].first ? streq(jstr(jr, "first_pass"), want[i].first) : jnull(jr, "first_pass"),
                      "%s first", want[i].name);
            CHECK_MSG(want[i].last ? streq(jstr(jr, "last_pass"), want[i].last) : jnull(jr, "last_pass"), "%s last",
                      want[i].name);
            CHECK_MSG(want[i].block >= 0 ? jnum(jr, "block") == want[i].block && jnum(jr, "offset") == 0
                                         : jnull(jr, "block") && jnull(jr, "offset"),
                      "%s block", want[i].name);
            CHECK_MSG(streq(jstr(jr, "lifetime"), "transient"), "%s lifetime", want[i].name);
        }
        CHECK(jtrue(cJSON_GetArrayItem(res, 2), "culled") &&
              streq(jstr(cJSON_GetArrayItem(res, 2), "cull_reason"), "not used by any pass that runs"));
        CHECK(jtrue(cJSON_GetArrayItem(res, 4), "output") && jnum(cJSON_GetArrayItem(res, 4), "last_position") == 4);
        CHECK(jnum(cJSON_GetArrayItem(res, 0), "width") == 100 && jnum(cJSON_GetArrayItem(res, 0), "height") == 50);
        CHECK(jnull(cJSON_GetArrayItem(res, 3), "width"));

        /* blocks */
        const cJSON *blocks = jget(root, "blocks");
        CHECK(cJSON_GetArraySize(blocks) == 3);
        const cJSON *b0 = cJSON_GetArrayItem(blocks, 0);
        CHECK(jnum(b0, "index") == 0 && streq(jstr(b0, "kind"), "image") && jnum(b0, "size_bytes") == 40000);
        CHECK(cJSON_GetArraySize(jget(b0, "members")) == 2);
        CHECK(streq(jstr(cJSON_GetArrayItem(jget(b0, "members"), 0), "resource"), "a"));
        CHECK(streq(jstr(cJSON_GetArrayItem(jget(b0, "members"), 1), "resource"), "out"));
        CHECK(jnum(cJSON_GetArrayItem(jget(b0, "members"), 1), "first_position") == 3);
        CHECK(streq(jstr(cJSON_GetArrayItem(blocks, 2), "kind"), "buffer"));

        /* totals */
        const cJSON *t = jget(root, "totals");
        CHECK(jnum(t, "passes_declared") == 5 && jnum(t, "passes_run") == 4 && jnum(t, "passes_culled") == 1);
        CHECK(jnum(t, "resources_declared") == 5 && jnum(t, "resources_culled") == 1 && jnum(t, "omitted") == 2);
        CHECK_MSG(jnum(t, "barriers") == 6, "barriers %g", jnum(t, "barriers"));
        CHECK(jnum(t, "final_barriers") == 1 && jnum(t, "blocks") == 3);
        CHECK(jnum(t, "transient_bytes_unaliased") == 101600 && jnum(t, "transient_bytes_aliased") == 81600);
        CHECK_MSG(jnum(t, "saving_percent") == 19.7, "saving %g", jnum(t, "saving_percent"));

        check_json_mirrors_plan(plan, pl, root, "hand graph");
        cJSON_Delete(root);
    }
    /* the same plan dumps to the same bytes (stable) */
    char *again = pg_dump_json(plan, pl);
    CHECK(json && again && strcmp(json, again) == 0);
    free(again);
    free(json);
    CHECK(pg_dump_json(NULL, pl) == NULL);

    /* --set is reported; aliasing off shows in the dump */
    pg_graph_plan_free(plan);
    pg_pipeline_free(pl);
    pl = NULL;
    pg_param_override ov = {"debug", "true"};
    pg_error err = {0};
    CHECK(pg_pipeline_load_string(k_graph, "dumptest.json", &ov, 1, &pl, &err) == PG_OK);
    if (pl) {
        pg_compile_desc d;
        memset(&d, 0, sizeof d);
        d.pipeline = pl;
        d.registry = &g_reg;
        pg_scene_vars_set(&d.vars, NULL, 100, NULL);
        d.output_width = 100;
        d.output_height = 50;
        d.disable_aliasing = true;
        plan = NULL;
        CHECK(pg_graph_compile(&d, &plan, &err) == PG_OK);
        json = plan ? pg_dump_json(plan, pl) : NULL;
        root = json ? cJSON_Parse(json) : NULL;
        CHECK(root != NULL);
        if (root) {
            CHECK(names_are(jget(jget(root, "pipeline"), "overridden"), "debug"));
            CHECK(cJSON_IsTrue(jget(jget(jget(root, "pipeline"), "parameters"), "debug")));
            CHECK(cJSON_IsFalse(jget(root, "aliasing")));
            CHECK(cJSON_GetArraySize(jget(root, "omitted")) == 0);
            CHECK(cJSON_GetArraySize(jget(root, "culled_passes")) == 2); /* junkp, debugp */
            const cJSON *t = jget(root, "totals");
            CHECK(jnum(t, "transient_bytes_aliased") == jnum(t, "transient_bytes_unaliased"));
            check_json_mirrors_plan(plan, pl, root, "no aliasing");
            cJSON_Delete(root);
        }
        free(json);
        pg_graph_plan_free(plan);
        pg_pipeline_free(pl);
    }
}

static void test_hand_graph_text_dot_svg(void)
{
    pg_pipeline *pl = load(k_graph);
    if (!pl) return;
    pg_graph_plan *plan = compile(pl, &g_reg, 100, 100, 50, false);
    if (!plan) {
        pg_pipeline_free(pl);
        return;
    }

    /* text: every section, lifetimes, blocks with offsets, the timeline, totals */
    char *text = capture(pg_dump_text, plan, pl);
    static const char *const sections[] = {"description: a graph for the dump tests",
                                           "parameters: debug=false",
                                           "pipeline 'dumptest'",
                                           "output 'out' 100x50",
                                           "execution order (4 passes):",
                                           "after the last pass:",
                                           "culled passes:",
                                           "culled resources:",
                                           "explain (left out, culled, and why):",
                                           "resources:",
                                           "memory blocks:",
                                           "memory timeline",
                                           "totals: 4 passes run, 1 culled; 6 barriers (+1 after the last pass)",
                                           NULL};
    for (int i = 0; sections[i]; i++) HAS(text, sections[i]);
    HAS(text, "junkp: nothing reads its writes (junk)");
    HAS(text, "junk: not used by any pass that runs");
    HAS(text, "omitted pass 'debugp': when: $debug == true");
    HAS(text, "final: no alpha-mask materials: no discard");
    HAS(text, "alias first use after 'a'");
    HAS(text, "undefined -> color_attachment");
    HAS(text, "gen..blur");
    HAS(text, "final..(end)");
    HAS(text, "#0 @ 0");
    HAS(text, "#0 image 39.1 KiB: a [0..1], out [3..4]");
    HAS(text, "    a                       [====] .  .  . \n");
    HAS(text, "    out                      .  .  . [====]\n");
    HAS(text, "101600 B) unaliased -> 79.7 KiB (81600 B) aliased, saving 19.7%");
    /* section order */
    const char *p1 = text ? strstr(text, "execution order") : NULL, *p2 = text ? strstr(text, "resources:") : NULL;
    const char *p3 = text ? strstr(text, "memory timeline") : NULL, *p4 = text ? strstr(text, "totals:") : NULL;
    CHECK(p1 && p2 && p3 && p4 && p1 < p2 && p2 < p3 && p3 < p4);
    if (getenv("PG_TEST_VERBOSE")) fputs(text, stdout);
    free(text);

    /* DOT: a node per pass and resource, culled ones dashed grey, barrier labels on edges */
    char *dot = capture(pg_dump_dot, plan, pl);
    CHECK(dot && !strncmp(dot, "digraph passgraph {", 19));
    for (uint32_t i = 0; i < plan->n_passes; i++) {
        char id[32];
        snprintf(id, sizeof id, "\n  p%u [", i);
        HAS(dot, id);
        char name[PG_NAME_MAX + 8];
        snprintf(name, sizeof name, "<b>%s</b>", plan->passes[i].name);
        HAS(dot, name);
    }
    for (uint32_t r = 0; r < plan->n_resources; r++) {
        char id[32];
        snprintf(id, sizeof id, "\n  r%u [", r);
        HAS(dot, id);
    }
    /* the culled pass (junkp = p2) and resource (junk = r2) are dashed grey */
    HAS(dot, "\n  p2 [shape=box, style=\"rounded,dashed\", color=\"#9a9a9a\"");
    HAS(dot, "culled: nothing reads its writes (junk)");
    HAS(dot, "\n  r2 [shape=note, style=dashed, color=\"#9a9a9a\"");
    HAS(dot, "  p2 -> r2 [style=dashed, color=\"#a0a0a0\"");
    /* executed passes are filled rounded boxes */
    HAS(dot, "\n  p0 [shape=box, style=\"rounded,filled\"");
    /* a -> blur carries the RAW+layout barrier; gen -> a its first use; out its alias first use */
    HAS(dot, "  r0 -> p1 [color=\"#c0392b\", fontcolor=\"#a02818\", label=\"RAW+layout color\xe2\x86\x92sampled\\n"
             "color_att\xe2\x86\x92shader_ro\"");
    HAS(dot, "  p0 -> r0 [color=\"#c0392b\", fontcolor=\"#a02818\", label=\"first use: color\\n"
             "undef\xe2\x86\x92" "color_att\"");
    HAS(dot, "label=\"alias after a color\xe2\x86\x92" "color\\nundef\xe2\x86\x92" "color_att\"");
    HAS(dot, "  r3 -> p4 [color=\"#c0392b\", fontcolor=\"#a02818\", label=\"RAW storage\xe2\x86\x92storage\"");
    /* read back after the last pass, the omitted items, the defines and left-out features */
    HAS(dot, "readback [shape=cds");
    HAS(dot, "  r4 -> readback [");
    HAS(dot, "label=\"output color\xe2\x86\x92transfer\\ncolor_att\xe2\x86\x92xfer_src\"");
    HAS(dot, "omitted [shape=note, style=dashed");
    HAS(dot, "pass 'debugp'");
    HAS(dot, "FAKE_FINAL");
    HAS(dot, "<i>no alpha-mask materials: no discard</i>");
    HAS(dot, "block #0 @ 0");
    HAS(dot, "<b>output</b>");
    /* every barrier of the plan is an edge label (its exact short label) */
    for (uint32_t i = 0; i < plan->n_passes; i++)
        for (uint32_t b = 0; b < plan->passes[i].n_barriers; b++) {
            char label[256], esc[300];
            pg_dump_barrier_label(plan, &plan->passes[i].barriers[b], label, sizeof label);
            size_t k = 0;
            for (const char *c = label; *c && k + 2 < sizeof esc; c++) {
                if (*c == '\n') esc[k++] = '\\', esc[k++] = 'n';
                else esc[k++] = *c;
            }
            esc[k] = 0;
            HAS(dot, esc);
        }
    CHECK(dot && dot[strlen(dot) - 2] == '}');
    free(dot);

    check_timeline(plan, pl, "hand graph");
    char *svg = capture(pg_dump_timeline_svg, plan, pl);
    HAS(svg, "data-resource=\"out\" data-block=\"0\"");
    HAS(svg, "data-resource=\"a\" data-block=\"0\"");
    HAS(svg, "data-resource=\"buf\" data-block=\"2\"");
    HASNT(svg, "data-resource=\"junk\"");
    HAS(svg, ">read back<");
    HAS(svg, ">final<");
    free(svg);
    pg_graph_plan_free(plan);

    /* 0 lights: final's buffer read is unused, so fill is culled; the DOT draws a dotted edge */
    plan = compile(pl, &g_reg, 0, 100, 50, true);
    if (plan) {
        dot = capture(pg_dump_dot, plan, pl);
        HAS(dot, "  r3 -> p4 [style=dotted, color=\"#a0a0a0\", fontcolor=\"#8a8a8a\", label=\"unused\"");
        HAS(dot, "\n  p3 [shape=box, style=\"rounded,dashed\"");
        free(dot);
        char *json = pg_dump_json(plan, pl);
        cJSON *root = json ? cJSON_Parse(json) : NULL;
        CHECK(root != NULL);
        if (root) {
            const cJSON *final = cJSON_GetArrayItem(jget(root, "passes"), 2);
            CHECK(streq(jstr(final, "name"), "final"));
            const cJSON *r0 = cJSON_GetArrayItem(jget(final, "reads"), 0);
            CHECK(jtrue(r0, "unused") && names_are(jget(r0, "stages"), "none"));
            CHECK(cJSON_GetArraySize(jget(final, "left_out")) == 1); /* features on: only the unused slot */
            CHECK(names_are(jget(root, "order"), "gen|blur|final"));
            check_json_mirrors_plan(plan, pl, root, "0 lights");
            cJSON_Delete(root);
        }
        free(json);
        check_timeline(plan, pl, "0 lights");
        pg_graph_plan_free(plan);
    }
    pg_pipeline_free(pl);

    /* NULL plans do not crash */
    text = capture(pg_dump_text, NULL, NULL);
    HAS(text, "(no plan)");
    free(text);
    dot = capture(pg_dump_dot, NULL, NULL);
    HAS(dot, "digraph");
    free(dot);
    svg = capture(pg_dump_timeline_svg, NULL, NULL);
    CHECK(svg && !strncmp(svg, "<svg", 4));
    free(svg);
}

/* ------------------------------------------------------------------------------------------ */
/* Graphviz                                                                                   */

static bool dot_installed(void)
{
    const char *path = getenv("PATH");
    if (!path) return false;
    char buf[4096];
    pg_strlcpy(buf, path, sizeof buf);
    char *save = NULL;
    for (char *d = strtok_r(buf, ":", &save); d; d = strtok_r(NULL, ":", &save)) {
        char cand[PG_PATH_MAX];
        snprintf(cand, sizeof cand, "%s/dot", d);
        if (access(cand, X_OK) == 0) return true;
    }
    return false;
}

/* renders dot_text to SVG with Graphviz; true when dot exits 0 and the file is an SVG */
static bool graphviz_accepts(const char *dot_text, const char *what)
{
    char path[] = "/tmp/pg_dump_test_XXXXXX";
    int fd = mkstemp(path);
    if (fd < 0) return false;
    close(fd);
    pg_error err = {0};
    pg_result r = pg_dump_run_graphviz(dot_text, "svg", path, &err);
    CHECK_MSG(r == PG_OK, "%s: dot -Tsvg: %s", what, err.msg);
    bool ok = false;
    FILE *f = fopen(path, "rb");
    if (f) {
        char head[4096] = "";
        size_t n = fread(head, 1, sizeof head - 1, f);
        head[n] = 0;
        ok = strstr(head, "<svg") != NULL;
        fclose(f);
    }
    CHECK_MSG(r != PG_OK || ok, "%s: dot wrote no SVG", what);
    remove(path);
    return r == PG_OK && ok;
}

static void test_graphviz_errors(void)
{
    CHECK(streq(pg_dump_graphviz_format_for("x/graph.svg"), "svg"));
    CHECK(streq(pg_dump_graphviz_format_for("graph.PNG"), "png"));
    CHECK(streq(pg_dump_graphviz_format_for("g.pdf"), "pdf"));
    CHECK(pg_dump_graphviz_format_for("graph.dot") == NULL);
    CHECK(pg_dump_graphviz_format_for("dir.svg/graph") == NULL);
    CHECK(pg_dump_graphviz_format_for(NULL) == NULL);
    pg_error err = {0};
    CHECK(pg_dump_run_graphviz("digraph{}", "svg;rm", "/tmp/x.svg", &err) == PG_ERR_INVALID_ARG);

    /* dot missing: the message names the package */
    const char *old = getenv("PATH");
    char *saved = old ? strdup(old) : NULL;
    setenv("PATH", "/nonexistent-pg-dump-test", 1);
    memset(&err, 0, sizeof err);
    CHECK(pg_dump_run_graphviz("digraph{}", "svg", "/tmp/pg_dump_never.svg", &err) == PG_ERR_IO);
    CHECK_MSG(strstr(err.msg, "graphviz") != NULL, "message lacks the package name: %s", err.msg);
    if (saved) setenv("PATH", saved, 1);
    else unsetenv("PATH");
    free(saved);

    if (!dot_installed()) {
        printf("test_graph_dump: Graphviz 'dot' not on PATH: skipping the dot -Tsvg checks\n");
        return;
    }
    /* bad DOT: dot's non-zero exit is an error */
    char path[] = "/tmp/pg_dump_bad_XXXXXX";
    int fd = mkstemp(path);
    if (fd >= 0) close(fd);
    memset(&err, 0, sizeof err);
    fprintf(stderr, "(a Graphviz syntax error is expected next)\n");
    CHECK(pg_dump_run_graphviz("digraph { this is not dot", "svg", path, &err) == PG_ERR_IO);
    CHECK_MSG(strstr(err.msg, "exit status") != NULL, "%s", err.msg);
    remove(path);
}

/* ------------------------------------------------------------------------------------------ */
/* shipped pipelines with the built-in pass types                                            */

static void test_shipped(void)
{
    pg_pass_registry reg = {0};
    pg_register_builtin_passes(&reg);
    const bool have_dot = dot_installed();
    static const char *const files[] = {"naive.json", "forward_plus.json", "deferred.json", "deferred_oct16.json",
                                        "deferred_packed.json", NULL};
    for (int i = 0; files[i]; i++) {
        char path[PG_PATH_MAX];
        snprintf(path, sizeof path, "%s/../pipelines/%s", PG_TEST_DIR, files[i]);
        for (int variant = 0; variant < 2; variant++) {
            /* 1000 lights with every scene feature, and 0 lights without features (culls) */
            pg_pipeline *pl = NULL;
            pg_error err = {0};
            CHECK_MSG(pg_pipeline_load(path, NULL, 0, &pl, &err) == PG_OK, "%s: %s", files[i], err.msg);
            if (!pl) continue;
            pg_graph_plan *plan = compile(pl, &reg, variant ? 0 : 1000, 1920, 1080, variant == 0);
            if (!plan) {
                pg_pipeline_free(pl);
                continue;
            }
            char what[128];
            snprintf(what, sizeof what, "%s (%s)", files[i], variant ? "0 lights" : "1000 lights");
            char *json = pg_dump_json(plan, pl);
            cJSON *root = json ? cJSON_Parse(json) : NULL;
            CHECK_MSG(root != NULL, "%s: JSON does not parse", what);
            if (root) {
                check_json_mirrors_plan(plan, pl, root, what);
                cJSON_Delete(root);
            }
            free(json);
            char *text = capture(pg_dump_text, plan, pl);
            HAS(text, "memory timeline");
            HAS(text, "totals:");
            free(text);
            check_timeline(plan, pl, what);
            char *dot = capture(pg_dump_dot, plan, pl);
            for (uint32_t p = 0; p < plan->n_passes; p++) {
                char name[PG_NAME_MAX + 8];
                snprintf(name, sizeof name, "<b>%s</b>", plan->passes[p].name);
                HAS(dot, name);
            }
            if (variant == 1 && plan->n_order < plan->n_passes) HAS(dot, "style=\"rounded,dashed\"");
            if (have_dot && dot) graphviz_accepts(dot, what);
            free(dot);
            pg_graph_plan_free(plan);
            pg_pipeline_free(pl);
        }
    }
    if (!have_dot) printf("test_graph_dump: Graphviz 'dot' not on PATH: shipped pipelines' DOT not rendered\n");
}

/* Parameter values in the JSON dump read back exactly: the largest double (cJSON's 15 digits made it
 * infinity) and 2^53 - 1 (2^53 was 9.00719925474099e+15). */
static void test_json_numbers(void)
{
    static const char *const graph =
        "{\"name\": \"numbers\",\n"
        " \"parameters\": {\"i\": {\"type\": \"int\", \"default\": 9007199254740991},\n"
        "                \"f\": {\"type\": \"float\", \"default\": 1.7976931348623157e308},\n"
        "                \"g\": {\"type\": \"float\", \"default\": 0.1}},\n"
        " \"resources\": [{\"name\": \"out\", \"type\": \"image\", \"format\": \"rgba8\"}],\n"
        " \"passes\": [{\"name\": \"gen\", \"type\": \"fake_color\", \"writes\": [\"out\"]}],\n"
        " \"output\": \"out\"}\n";
    pg_pipeline *pl = load(graph);
    pg_graph_plan *plan = pl ? compile(pl, &g_reg, 100, 16, 16, false) : NULL;
    char *json = plan ? pg_dump_json(plan, pl) : NULL;
    cJSON *root = json ? cJSON_Parse(json) : NULL;
    const cJSON *ps = root ? jget(jget(root, "pipeline"), "parameters") : NULL;
    CHECK_MSG(ps != NULL, "no parameters in the JSON dump");
    if (ps) {
        CHECK_MSG(jget(ps, "i") && jget(ps, "i")->valuedouble == 9007199254740991.0, "i read back as %.17g",
                  jget(ps, "i") ? jget(ps, "i")->valuedouble : 0.0);
        CHECK_MSG(jget(ps, "f") && jget(ps, "f")->valuedouble == 1.7976931348623157e308, "f read back as %.17g",
                  jget(ps, "f") ? jget(ps, "f")->valuedouble : 0.0);
        CHECK_MSG(jget(ps, "g") && jget(ps, "g")->valuedouble == 0.1, "g read back as %.17g",
                  jget(ps, "g") ? jget(ps, "g")->valuedouble : 0.0);
        CHECK_MSG(json && strstr(json, "9007199254740991"), "2^53 - 1 not written as an integer");
    }
    cJSON_Delete(root);
    free(json);
    pg_graph_plan_free(plan);
    pg_pipeline_free(pl);
}

int main(void)
{
    pg_error err = {0};
    for (size_t i = 0; i < sizeof g_types / sizeof g_types[0]; i++)
        CHECK_MSG(pg_registry_add(&g_reg, &g_types[i], &err) == PG_OK, "%s", err.msg);
    test_hand_graph_json();
    test_json_numbers();
    test_hand_graph_text_dot_svg();
    test_graphviz_errors();
    test_shipped();
    return pg_test_finish("test_graph_dump");
}
