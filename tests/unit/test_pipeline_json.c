/* test_pipeline_json.c - the pipeline JSON loader (core/graph/pipeline_json*.c) and the pass option
 * readers (core/graph/pass_options.c): every field of valid pipelines, includes and their merge order,
 * parameters, --set overrides, "$param" substitution, "when", and the malformed corpus in
 * tests/corpus/pipelines (MANIFEST: file, expected code, expected message substring).
 * Must stay clean under valgrind --leak-check=full. */
#include "pass_api.h"
#include "pipeline.h"
#include "pipeline_paths.h"
#include "test_util.h"

#include <cjson/cJSON.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef PG_TEST_DIR
#error "PG_TEST_DIR must name the tests/ folder"
#endif

#define CORPUS PG_TEST_DIR "/corpus/pipelines"
#define GOOD CORPUS "/good"

static const pg_pass_desc *find_pass(const pg_pipeline *p, const char *name)
{
    for (uint32_t i = 0; i < p->n_passes; i++)
        if (strcmp(p->passes[i].name, name) == 0) return &p->passes[i];
    return NULL;
}

static bool has_omitted(const pg_pipeline *p, const char *what, const char *why_part)
{
    for (uint32_t i = 0; i < p->n_omitted; i++)
        if (strcmp(p->omitted[i].what, what) == 0 && strstr(p->omitted[i].why, why_part))
            return true;
    return false;
}

/* Loads text expecting failure with code and a message containing sub (and the file name). */
static void expect_fail(const char *text, const pg_param_override *ov, uint32_t n_ov,
                        pg_result code, const char *sub)
{
    pg_pipeline *p = (pg_pipeline *)1;
    pg_error err = {0};
    pg_result r = pg_pipeline_load_string(text, GOOD "/inline.json", ov, n_ov, &p, &err);
    CHECK_MSG(r == code, "expected %s, got %s: %s", pg_result_name(code), pg_result_name(r),
              err.msg);
    CHECK_MSG(p == NULL, "out must be NULL on failure");
    CHECK_MSG(err.code == code, "err.code %s", pg_result_name(err.code));
    CHECK_MSG(strstr(err.msg, sub) != NULL, "message lacks '%s': %s", sub, err.msg);
    CHECK_MSG(strstr(err.msg, "inline.json") != NULL, "message lacks the file: %s", err.msg);
    if (r == PG_OK) pg_pipeline_free(p);
}

/* ---------------------------------------------------------------- the README example */

static void test_example_file(void)
{
    pg_pipeline *p = NULL;
    pg_error err = {0};
    pg_result r = pg_pipeline_load(GOOD "/example.json", NULL, 0, &p, &err);
    CHECK_MSG(r == PG_OK, "%s", err.msg);
    if (r) return;
    CHECK(strcmp(p->name, "naive") == 0);
    CHECK(strstr(p->description, "exact reference") != NULL);
    CHECK(strcmp(p->path, GOOD "/example.json") == 0);
    CHECK(strcmp(p->output, "ldr") == 0);
    CHECK(strcmp(p->hdr_output, "hdr") == 0);

    /* parameters: the fragment's (debug from common.json, light_speed) come first; the
     * includer's identical "debug" is accepted */
    CHECK(p->n_params == 5);
    CHECK(strcmp(p->params[0].name, "debug") == 0);
    CHECK(strcmp(p->params[1].name, "light_speed") == 0);
    CHECK(strcmp(p->params[2].name, "hdr_format") == 0);
    const pg_param *hf = pg_pipeline_find_param(p, "hdr_format");
    CHECK(hf && hf->type == PG_PARAM_ENUM && hf->n_values == 2 &&
          strcmp(hf->values[1], "rgba32f") == 0 && strcmp(hf->enum_value, "rgba16f") == 0 &&
          !hf->overridden && strstr(hf->description, "scene-linear"));
    const pg_param *ex = pg_pipeline_find_param(p, "exposure");
    CHECK(ex && ex->type == PG_PARAM_FLOAT && ex->number == 1.0 && ex->min == 0.0 &&
          ex->max == 1000.0);
    const pg_param *gx = pg_pipeline_find_param(p, "grid_x");
    CHECK(gx && gx->type == PG_PARAM_INT && gx->number == 16 && gx->min == 1 && gx->max == 256);
    const pg_param *dbg = pg_pipeline_find_param(p, "debug");
    CHECK(dbg && dbg->type == PG_PARAM_BOOL && !dbg->boolean && isinf(dbg->min) &&
          dbg->min < 0 && isinf(dbg->max));
    CHECK(pg_pipeline_find_param(p, "nope") == NULL);

    /* resources: lights (from the fragment) first; grid omitted (debug false) */
    CHECK(p->n_resources == 7);
    CHECK(strcmp(p->resources[0].name, "lights") == 0);
    const pg_resource_desc *lights = pg_pipeline_find_resource(p, "lights");
    CHECK(lights && lights->kind == PG_RES_BUFFER && lights->stride == 32 &&
          lights->n_count_terms == 1 && lights->count[0].kind == PG_COUNT_VAR && !strcmp(lights->count[0].var, "lights") &&
          lights->lifetime == PG_LIFETIME_PERSISTENT);
    CHECK(lights && strcmp(lights->file, GOOD "/fragments/lights.json") == 0 &&
          strcmp(lights->json_path, "resources[0]") == 0);
    const pg_resource_desc *hdr = pg_pipeline_find_resource(p, "hdr");
    CHECK(hdr && hdr->kind == PG_RES_IMAGE && hdr->format == PG_FMT_RGBA16F &&
          hdr->extent_mode == PG_EXTENT_RELATIVE && hdr->scale[0] == 1.0f &&
          hdr->scale[1] == 1.0f && hdr->lifetime == PG_LIFETIME_TRANSIENT);
    CHECK(hdr && strcmp(hdr->file, GOOD "/example.json") == 0 &&
          strcmp(hdr->json_path, "resources[0]") == 0);
    const pg_resource_desc *depth = pg_pipeline_find_resource(p, "depth");
    CHECK(depth && depth->format == PG_FMT_D32F && depth->extent_mode == PG_EXTENT_RELATIVE);
    const pg_resource_desc *half = pg_pipeline_find_resource(p, "half");
    CHECK(half && half->scale[0] == 0.5f && half->scale[1] == 0.5f);
    const pg_resource_desc *lut = pg_pipeline_find_resource(p, "lut");
    CHECK(lut && lut->extent_mode == PG_EXTENT_ABSOLUTE && lut->size[0] == 64 &&
          lut->size[1] == 64 && lut->lifetime == PG_LIFETIME_PERSISTENT &&
          lut->format == PG_FMT_RGBA8_UNORM);
    const pg_resource_desc *swap = pg_pipeline_find_resource(p, "swap");
    CHECK(swap && swap->lifetime == PG_LIFETIME_IMPORTED);
    CHECK(pg_pipeline_find_resource(p, "grid") == NULL);
    const pg_resource_desc *ldr = pg_pipeline_find_resource(p, "ldr");
    CHECK(ldr && strcmp(ldr->json_path, "resources[5]") == 0);

    /* passes: animate (fragment) first */
    CHECK(p->n_passes == 3);
    CHECK(strcmp(p->passes[0].name, "animate") == 0 && strcmp(p->passes[1].name, "shade") == 0 &&
          strcmp(p->passes[2].name, "display") == 0);
    const pg_pass_desc *an = &p->passes[0];
    CHECK(strcmp(an->type, "light_animate") == 0 && an->side_effects && an->n_writes == 1 &&
          strcmp(an->writes[0], "lights") == 0 && an->n_reads == 0);
    CHECK(strcmp(an->file, GOOD "/fragments/lights.json") == 0 &&
          strcmp(an->json_path, "passes[0]") == 0);
    const cJSON *speed = cJSON_GetObjectItemCaseSensitive(an->options, "speed");
    CHECK(cJSON_IsNumber(speed) && speed->valuedouble == 0.5);
    const pg_pass_desc *sh = &p->passes[1];
    CHECK(sh->n_reads == 1 && sh->n_writes == 2 && strcmp(sh->writes[1], "depth") == 0 &&
          !sh->side_effects && sh->n_after == 0);
    CHECK(strcmp(sh->json_path, "passes[0]") == 0);
    const cJSON *shading = cJSON_GetObjectItemCaseSensitive(sh->options, "shading");
    CHECK(cJSON_IsString(shading) && strcmp(shading->valuestring, "lambert") == 0);
    const pg_pass_desc *di = &p->passes[2];
    CHECK(di->n_after == 1 && strcmp(di->after[0], "shade") == 0);
    const cJSON *e = cJSON_GetObjectItemCaseSensitive(di->options, "exposure");
    CHECK(cJSON_IsNumber(e) && e->valuedouble == 1.0);

    CHECK(p->n_omitted == 1);
    CHECK(has_omitted(p, "resource 'grid'", "when: $debug == true (debug is 'false')"));
    pg_pipeline_free(p);

    /* with overrides: debug on drops display, adds grid with the overridden grid_x */
    pg_param_override ov[] = {{"debug", "true"}, {"grid_x", "32"}, {"hdr_format", "rgba32f"},
                              {"exposure", "2.5"}, {"light_speed", "0"}};
    r = pg_pipeline_load(GOOD "/example.json", ov, 5, &p, &err);
    CHECK_MSG(r == PG_OK, "%s", err.msg);
    if (r) return;
    CHECK(pg_pipeline_find_param(p, "debug")->boolean);
    CHECK(pg_pipeline_find_param(p, "debug")->overridden);
    CHECK(!pg_pipeline_find_param(p, "exposure") || pg_pipeline_find_param(p, "exposure")->number == 2.5);
    const pg_resource_desc *grid = pg_pipeline_find_resource(p, "grid");
    CHECK(grid && grid->n_count_terms == 3 && grid->count[0].kind == PG_COUNT_CONST &&
          grid->count[0].value == 32 && grid->count[1].value == 9 && grid->count[2].value == 24);
    CHECK(pg_pipeline_find_resource(p, "hdr")->format == PG_FMT_RGBA32F);
    CHECK(p->n_passes == 2 && find_pass(p, "display") == NULL);
    CHECK(has_omitted(p, "pass 'display'", "when: $debug != true (debug is 'true')"));
    CHECK(p->n_omitted == 1);
    pg_pipeline_free(p);
}

/* ---------------------------------------------------------------- includes, merge order */

static const char *k_merge =
    "{\n"
    "  \"include\": [\"fragments/lights.json\", \"fragments/grid.json\"],\n"
    "  \"parameters\": {\"n\": {\"type\": \"int\", \"default\": 4},\n"
    "                 \"mode\": {\"type\": \"enum\", \"values\": [\"packed\", \"float\"], \"default\": \"packed\"}},\n"
    "  \"resources\": [\n"
    "    {\"name\": \"hdr\", \"type\": \"image\", \"format\": \"rgba16f\", \"description\": \"colour\"},\n"
    "    {\"name\": \"packed\", \"type\": \"image\", \"format\": \"rg16_snorm\", \"when\": \"$mode == packed\"},\n"
    "    {\"name\": \"floaty\", \"type\": \"image\", \"format\": \"rgba32f\", \"when\": \"$mode == float\"},\n"
    "    {\"name\": \"tiles\", \"type\": \"buffer\", \"stride\": 16, \"when\": \"  $n   !=   4 \"},\n"
    "    {\"name\": \"big\", \"type\": \"buffer\", \"stride\": 65536, \"count\": [\"pixels\", 0, \"lights\", 4294967295]}\n"
    "  ],\n"
    "  \"passes\": [\n"
    "    {\"name\": \"pack\", \"type\": \"gbuffer_packed\", \"reads\": [\"lights\"], \"writes\": [\"packed\"], \"when\": \"$mode==packed\"},\n"
    "    {\"name\": \"flt\", \"type\": \"gbuffer_float\", \"writes\": [\"floaty\"], \"when\": \"$mode == float\"},\n"
    "    {\"name\": \"shade\", \"type\": \"deferred\", \"reads\": [\"lights\"], \"writes\": [\"hdr\"],\n"
    "     \"after\": [\"pack\", \"flt\", \"grid_debug\", \"animate\", \"animate\"],\n"
    "     \"options\": {\"n\": \"$n\", \"mode\": \"$mode\", \"dbg\": \"$debug\", \"list\": [\"$n\", [\"$mode\"]],\n"
    "                 \"literal\": \"$not a ref\", \"dollar\": \"$\", \"keep\": \"n\"}}\n"
    "  ],\n"
    "  \"output\": \"hdr\"\n"
    "}\n";

static void test_merge(void)
{
    pg_pipeline *p = NULL;
    pg_error err = {0};
    pg_result r = pg_pipeline_load_string(k_merge, GOOD "/merge.json", NULL, 0, &p, &err);
    CHECK_MSG(r == PG_OK, "%s", err.msg);
    if (r) return;
    CHECK(strcmp(p->name, "merge") == 0); /* default name: the file name */
    CHECK(strcmp(p->path, GOOD "/merge.json") == 0);
    /* params: common(debug) lights(light_speed) grid(grid_x; common again is identical) own */
    const char *pn[] = {"debug", "light_speed", "grid_x", "n", "mode"};
    CHECK(p->n_params == 5);
    for (uint32_t i = 0; i < 5 && i < p->n_params; i++)
        CHECK_MSG(strcmp(p->params[i].name, pn[i]) == 0, "param %u is %s", i, p->params[i].name);
    /* resources: lights, (grid omitted), hdr, packed, (floaty omitted), (tiles omitted), big */
    const char *rn[] = {"lights", "hdr", "packed", "big"};
    CHECK(p->n_resources == 4);
    for (uint32_t i = 0; i < 4 && i < p->n_resources; i++)
        CHECK_MSG(strcmp(p->resources[i].name, rn[i]) == 0, "resource %u is %s", i,
                  p->resources[i].name);
    const pg_resource_desc *big = pg_pipeline_find_resource(p, "big");
    CHECK(big && big->stride == 65536 && big->n_count_terms == 4 &&
          big->count[0].kind == PG_COUNT_PIXELS && big->count[1].kind == PG_COUNT_CONST &&
          big->count[1].value == 0 && big->count[2].kind == PG_COUNT_VAR && !strcmp(big->count[2].var, "lights") &&
          big->count[3].value == 4294967295.0);
    const pg_resource_desc *tiles_absent = pg_pipeline_find_resource(p, "tiles");
    CHECK(tiles_absent == NULL);
    CHECK(has_omitted(p, "resource 'tiles'", "when: $n   !=   4 (n is '4')"));
    CHECK(has_omitted(p, "resource 'grid'", "(debug is 'false')"));
    CHECK(has_omitted(p, "resource 'floaty'", "when: $mode == float (mode is 'packed')"));
    CHECK(has_omitted(p, "pass 'grid_debug'", "debug"));
    CHECK(has_omitted(p, "pass 'flt'", "mode is 'packed'"));
    CHECK(p->n_omitted == 5);
    /* passes: animate (lights.json), pack, shade */
    CHECK(p->n_passes == 3);
    CHECK(strcmp(p->passes[0].name, "animate") == 0);
    const pg_pass_desc *sh = find_pass(p, "shade");
    CHECK(sh != NULL);
    if (sh) {
        /* after: omitted flt and grid_debug dropped, duplicate animate dropped */
        CHECK(sh->n_after == 2 && strcmp(sh->after[0], "pack") == 0 &&
              strcmp(sh->after[1], "animate") == 0);
        const cJSON *o = sh->options;
        CHECK(cJSON_IsObject(o));
        const cJSON *n = cJSON_GetObjectItemCaseSensitive(o, "n");
        CHECK(cJSON_IsNumber(n) && n->valuedouble == 4);
        const cJSON *mode = cJSON_GetObjectItemCaseSensitive(o, "mode");
        CHECK(cJSON_IsString(mode) && strcmp(mode->valuestring, "packed") == 0);
        CHECK(cJSON_IsFalse(cJSON_GetObjectItemCaseSensitive(o, "dbg")));
        const cJSON *list = cJSON_GetObjectItemCaseSensitive(o, "list");
        CHECK(cJSON_IsArray(list) && cJSON_IsNumber(cJSON_GetArrayItem(list, 0)) &&
              cJSON_IsString(cJSON_GetArrayItem(cJSON_GetArrayItem(list, 1), 0)));
        const cJSON *lit = cJSON_GetObjectItemCaseSensitive(o, "literal");
        CHECK(cJSON_IsString(lit) && strcmp(lit->valuestring, "$not a ref") == 0);
        const cJSON *dol = cJSON_GetObjectItemCaseSensitive(o, "dollar");
        CHECK(cJSON_IsString(dol) && strcmp(dol->valuestring, "$") == 0);
        CHECK(cJSON_GetArraySize((cJSON *)o) == 7);
    }
    /* a pass without "options" still gets an (empty) object */
    const pg_pass_desc *pk = find_pass(p, "pack");
    CHECK(pk && cJSON_IsObject(pk->options) && pk->options->child == NULL);
    pg_pipeline_free(p);

    /* enum switch: the other variant survives; grid_debug nested options substituted */
    pg_param_override ov[] = {{"mode", "float"}, {"debug", "1"}, {"grid_x", "3"}, {"n", "-7"}};
    r = pg_pipeline_load_string(k_merge, GOOD "/merge.json", ov, 4, &p, &err);
    CHECK_MSG(r == PG_OK, "%s", err.msg);
    if (r) return;
    CHECK(pg_pipeline_find_resource(p, "floaty") && !pg_pipeline_find_resource(p, "packed"));
    CHECK(pg_pipeline_find_resource(p, "tiles") != NULL);
    CHECK(find_pass(p, "flt") && !find_pass(p, "pack"));
    const pg_resource_desc *grid = pg_pipeline_find_resource(p, "grid");
    CHECK(grid && grid->n_count_terms == 4 && grid->count[0].value == 3 &&
          grid->count[3].kind == PG_COUNT_PIXELS);
    CHECK(grid && strcmp(grid->file, GOOD "/fragments/grid.json") == 0);
    const pg_pass_desc *gd = find_pass(p, "grid_debug");
    CHECK(gd != NULL);
    if (gd) {
        const cJSON *dims = cJSON_GetObjectItemCaseSensitive(gd->options, "dims");
        CHECK(cJSON_GetArraySize(dims) == 3 && cJSON_GetArrayItem(dims, 0)->valuedouble == 3);
        const cJSON *z = cJSON_GetArrayItem(dims, 2);
        CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(z, "on")));
    }
    sh = find_pass(p, "shade");
    CHECK(sh && sh->n_after == 3); /* flt, grid_debug, animate */
    CHECK(pg_pipeline_find_param(p, "n")->number == -7);
    CHECK(p->n_omitted == 2); /* packed, pack */
    pg_pipeline_free(p);
}

/* ---------------------------------------------------------------- parameters and overrides */

static const char *k_params =
    "{\"name\": \"params\",\n"
    " \"parameters\": {\n"
    "   \"i\": {\"type\": \"int\", \"default\": 8, \"min\": -4, \"max\": 100},\n"
    "   \"f\": {\"type\": \"float\", \"default\": 0.1, \"min\": 0, \"max\": 2.5},\n"
    "   \"b\": {\"type\": \"bool\", \"default\": true},\n"
    "   \"e\": {\"type\": \"enum\", \"values\": [\"a\", \"b-2\", \"c.3\"], \"default\": \"c.3\"},\n"
    "   \"u\": {\"type\": \"float\", \"default\": -1e300},\n"
    "   \"t\": {\"type\": \"int\", \"default\": 8, \"values\": [8, 16]}\n"
    " },\n"
    " \"resources\": [{\"name\": \"out\", \"type\": \"image\", \"format\": \"rgba8\", \"scale\": \"$f\"}],\n"
    " \"passes\": [{\"name\": \"p\", \"type\": \"t\", \"writes\": [\"out\"],\n"
    "   \"options\": {\"i\": \"$i\", \"f\": \"$f\", \"b\": \"$b\", \"e\": \"$e\", \"u\": \"$u\"}}],\n"
    " \"output\": \"out\"}\n";

static void test_params(void)
{
    pg_pipeline *p = NULL;
    pg_error err = {0};
    pg_result r = pg_pipeline_load_string(k_params, "params.json", NULL, 0, &p, &err);
    CHECK_MSG(r == PG_OK, "%s", err.msg);
    if (r) return;
    char buf[64];
    pg_param_format(pg_pipeline_find_param(p, "i"), buf, sizeof buf);
    CHECK(strcmp(buf, "8") == 0);
    pg_param_format(pg_pipeline_find_param(p, "f"), buf, sizeof buf);
    CHECK_MSG(strcmp(buf, "0.1") == 0, "%s", buf);
    pg_param_format(pg_pipeline_find_param(p, "b"), buf, sizeof buf);
    CHECK(strcmp(buf, "true") == 0);
    pg_param_format(pg_pipeline_find_param(p, "e"), buf, sizeof buf);
    CHECK(strcmp(buf, "c.3") == 0);
    pg_param_format(pg_pipeline_find_param(p, "u"), buf, sizeof buf);
    CHECK(strcmp(buf, "-1e+300") == 0);
    CHECK(fabsf(pg_pipeline_find_resource(p, "out")->scale[0] - 0.1f) < 1e-7f);
    const pg_pass_desc *d = &p->passes[0];
    CHECK(cJSON_IsNumber(cJSON_GetObjectItemCaseSensitive(d->options, "i")));
    CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(d->options, "b")));
    CHECK(strcmp(cJSON_GetObjectItemCaseSensitive(d->options, "e")->valuestring, "c.3") == 0);
    /* the option readers on substituted values */
    int64_t iv = 0;
    double fv = 0;
    bool bv = false;
    int ev = -1;
    const char *const echoices[] = {"a", "b-2", "c.3", NULL};
    CHECK(pg_opt_int(d, "i", 0, 0, 10, &iv, &err) == PG_OK && iv == 8);
    CHECK(pg_opt_float(d, "f", 0, 0, 1, &fv, &err) == PG_OK && fv == 0.1);
    CHECK(pg_opt_bool(d, "b", false, &bv, &err) == PG_OK && bv);
    CHECK(pg_opt_enum(d, "e", echoices, 0, &ev, &err) == PG_OK && ev == 2);
    pg_pipeline_free(p);

    /* good overrides */
    pg_param_override ok[] = {{"i", "-4"}, {"f", "2.5"}, {"b", "0"}, {"e", "b-2"},
                              {"i", "+100"}, {"u", "-3e-2"}, {"t", "16"}};
    r = pg_pipeline_load_string(k_params, "params.json", ok, 7, &p, &err);
    CHECK_MSG(r == PG_OK, "%s", err.msg);
    if (!r) {
        CHECK(pg_pipeline_find_param(p, "i")->number == 100); /* last --set wins */
        CHECK(pg_pipeline_find_param(p, "f")->number == 2.5);
        CHECK(!pg_pipeline_find_param(p, "b")->boolean);
        CHECK(strcmp(pg_pipeline_find_param(p, "e")->enum_value, "b-2") == 0);
        CHECK(pg_pipeline_find_param(p, "u")->number == -0.03);
        CHECK(pg_pipeline_find_param(p, "t")->number == 16); /* an int with values: one of them */
        for (uint32_t i = 0; i < p->n_params; i++) CHECK(p->params[i].overridden);
        CHECK(pg_pipeline_find_resource(p, "out")->scale[1] == 2.5f);
        CHECK(cJSON_IsFalse(cJSON_GetObjectItemCaseSensitive(p->passes[0].options, "b")));
        pg_pipeline_free(p);
    }

    /* bad overrides: PG_ERR_PARAM naming --set key=value and the cause */
    struct {
        const char *key, *value, *sub;
    } bad[] = {
        {"j", "1", "--set j=1: unknown parameter 'j' (declared: i, f, b, e, u, t)"},
        {"t", "12", "--set t=12: int parameter 't': 12 is not one of: 8, 16"},
        {"i", "1.5", "--set i=1.5: int parameter 'i': '1.5' is not an integer"},
        {"i", "abc", "'abc' is not an integer"},
        {"i", "", "'' is not an integer"},
        {"i", "101", "--set i=101: int parameter 'i': 101 is out of range [-4, 100]"},
        {"i", "-5", "out of range"},
        {"i", "99999999999999999999", "too large"},
        {"i", "9007199254740993", "9007199254740993 is too large"}, /* 2^53 + 1: no double holds it */
        {"i", "9007199254740992", "9007199254740992 is too large"}, /* 2^53: what 2^53 + 1 in JSON reads as */
        {"i", "-9007199254740993", "too large"},
        {"i", "0x10", "not an integer"},
        {"f", "nan", "'nan' is not a number"},
        {"f", "inf", "not a number"},
        {"f", "1e999", "not a finite number"},
        {"f", "2.6", "2.6 is out of range [0, 2.5]"},
        {"f", "1.0.0", "not a number"},
        {"f", "-0.0001", "out of range"},
        {"b", "yes", "--set b=yes: bool parameter 'b': 'yes' is not a bool"},
        {"b", "TRUE", "not a bool"},
        {"e", "d", "--set e=d: enum parameter 'e': 'd' is not one of: a, b-2, c.3"},
        {"e", "A", "not one of"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        pg_param_override o = {bad[i].key, bad[i].value};
        pg_error e2 = {0};
        p = (pg_pipeline *)1;
        r = pg_pipeline_load_string(k_params, "dir/params.json", &o, 1, &p, &e2);
        CHECK_MSG(r == PG_ERR_PARAM && p == NULL, "--set %s=%s: %s", bad[i].key, bad[i].value,
                  e2.msg);
        CHECK_MSG(strstr(e2.msg, bad[i].sub) && strstr(e2.msg, "dir/params.json: "),
                  "--set %s=%s: '%s' lacks '%s'", bad[i].key, bad[i].value, e2.msg, bad[i].sub);
        if (r == PG_OK) pg_pipeline_free(p);
    }
    /* NULL key / value are rejected, not dereferenced */
    pg_param_override nul = {NULL, NULL};
    r = pg_pipeline_load_string(k_params, "params.json", &nul, 1, &p, &err);
    CHECK(r == PG_ERR_PARAM);
    r = pg_pipeline_load_string(k_params, "params.json", NULL, 2, &p, &err);
    CHECK(r == PG_ERR_INVALID_ARG);
}

/* ---------------------------------------------------------------- inline failures */

static void test_inline_errors(void)
{
    /* a $ref to a parameter that does not exist in an unexpected place: the resource name */
    expect_fail("{\"resources\": [{\"name\": \"$nm\", \"type\": \"image\", \"format\": \"rgba8\"}],"
                " \"output\": \"x\"}",
                NULL, 0, PG_ERR_PARAM, "resources[0].name: unknown parameter '$nm' (declared: none)");
    /* substituted names are allowed */
    pg_pipeline *p = NULL;
    pg_error err = {0};
    const char *named =
        "{\"parameters\": {\"nm\": {\"type\": \"enum\", \"values\": [\"tgt\"], \"default\": \"tgt\"}},"
        " \"resources\": [{\"name\": \"$nm\", \"type\": \"image\", \"format\": \"rgba8\"}],"
        " \"output\": \"tgt\"}";
    CHECK(pg_pipeline_load_string(named, "n.json", NULL, 0, &p, &err) == PG_OK);
    CHECK(p && p->n_passes == 0 && strcmp(p->resources[0].name, "tgt") == 0);
    pg_pipeline_free(p);
    /* an omitted pass may read omitted resources, but not undeclared ones */
    expect_fail("{\"parameters\": {\"on\": {\"type\": \"bool\", \"default\": false}},"
                " \"resources\": [{\"name\": \"o\", \"type\": \"image\", \"format\": \"rgba8\"}],"
                " \"passes\": [{\"name\": \"x\", \"type\": \"t\", \"reads\": [\"typo\"],"
                " \"writes\": [\"o\"], \"when\": \"$on == true\"}], \"output\": \"o\"}",
                NULL, 0, PG_ERR_UNKNOWN_RESOURCE, "passes[0].reads[0]: unknown resource 'typo'");
    /* when with a float parameter compares numbers */
    const char *fl =
        "{\"parameters\": {\"s\": {\"type\": \"float\", \"default\": 0.5}},"
        " \"resources\": [{\"name\": \"o\", \"type\": \"image\", \"format\": \"rgba8\"},"
        "  {\"name\": \"h\", \"type\": \"image\", \"format\": \"rgba8\", \"when\": \"$s == 0.50\"},"
        "  {\"name\": \"k\", \"type\": \"image\", \"format\": \"rgba8\", \"when\": \"$s != 5e-1\"}],"
        " \"output\": \"o\"}";
    CHECK(pg_pipeline_load_string(fl, "fl.json", NULL, 0, &p, &err) == PG_OK);
    CHECK(p && pg_pipeline_find_resource(p, "h") && !pg_pipeline_find_resource(p, "k"));
    CHECK(p && has_omitted(p, "resource 'k'", "when: $s != 5e-1 (s is '0.5')"));
    pg_pipeline_free(p);
    /* identical parameter in the includer and a fragment is fine; a different one is not */
    const char *same =
        "{\"include\": [\"fragments/common.json\"], \"parameters\": {\"debug\": {\"type\": \"bool\","
        " \"description\": \"Extra debug resources and passes.\", \"default\": false}},"
        " \"resources\": [{\"name\": \"o\", \"type\": \"image\", \"format\": \"rgba8\"}], \"output\": \"o\"}";
    CHECK(pg_pipeline_load_string(same, GOOD "/same.json", NULL, 0, &p, &err) == PG_OK);
    CHECK(p && p->n_params == 1);
    pg_pipeline_free(p);
    expect_fail("{\"include\": [\"fragments/common.json\"], \"parameters\": {\"debug\": {\"type\": \"bool\","
                " \"default\": false}}, \"resources\": [{\"name\": \"o\", \"type\": \"image\", "
                "\"format\": \"rgba8\"}], \"output\": \"o\"}",
                NULL, 0, PG_ERR_PARAM, "already declared differently at " GOOD "/fragments/common.json");
    /* include a fragment by absolute path */
    const char *abs_inc = "{\"include\": [\"" GOOD "/fragments/lights.json\"],"
                          " \"resources\": [{\"name\": \"o\", \"type\": \"image\", \"format\": \"rgba8\"}],"
                          " \"output\": \"o\"}";
    /* outside the including file's folder and the data folder: refused by name ... */
    CHECK(pg_pipeline_load_string(abs_inc, "/nonexistent/x.json", NULL, 0, &p, &err) == PG_ERR_INCLUDE);
    CHECK_MSG(!strcmp(err.msg, "/nonexistent/x.json: include[0]: include '" GOOD "/fragments/lights.json'"
                               " is outside the allowed folders (the including file's folder, the data"
                               " folder, --include-dir)"), "%s", err.msg);
    /* ... unless its folder is named (--include-dir) */
    const char *dirs[] = {GOOD "/fragments"};
    CHECK(pg_pipeline_set_include_dirs(dirs, 1, &err) == PG_OK);
    CHECK_MSG(pg_pipeline_load_string(abs_inc, "/nonexistent/x.json", NULL, 0, &p, &err) == PG_OK, "%s", err.msg);
    CHECK(p && p->n_passes == 1 && p->n_resources == 2);
    pg_pipeline_free(p);
    CHECK(pg_pipeline_set_include_dirs(NULL, 0, &err) == PG_OK);
    CHECK(pg_pipeline_set_include_dirs(dirs + 0, 1, &err) == PG_OK && pg_pipeline_set_include_dirs(NULL, 0, &err) == PG_OK);
    const char *not_dir[] = {GOOD "/example.json"};
    CHECK(pg_pipeline_set_include_dirs(not_dir, 1, &err) == PG_ERR_IO && strstr(err.msg, "not a directory"));
    /* absolute and ../ escapes are refused before the file is opened */
    expect_fail("{\"include\": [\"/etc/passwd\"], \"output\": \"o\"}", NULL, 0, PG_ERR_INCLUDE,
                "include[0]: include '/etc/passwd' is outside the allowed folders");
    expect_fail("{\"include\": [\"../../../../../../../../etc/passwd\"], \"output\": \"o\"}", NULL, 0,
                PG_ERR_INCLUDE, "include '../../../../../../../../etc/passwd' is outside the allowed folders");
    /* ../ that stays inside the including file's folder tree is fine */
    const char *up = "{\"include\": [\"fragments/../fragments/lights.json\"],"
                     " \"resources\": [{\"name\": \"o\", \"type\": \"image\", \"format\": \"rgba8\"}],"
                     " \"output\": \"o\"}";
    CHECK_MSG(pg_pipeline_load_string(up, GOOD "/up.json", NULL, 0, &p, &err) == PG_OK, "%s", err.msg);
    pg_pipeline_free(p);
    /* a file that is not JSON: line and column, never its text */
    CHECK(pg_pipeline_load_string("root:x:0:0:root:/root:/bin/bash\n", "passwd", NULL, 0, &p, &err) == PG_ERR_PARSE);
    CHECK_MSG(!strcmp(err.msg, "passwd:1:1: JSON syntax error"), "%s", err.msg);
    { /* nesting past the parser's limit is named (1,000 levels; the object counts) */
        static char deep[2 * 1100 + 64];
        for (int depth = 1000; depth <= 1001; depth++) {
            int n = snprintf(deep, sizeof deep, "{\"description\": \"{{{\", \"passes\": ");
            for (int i = 1; i < depth; i++) deep[n++] = '[';
            for (int i = 1; i < depth; i++) deep[n++] = ']';
            snprintf(deep + n, sizeof deep - (size_t)n, ", \"output\": \"o\"}");
            err = (pg_error){0};
            pg_result r = pg_pipeline_load_string(deep, "deep.json", NULL, 0, &p, &err);
            if (r == PG_OK) pg_pipeline_free(p);
            bool note = strstr(err.msg, "nested deeper than 1000 levels") != NULL;
            CHECK_MSG(r != PG_OK && note == (depth > 1000) && (depth == 1000 || r == PG_ERR_PARSE), "depth %d: %s",
                      depth, err.msg);
        }
    }
    /* a syntax error on the second line */
    expect_fail("{\"output\": \"o\",\n \"resources\": [1, 2,,]}", NULL, 0, PG_ERR_PARSE,
                "inline.json:2:");
    /* no output at all */
    expect_fail("{\"name\": \"x\"}", NULL, 0, PG_ERR_NO_OUTPUT, "output: missing");
    /* JSON null where an object is expected */
    expect_fail("null", NULL, 0, PG_ERR_SCHEMA, "expected a JSON object, got null");
    expect_fail("{\"passes\": [{\"name\": \"a\", \"type\": \"t\", \"options\": null}], \"output\": \"x\"}",
                NULL, 0, PG_ERR_SCHEMA, "passes[0].options: expected an object, got null");
    /* hdr_output pointing at an omitted image */
    expect_fail("{\"parameters\": {\"d\": {\"type\": \"bool\", \"default\": false}},"
                " \"resources\": [{\"name\": \"o\", \"type\": \"image\", \"format\": \"rgba8\"},"
                " {\"name\": \"h\", \"type\": \"image\", \"format\": \"rgba16f\", \"when\": \"$d == true\"}],"
                " \"output\": \"o\", \"hdr_output\": \"h\"}",
                NULL, 0, PG_ERR_NO_OUTPUT, "hdr_output: resource 'h' is omitted: when: $d == true (d is 'false')");
}

/* ---------------------------------------------------------------- option readers */

static void test_options(void)
{
    const char *text =
        "{\"resources\": [{\"name\": \"o\", \"type\": \"image\", \"format\": \"rgba8\"}],"
        " \"passes\": [{\"name\": \"a\", \"type\": \"tone\", \"writes\": [\"o\"], \"options\": {"
        "   \"f\": 1.5, \"i\": 7, \"half\": 2.5, \"big\": 1e300, \"s\": \"aces\", \"t\": true,"
        "   \"n\": null, \"arr\": [1], \"neg\": -3}}],"
        " \"output\": \"o\"}";
    pg_pipeline *p = NULL;
    pg_error err = {0};
    CHECK(pg_pipeline_load_string(text, "opt.json", NULL, 0, &p, &err) == PG_OK);
    if (!p) return;
    const pg_pass_desc *d = &p->passes[0];
    double f = 0;
    int64_t i = 0;
    bool b = false;
    int e = -1;
    const char *const tm[] = {"reinhard", "aces", "none", NULL};

    CHECK(pg_opt_float(d, "f", 0, 0, 10, &f, &err) == PG_OK && f == 1.5);
    CHECK(pg_opt_float(d, "missing", 3.25, 0, 10, &f, &err) == PG_OK && f == 3.25);
    CHECK(pg_opt_float(d, "i", 0, 0, 10, &f, &err) == PG_OK && f == 7);
    CHECK(pg_opt_float(d, "f", 0, 2, 10, &f, &err) == PG_ERR_SCHEMA);
    CHECK_MSG(strstr(err.msg, "opt.json: passes[0].options.f: expected a number in [2, 10], got 1.5"),
              "%s", err.msg);
    CHECK(pg_opt_float(d, "s", 0, 0, 10, &f, &err) == PG_ERR_SCHEMA);
    CHECK_MSG(strstr(err.msg, "got \"aces\""), "%s", err.msg);
    CHECK(pg_opt_float(d, "big", 0, -INFINITY, INFINITY, &f, &err) == PG_OK && f == 1e300);

    CHECK(pg_opt_int(d, "i", 0, 0, 10, &i, &err) == PG_OK && i == 7);
    CHECK(pg_opt_int(d, "neg", 0, -10, 10, &i, &err) == PG_OK && i == -3);
    CHECK(pg_opt_int(d, "missing", -2, -5, 5, &i, &err) == PG_OK && i == -2);
    CHECK(pg_opt_int(d, "half", 0, 0, 10, &i, &err) == PG_ERR_SCHEMA);
    CHECK_MSG(strstr(err.msg, "passes[0].options.half: expected an integer in [0, 10], got 2.5"),
              "%s", err.msg);
    CHECK(pg_opt_int(d, "i", 0, 8, 10, &i, &err) == PG_ERR_SCHEMA);
    CHECK(pg_opt_int(d, "big", 0, INT64_MIN, INT64_MAX, &i, &err) == PG_ERR_SCHEMA);
    CHECK(pg_opt_int(d, "t", 0, 0, 1, &i, &err) == PG_ERR_SCHEMA);
    CHECK(pg_opt_int(d, "n", 0, 0, 1, &i, &err) == PG_ERR_SCHEMA && strstr(err.msg, "got null"));

    CHECK(pg_opt_bool(d, "t", false, &b, &err) == PG_OK && b);
    CHECK(pg_opt_bool(d, "missing", true, &b, &err) == PG_OK && b);
    CHECK(pg_opt_bool(d, "i", false, &b, &err) == PG_ERR_SCHEMA);
    CHECK_MSG(strstr(err.msg, "passes[0].options.i: expected true or false, got 7"), "%s", err.msg);

    CHECK(pg_opt_enum(d, "s", tm, 0, &e, &err) == PG_OK && e == 1);
    CHECK(pg_opt_enum(d, "missing", tm, 2, &e, &err) == PG_OK && e == 2);
    CHECK(pg_opt_enum(d, "f", tm, 0, &e, &err) == PG_ERR_SCHEMA);
    CHECK_MSG(strstr(err.msg, "expected one of \"reinhard\", \"aces\", \"none\", got 1.5"), "%s",
              err.msg);
    const char *const tm2[] = {"reinhard", NULL};
    CHECK(pg_opt_enum(d, "s", tm2, 0, &e, &err) == PG_ERR_SCHEMA);

    const char *const known[] = {"f", "i", "half", "big", "s", "t", "n", "arr", "neg", NULL};
    CHECK(pg_opt_check_known(d, known, &err) == PG_OK);
    const char *const fewer[] = {"f", "i", "half", "big", "s", "t", "n", "neg", NULL};
    CHECK(pg_opt_check_known(d, fewer, &err) == PG_ERR_SCHEMA);
    CHECK_MSG(strstr(err.msg, "opt.json: passes[0].options: unknown option \"arr\" for pass type "
                              "'tone' (known: \"f\", \"i\""),
              "%s", err.msg);
    const char *const none[] = {NULL};
    CHECK(pg_opt_check_known(d, none, &err) == PG_ERR_SCHEMA);
    CHECK_MSG(strstr(err.msg, "takes no options"), "%s", err.msg);
    /* a desc with NULL options (hand-made) reads defaults */
    pg_pass_desc bare;
    memset(&bare, 0, sizeof bare);
    CHECK(pg_opt_float(&bare, "x", 4, 0, 5, &f, &err) == PG_OK && f == 4);
    CHECK(pg_opt_check_known(&bare, none, &err) == PG_OK);
    pg_pipeline_free(p);
}

/* ---------------------------------------------------------------- the corpus */

static void test_corpus(void)
{
    char cwd[4096];
    if (!getcwd(cwd, sizeof cwd)) {
        CHECK_MSG(0, "getcwd failed");
        return;
    }
    /* load by relative names so messages read like the manifest: "inc/x.json: ..." */
    if (chdir(CORPUS) != 0) {
        CHECK_MSG(0, "cannot chdir to %s", CORPUS);
        return;
    }
    FILE *m = fopen("MANIFEST", "r");
    CHECK_MSG(m != NULL, "no MANIFEST in %s", CORPUS);
    char listed[256][80];
    int n_listed = 0, n_cases = 0;
    char line[1024];
    while (m && fgets(line, sizeof line, m)) {
        line[strcspn(line, "\r\n")] = 0;
        if (line[0] == '#' || line[0] == 0) continue;
        char file[80], code[40];
        int used = 0;
        if (sscanf(line, "%79s %39s %n", file, code, &used) != 2 || used == 0) {
            CHECK_MSG(0, "bad MANIFEST line: %s", line);
            continue;
        }
        const char *sub = line + used;
        if (n_listed < 256) pg_strlcpy(listed[n_listed++], file, sizeof listed[0]);
        n_cases++;
        pg_pipeline *p = (pg_pipeline *)1;
        pg_error err = {0};
        pg_result r = pg_pipeline_load(file, NULL, 0, &p, &err);
        CHECK_MSG(r != PG_OK && strcmp(pg_result_name(r), code) == 0, "%s: expected %s, got %s: %s",
                  file, code, pg_result_name(r), err.msg);
        CHECK_MSG(p == NULL, "%s: out not NULL on failure", file);
        CHECK_MSG(*sub && strstr(err.msg, sub), "%s: message lacks '%s': %s", file, sub, err.msg);
        /* the message names the file, or (for errors in a fragment) the fragment named in sub */
        CHECK_MSG(strstr(err.msg, file) || strstr(sub, ".json"), "%s: message lacks the file: %s",
                  file, err.msg);
        if (r == PG_OK) pg_pipeline_free(p);
        if (getenv("PG_TEST_VERBOSE")) printf("  %-40s %s\n", file, err.msg);
    }
    if (m) fclose(m);
    CHECK_MSG(n_cases >= 40, "only %d corpus cases", n_cases);
    /* every bad file at the top of the corpus is listed */
    DIR *dir = opendir(".");
    CHECK(dir != NULL);
    struct dirent *de;
    while (dir && (de = readdir(dir))) {
        size_t len = strlen(de->d_name);
        if (len < 5 || strcmp(de->d_name + len - 5, ".json") != 0) continue;
        bool found = false;
        for (int i = 0; i < n_listed && !found; i++) found = strcmp(listed[i], de->d_name) == 0;
        CHECK_MSG(found, "%s is not in the MANIFEST", de->d_name);
    }
    if (dir) closedir(dir);
    CHECK(chdir(cwd) == 0);
    printf("test_pipeline_json: %d corpus files\n", n_cases);
}

/* ---------------------------------------------------------------- robustness */

static void test_mutations(void)
{
    char *text = NULL;
    size_t len = 0;
    pg_error err = {0};
    CHECK(pg_read_file(GOOD "/example.json", &text, &len, &err) == PG_OK);
    if (!text) return;
    char *buf = malloc(len + 1);
    int ok = 0, failed = 0;
    /* every prefix: must fail cleanly (or succeed) with a message naming the file */
    for (size_t cut = 0; cut < len; cut += 3) {
        memcpy(buf, text, cut);
        buf[cut] = 0;
        pg_pipeline *p = NULL;
        pg_result r = pg_pipeline_load_string(buf, GOOD "/cut.json", NULL, 0, &p, &err);
        if (r == PG_OK) {
            ok++;
            pg_pipeline_free(p);
        } else {
            failed++;
            if (!strstr(err.msg, "cut.json")) CHECK_MSG(0, "cut %zu: %s", cut, err.msg);
        }
    }
    /* single-byte mutations from a fixed-seed generator */
    uint32_t seed = 12345u;
    const char pool[] = "{}[],:\"$0123456789.-eE \ntruefalsnul\\";
    for (int iter = 0; iter < 600; iter++) {
        memcpy(buf, text, len + 1);
        for (int k = 0; k < 1 + iter % 3; k++) {
            seed = seed * 1664525u + 1013904223u;
            size_t at = (seed >> 8) % len;
            seed = seed * 1664525u + 1013904223u;
            buf[at] = pool[(seed >> 8) % (sizeof pool - 1)];
        }
        pg_pipeline *p = NULL;
        pg_result r = pg_pipeline_load_string(buf, GOOD "/mut.json", NULL, 0, &p, &err);
        if (r == PG_OK) {
            ok++;
            CHECK(p != NULL && p->n_passes <= PG_MAX_PASSES);
            pg_pipeline_free(p);
        } else {
            failed++;
            if (!strstr(err.msg, "mut.json") || err.code != r)
                CHECK_MSG(0, "mutation %d: %s", iter, err.msg);
        }
    }
    CHECK(failed > 0 && ok > 0);
    free(buf);
    free(text);
}

static void test_api_edges(void)
{
    pg_pipeline *p = (pg_pipeline *)1;
    pg_error err = {0};
    CHECK(pg_pipeline_load(CORPUS "/no_such_file.json", NULL, 0, &p, &err) == PG_ERR_IO);
    CHECK(p == NULL && strstr(err.msg, "no_such_file.json"));
    CHECK(pg_pipeline_load(CORPUS "/inc", NULL, 0, &p, &err) == PG_ERR_IO);
    CHECK_MSG(!strcmp(err.msg, "pipeline '" CORPUS "/inc': is a directory, not a regular file"), "%s", err.msg);
    /* the common reader says the same for any path (include files, shaders, scenarios) */
    char *text = (char *)1;
    CHECK(pg_read_file_as(CORPUS "/inc", "a thing", &text, NULL, &err) == PG_ERR_IO && text == NULL);
    CHECK_MSG(!strcmp(err.msg, CORPUS "/inc: is a directory (expected a thing)"), "%s", err.msg);
    CHECK(pg_read_file(CORPUS "/inc", &text, NULL, &err) == PG_ERR_IO);
    CHECK_MSG(!strcmp(err.msg, CORPUS "/inc: is a directory"), "%s", err.msg);
    CHECK(pg_pipeline_load(NULL, NULL, 0, &p, &err) == PG_ERR_INVALID_ARG);
    CHECK(pg_pipeline_load_string(NULL, "x.json", NULL, 0, &p, &err) == PG_ERR_INVALID_ARG);
    CHECK(pg_pipeline_load_string("{}", "x.json", NULL, 0, NULL, &err) == PG_ERR_INVALID_ARG);
    /* err may be NULL */
    CHECK(pg_pipeline_load_string("{", "x.json", NULL, 0, &p, NULL) == PG_ERR_PARSE);
    /* virtual_path NULL: messages say <string> */
    CHECK(pg_pipeline_load_string("{}", NULL, NULL, 0, &p, &err) == PG_ERR_NO_OUTPUT);
    CHECK(strstr(err.msg, "<string>: output: missing") != NULL);
    pg_pipeline_free(NULL);
    CHECK(pg_pipeline_find_resource(NULL, "x") == NULL);
    CHECK(pg_pipeline_find_param(NULL, "x") == NULL);
    /* a minimal pipeline: one imported image and nothing else */
    CHECK(pg_pipeline_load_string("{\"resources\": [{\"name\": \"s\", \"type\": \"image\","
                                  " \"format\": \"rgba8_srgb\", \"lifetime\": \"imported\"}],"
                                  " \"output\": \"s\"}",
                                  "/a/b/min.v1.json", NULL, 0, &p, &err) == PG_OK);
    CHECK(p && strcmp(p->name, "min") == 0 && p->n_passes == 0 && p->n_omitted == 0 &&
          p->hdr_output[0] == 0);
    pg_pipeline_free(p);
}

int main(void)
{
    test_example_file();
    test_merge();
    test_params();
    test_inline_errors();
    test_options();
    test_corpus();
    test_mutations();
    test_api_edges();
    return pg_test_finish("test_pipeline_json");
}
