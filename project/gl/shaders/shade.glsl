// Colour and opacity of one segment (front scalar, back scalar, length): the integrators'
// lookups, shared by the projected and the exact cells' fragment stages (compiled in front of
// volume_fs.glsl and exact_fs.glsl, after `#version 330 core`).
uniform int u_mode;  // 0: exp texture, 1: pre-integrated
uniform sampler1D u_tf;  // rgb: colour, a: extinction, over [u_s_lo, u_s_hi]
uniform sampler2D u_exp;
uniform sampler3D u_pre;
uniform sampler2D u_opaque_t;
uniform float u_s_lo;
uniform float u_s_hi;
uniform float u_max_len;
uniform float u_kappa_max;
uniform float u_exp_size;
uniform float u_pre_scalars;
uniform float u_pre_lengths;
uniform float u_tf_size;
out vec4 o_color;
// Texture coordinate of grid index x (texel centres on the grid) in a table of n texels.
float grid(float x, float n) { return (clamp(x, 0.0, n - 1.0) + 0.5) / n; }
vec4 tf(float s) {
    return texture(u_tf, grid((s - u_s_lo) / (u_s_hi - u_s_lo) * (u_tf_size - 1.0), u_tf_size));
}
// Premultiplied colour and opacity of a segment of length u > 0.
vec4 shade(float sf, float sb, float u) {
    if (u_mode == 0) {
        if (!(u_kappa_max > 0.0)) return vec4(0.0);
        float v = 0.5 * (tf(sf).a + tf(sb).a);
        float x = u / u_max_len * (u_exp_size - 1.0);
        float y = v / u_kappa_max * (u_exp_size - 1.0);
        float alpha = texture(u_exp, vec2(grid(x, u_exp_size), grid(y, u_exp_size))).r;
        return vec4(tf(0.5 * (sf + sb)).rgb * alpha, alpha);
    }
    float scale = (u_pre_scalars - 1.0) / (u_s_hi - u_s_lo);
    float x = (sf - u_s_lo) * scale;
    float y = (sb - u_s_lo) * scale;
    float z = u / u_max_len * (u_pre_lengths - 1.0);
    return texture(u_pre, vec3(grid(z, u_pre_lengths), grid(y, u_pre_scalars),
                               grid(x, u_pre_scalars)));
}
