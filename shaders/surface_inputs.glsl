// surface_inputs.glsl - the fragment inputs scene.vert writes, for every fragment shader that
// evaluates a material (forward.frag, gbuffer.frag, ...). Include before surface.glsl.
layout(location = 0) in vec3 v_rel;     // camera-relative position (world - camera)
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec2 v_uv;
layout(location = 3) in vec4 v_tangent;
#ifdef PG_VERTEX_COLORS
layout(location = 4) in vec4 v_color;
#endif
#ifdef PG_UV1
layout(location = 5) in vec2 v_uv1;
#endif

SurfaceInput pg_surface_input()
{
    SurfaceInput si;
    si.normal = v_normal;
    si.uv0 = v_uv;
    si.uv1 = vec2(0.0);
#ifdef PG_UV1
    si.uv1 = v_uv1;
#endif
    si.tangent = v_tangent;
    si.color = vec4(1.0);
#ifdef PG_VERTEX_COLORS
    si.color = v_color;
#endif
    si.front_facing = gl_FrontFacing;
    // derivatives here, in the shader's uniform control flow (see surface.glsl)
    si.duv0 = vec4(dFdx(v_uv), dFdy(v_uv));
    si.duv1 = vec4(0.0);
#ifdef PG_UV1
    si.duv1 = vec4(dFdx(v_uv1), dFdy(v_uv1));
#endif
    return si;
}
