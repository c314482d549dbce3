/* node_place.c - lights and cameras placed by their nodes' world matrices (node_place.h). */
#include "node_place.h"

#include <math.h>

bool pg_place_light(const double m[16], pg_scene_light *L)
{
    const double d[3] = {-m[8], -m[9], -m[10]};
    const double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; k++) {
        L->position[k] = (float)m[12 + k];
        if (dl > 1e-30) L->direction[k] = (float)(d[k] / dl);
    }
    return dl > 1e-30;
}

bool pg_place_camera(const double m[16], pg_scene_camera *C)
{
    double f[3] = {-m[8], -m[9], -m[10]}, u[3] = {m[4], m[5], m[6]};
    const double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(fl > 1e-30)) return false;
    for (int k = 0; k < 3; k++) f[k] /= fl;
    const double fu = f[0] * u[0] + f[1] * u[1] + f[2] * u[2];
    for (int k = 0; k < 3; k++) u[k] -= fu * f[k];
    const double ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (!(ul > 1e-12 * fl)) return false;
    for (int k = 0; k < 3; k++) {
        C->position[k] = (float)m[12 + k];
        C->forward[k] = (float)f[k];
        C->up[k] = (float)(u[k] / ul);
    }
    return true;
}

void pg_mat4_widen(const float f[16], double out[16])
{
    for (int i = 0; i < 16; i++) out[i] = f[i];
}
