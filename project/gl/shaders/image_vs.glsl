// A picture made elsewhere (the viewer's particle-based modes), vertex stage: one triangle strip
// over the whole framebuffer from gl_VertexID (no attributes). Compiled after
// `#version 330 core`.
void main() {
    gl_Position = vec4((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0,
                       0.0, 1.0);
}
