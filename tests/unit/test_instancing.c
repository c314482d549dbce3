/* test_instancing.c - EXT_mesh_gpu_instancing (scene/scene_gltf_instancing.cpp) on the CPU, with the
 * files of tests/corpus/gltf/instancing/ (gen_instancing.py):
 * - grove.gltf (7 instances: FLOAT translations and scales, normalized SHORT rotations, one mirrored
 *   instance) loads to exactly the vertices and indices of grove_twin.gltf, the same boxes as child
 *   nodes: the same bytes, winding included, no warning;
 * - grove_moving.gltf (the instanced node turns) poses like grove_moving_twin.gltf at every quarter
 *   second of its animation, within float rounding (the instance's transform is baked into the
 *   mesh-space vertices there, the twin composes it with the node's at each pose). The twin's
 *   rotations (decoded SHORTs) are not exactly unit: the pose once used them unnormalised while
 *   the rest pose normalised them, and the two files were 1.3e-5 m apart (now 4.8e-7).
 * Bad instancing is refused naming the field: the files of the corpus MANIFEST (instancing_*.gltf,
 * test_scene).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "animation.h"
#include "scene.h"
#include "test_scene_file.h"
#include "test_util.h"

static pg_scene *load_file(const char *rel) { return pg_test_load_gltf("instancing", rel); }

static void same_as_nodes(void)
{
    pg_scene *a = load_file("grove.gltf"), *b = load_file("grove_twin.gltf");
    if (a && b) {
        CHECK_MSG(a->n_vertices == b->n_vertices && a->n_indices == b->n_indices,
                  "grove: %u vertices, %u indices; twin: %u, %u", a->n_vertices, a->n_indices, b->n_vertices,
                  b->n_indices);
        CHECK(a->n_vertices == 4 + 7 * 24 && a->n_indices == 6 + 7 * 36);
        if (a->n_vertices == b->n_vertices && a->n_indices == b->n_indices) {
            uint32_t dv = 0, di = 0;
            for (uint32_t v = 0; v < a->n_vertices; v++)
                dv += memcmp(&a->vertices[v], &b->vertices[v], sizeof a->vertices[v]) != 0;
            for (uint32_t i = 0; i < a->n_indices; i++) di += a->indices[i] != b->indices[i];
            CHECK_MSG(dv == 0 && di == 0, "grove vs twin: %u vertices, %u indices differ", dv, di);
            printf("grove.gltf: %u vertices, %u indices, the same bytes as its twin of plain nodes\n", a->n_vertices,
                   a->n_indices);
        }
        CHECK_MSG(a->n_warnings == 0, "grove.gltf: %u warnings (%s)", a->n_warnings,
                  a->n_warnings ? a->warnings[0] : "");
        /* the mirrored instance (scale x -1, the 5th box, primitive 5 after the floor's): its winding
         * was flipped, so every triangle, counter-clockwise, still faces its vertices' normal */
        uint32_t facing = 0, triangles = 0;
        for (uint32_t p = 0; p < a->n_primitives; p++) {
            const pg_primitive *pr = &a->primitives[p];
            if (pr->first_index != 6 + 4 * 36) continue;
            for (uint32_t t = 0; t + 2 < pr->index_count; t += 3, triangles++) {
                const pg_vertex *v = a->vertices + pr->vertex_offset;
                const uint32_t *ix = a->indices + pr->first_index + t;
                const float *p0 = v[ix[0]].position, *p1 = v[ix[1]].position, *p2 = v[ix[2]].position;
                const float *n0 = v[ix[0]].normal;
                float e1[3], e2[3];
                for (int k = 0; k < 3; k++) {
                    e1[k] = p1[k] - p0[k];
                    e2[k] = p2[k] - p0[k];
                }
                const float g[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                    e1[0] * e2[1] - e1[1] * e2[0]};
                facing += g[0] * n0[0] + g[1] * n0[1] + g[2] * n0[2] > 0;
            }
        }
        CHECK_MSG(triangles == 12 && facing == 12, "mirrored instance: %u of %u triangles face their normal", facing,
                  triangles);
    }
    pg_scene_free(a);
    pg_scene_free(b);
}

static void moving(void)
{
    pg_scene *a = load_file("grove_moving.gltf"), *b = load_file("grove_moving_twin.gltf");
    if (a && b && a->n_vertices == b->n_vertices) {
        CHECK(a->anim && b->anim && a->features.has_animation);
        double worst = 0, worst_n = 0;
        for (double t = 0; t <= 4.0; t += 0.25) {
            pg_error err = {0};
            CHECK(pg_scene_pose(a, 0, t, &err) == PG_OK && pg_scene_pose(b, 0, t, &err) == PG_OK);
            for (uint32_t v = 0; v < a->n_vertices; v++)
                for (int k = 0; k < 3; k++) {
                    worst = fmax(worst, fabs((double)a->vertices[v].position[k] - b->vertices[v].position[k]));
                    worst_n = fmax(worst_n, fabs((double)a->vertices[v].normal[k] - b->vertices[v].normal[k]));
                }
        }
        /* positions within 4 m of the origin: a float's rounding there is 2.4e-7 m per operation; the twin
         * composes more of them (its node's TRS at every pose) */
        CHECK_MSG(worst <= 2e-6 && worst_n <= 2e-6, "grove_moving vs twin: %.3g m, normals %.3g", worst, worst_n);
        printf("grove_moving.gltf: posed like its twin at 17 times, within %.3g m (normals %.3g)\n", worst, worst_n);
    } else {
        CHECK_MSG(a && b, "grove_moving: not loaded");
    }
    pg_scene_free(a);
    pg_scene_free(b);
}

int main(void)
{
    same_as_nodes();
    moving();
    return pg_test_finish("test_instancing");
}
