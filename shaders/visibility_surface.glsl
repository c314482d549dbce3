// visibility_surface.glsl - rebuilds the surface seen at a pixel from its visibility id (the
// (draw << PG_VIS_TRI_BITS) | triangle that visibility.frag wrote), for compute passes
// (deferred_lighting with packing "visibility", visibility_resolve), from the scene's streams that
// visibility_streams.glsl declares (set PG_VIS_SET, from binding PG_VIS_BINDING on).
// Include after common.glsl (FRAME_UNIFORMS_BLOCK), depth_reconstruct.glsl and surface.glsl
// (compiled with PG_SURFACE_GRADS).
//
// The attributes are interpolated with the barycentrics of the point where the ray through the
// pixel centre meets the triangle's plane: perspective-correct by construction, the same point
// the rasterizer interpolates at. Texture coordinates get analytic screen-space derivatives from
// the rays through the pixels of the pixel's 2x2 quad, intersected with the same plane: the
// differences a rasterizer's fine derivatives take (surface.glsl samples with them).
// gl_FrontFacing becomes the side of the triangle the ray arrives from, with glTF's
// counter-clockwise winding as front (clockwise for a draw the frame's pose mirrors), as the
// rasterizer decides it.
#include "visibility_streams.glsl"

// Camera-relative origin and direction of the ray through pixel position `frag` (pixels).
void pg_vis_ray(vec2 frag, vec2 size, out vec3 o, out vec3 dir)
{
    vec2 uv = frag / size;
    if (PG_ORTHO) {
        o = PG_VIEW_TO_REL(pg_ortho_view_pos_from_view_depth(uv, 0.0, frame.proj));
        dir = PG_VIEW_TO_REL(vec3(0.0, 0.0, -1.0));
    } else {
        o = vec3(0.0);
        dir = PG_VIEW_TO_REL(pg_view_pos_from_view_depth(uv, 1.0, frame.proj));
    }
}

// Barycentrics (of p0, p1, p2) of the point where the ray meets the plane of the triangle
// p0, p0 + e1, p0 + e2 (Moller-Trumbore without the inside test); a ray parallel to the plane
// gets the centroid.
vec3 pg_vis_bary(vec3 o, vec3 dir, vec3 p0, vec3 e1, vec3 e2)
{
    vec3 pv = cross(dir, e2);
    float det = dot(e1, pv);
    if (!(abs(det) > 0.0) || isinf(det)) return vec3(1.0 / 3.0);
    float inv = 1.0 / det;
    vec3 tv = o - p0;
    float u = dot(tv, pv) * inv;
    float v = dot(dir, cross(tv, e1)) * inv;
    vec3 b = vec3(1.0 - u - v, u, v);
    return any(isnan(b)) || any(isinf(b)) ? vec3(1.0 / 3.0) : b;
}

// The surface inputs, material index and camera-relative position at pixel centre `frag` of
// the triangle `id` names.
void pg_vis_fetch(uint id, vec2 frag, vec2 size, out SurfaceInput si, out uint material, out vec3 P)
{
    uint draw_i = id >> uint(PG_VIS_TRI_BITS);
    uint tri = id & ((1u << uint(PG_VIS_TRI_BITS)) - 1u);
    uvec4 d = vis_draws[draw_i];
    material = d.z;
    uint base = d.x + 3u * tri;
    uint v0 = vis_indices[base] + d.y, v1 = vis_indices[base + 1u] + d.y, v2 = vis_indices[base + 2u] + d.y;
    // camera-relative corners, rounded as scene.vert rounds v_rel
    vec3 cam = frame.camera_pos.xyz;
    vec3 p0 = pg_vis_vec3(v0, 0u) - cam, p1 = pg_vis_vec3(v1, 0u) - cam, p2 = pg_vis_vec3(v2, 0u) - cam;
    vec3 e1 = p1 - p0, e2 = p2 - p0;
    vec3 o, dir, on, dn;
    pg_vis_ray(frag, size, o, dir);
    vec3 b = pg_vis_bary(o, dir, p0, e1, e2);
    // d(barycentrics)/dx and /dy over one pixel, as a rasterizer's fine derivatives within the
    // pixel's 2x2 quad: across the quad's pair in the pixel's row (x) and in its column (y), all
    // on this triangle's plane (helper invocations evaluate the same plane). The pixel is one of
    // each pair, so one more ray per axis: to its partner.
    vec2 q = floor(frag * 0.5) * 2.0 + 0.5; // the quad's top-left pixel centre
    vec2 s = vec2(frag.x == q.x ? 1.0 : -1.0, frag.y == q.y ? 1.0 : -1.0);
    pg_vis_ray(frag + vec2(s.x, 0.0), size, on, dn);
    vec3 bx = (pg_vis_bary(on, dn, p0, e1, e2) - b) * s.x;
    pg_vis_ray(frag + vec2(0.0, s.y), size, on, dn);
    vec3 by = (pg_vis_bary(on, dn, p0, e1, e2) - b) * s.y;
    // the pixel centre is inside the triangle up to rounding: keep the point on it
    b = clamp(b, 0.0, 1.0);
    b /= max(b.x + b.y + b.z, 1e-30);
    P = b.x * p0 + b.y * p1 + b.z * p2;
    si.normal = b.x * pg_vis_vec3(v0, 3u) + b.y * pg_vis_vec3(v1, 3u) + b.z * pg_vis_vec3(v2, 3u);
    vec2 t0 = pg_vis_vec2(v0, 6u), t1 = pg_vis_vec2(v1, 6u), t2 = pg_vis_vec2(v2, 6u);
    si.uv0 = b.x * t0 + b.y * t1 + b.z * t2;
    si.duv0 = vec4(bx.x * t0 + bx.y * t1 + bx.z * t2, by.x * t0 + by.y * t1 + by.z * t2);
    si.tangent = b.x * pg_vis_vec4(v0, 8u) + b.y * pg_vis_vec4(v1, 8u) + b.z * pg_vis_vec4(v2, 8u);
    si.uv1 = vec2(0.0);
    si.duv1 = vec4(0.0);
#ifdef PG_UV1
    vec2 s0 = vis_uv1[v0], s1 = vis_uv1[v1], s2 = vis_uv1[v2];
    si.uv1 = b.x * s0 + b.y * s1 + b.z * s2;
    si.duv1 = vec4(bx.x * s0 + bx.y * s1 + bx.z * s2, by.x * s0 + by.y * s1 + by.z * s2);
#endif
    si.color = vec4(1.0);
#ifdef PG_VERTEX_COLORS
    si.color = b.x * vis_colors[v0] + b.y * vis_colors[v1] + b.z * vis_colors[v2];
#endif
    // counter-clockwise as seen along the ray = its normal faces against the ray; clockwise where
    // the frame's pose mirrors the draw against its indices' winding (visibility_common.h bit 2)
    si.front_facing = (dot(cross(e1, e2), dir) < 0.0) != ((d.w & 4u) != 0u);
}
