// A cell reaching behind a perspective eye (or too close to it to project), vertex stage: a
// rectangle over the screen where its part in front of the eye may be, from gl_VertexID (no
// attributes). Compiled after `#version 330 core`.
uniform vec4 u_rect;  // x0, y0, x1, y1 in normalized device coordinates
void main() {
    gl_Position = vec4((gl_VertexID & 1) != 0 ? u_rect.z : u_rect.x,
                       (gl_VertexID & 2) != 0 ? u_rect.w : u_rect.y, -1.0, 1.0);
}
