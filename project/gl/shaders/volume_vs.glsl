// Projected tetrahedra, vertex stage: a classified cell's triangles (pixel positions, thickness,
// front and back scalar, front ray parameter) to clip space, attributes screen-linear.
// Compiled after `#version 330 core` (gl_renderer.cpp).
layout(location = 0) in vec2 a_pos;
layout(location = 1) in vec4 a_attr;
uniform vec2 u_size;
uniform float u_depth_scale;
noperspective out float v_u;
noperspective out float v_sf;
noperspective out float v_sb;
noperspective out float v_tf;
void main() {
    vec2 ndc = vec2(2.0 * a_pos.x / u_size.x - 1.0, 1.0 - 2.0 * a_pos.y / u_size.y);
    float z = clamp(a_attr.w * u_depth_scale, 0.0, 1.0) * 2.0 - 1.0;
    gl_Position = vec4(ndc, z, 1.0);
    v_u = a_attr.x;
    v_sf = a_attr.y;
    v_sb = a_attr.z;
    v_tf = a_attr.w;
}
