// A picture made elsewhere, fragment stage: each pixel its texel, unfiltered (texelFetch), the
// picture's row 0 (uploaded first) at the top of the framebuffer. Compiled after
// `#version 330 core`.
uniform sampler2D u_image;
uniform int u_height;
layout(location = 0) out vec4 o_color;
void main() {
    ivec2 texel = ivec2(int(gl_FragCoord.x), u_height - 1 - int(gl_FragCoord.y));
    o_color = vec4(texelFetch(u_image, texel, 0).rgb, 1.0);
}
