/* scene_camera.c - cameras (the default and framing cameras, the file's cameras) and
 * camera / matrix math.
 *
 * Matrix convention (used everywhere in passgraph): column-major float[16], element (row r,
 * column c) at m[c*4 + r]; vectors are columns, p' = M * p.
 *
 * Camera convention:
 *   world: right-handed, +Y up.
 *   view (pg_camera_view): right-handed look-at; camera space has +X right, +Y up and the camera
 *     looking down -Z (the OpenGL/glTF camera convention).
 *   projection (pg_camera_proj): perspective into Vulkan clip space: x_ndc -1 = left,
 *     y_ndc -1 = TOP of the image (the view's +Y is negated, so the image is upright with the
 *     Vulkan viewport's y-down), depth z_ndc = 0 at near and 1 at far (standard, NOT reversed Z),
 *     w_clip = -z_view. A viewport with positive height (no VK_KHR_maintenance1 flip) is expected.
 */
#include "scene.h"
#include "scene_internal.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------------------------------ */
/* camera and matrices                                                                         */

pg_camera pg_camera_default_for_scene(const pg_scene *scene, float aspect)
{
    float mn[3] = {-1, -1, -1}, mx[3] = {1, 1, 1};
    if (scene && scene->bounds_min[0] <= scene->bounds_max[0] &&
        scene->bounds_min[1] <= scene->bounds_max[1] &&
        scene->bounds_min[2] <= scene->bounds_max[2]) {
        memcpy(mn, scene->bounds_min, sizeof mn);
        memcpy(mx, scene->bounds_max, sizeof mx);
    }
    float size[3], center[3];
    for (int k = 0; k < 3; k++) {
        size[k] = mx[k] - mn[k];
        center[k] = 0.5f * (mn[k] + mx[k]);
    }
    float diag = v3_len(size);
    if (!(diag > 1e-6f)) diag = 1.0f;
    if (!(size[0] > 1e-6f)) { /* flat along x: still look along +X from in front of it */
        mn[0] = center[0] - 0.5f * diag;
        mx[0] = center[0] + 0.5f * diag;
        size[0] = diag;
    }
    pg_camera c;
    memset(&c, 0, sizeof c);
    c.position[0] = mn[0] + 0.2f * size[0];
    c.position[1] = mn[1] + 0.18f * size[1];
    c.position[2] = center[2];
    c.target[0] = mx[0];
    c.target[1] = c.position[1];
    c.target[2] = center[2];
    c.up[0] = 0;
    c.up[1] = 1;
    c.up[2] = 0;
    c.fov_y_deg = 60.0f;
    c.near_z = fmaxf(0.01f, 0.001f * diag);
    c.far_z = 2.0f * diag;
    c.aspect = aspect > 0 && isfinite(aspect) ? aspect : 1.0f;
    return c;
}

static bool scene_has_bounds(const pg_scene *scene)
{
    return scene && scene->n_indices > 0 && scene->bounds_min[0] <= scene->bounds_max[0] &&
           scene->bounds_min[1] <= scene->bounds_max[1] && scene->bounds_min[2] <= scene->bounds_max[2];
}

/* The distance from p to the farthest corner of the scene's bounds. */
static double farthest_corner(const pg_scene *scene, const float p[3])
{
    double m = 0;
    for (int i = 0; i < 8; i++) {
        double d2 = 0;
        for (int k = 0; k < 3; k++) {
            double v = ((i >> k) & 1) ? scene->bounds_max[k] : scene->bounds_min[k];
            d2 += (v - p[k]) * (v - p[k]);
        }
        m = fmax(m, d2);
    }
    return sqrt(m);
}

/* The sum of the triangles' area-weighted face normals (counter-clockwise front; twice the area
 * times the normal, each) and of their lengths. */
static void area_normals(const pg_scene *scene, double sum[3], double *area)
{
    sum[0] = sum[1] = sum[2] = *area = 0;
    for (uint32_t p = 0; p < scene->n_primitives; p++) {
        const pg_primitive *pr = &scene->primitives[p];
        for (uint32_t t = 0; t + 2 < pr->index_count; t += 3) {
            const uint32_t *ix = &scene->indices[pr->first_index + t];
            int64_t i0 = (int64_t)ix[0] + pr->vertex_offset, i1 = (int64_t)ix[1] + pr->vertex_offset,
                    i2 = (int64_t)ix[2] + pr->vertex_offset;
            if (i0 < 0 || i1 < 0 || i2 < 0 || i0 >= scene->n_vertices || i1 >= scene->n_vertices ||
                i2 >= scene->n_vertices)
                continue;
            float e1[3], e2[3], c[3];
            v3_sub(scene->vertices[i1].position, scene->vertices[i0].position, e1);
            v3_sub(scene->vertices[i2].position, scene->vertices[i0].position, e2);
            v3_cross(e1, e2, c);
            for (int a = 0; a < 3; a++) sum[a] += c[a];
            *area += sqrt((double)c[0] * c[0] + (double)c[1] * c[1] + (double)c[2] * c[2]);
        }
    }
}

/* The axis a flat scene is thin along (its extent under PG_FLAT_RATIO of the middle one: a plate,
 * not a rod), -1 when it is not flat; *side = +1 / -1: the side the triangles' area-weighted normals face along it (+1 on
 * a tie). */
#define PG_FLAT_RATIO 0.1
static int flat_axis(const pg_scene *scene, const double ext[3], int *side)
{
    int k = 0;
    for (int a = 1; a < 3; a++)
        if (ext[a] < ext[k]) k = a;
    double mid = ext[0] + ext[1] + ext[2] - ext[k] - fmax(ext[0], fmax(ext[1], ext[2])); /* middle extent */
    *side = 1;
    if (!(ext[k] < PG_FLAT_RATIO * mid)) return -1; /* a rod (two thin axes) is not flat */
    double sum[3], area;
    area_normals(scene, sum, &area);
    *side = sum[k] < 0 ? -1 : 1;
    return k;
}

/* A flat scene no axis is thin along (a tilted panel): nearly all of its triangle area faces one way
 * (the area-weighted normals' sum at least PG_SHEET_ALIGN of the total area) and its vertices lie
 * within PG_FLAT_RATIO of its narrower extent in that plane from it. n: the unit normal its front
 * faces along. */
#define PG_SHEET_ALIGN 0.95
static bool tilted_sheet(const pg_scene *scene, double n[3])
{
    double sum[3], area;
    area_normals(scene, sum, &area);
    double len = sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    if (!(area > 0) || !(len >= PG_SHEET_ALIGN * area)) return false;
    for (int a = 0; a < 3; a++) n[a] = sum[a] / len;
    /* two axes in the plane: u = n x (the world axis least along n), w = n x u */
    int least = 0;
    for (int a = 1; a < 3; a++)
        if (fabs(n[a]) < fabs(n[least])) least = a;
    double e[3] = {0, 0, 0}, u[3], w[3];
    e[least] = 1;
    u[0] = n[1] * e[2] - n[2] * e[1], u[1] = n[2] * e[0] - n[0] * e[2], u[2] = n[0] * e[1] - n[1] * e[0];
    double ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int a = 0; a < 3; a++) u[a] /= ul;
    w[0] = n[1] * u[2] - n[2] * u[1], w[1] = n[2] * u[0] - n[0] * u[2], w[2] = n[0] * u[1] - n[1] * u[0];
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}; /* along n, u, w */
    for (uint32_t i = 0; i < scene->n_vertices; i++) {
        const float *q = scene->vertices[i].position;
        double d[3] = {q[0] * n[0] + q[1] * n[1] + q[2] * n[2], q[0] * u[0] + q[1] * u[1] + q[2] * u[2],
                       q[0] * w[0] + q[1] * w[1] + q[2] * w[2]};
        for (int a = 0; a < 3; a++) lo[a] = fmin(lo[a], d[a]), hi[a] = fmax(hi[a], d[a]);
    }
    return hi[0] - lo[0] < PG_FLAT_RATIO * fmin(hi[1] - lo[1], hi[2] - lo[2]);
}

pg_camera pg_camera_frame_object(const pg_scene *scene, float aspect, float *out_radius, float *out_distance)
{
    float mn[3] = {-1, -1, -1}, mx[3] = {1, 1, 1};
    bool has = scene_has_bounds(scene);
    if (has) {
        memcpy(mn, scene->bounds_min, sizeof mn);
        memcpy(mx, scene->bounds_max, sizeof mx);
    }
    double c[3], ext[3], h2 = 0;
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5 * ((double)mn[k] + (double)mx[k]);
        ext[k] = (double)mx[k] - (double)mn[k];
        h2 += 0.25 * ext[k] * ext[k];
    }
    double r = sqrt(h2);
    if (!(r > 1e-30)) r = 1.0;
    if (!(aspect > 0) || !isfinite(aspect)) aspect = 1.0f;
    const double pi = 3.14159265358979323846;
    double ty = tan(0.5 * 45.0 * pi / 180.0), tx = ty * aspect;
    /* direction from the target to the camera, and up */
    double dir[3], up[3] = {0, 1, 0};
    int side = 1, k = has ? flat_axis(scene, ext, &side) : -1;
    if (k >= 0) { /* flat: seen from the front, along its normal */
        dir[0] = dir[1] = dir[2] = 0;
        dir[k] = side;
        if (k == 1) { /* a floor (or ceiling): from above (below), far edge at the top */
            up[1] = 0;
            up[2] = -side;
        }
    } else if (has && scene->vertices && tilted_sheet(scene, dir)) { /* flat and tilted: along its normal */
        if (fabs(dir[1]) > 0.9) { /* mostly a floor (ceiling): as above */
            up[1] = 0;
            up[2] = dir[1] > 0 ? -1 : 1;
        }
    } else {
        double az = 35.0 * pi / 180.0, el = 25.0 * pi / 180.0;
        dir[0] = sin(az) * cos(el), dir[1] = sin(el), dir[2] = cos(az) * cos(el);
    }
    /* camera basis: right = up x dir, true up = dir x right */
    double rt[3] = {up[1] * dir[2] - up[2] * dir[1], up[2] * dir[0] - up[0] * dir[2], up[0] * dir[1] - up[1] * dir[0]};
    double rl = sqrt(rt[0] * rt[0] + rt[1] * rt[1] + rt[2] * rt[2]);
    for (int a = 0; a < 3; a++) rt[a] /= rl;
    double uv[3] = {dir[1] * rt[2] - dir[2] * rt[1], dir[2] * rt[0] - dir[0] * rt[2], dir[0] * rt[1] - dir[1] * rt[0]};
    /* Fit the points (every vertex; the box corners without geometry) into m = 90% of both
     * half-angles: a point at lateral offsets (x, y) and depth z towards the camera is inside when
     * |x| <= m tx (d - z) and |y| <= m ty (d - z). Each pass after the first aims at the middle of
     * the previous pass's screen box (perspective moves it again a little: six passes bring the centre
     * within 1% of the image), so an object that fills one side of its bounds is centred. */
    const double m = 0.9;
    double d = 0, zmin = 0, zmax = 0;
    uint32_t nv = has && scene->vertices ? scene->n_vertices : 0;
    for (int pass = 0; pass < 6; pass++) {
        d = 0, zmin = 1e300, zmax = -1e300;
        for (uint32_t i = 0; i < (nv ? nv : 8u); i++) {
            double q[3];
            for (int a = 0; a < 3; a++)
                q[a] = (nv ? (double)scene->vertices[i].position[a] : ((i >> a) & 1) ? mx[a] : mn[a]) - c[a];
            double x = q[0] * rt[0] + q[1] * rt[1] + q[2] * rt[2];
            double y = q[0] * uv[0] + q[1] * uv[1] + q[2] * uv[2];
            double z = q[0] * dir[0] + q[1] * dir[1] + q[2] * dir[2];
            d = fmax(d, fmax(z + fabs(x) / (m * tx), z + fabs(y) / (m * ty)));
            zmin = fmin(zmin, z), zmax = fmax(zmax, z);
        }
        d = fmax(d, zmax + 0.05 * r);
        if (pass == 5) break;
        double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300; /* screen box, tangent units */
        for (uint32_t i = 0; i < (nv ? nv : 8u); i++) {
            double q[3];
            for (int a = 0; a < 3; a++)
                q[a] = (nv ? (double)scene->vertices[i].position[a] : ((i >> a) & 1) ? mx[a] : mn[a]) - c[a];
            double z = q[0] * dir[0] + q[1] * dir[1] + q[2] * dir[2];
            double x = (q[0] * rt[0] + q[1] * rt[1] + q[2] * rt[2]) / (d - z);
            double y = (q[0] * uv[0] + q[1] * uv[1] + q[2] * uv[2]) / (d - z);
            x0 = fmin(x0, x), x1 = fmax(x1, x), y0 = fmin(y0, y), y1 = fmax(y1, y);
        }
        double sx = 0.5 * (x0 + x1) * d, sy = 0.5 * (y0 + y1) * d; /* shift at the target's depth */
        for (int a = 0; a < 3; a++) c[a] += sx * rt[a] + sy * uv[a];
    }
    pg_camera cam;
    memset(&cam, 0, sizeof cam);
    for (int a = 0; a < 3; a++) {
        cam.position[a] = (float)(c[a] + d * dir[a]);
        cam.target[a] = (float)c[a];
        cam.up[a] = (float)up[a];
    }
    cam.fov_y_deg = 45.0f;
    double depth = zmax - zmin, pad = 0.05 * fmax(depth, 0.02 * r);
    cam.near_z = (float)fmax(d - zmax - pad, 0.5 * (d - zmax));
    cam.far_z = (float)(d - zmin + pad);
    cam.aspect = aspect;
    if (out_radius) *out_radius = (float)r;
    if (out_distance) *out_distance = (float)d;
    return cam;
}

pg_result pg_camera_from_scene(const pg_scene *scene, uint32_t index, float aspect, pg_camera *out, pg_error *err)
{
    if (!scene || index >= scene->n_cameras)
        return pg_fail(err, PG_ERR_INVALID_ARG, "camera %u: out of range (%u cameras)", index,
                       scene ? scene->n_cameras : 0);
    const pg_scene_camera *sc = &scene->cameras[index];
    pg_camera cam;
    memset(&cam, 0, sizeof cam);
    double dist = 1.0; /* look-at distance: any positive value gives the same view */
    if (scene_has_bounds(scene)) {
        double cc = 0, r2 = 0;
        for (int k = 0; k < 3; k++) {
            double c = 0.5 * ((double)scene->bounds_min[k] + scene->bounds_max[k]);
            double h = 0.5 * ((double)scene->bounds_max[k] - scene->bounds_min[k]);
            cc += (c - sc->position[k]) * sc->forward[k];
            r2 += h * h;
        }
        dist = cc > 1e-6 * sqrt(r2) ? cc : (sqrt(r2) > 0 ? sqrt(r2) : 1.0);
    }
    for (int k = 0; k < 3; k++) {
        cam.position[k] = sc->position[k];
        cam.target[k] = (float)(sc->position[k] + dist * sc->forward[k]);
        cam.up[k] = sc->up[k];
    }
    cam.fov_y_deg = sc->yfov_rad * (float)(180.0 / 3.14159265358979323846);
    cam.near_z = sc->znear;
    float far = sc->zfar;
    if (!(far > 0)) { /* infinite: to the farthest corner of the bounds, twice */
        far = (float)(2.0 * farthest_corner(scene, sc->position));
        if (far < 1000.0f * sc->znear) far = 1000.0f * sc->znear;
    }
    cam.far_z = far;
    cam.aspect = aspect > 0 && isfinite(aspect) ? aspect : 1.0f;
    if (sc->type == PG_CAMERA_ORTHOGRAPHIC) {
        cam.ortho_height = 2.0f * fabsf(sc->ymag);
        cam.fov_y_deg = 45.0f; /* unused */
        if (!(cam.near_z > 1e-6f * cam.far_z)) cam.near_z = 1e-6f * cam.far_z;
    }
    pg_camera_raise_near(&cam, scene);
    *out = cam;
    return PG_OK;
}

pg_result pg_scene_find_camera(const pg_scene *scene, const char *spec, uint32_t *out_index, pg_error *err)
{
    uint32_t n = scene ? scene->n_cameras : 0;
    if (spec && spec[0]) {
        const char *p = spec;
        bool digits = true;
        for (; *p; p++)
            if (*p < '0' || *p > '9') digits = false;
        if (digits && strlen(spec) < 10) {
            unsigned long v = strtoul(spec, NULL, 10);
            if (v < n) {
                *out_index = (uint32_t)v;
                return PG_OK;
            }
        }
        for (uint32_t i = 0; i < n; i++)
            if (!strcmp(scene->cameras[i].name, spec)) {
                *out_index = i;
                return PG_OK;
            }
        for (uint32_t i = 0; i < n; i++)
            if (!strcmp(scene->cameras[i].node_name, spec)) {
                *out_index = i;
                return PG_OK;
            }
    }
    const char *file = scene ? scene->path : "(no scene)";
    if (n == 0)
        return pg_fail(err, PG_ERR_INVALID_ARG, "--camera %s: %s has no cameras; use --camera auto", spec ? spec : "",
                       file);
    char list[768];
    size_t len = 0;
    list[0] = 0;
    for (uint32_t i = 0; i < n && len + 1 < sizeof list; i++) {
        int w = snprintf(list + len, sizeof list - len, "%s%u '%s' (node '%s'%s)", i ? ", " : "", i,
                         scene->cameras[i].name, scene->cameras[i].node_name,
                         scene->cameras[i].type == PG_CAMERA_ORTHOGRAPHIC ? ", orthographic" : "");
        if (w < 0) break;
        len += (size_t)w;
        if (len >= sizeof list) len = sizeof list - 1;
    }
    return pg_fail(err, PG_ERR_INVALID_ARG, "--camera %s: no such camera in %s; available: %s, or auto",
                   spec ? spec : "", file, list);
}

void pg_camera_view(const pg_camera *cam, float out[16])
{
    float f[3], s[3], u[3];
    v3_sub(cam->target, cam->position, f);
    if (!v3_normalize(f)) {
        f[0] = 0;
        f[1] = 0;
        f[2] = -1;
    }
    float up[3] = {cam->up[0], cam->up[1], cam->up[2]};
    if (!v3_normalize(up)) {
        up[0] = 0;
        up[1] = 1;
        up[2] = 0;
    }
    v3_cross(f, up, s);
    if (!v3_normalize(s)) { /* up parallel to the view direction: pick another up */
        float alt[3] = {0, 0, 1};
        if (fabsf(f[2]) > 0.9f) {
            alt[1] = 1;
            alt[2] = 0;
        }
        v3_cross(f, alt, s);
        v3_normalize(s);
    }
    v3_cross(s, f, u);
    const float *e = cam->position;
    /* rows: s, u, -f */
    out[0] = s[0];
    out[4] = s[1];
    out[8] = s[2];
    out[12] = -v3_dot(s, e);
    out[1] = u[0];
    out[5] = u[1];
    out[9] = u[2];
    out[13] = -v3_dot(u, e);
    out[2] = -f[0];
    out[6] = -f[1];
    out[10] = -f[2];
    out[14] = v3_dot(f, e);
    out[3] = 0;
    out[7] = 0;
    out[11] = 0;
    out[15] = 1;
}

void pg_camera_depth_planes(const pg_camera *cam, float *near_z, float *far_z)
{
    float n = cam->near_z > 0 ? cam->near_z : 0.01f;
    float fz = cam->far_z > n ? cam->far_z : n * 1000.0f;
    *near_z = n;
    *far_z = fz;
}

bool pg_camera_raise_near(pg_camera *cam, const pg_scene *scene)
{
    if (cam->ortho_height > 0) return false; /* its own rule: pg_camera_from_scene */
    double far = cam->far_z > 0 ? cam->far_z : 1e30;
    if (scene_has_bounds(scene)) far = fmin(far, farthest_corner(scene, cam->position));
    const float lo = (float)(PG_NEAR_FAR_MIN * far);
    if (cam->near_z >= lo) return false;
    cam->near_z = lo;
    if (!(cam->far_z > lo)) cam->far_z = lo * 1000.0f;
    return true;
}

void pg_camera_proj(const pg_camera *cam, float out[16])
{
    float fov = cam->fov_y_deg;
    if (!(fov > 0.0f && fov < 180.0f)) fov = 60.0f;
    float aspect = cam->aspect > 0 && isfinite(cam->aspect) ? cam->aspect : 1.0f;
    float n, fz;
    pg_camera_depth_planes(cam, &n, &fz);
    memset(out, 0, 16 * sizeof(float));
    if (cam->ortho_height > 0 && isfinite(cam->ortho_height)) {
        float hh = 0.5f * cam->ortho_height;
        out[0] = 1.0f / (hh * aspect);
        out[5] = -1.0f / hh;             /* Vulkan: clip y down */
        out[10] = 1.0f / (n - fz);       /* z_ndc = (-z - n) / (f - n) */
        out[14] = n / (n - fz);
        out[15] = 1.0f;
        return;
    }
    float t = 1.0f / tanf(fov * PG_PI_F / 360.0f);
    out[0] = t / aspect;
    out[5] = -t;                     /* Vulkan: clip y down */
    out[10] = fz / (n - fz);         /* z_ndc: 0 at near, 1 at far */
    out[14] = n * fz / (n - fz);
    out[11] = -1.0f;                 /* w_clip = -z_view */
}

void pg_mat4_mul(const float a[16], const float b[16], float out[16])
{
    float r[16];
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            float acc = 0;
            for (int k = 0; k < 4; k++) acc += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = acc;
        }
    memcpy(out, r, sizeof r);
}

bool pg_mat4_invert(const float m[16], float out[16])
{
    double a[16], inv[16];
    double maxabs = 0;
    for (int i = 0; i < 16; i++) {
        a[i] = m[i];
        if (!isfinite(a[i])) return false;
        if (fabs(a[i]) > maxabs) maxabs = fabs(a[i]);
    }
    if (maxabs == 0) return false;
    inv[0] = a[5] * a[10] * a[15] - a[5] * a[11] * a[14] - a[9] * a[6] * a[15] +
             a[9] * a[7] * a[14] + a[13] * a[6] * a[11] - a[13] * a[7] * a[10];
    inv[4] = -a[4] * a[10] * a[15] + a[4] * a[11] * a[14] + a[8] * a[6] * a[15] -
             a[8] * a[7] * a[14] - a[12] * a[6] * a[11] + a[12] * a[7] * a[10];
    inv[8] = a[4] * a[9] * a[15] - a[4] * a[11] * a[13] - a[8] * a[5] * a[15] +
             a[8] * a[7] * a[13] + a[12] * a[5] * a[11] - a[12] * a[7] * a[9];
    inv[12] = -a[4] * a[9] * a[14] + a[4] * a[10] * a[13] + a[8] * a[5] * a[14] -
              a[8] * a[6] * a[13] - a[12] * a[5] * a[10] + a[12] * a[6] * a[9];
    inv[1] = -a[1] * a[10] * a[15] + a[1] * a[11] * a[14] + a[9] * a[2] * a[15] -
             a[9] * a[3] * a[14] - a[13] * a[2] * a[11] + a[13] * a[3] * a[10];
    inv[5] = a[0] * a[10] * a[15] - a[0] * a[11] * a[14] - a[8] * a[2] * a[15] +
             a[8] * a[3] * a[14] + a[12] * a[2] * a[11] - a[12] * a[3] * a[10];
    inv[9] = -a[0] * a[9] * a[15] + a[0] * a[11] * a[13] + a[8] * a[1] * a[15] -
             a[8] * a[3] * a[13] - a[12] * a[1] * a[11] + a[12] * a[3] * a[9];
    inv[13] = a[0] * a[9] * a[14] - a[0] * a[10] * a[13] - a[8] * a[1] * a[14] +
              a[8] * a[2] * a[13] + a[12] * a[1] * a[10] - a[12] * a[2] * a[9];
    inv[2] = a[1] * a[6] * a[15] - a[1] * a[7] * a[14] - a[5] * a[2] * a[15] +
             a[5] * a[3] * a[14] + a[13] * a[2] * a[7] - a[13] * a[3] * a[6];
    inv[6] = -a[0] * a[6] * a[15] + a[0] * a[7] * a[14] + a[4] * a[2] * a[15] -
             a[4] * a[3] * a[14] - a[12] * a[2] * a[7] + a[12] * a[3] * a[6];
    inv[10] = a[0] * a[5] * a[15] - a[0] * a[7] * a[13] - a[4] * a[1] * a[15] +
              a[4] * a[3] * a[13] + a[12] * a[1] * a[7] - a[12] * a[3] * a[5];
    inv[14] = -a[0] * a[5] * a[14] + a[0] * a[6] * a[13] + a[4] * a[1] * a[14] -
              a[4] * a[2] * a[13] - a[12] * a[1] * a[6] + a[12] * a[2] * a[5];
    inv[3] = -a[1] * a[6] * a[11] + a[1] * a[7] * a[10] + a[5] * a[2] * a[11] -
             a[5] * a[3] * a[10] - a[9] * a[2] * a[7] + a[9] * a[3] * a[6];
    inv[7] = a[0] * a[6] * a[11] - a[0] * a[7] * a[10] - a[4] * a[2] * a[11] +
             a[4] * a[3] * a[10] + a[8] * a[2] * a[7] - a[8] * a[3] * a[6];
    inv[11] = -a[0] * a[5] * a[11] + a[0] * a[7] * a[9] + a[4] * a[1] * a[11] -
              a[4] * a[3] * a[9] - a[8] * a[1] * a[7] + a[8] * a[3] * a[5];
    inv[15] = a[0] * a[5] * a[10] - a[0] * a[6] * a[9] - a[4] * a[1] * a[10] +
              a[4] * a[2] * a[9] + a[8] * a[1] * a[6] - a[8] * a[2] * a[5];
    double det = a[0] * inv[0] + a[1] * inv[4] + a[2] * inv[8] + a[3] * inv[12];
    /* Singular (or numerically so) relative to the matrix's scale. Hadamard's inequality bounds
     * |det| by the product of the row norms and by the product of the column norms; the smaller
     * one is the right scale: a view matrix with a large translation (camera ~1e5 from the
     * origin) has det 1 and huge rows but unit columns 0..2, and must stay invertible. */
    double prod_rows = 1, prod_cols = 1;
    for (int i = 0; i < 4; i++) {
        double rn = 0, cn = 0;
        for (int j = 0; j < 4; j++) {
            rn += a[j * 4 + i] * a[j * 4 + i];
            cn += a[i * 4 + j] * a[i * 4 + j];
        }
        prod_rows *= sqrt(rn);
        prod_cols *= sqrt(cn);
    }
    double scale = prod_rows < prod_cols ? prod_rows : prod_cols;
    if (!isfinite(det) || fabs(det) <= 1e-12 * scale) return false;
    double id = 1.0 / det;
    float r[16];
    for (int i = 0; i < 16; i++) {
        double v = inv[i] * id;
        if (!isfinite(v) || fabs(v) > FLT_MAX) return false;
        r[i] = (float)v;
    }
    memcpy(out, r, sizeof r);
    return true;
}
