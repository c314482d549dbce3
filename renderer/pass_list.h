/* pass_list.h - the built-in pass types. Adding a pass type = one file in passes/ exporting a
 * const pg_pass_type, plus one line in pass_list.c. */
#ifndef PG_PASS_LIST_H
#define PG_PASS_LIST_H

#include "pass_api.h"

extern const pg_pass_type pg_pass_light_animate;
extern const pg_pass_type pg_pass_forward_naive;
extern const pg_pass_type pg_pass_forward_transparent;
extern const pg_pass_type pg_pass_display_tonemap;
extern const pg_pass_type pg_pass_display_ocio;
extern const pg_pass_type pg_pass_cluster_assign;
extern const pg_pass_type pg_pass_forward_plus;
extern const pg_pass_type pg_pass_depth_prepass;
extern const pg_pass_type pg_pass_gbuffer;
extern const pg_pass_type pg_pass_deferred_lighting;
extern const pg_pass_type pg_pass_reference_lighting;
extern const pg_pass_type pg_pass_visibility;
extern const pg_pass_type pg_pass_visibility_resolve;
extern const pg_pass_type pg_pass_luminance_histogram;
extern const pg_pass_type pg_pass_light_tree;
extern const pg_pass_type pg_pass_stochastic_lights;
extern const pg_pass_type pg_pass_environment_filter;
extern const pg_pass_type pg_pass_environment_background;
extern const pg_pass_type pg_pass_geometry_animate;
extern const pg_pass_type pg_pass_shader;

/* Fills reg with every built-in pass type. */
void pg_register_builtin_passes(pg_pass_registry *reg);

#endif
