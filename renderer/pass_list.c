#include "pass_list.h"

#include <string.h>

void pg_register_builtin_passes(pg_pass_registry *reg)
{
    static const pg_pass_type *const builtin[] = {
        &pg_pass_light_animate,
        &pg_pass_forward_naive,
        &pg_pass_display_tonemap,
        &pg_pass_display_ocio,
        &pg_pass_cluster_assign,
        &pg_pass_forward_plus,
        &pg_pass_depth_prepass,
        &pg_pass_gbuffer,
        &pg_pass_deferred_lighting,
        &pg_pass_reference_lighting,
        &pg_pass_forward_transparent,
        &pg_pass_visibility,
        &pg_pass_visibility_resolve,
        &pg_pass_luminance_histogram,
        &pg_pass_light_tree,
        &pg_pass_stochastic_lights,
        &pg_pass_environment_filter,
        &pg_pass_environment_background,
        &pg_pass_geometry_animate,
        &pg_pass_shader,
    };
    memset(reg, 0, sizeof *reg);
    for (size_t i = 0; i < sizeof builtin / sizeof builtin[0]; i++) reg->types[reg->count++] = builtin[i];
}
