/* material.c - the material helpers the loaders and the animation share (scene.h): the
 * KHR_texture_transform matrix and Blinn-Phong's terms from metallic and roughness. */
#include <math.h>

#include "scene.h"

void pg_material_uv_transform(const double offset[2], double rotation, const double scale[2], float m[6])
{
    const double cr = cos(rotation), sr = sin(rotation);
    m[0] = (float)(scale[0] * cr);
    m[1] = (float)(scale[1] * sr);
    m[2] = (float)offset[0];
    m[3] = (float)(-scale[0] * sr);
    m[4] = (float)(scale[1] * cr);
    m[5] = (float)offset[1];
}

static double clamp01_default1(double x)
{
    return x >= 0.0 ? (x <= 1.0 ? x : 1.0) : (x < 0.0 ? 0.0 : 1.0); /* NaN -> 1 */
}

void pg_material_specular_from(double metallic, double roughness, float *specular, float *shininess)
{
    const double metal = clamp01_default1(metallic), rough = clamp01_default1(roughness);
    *specular = (float)(0.04 + 0.5 * (1.0 - rough) * (1.0 - metal));
    const double r4 = rough * rough * rough * rough;
    const double sh = 2.0 / (r4 + 1e-4) - 2.0;
    *shininess = (float)(sh < 1 ? 1 : sh > 512 ? 512 : sh);
}
