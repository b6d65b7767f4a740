// Opaque surfaces, vertex stage: world positions to clip space (perspective or orthographic),
// flat normal and colour. Compiled after `#version 330 core`.
layout(location = 0) in vec3 a_world;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_color;
uniform vec3 u_eye;
uniform vec3 u_right;
uniform vec3 u_up;
uniform vec3 u_forward;
uniform float u_half_w;
uniform float u_half_h;
uniform int u_ortho;
out vec3 v_world;
flat out vec3 v_normal;
flat out vec3 v_color;
void main() {
    vec3 d = a_world - u_eye;
    float w = u_ortho != 0 ? 1.0 : dot(d, u_forward);
    gl_Position = vec4(dot(d, u_right) / u_half_w, dot(d, u_up) / u_half_h, 0.0, w);
    v_world = a_world;
    v_normal = a_normal;
    v_color = a_color;
}
