/* file_light.c - a scene file's light as the light table holds it (scene_gpu.h
 * pg_gpu_file_light_from): used by the upload (scene_gpu.c) and by the per-frame placement of lights
 * on animated nodes (scene_gpu_anim.c). */
#include "scene_gpu.h"

#include <math.h>
#include <string.h>

void pg_gpu_file_light_from(const pg_scene_light *L, pg_gpu_file_light *out)
{
    /* the shading has no 1/pi in its Lambert term (albedo x colour x N.L), so a light in the
     * extension's units (candela, lux) is divided by pi once here */
    float k = L->intensity / 3.14159265358979f;
    /* an animated colour or intensity (KHR_animation_pointer) past what the loaders take: clamped */
    const double peak = fmax(fmax(L->color[0], L->color[1]), L->color[2]) * (double)L->intensity,
                 most = L->type == PG_LIGHT_DIRECTIONAL ? PG_LIGHT_MAX_LUX : PG_LIGHT_MAX_CANDELA;
    if (peak > most) k = (float)(most / peak * L->intensity / 3.14159265358979);
    pg_gpu_file_light g = {
        {L->position[0], L->position[1], L->position[2], L->range},
        {L->color[0] * k, L->color[1] * k, L->color[2] * k, (float)L->type},
        {L->direction[0], L->direction[1], L->direction[2], 0.0f},
    };
    if (L->type == PG_LIGHT_SPOT) { /* the spot record: axis x scale, offset (the extension's) */
        float ci = cosf(L->inner_cone), co = cosf(L->outer_cone), sc = 1.0f / fmaxf(ci - co, 1e-3f);
        for (int k = 0; k < 3; k++) g.direction[k] *= sc;
        g.direction[3] = -co * sc;
    }
    memcpy(out, &g, sizeof g);
}
