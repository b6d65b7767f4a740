// Opaque surfaces, fragment stage: Lambert-shaded colour, the ray parameter of the surface (for
// the volume's cut) and its depth. Compiled after `#version 330 core`.
in vec3 v_world;
flat in vec3 v_normal;
flat in vec3 v_color;
uniform vec3 u_eye;
uniform vec3 u_forward;
uniform int u_ortho;
uniform float u_depth_scale;
layout(location = 0) out vec4 o_color;
layout(location = 1) out float o_t;
void main() {
    vec3 d = v_world - u_eye;
    float t = u_ortho != 0 ? dot(d, u_forward) : length(d);
    vec3 dir = u_ortho != 0 ? u_forward : normalize(d);
    float lambert = abs(dot(v_normal, dir));
    o_color = vec4(v_color * (0.2 + 0.8 * lambert), 1.0);
    o_t = t;
    gl_FragDepth = clamp(t * u_depth_scale, 0.0, 1.0);
}
