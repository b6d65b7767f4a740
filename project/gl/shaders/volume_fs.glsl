// Projected tetrahedra, fragment stage: the segment cut at the opaque surface's ray parameter,
// then shaded by shade(). Compiled after `#version 330 core` and shade.glsl.
noperspective in float v_u;
noperspective in float v_sf;
noperspective in float v_sb;
noperspective in float v_tf;
void main() {
    float u = v_u, sf = v_sf, sb = v_sb;
    float room = texelFetch(u_opaque_t, ivec2(gl_FragCoord.xy), 0).r - v_tf;
    if (!(room > 0.0)) discard;
    if (room < u) {
        sb = sf + (sb - sf) * room / u;
        u = room;
    }
    if (!(u > 0.0)) discard;
    if (u_mode == 0 && !(u_kappa_max > 0.0)) discard;
    o_color = shade(sf, sb, u);
}
