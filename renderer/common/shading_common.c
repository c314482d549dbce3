#include "shading_common.h"

#include <stdio.h>
#include <string.h>

#include "cluster_grid.h"
#include "cluster_windows.h"

const char *const pg_debug_views[] = {"none",     "cluster_heat", "cluster_x", "cluster_y", "cluster_z",
                                      "overflow", "albedo",       "normal",    "depth",     NULL};
const char *const pg_shading_models[] = {"lambert", "blinn_phong", "pbr", "auto", NULL};

int pg_shading_model(const pg_declare_in *in, int option)
{
    return option == PG_SHADING_AUTO ? pg_scene_features_of(in).auto_shading : option;
}

void pg_material_model_declare(const pg_declare_in *in, pg_pass_decl *out, int option)
{
    const pg_scene_features f = pg_scene_features_of(in);
    const int model = pg_shading_model(in, option);
    if (option == PG_SHADING_AUTO)
        pg_decl_explain(out, "shading auto: %s (%s)", pg_shading_models[model],
                        model == PG_SHADING_PBR ? "the scene's glTF metallic-roughness materials"
                        : f.auto_shading == PG_SHADING_LAMBERT ? "a generated scene, or a scenario's choice"
                                                               : "the scenario's choice");
    if (model == PG_SHADING_BLINN_PHONG) pg_decl_define(out, "PG_BLINN_PHONG");
    if (model == PG_SHADING_PBR) {
        pg_decl_define(out, "PG_PBR");
        if (f.has_metallic_roughness_tex) pg_decl_define(out, "PG_METALLIC_ROUGHNESS_TEXTURES");
        else pg_decl_explain(out, "no metallicRoughnessTexture: its sampling compiled out");
        if (f.has_occlusion_tex) pg_decl_define(out, "PG_OCCLUSION_TEXTURES");
        else pg_decl_explain(out, "no occlusionTexture: its sampling compiled out");
    } else if (f.has_metallic_roughness_tex || f.has_occlusion_tex) {
        pg_decl_explain(out, "shading %s: the metallic-roughness and occlusion textures are not read (the pbr model "
                             "reads them)",
                        pg_shading_models[model]);
    }
    if (f.has_unlit) pg_decl_define(out, "PG_UNLIT");
}

pg_result pg_shading_opts_read(const pg_pass_desc *desc, bool clustered, const char *const *extra_known,
                               pg_shading_params *sp, pg_error *err)
{
    pg_shading_opts *o = &sp->o;
    sp->clustered = clustered;
    const char *known[24];
    uint32_t n = 0;
    known[n++] = "shading";
    known[n++] = "ambient";
    known[n++] = "view";
    for (uint32_t i = 0; extra_known && extra_known[i] && n < 23; i++) known[n++] = extra_known[i];
    known[n] = NULL;
    pg_result r;
    memset(o, 0, sizeof *o);
    if ((r = pg_opt_check_known(desc, known, err))) return r;
    if ((r = pg_opt_enum(desc, "shading", pg_shading_models, PG_SHADING_AUTO, &o->shading, err))) return r;
    if ((r = pg_opt_float(desc, "ambient", 0.0, 0.0, 1e6, &o->ambient, err))) return r;
    sp->ambient = (float)o->ambient;
    if ((r = pg_opt_enum(desc, "view", pg_debug_views, 0, &o->view, err))) return r;
    if (!clustered && o->view >= 1 && o->view <= 5) {
        char key[64];
        snprintf(key, sizeof key, "%s.options.view", desc->json_path);
        return pg_fail(err, PG_ERR_SCHEMA, "%s: %s: debug view '%s' needs a clustered pass (forward_plus or deferred_lighting)",
                       desc->file, key, pg_debug_views[o->view]);
    }
    return PG_OK;
}

pg_result pg_shading_grid_declare(pg_shading_params *sp, const pg_declare_in *in, pg_error *err)
{
    if (!sp->clustered) return PG_OK;
    return pg_cluster_grid_declare(in, sp->cluster_counts, sp->cluster_lists, sp->o.grid, err);
}

void pg_shading_declare(pg_shading_params *sp, const pg_declare_in *in, pg_pass_decl *out)
{
    const pg_shading_opts *o = &sp->o;
    const bool clustered = sp->clustered;
    pg_decl_runtime_param(out, &sp->ambient, sizeof sp->ambient); /* pg_shading_runtime_options */
    pg_decl_runtime_param(out, &sp->o.ambient, sizeof sp->o.ambient);
    pg_material_model_declare(in, out, o->shading);
    if (pg_scene_features_of(in).has_file_lights) pg_decl_define(out, "PG_GLTF_FALLOFF");
    if (pg_scene_features_of(in).has_spot_lights) pg_decl_define(out, "PG_SPOT_LIGHTS");
    if (o->view) {
        pg_decl_define_int(out, "PG_DEBUG_VIEW", o->view);
        pg_decl_explain(out, "debug view '%s': output shows it instead of lighting", pg_debug_views[o->view]);
    }
    if (clustered) {
        pg_decl_define(out, "PG_CLUSTERED");
        pg_decl_define_int(out, "GRID_X", o->grid[0]);
        pg_decl_define_int(out, "GRID_Y", o->grid[1]);
        pg_decl_define_int(out, "GRID_Z", o->grid[2]);
    }
    /* a debug view that shows no lighting and needs no cluster data reads no lights either */
    bool view_needs_lights = o->view == 0 || (o->view >= 1 && o->view <= 5);
    if (pg_lights_of(in) > 0 && view_needs_lights) {
        pg_decl_define(out, "PG_HAS_LIGHTS");
        sp->has_lights = true;
    } else {
        sp->has_lights = false;
        const char *why = pg_lights_of(in) == 0 ? "0 lights: light loop compiled out"
                                                        : "debug view reads no lights";
        if (pg_slot_ok(sp->lights)) pg_decl_mark_unused(out, sp->lights, why);
        if (clustered && pg_slot_ok(sp->cluster_counts)) {
            pg_decl_mark_unused(out, sp->cluster_counts, why);
            pg_decl_mark_unused(out, sp->cluster_lists, why);
        }
    }
}

const char *const pg_shading_runtime_options[] = {"ambient", NULL};

uint32_t pg_light_set_defines(const pg_pass_create_ctx *ctx, const pg_shading_params *sp, char buf[2][40],
                              const char **defs)
{
    if (!sp->has_lights || !sp->clustered) return 0;
    return pg_list_window_defines(ctx->gpu, pg_ctx_res(ctx, sp->cluster_lists)->size, buf, defs);
}

pg_result pg_light_set_create(const pg_pass_create_ctx *ctx, const pg_shading_params *sp, pg_pass_set *out,
                              pg_error *err)
{
    return pg_light_set_create_ex(ctx, sp, NULL, out, err);
}

pg_result pg_light_set_create_ex(const pg_pass_create_ctx *ctx, const pg_shading_params *sp,
                                 const pg_phys_resource *extra, pg_pass_set *out, pg_error *err)
{
    memset(out, 0, sizeof *out);
    if (!sp->has_lights && !sp->has_env) return PG_OK;
    pg_set_binding b[5];
    uint32_t n = 0, windows[5] = {0};
    if (sp->has_lights) {
        b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pg_ctx_res(ctx, sp->lights), VK_NULL_HANDLE, 0};
        if (sp->clustered) {
            b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pg_ctx_res(ctx, sp->cluster_counts),
                                      VK_NULL_HANDLE, 0};
            const pg_phys_resource *lists = pg_ctx_res(ctx, sp->cluster_lists);
            windows[n] = pg_list_windows(ctx->gpu, lists->size); /* cluster_windows.h */
            b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, lists, VK_NULL_HANDLE, 0};
        }
        if (extra) b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, extra, VK_NULL_HANDLE, 0};
    }
    if (sp->has_env) /* PG_ENV_BINDING */
        b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, pg_ctx_res(ctx, sp->environment), VK_NULL_HANDLE, 0};
    char name[PG_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s.lights", ctx->pass->name);
    return pg_pass_set_create_windowed(ctx->gpu, n, b, NULL, windows, pg_list_window_bytes(ctx->gpu), name, out, err);
}

void pg_environment_slot_declare(const pg_declare_in *in, pg_pass_decl *out, pg_shading_params *sp, uint32_t stages,
                                 bool extra)
{
    const bool env = pg_scene_features_of(in).has_environment;
    sp->has_env = false;
    sp->environment = PG_SLOT_NONE;
    if (in->desc->n_reads <= out->n_reads) {
        if (env)
            pg_decl_explain(out, "no environment slot bound (reads[%u]): the environment light does not reach this "
                                 "pass", out->n_reads);
        return;
    }
    sp->environment = pg_decl_read(out, "environment", PG_RES_BUFFER, PG_ACCESS_STORAGE_READ, stages, 0);
    if (!env) {
        pg_decl_mark_unused(out, sp->environment, "no environment light: its term compiled out");
        return;
    }
    if (sp->o.view != 0) {
        pg_decl_mark_unused(out, sp->environment, "debug view: no environment light");
        return;
    }
    sp->has_env = true;
    pg_decl_define(out, "PG_ENVIRONMENT");
    pg_decl_define(out, "PG_ENVIRONMENT_FILTERED");
    pg_decl_define_int(out, "PG_ENV_BINDING", pg_lights_of(in) > 0 ? 1 + (sp->clustered ? 2 : 0) + (extra ? 1 : 0) : 0);
    pg_decl_explain(out, "environment light: diffuse table and %s (frame intensity and rotation: run-time values)",
                    pg_shading_model(in, sp->o.shading) == PG_SHADING_PBR ? "split-sum specular"
                                                                           : "no specular term (pbr has one)");
}

pg_result pg_hdr_storage_check(const pg_declare_in *in, pg_slot hdr, const char *what, pg_error *err)
{
    char where[32];
    const pg_resource_desc *rd = pg_decl_slot_resource(in, hdr, PG_RES_IMAGE, where, sizeof where);
    if (rd && rd->format != PG_FMT_RGBA16F && rd->format != PG_FMT_RGBA32F)
        return pg_fail(err, PG_ERR_FORMAT,
                       "%s: %s.%s: pass '%s' slot hdr: %s writes rgba16f or rgba32f, not %s (resource '%s')",
                       in->desc->file, in->desc->json_path, where, in->desc->name, what,
                       pg_format_get(rd->format)->name, rd->name);
    return PG_OK;
}

const char *pg_hdr_format_define(const pg_phys_resource *hdr, char *buf, size_t size)
{
    snprintf(buf, size, "PG_HDR_FORMAT=%s", pg_format_get(hdr->pg_fmt)->name);
    return buf;
}

pg_result pg_emissive_slot_declare(const pg_declare_in *in, pg_pass_decl *out, bool is_write, bool full_precision,
                                   pg_slot *slot, bool *used, pg_error *err)
{
    const pg_pass_desc *d = in->desc;
    const uint32_t index = is_write ? out->n_writes : out->n_reads; /* the desc position it binds */
    const bool bound = (is_write ? d->n_writes : d->n_reads) > index;
    *used = false;
    *slot = PG_SLOT_NONE;
    if (!bound) {
        if (pg_scene_features_of(in).has_emissive)
            pg_decl_explain(out, "no emissive slot bound (%s[%u]): emissive materials are not drawn",
                            is_write ? "writes" : "reads", index);
        return PG_OK;
    }
    if (is_write)
        *slot = pg_decl_write(out, "emissive", PG_RES_IMAGE, PG_ACCESS_COLOR_WRITE, PG_STAGE_FRAGMENT, PG_FMTCLASS_FLOAT);
    else
        *slot = pg_decl_read(out, "emissive", PG_RES_IMAGE, PG_ACCESS_SAMPLED, PG_STAGE_COMPUTE, PG_FMTCLASS_FLOAT);
    const char *name = is_write ? d->writes[index] : d->reads[index];
    const pg_resource_desc *rd = pg_pipeline_find_resource(in->pipeline, name);
    if (rd && rd->kind == PG_RES_IMAGE &&
        !(rd->format == PG_FMT_RGBA32F || (!full_precision && rd->format == PG_FMT_RGBA16F)))
        return pg_fail(err, PG_ERR_FORMAT, "%s: %s.%s[%u]: the emissive target holds scene-linear colour: %s, resource '%s' is %s",
                       d->file, d->json_path, is_write ? "writes" : "reads", index,
                       full_precision ? "rgba32f (full precision, as the rest of this G-buffer)" : "rgba16f or rgba32f",
                       rd->name, pg_format_get(rd->format)->name);
    if (!pg_scene_features_of(in).has_emissive) {
        pg_decl_mark_unused(out, *slot, "no emissive materials: emissive target not allocated");
        return PG_OK;
    }
    *used = true;
    return PG_OK;
}
