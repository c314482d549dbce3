/* pass_plugin.h - pass types from a shared library (a plug-in), loaded by `--plugin FILE.so`
 * (docs/plugins.md).
 *
 * A plug-in is a shared object built against passgraph's headers (pass_api.h and, for Vulkan
 * work, graph_execute.h, pass_set.h, shader.h, vk_pipeline.h) and linked against nothing of
 * passgraph's: the passgraph executable exports its symbols (-rdynamic), which the plug-in's
 * undefined references bind to when it is loaded. It exports two functions with C linkage:
 *
 *   uint32_t passgraph_plugin_api_version(void);        returns PG_PLUGIN_API_VERSION
 *   pg_result passgraph_plugin_register(pg_pass_registry *reg, pg_error *err);
 *                                                       pg_registry_add() for each of its types
 *
 * The loader refuses a library that cannot be loaded, lacks either function, reports another API
 * version, or registers a type whose name exists already; each message names the file. The library
 * stays loaded until the command ends (its pass types are referenced by compiled plans).
 *
 * PG_PLUGIN_API_VERSION changes whenever pg_pass_type, the declare/create/record contexts or any
 * function a pass calls change their layout or meaning. */
#ifndef PG_PASS_PLUGIN_H
#define PG_PASS_PLUGIN_H

#include "pass_api.h"

#define PG_PLUGIN_API_VERSION 2u
#define PG_PLUGIN_VERSION_SYMBOL "passgraph_plugin_api_version"
#define PG_PLUGIN_REGISTER_SYMBOL "passgraph_plugin_register"

/* exported with C linkage: a plug-in written in C++ gets the names the loader looks up */
#ifdef __cplusplus
#define PG_PLUGIN_LINKAGE extern "C"
#else
#define PG_PLUGIN_LINKAGE
#endif
#if defined(__GNUC__)
#define PG_PLUGIN_EXPORT PG_PLUGIN_LINKAGE __attribute__((visibility("default")))
#else
#define PG_PLUGIN_EXPORT PG_PLUGIN_LINKAGE
#endif

typedef uint32_t (*pg_plugin_version_fn)(void);
typedef pg_result (*pg_plugin_register_fn)(pg_pass_registry *reg, pg_error *err);

#endif
