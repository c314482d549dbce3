/* scene_internal.h - what scene.c and scene_camera.c share: pi and the small 3-vector helpers (not
 * part of the scene library's interface; scene.h is).
 */
#ifndef PG_SCENE_INTERNAL_H
#define PG_SCENE_INTERNAL_H

#include <math.h>
#include <stdbool.h>

#define PG_PI_F 3.14159265358979323846f

static inline void v3_sub(const float a[3], const float b[3], float o[3])
{
    o[0] = a[0] - b[0];
    o[1] = a[1] - b[1];
    o[2] = a[2] - b[2];
}
static inline void v3_cross(const float a[3], const float b[3], float o[3])
{
    float x = a[1] * b[2] - a[2] * b[1];
    float y = a[2] * b[0] - a[0] * b[2];
    float z = a[0] * b[1] - a[1] * b[0];
    o[0] = x;
    o[1] = y;
    o[2] = z;
}
static inline float v3_dot(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static inline float v3_len(const float a[3]) { return sqrtf(v3_dot(a, a)); }
static inline bool v3_normalize(float a[3])
{
    float l = v3_len(a);
    if (!(l > 1e-30f) || !isfinite(l)) return false;
    a[0] /= l;
    a[1] /= l;
    a[2] /= l;
    return true;
}

#endif
