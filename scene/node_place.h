/* node_place.h - a glTF light or camera placed by its node's world matrix (column-major 4x4): one
 * rule for the loader (scene_gltf_nodes.cpp, at the file's rest pose), the CPU pose
 * (scene_pose.c, at --time) and the per-frame upload of lights on animated nodes
 * (renderer/scene_gpu_anim.c). Computed in double. */
#ifndef PG_NODE_PLACE_H
#define PG_NODE_PLACE_H

#include <stdbool.h>

#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The light's position is the matrix's translation; its direction the node's -Z axis, normalised.
 * Returns false (direction left as is, position still set) when that axis is degenerate
 * (|-Z| <= 1e-30). */
bool pg_place_light(const double m[16], pg_scene_light *L);
/* The camera looks down the node's -Z with +Y up, orthonormalised (up made perpendicular to the
 * forward axis). Returns false, and leaves the camera as it was, when the matrix is singular there
 * (|-Z| <= 1e-30, or +Y parallel to -Z within 1e-12 of |-Z|). */
bool pg_place_camera(const double m[16], pg_scene_camera *C);
/* A float matrix (a pose's node_world) widened to double. */
void pg_mat4_widen(const float f[16], double out[16]);

#ifdef __cplusplus
}
#endif
#endif
