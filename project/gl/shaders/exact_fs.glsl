// A cell drawn exactly per pixel, fragment stage: each pixel's ray clipped against the cell's
// four face planes (eye-relative), at the eye and at the opaque surface, the scalar linear along
// it, shaded by shade(). Compiled after `#version 330 core` and shade.glsl.
uniform vec4 u_plane[4];  // unit outward normal n, and offset - n . eye: n . x = w outside < 0
uniform vec4 u_scalar;    // the scalar's gradient, and the scalar at the eye
uniform vec3 u_dir0;      // the ray direction at image point (0, 0), over its forward part
uniform vec3 u_dir_x;     // its change per pixel along x and along y (row 0 at the top)
uniform vec3 u_dir_y;
uniform float u_height;
void main() {
    vec3 dir = normalize(u_dir0 + gl_FragCoord.x * u_dir_x +
                         (u_height - gl_FragCoord.y) * u_dir_y);
    float t_in = 0.0;
    float t_out = texelFetch(u_opaque_t, ivec2(gl_FragCoord.xy), 0).r;
    for (int k = 0; k < 4; ++k) {
        float denom = dot(u_plane[k].xyz, dir);
        float num = u_plane[k].w;
        if (denom < 0.0) {
            t_in = max(t_in, num / denom);
        } else if (denom > 0.0) {
            t_out = min(t_out, num / denom);
        } else if (num < 0.0) {
            discard;
        }
    }
    if (!(t_out > t_in)) discard;
    if (u_mode == 0 && !(u_kappa_max > 0.0)) discard;
    float slope = dot(u_scalar.xyz, dir);
    o_color = shade(u_scalar.w + t_in * slope, u_scalar.w + t_out * slope, t_out - t_in);
}
