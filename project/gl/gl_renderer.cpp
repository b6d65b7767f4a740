#include <core/parallel.h>
#include <project/gl/gl_renderer.h>
#include <project/tet_projection.h>

#include <epoxy/gl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

namespace tr::gl {
namespace {

constexpr int kTfSize = 4096;          // texels of the 1D colour + extinction table
constexpr int kFloatsPerVertex = 6;    // x, y (pixels), thickness, s_front, s_back, t_front
constexpr int kVerticesPerCell = 5;    // the thick vertex, then the hull (4th repeated if 3)
constexpr int kIndicesPerCell = 12;    // four triangles around the thick vertex
constexpr float kNoSurface = 3.0e38f;  // ray parameter where no opaque surface is
// A perspective corner projected farther than this many times (width + height) pixels from the
// image centre sends its cell to the exact path: seen from the eye, it lies within about 1-3
// degrees of the eye's plane (90-30 degree views), where single-precision screen positions and
// attributes of the projected triangles stop being trustworthy.
constexpr double kExactGuard = 16.0;

const char* kVolumeVs = R"(#version 330 core
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
)";

// Colour and opacity of one segment (front scalar, back scalar, length): the integrators'
// lookups, shared by the projected and the exact cells' fragment shaders.
const char* kShadeGlsl = R"(
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
)";

const char* kVolumeFsMain = R"(
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
)";

// A cell reaching behind a perspective eye (or too close to it to project): a rectangle over
// the screen where its part in front of the eye may be, each pixel's ray clipped exactly
// against the cell's four face planes (eye-relative), at the eye and at the opaque surface.
const char* kExactVs = R"(#version 330 core
uniform vec4 u_rect;  // x0, y0, x1, y1 in normalized device coordinates
void main() {
    gl_Position = vec4((gl_VertexID & 1) != 0 ? u_rect.z : u_rect.x,
                       (gl_VertexID & 2) != 0 ? u_rect.w : u_rect.y, -1.0, 1.0);
}
)";

const char* kExactFsMain = R"(
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
)";

const char* kOpaqueVs = R"(#version 330 core
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
)";

const char* kOpaqueFs = R"(#version 330 core
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
)";

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

Result<GLuint> compile(GLenum type, const char* source, const char* name) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096] = {0};
        glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
        glDeleteShader(shader);
        return make_error(ErrorCode::kUnsupported,
                          std::string("GL shader '") + name + "' does not compile: " + log);
    }
    return shader;
}

Result<GLuint> link(const char* vs, const char* fs, const char* name) {
    TR_TRY(const GLuint v, compile(GL_VERTEX_SHADER, vs, name));
    auto f = compile(GL_FRAGMENT_SHADER, fs, name);
    if (!f.ok()) {
        glDeleteShader(v);
        return f.error();
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, v);
    glAttachShader(program, *f);
    glLinkProgram(program);
    glDeleteShader(v);
    glDeleteShader(*f);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {0};
        glGetProgramInfoLog(program, sizeof(log), nullptr, log);
        glDeleteProgram(program);
        return make_error(ErrorCode::kUnsupported,
                          std::string("GL program '") + name + "' does not link: " + log);
    }
    return program;
}

// What the exact fragment shader needs of one cell (its place in the order, its rectangle on
// screen, its planes and scalar relative to the eye), in single precision as GL takes it.
struct ExactCell {
    std::size_t index;  // in the order
    float rect[4];      // x0, y0, x1, y1 in normalized device coordinates
    float planes[16];   // per face: unit outward normal, offset - normal . eye
    float scalar[4];    // gradient, scalar at the eye
};

// Whether cell `t` takes the exact path: a corner at or behind a perspective eye (the CPU
// renderer's test), or projected so far outside the image (a corner just in front of the eye)
// that single-precision screen positions and attributes would not hold it.
bool needs_exact(const TetMesh& mesh, CellId t, const CameraFrame& camera) {
    const double guard = kExactGuard * (camera.width() + camera.height());
    for (PointId p : mesh.tet(t)) {
        const Vec3 q = camera.project(mesh.point(p));
        if (q.z <= 0) return true;
        if (std::abs(q.x - 0.5 * camera.width()) > guard) return true;
        if (std::abs(q.y - 0.5 * camera.height()) > guard) return true;
    }
    return false;
}

// The exact cell of order index `index` (tet `t`): its screen rectangle, planes and scalar.
// False when nothing of it in front of the eye reaches the image (or the tet is degenerate).
// The part of the tet in front of the eye projects to the convex hull of its front corners'
// images and of the directions (right, up parts) of the points where it meets the eye's plane:
// a direction with a positive right part makes the rectangle reach the image's right edge, and
// so on; one with neither part (the eye on the tet's boundary or inside it) the whole image.
bool exact_cell(const TetMesh& mesh, std::span<const float> scalar, CellId t, std::size_t index,
                const CameraFrame& camera, ExactCell& out) {
    const Vec3& eye = camera.eye();
    const Tet& tet = mesh.tet(t);
    Vec3 d[4];
    double z[4];
    constexpr double kInf = std::numeric_limits<double>::infinity();
    double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
    bool front = false;
    for (int k = 0; k < 4; ++k) {
        d[k] = mesh.point(tet[k]) - eye;
        z[k] = glm::dot(d[k], camera.forward());
        if (z[k] > 0) {
            const Vec3 q = camera.project(mesh.point(tet[k]));
            x0 = std::min(x0, q.x), x1 = std::max(x1, q.x);
            y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
            front = true;
        }
    }
    if (!front) return false;
    for (int a = 0; a < 4; ++a) {
        if (z[a] > 0) continue;
        for (int b = 0; b < 4; ++b) {
            if (!(z[b] > 0)) continue;
            const Vec3 q = d[a] + (d[b] - d[a]) * (-z[a] / (z[b] - z[a]));
            const double right = glm::dot(q, camera.right()), up = glm::dot(q, camera.up());
            if (right == 0 && up == 0) x0 = y0 = -kInf, x1 = y1 = kInf;
            if (right > 0) x1 = kInf;
            if (right < 0) x0 = -kInf;
            if (up > 0) y0 = -kInf;  // image rows go down
            if (up < 0) y1 = kInf;
        }
    }
    const double w = camera.width(), h = camera.height();
    // Pixels whose centres may be inside, padded by a pixel (the fragment shader decides).
    x0 = std::clamp(std::floor(x0) - 1.0, 0.0, w), x1 = std::clamp(std::ceil(x1) + 1.0, 0.0, w);
    y0 = std::clamp(std::floor(y0) - 1.0, 0.0, h), y1 = std::clamp(std::ceil(y1) + 1.0, 0.0, h);
    if (!(x1 > x0) || !(y1 > y0)) return false;
    const TetPlanes planes = tet_planes(mesh, scalar, t);
    for (int k = 0; k < 4; ++k) {
        const double len = glm::length(planes.normals[k]);
        if (!(len > 0)) return false;
        const Vec3 n = planes.normals[k] / len;
        out.planes[4 * k + 0] = static_cast<float>(n.x);
        out.planes[4 * k + 1] = static_cast<float>(n.y);
        out.planes[4 * k + 2] = static_cast<float>(n.z);
        out.planes[4 * k + 3] =
            static_cast<float>((planes.offsets[k] - glm::dot(planes.normals[k], eye)) / len);
    }
    out.index = index;
    out.rect[0] = static_cast<float>(2 * x0 / w - 1);
    out.rect[1] = static_cast<float>(1 - 2 * y1 / h);
    out.rect[2] = static_cast<float>(2 * x1 / w - 1);
    out.rect[3] = static_cast<float>(1 - 2 * y0 / h);
    out.scalar[0] = static_cast<float>(planes.gradient.x);
    out.scalar[1] = static_cast<float>(planes.gradient.y);
    out.scalar[2] = static_cast<float>(planes.gradient.z);
    out.scalar[3] = static_cast<float>(planes.s0 + glm::dot(planes.gradient, eye - planes.p0));
    return true;
}

}  // namespace

Result<GlContextInfo> check_gl_context() {
    GlContextInfo info;
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    if (!version) return make_error(ErrorCode::kUnsupported, "no current OpenGL context");
    info.version = version;
    info.renderer = renderer ? renderer : "?";
    const int v = epoxy_gl_version();
    info.major = v / 10;
    info.minor = v % 10;
    if (v >= 32) {
        GLint mask = 0;
        glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
        info.core = (mask & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
    }
    if (v < 33 || !info.core) {
        return make_error(ErrorCode::kUnsupported,
                          "needs OpenGL 3.3 core; the context is OpenGL " + info.version + " (" +
                              (info.core ? "core" : "not core") + ", " + info.renderer + ")");
    }
    return info;
}

struct GlTetRenderer::State {
    GLuint volume_program = 0, opaque_program = 0, exact_program = 0;
    GLuint exact_vao = 0;  // no attributes: the exact shader's quad comes from gl_VertexID
    GLuint volume_vao = 0, volume_vbo = 0, volume_ibo = 0;
    std::size_t ibo_cells = 0;  // cells the index buffer covers
    GLuint opaque_vao = 0, opaque_vbo = 0;
    GLsizei opaque_vertices = 0;
    Bounds3 opaque_bounds;
    GLuint tf_tex = 0, exp_tex = 0, pre_tex = 0;
    GLuint color_tex = 0, t_tex = 0, depth_tex = 0;
    GLuint opaque_fbo = 0, volume_fbo = 0;
    int width = 0, height = 0;
    const TetMesh* mesh = nullptr;
    std::vector<float> scalar;
    std::vector<float> staging;
    std::vector<std::uint8_t> exact_flags;  // per index of the order: drawn exactly
    std::vector<ExactCell> exact_cells;
    int mode = 0;
    SegmentShaderTables tables;
    std::unique_ptr<TransferFunction> tf;
    std::unique_ptr<SegmentShader> shader;

    void resize(int w, int h);
};

void GlTetRenderer::State::resize(int w, int h) {
    if (w == width && h == height && color_tex) return;
    width = w, height = h;
    if (!color_tex) {
        glGenTextures(1, &color_tex);
        glGenTextures(1, &t_tex);
        glGenTextures(1, &depth_tex);
        glGenFramebuffers(1, &opaque_fbo);
        glGenFramebuffers(1, &volume_fbo);
    }
    auto setup = [&](GLuint tex, GLint internal, GLenum format, GLenum type) {
        glBindTexture(GL_TEXTURE_2D, tex);
        glTexImage2D(GL_TEXTURE_2D, 0, internal, w, h, 0, format, type, nullptr);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    };
    setup(color_tex, GL_RGBA32F, GL_RGBA, GL_FLOAT);
    setup(t_tex, GL_R32F, GL_RED, GL_FLOAT);
    setup(depth_tex, GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT);
    glBindFramebuffer(GL_FRAMEBUFFER, opaque_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_tex, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, t_tex, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_tex, 0);
    const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, both);
    glBindFramebuffer(GL_FRAMEBUFFER, volume_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_tex, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_tex, 0);
    glDrawBuffer(GL_COLOR_ATTACHMENT0);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Result<std::unique_ptr<GlTetRenderer>> GlTetRenderer::create() {
    std::unique_ptr<GlTetRenderer> r(new GlTetRenderer());
    r->state_ = std::make_unique<State>();
    State& s = *r->state_;
    const std::string volume_fs = std::string("#version 330 core\n") + kShadeGlsl + kVolumeFsMain;
    const std::string exact_fs = std::string("#version 330 core\n") + kShadeGlsl + kExactFsMain;
    TR_TRY(s.volume_program, link(kVolumeVs, volume_fs.c_str(), "volume"));
    TR_TRY(s.opaque_program, link(kOpaqueVs, kOpaqueFs, "opaque"));
    TR_TRY(s.exact_program, link(kExactVs, exact_fs.c_str(), "exact"));
    glGenVertexArrays(1, &s.exact_vao);
    glGenVertexArrays(1, &s.volume_vao);
    glGenBuffers(1, &s.volume_vbo);
    glGenBuffers(1, &s.volume_ibo);
    glBindVertexArray(s.volume_vao);
    glBindBuffer(GL_ARRAY_BUFFER, s.volume_vbo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, s.volume_ibo);
    const GLsizei stride = kFloatsPerVertex * sizeof(float);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(2 * sizeof(float)));
    glGenVertexArrays(1, &s.opaque_vao);
    glGenBuffers(1, &s.opaque_vbo);
    glBindVertexArray(s.opaque_vao);
    glBindBuffer(GL_ARRAY_BUFFER, s.opaque_vbo);
    for (int a = 0; a < 3; ++a) {
        glEnableVertexAttribArray(a);
        glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, 9 * sizeof(float),
                              reinterpret_cast<const void*>(a * 3 * sizeof(float)));
    }
    glBindVertexArray(0);
    glGenTextures(1, &s.tf_tex);
    glGenTextures(1, &s.exp_tex);
    glGenTextures(1, &s.pre_tex);
    // Samplers: 0 transfer function, 1 exp texture, 2 pre-integrated, 3 opaque ray parameter.
    for (const GLuint p : {s.volume_program, s.exact_program}) {
        glUseProgram(p);
        glUniform1i(glGetUniformLocation(p, "u_tf"), 0);
        glUniform1i(glGetUniformLocation(p, "u_exp"), 1);
        glUniform1i(glGetUniformLocation(p, "u_pre"), 2);
        glUniform1i(glGetUniformLocation(p, "u_opaque_t"), 3);
    }
    glUseProgram(0);
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        return make_error(ErrorCode::kUnsupported,
                          "GL error " + std::to_string(e) + " while setting up the renderer");
    }
    return r;
}

GlTetRenderer::~GlTetRenderer() {
    if (!state_) return;
    State& s = *state_;
    glDeleteProgram(s.volume_program);
    glDeleteProgram(s.opaque_program);
    glDeleteProgram(s.exact_program);
    const GLuint arrays[3] = {s.volume_vao, s.opaque_vao, s.exact_vao};
    glDeleteVertexArrays(3, arrays);
    const GLuint buffers[3] = {s.volume_vbo, s.volume_ibo, s.opaque_vbo};
    glDeleteBuffers(3, buffers);
    const GLuint textures[6] = {s.tf_tex, s.exp_tex, s.pre_tex, s.color_tex, s.t_tex, s.depth_tex};
    glDeleteTextures(6, textures);
    const GLuint fbos[2] = {s.opaque_fbo, s.volume_fbo};
    glDeleteFramebuffers(2, fbos);
}

void GlTetRenderer::set_mesh(const TetMesh* mesh, std::span<const float> scalar) {
    state_->mesh = mesh;
    set_scalar(scalar);
}

void GlTetRenderer::set_scalar(std::span<const float> scalar) {
    state_->scalar.assign(scalar.begin(), scalar.end());
}

void GlTetRenderer::set_transfer_function(const TransferFunction& tf, Integrator integrator,
                                          double max_length) {
    State& s = *state_;
    if (integrator == Integrator::kExact) integrator = Integrator::kPreintegrated;
    s.mode = integrator == Integrator::kExpTexture ? 0 : 1;
    s.tf = std::make_unique<TransferFunction>(tf);
    s.shader = std::make_unique<SegmentShader>(*s.tf, integrator, max_length);
    s.tables = s.shader->tables();
    // Colour and extinction over the tables' scalar range.
    std::vector<float> table(kTfSize * 4);
    for (int i = 0; i < kTfSize; ++i) {
        const double sv = s.tables.s_lo + (s.tables.s_hi - s.tables.s_lo) * i / (kTfSize - 1);
        const Vec3 c = tf.color(sv);
        table[i * 4 + 0] = static_cast<float>(c.x);
        table[i * 4 + 1] = static_cast<float>(c.y);
        table[i * 4 + 2] = static_cast<float>(c.z);
        table[i * 4 + 3] = static_cast<float>(tf.extinction(sv));
    }
    glBindTexture(GL_TEXTURE_1D, s.tf_tex);
    glTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, kTfSize, 0, GL_RGBA, GL_FLOAT, table.data());
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_1D, 0);
    if (s.mode == 0) {
        glBindTexture(GL_TEXTURE_2D, s.exp_tex);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, s.tables.exp_size, s.tables.exp_size, 0, GL_RED,
                     GL_FLOAT, s.tables.exp_table.data());
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glBindTexture(GL_TEXTURE_2D, 0);
    } else {
        glBindTexture(GL_TEXTURE_3D, s.pre_tex);
        glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA32F, s.tables.pre_lengths, s.tables.pre_scalars,
                     s.tables.pre_scalars, 0, GL_RGBA, GL_FLOAT, s.tables.preint_table.data());
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
        glBindTexture(GL_TEXTURE_3D, 0);
    }
}

void GlTetRenderer::set_opaque(const std::vector<OpaqueSurface>& surfaces) {
    State& s = *state_;
    std::vector<float> vertices;
    s.opaque_bounds = Bounds3{};
    for (const OpaqueSurface& surface : surfaces) {
        for (const auto& tri : surface.surface->triangles) {
            const Vec3& a = surface.surface->points[tri[0]];
            const Vec3& b = surface.surface->points[tri[1]];
            const Vec3& c = surface.surface->points[tri[2]];
            const Vec3 cross = glm::cross(b - a, c - a);
            const double len = glm::length(cross);
            if (!(len > 0)) continue;
            const Vec3 n = cross / len;
            for (const Vec3* p : {&a, &b, &c}) {
                s.opaque_bounds.extend(*p);
                for (const Vec3& v : {*p, n, surface.color}) {
                    vertices.push_back(static_cast<float>(v.x));
                    vertices.push_back(static_cast<float>(v.y));
                    vertices.push_back(static_cast<float>(v.z));
                }
            }
        }
    }
    glBindBuffer(GL_ARRAY_BUFFER, s.opaque_vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
                 vertices.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    s.opaque_vertices = static_cast<GLsizei>(vertices.size() / 9);
}

GlFrameStats GlTetRenderer::render(const CameraFrame& camera, std::span<const CellId> order,
                                   const Vec3& background) {
    State& s = *state_;
    GlFrameStats stats;
    stats.cells = order.size();
    const int w = camera.width(), h = camera.height();
    s.resize(w, h);

    // Depth: the ray parameter over the farthest distance anything can be.
    Bounds3 bounds = s.mesh ? s.mesh->bounds() : Bounds3{};
    if (s.opaque_vertices > 0) {
        bounds.extend(s.opaque_bounds.lo);
        bounds.extend(s.opaque_bounds.hi);
    }
    const Vec3 centre = 0.5 * (bounds.lo + bounds.hi);
    const double far =
        std::max(glm::length(centre - camera.eye()) + 0.5 * bounds.diagonal(), 1e-30) * 1.01 +
        (camera.orthographic() ? 0.5 * bounds.diagonal() : 0.0);
    const float depth_scale = static_cast<float>(1.0 / far);

    // CPU: classify every cell of the order into its slot of the vertex stream.
    const auto classify_start = std::chrono::steady_clock::now();
    const std::size_t n = order.size();
    s.staging.resize(n * kVerticesPerCell * kFloatsPerVertex);
    s.exact_flags.assign(n, 0);
    s.exact_cells.clear();
    std::atomic<std::size_t> drawn{0};
    if (s.mesh && n > 0) {
        const TetMesh& mesh = *s.mesh;
        const std::span<const float> scalar = s.scalar;
        const bool orthographic = camera.orthographic();
        parallel_for_chunks(0, n, 2048, [&](std::size_t begin, std::size_t end) {
            std::size_t local = 0;
            for (std::size_t i = begin; i < end; ++i) {
                float* out = &s.staging[i * kVerticesPerCell * kFloatsPerVertex];
                const CellId t = order[i];
                // Cells reaching behind the eye (or too close to it to project) are drawn
                // exactly per pixel instead, in their place in the order.
                const bool exact = !orthographic && needs_exact(mesh, t, camera);
                s.exact_flags[i] = exact ? 1 : 0;
                bool ok = !exact;
                StProjection st;
                if (ok) {
                    const TetPlanes planes = tet_planes(mesh, scalar, t);
                    ok = shirley_tuchman_projection(mesh, scalar, t, planes, camera, st);
                }
                if (!ok) {
                    std::memset(out, 0, kVerticesPerCell * kFloatsPerVertex * sizeof(float));
                    continue;
                }
                ++local;
                auto put = [&](int slot, const StVertex& v) {
                    float* o = out + slot * kFloatsPerVertex;
                    o[0] = static_cast<float>(v.x);
                    o[1] = static_cast<float>(v.y);
                    o[2] = static_cast<float>(v.thickness);
                    o[3] = static_cast<float>(v.s_front);
                    o[4] = static_cast<float>(v.s_back);
                    o[5] = static_cast<float>(v.t_front);
                };
                put(0, st.thick);
                for (int k = 0; k < 4; ++k)
                    put(1 + k, st.corners[st.hull[std::min(k, st.num_hull - 1)]]);
            }
            drawn += local;
        });
        for (std::size_t i = 0; i < n; ++i) {
            ExactCell cell;
            if (s.exact_flags[i] && exact_cell(mesh, scalar, order[i], i, camera, cell))
                s.exact_cells.push_back(cell);
        }
    }
    stats.cells_exact = s.exact_cells.size();
    stats.cells_drawn = drawn.load() + s.exact_cells.size();
    stats.classify_ms = ms_since(classify_start);

    const auto raster_start = std::chrono::steady_clock::now();
    if (s.ibo_cells < n) {
        // Four triangles (thick, hull[k], hull[k + 1]) per cell slot.
        const std::size_t cells = std::max<std::size_t>(n, 2 * s.ibo_cells);
        std::vector<std::uint32_t> indices(cells * kIndicesPerCell);
        for (std::size_t c = 0; c < cells; ++c) {
            const auto b = static_cast<std::uint32_t>(c * kVerticesPerCell);
            const std::uint32_t tri[kIndicesPerCell] = {b, b + 1, b + 2, b, b + 2, b + 3,
                                                        b, b + 3, b + 4, b, b + 4, b + 1};
            std::copy(tri, tri + kIndicesPerCell, &indices[c * kIndicesPerCell]);
        }
        glBindVertexArray(s.volume_vao);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                     static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
                     indices.data(), GL_STATIC_DRAW);
        glBindVertexArray(0);
        s.ibo_cells = cells;
    }

    // Background and opaque surfaces: colour, ray parameter, depth.
    glViewport(0, 0, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, s.opaque_fbo);
    const float clear_color[4] = {static_cast<float>(background.x),
                                  static_cast<float>(background.y),
                                  static_cast<float>(background.z), 0.0f};
    const float clear_t[4] = {kNoSurface, 0, 0, 0};
    const float clear_depth = 1.0f;
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glClearBufferfv(GL_COLOR, 0, clear_color);
    glClearBufferfv(GL_COLOR, 1, clear_t);
    glClearBufferfv(GL_DEPTH, 0, &clear_depth);
    const Vec3 eye = camera.eye();
    auto set3 = [](GLuint program, const char* name, const Vec3& v) {
        glUniform3f(glGetUniformLocation(program, name), static_cast<float>(v.x),
                    static_cast<float>(v.y), static_cast<float>(v.z));
    };
    if (s.opaque_vertices > 0) {
        const GLuint p = s.opaque_program;
        glUseProgram(p);
        set3(p, "u_eye", eye);
        set3(p, "u_right", camera.right());
        set3(p, "u_up", camera.up());
        set3(p, "u_forward", camera.forward());
        // Half the view's extent at unit depth (perspective) or in world units (orthographic),
        // measured from the camera itself so that it matches CameraFrame::project.
        const Vec3 corner = camera.ray(w, 0).direction;
        double half_w = 0, half_h = 0;
        if (camera.orthographic()) {
            const Ray r = camera.ray(w, 0);
            half_w = glm::dot(r.origin - eye, camera.right());
            half_h = glm::dot(r.origin - eye, camera.up());
        } else {
            half_w = glm::dot(corner, camera.right()) / glm::dot(corner, camera.forward());
            half_h = glm::dot(corner, camera.up()) / glm::dot(corner, camera.forward());
        }
        glUniform1f(glGetUniformLocation(p, "u_half_w"), static_cast<float>(half_w));
        glUniform1f(glGetUniformLocation(p, "u_half_h"), static_cast<float>(half_h));
        glUniform1i(glGetUniformLocation(p, "u_ortho"), camera.orthographic() ? 1 : 0);
        glUniform1f(glGetUniformLocation(p, "u_depth_scale"), depth_scale);
        glBindVertexArray(s.opaque_vao);
        glDrawArrays(GL_TRIANGLES, 0, s.opaque_vertices);
    }

    // The volume: depth test on, no depth write, premultiplied over.
    glBindFramebuffer(GL_FRAMEBUFFER, s.volume_fbo);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    if (s.shader && n > 0) {
        // The shading uniforms, the same in both programs.
        for (const GLuint p : {s.volume_program, s.exact_program}) {
            glUseProgram(p);
            glUniform1i(glGetUniformLocation(p, "u_mode"), s.mode);
            glUniform1f(glGetUniformLocation(p, "u_s_lo"), static_cast<float>(s.tables.s_lo));
            glUniform1f(glGetUniformLocation(p, "u_s_hi"), static_cast<float>(s.tables.s_hi));
            glUniform1f(glGetUniformLocation(p, "u_max_len"),
                        static_cast<float>(s.tables.max_length));
            glUniform1f(glGetUniformLocation(p, "u_kappa_max"),
                        static_cast<float>(s.tables.kappa_max));
            glUniform1f(glGetUniformLocation(p, "u_exp_size"),
                        static_cast<float>(s.tables.exp_size));
            glUniform1f(glGetUniformLocation(p, "u_pre_scalars"),
                        static_cast<float>(s.tables.pre_scalars));
            glUniform1f(glGetUniformLocation(p, "u_pre_lengths"),
                        static_cast<float>(s.tables.pre_lengths));
            glUniform1f(glGetUniformLocation(p, "u_tf_size"), static_cast<float>(kTfSize));
        }
        GLint rect_loc = -1, plane_loc = -1, scalar_loc = -1;
        if (!s.exact_cells.empty()) {
            // Pixel (x, y)'s ray direction, scaled to unit forward part, is linear in x and y.
            const GLuint p = s.exact_program;
            auto forward_scaled = [&](double x, double y) {
                const Vec3 dir = camera.ray(x, y).direction;
                return dir / glm::dot(dir, camera.forward());
            };
            const Vec3 dir0 = forward_scaled(0, 0);
            set3(p, "u_dir0", dir0);
            set3(p, "u_dir_x", (forward_scaled(w, 0) - dir0) / static_cast<double>(w));
            set3(p, "u_dir_y", (forward_scaled(0, h) - dir0) / static_cast<double>(h));
            glUniform1f(glGetUniformLocation(p, "u_height"), static_cast<float>(h));
            rect_loc = glGetUniformLocation(p, "u_rect");
            plane_loc = glGetUniformLocation(p, "u_plane");
            scalar_loc = glGetUniformLocation(p, "u_scalar");
        }
        const GLuint p = s.volume_program;
        glUseProgram(p);
        glUniform2f(glGetUniformLocation(p, "u_size"), static_cast<float>(w),
                    static_cast<float>(h));
        glUniform1f(glGetUniformLocation(p, "u_depth_scale"), depth_scale);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_1D, s.tf_tex);
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D, s.exp_tex);
        glActiveTexture(GL_TEXTURE2);
        glBindTexture(GL_TEXTURE_3D, s.pre_tex);
        glActiveTexture(GL_TEXTURE3);
        glBindTexture(GL_TEXTURE_2D, s.t_tex);
        glBindVertexArray(s.volume_vao);
        glBindBuffer(GL_ARRAY_BUFFER, s.volume_vbo);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(s.staging.size() * sizeof(float)),
                     s.staging.data(), GL_STREAM_DRAW);
        // The projected cells in batches between the exact ones, each exact cell in its place
        // (blending is order-dependent). Exact fragments sit at depth 0: the opaque surfaces
        // cut them in the shader.
        std::size_t next = 0;  // the first projected cell not yet drawn
        auto draw_projected = [&](std::size_t end) {
            if (end <= next) return;
            glUseProgram(s.volume_program);
            glBindVertexArray(s.volume_vao);
            glDrawElements(
                GL_TRIANGLES, static_cast<GLsizei>((end - next) * kIndicesPerCell), GL_UNSIGNED_INT,
                reinterpret_cast<const void*>(next * kIndicesPerCell * sizeof(std::uint32_t)));
        };
        for (const ExactCell& cell : s.exact_cells) {
            draw_projected(cell.index);
            glUseProgram(s.exact_program);
            glBindVertexArray(s.exact_vao);
            glUniform4fv(rect_loc, 1, cell.rect);
            glUniform4fv(plane_loc, 4, cell.planes);
            glUniform4fv(scalar_loc, 1, cell.scalar);
            glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
            next = cell.index + 1;
        }
        draw_projected(n);
        glBindTexture(GL_TEXTURE_2D, 0);
        glActiveTexture(GL_TEXTURE0);
    }
    glBindVertexArray(0);
    glUseProgram(0);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glFinish();
    stats.raster_ms = ms_since(raster_start);
    return stats;
}

Image GlTetRenderer::read_image() const {
    const State& s = *state_;
    Image image(s.width, s.height);
    if (s.width == 0) return image;
    std::vector<float> rgb(static_cast<std::size_t>(s.width) * s.height * 3);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s.volume_fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, s.width, s.height, GL_RGB, GL_FLOAT, rgb.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    for (int y = 0; y < s.height; ++y) {
        const float* row = &rgb[static_cast<std::size_t>(s.height - 1 - y) * s.width * 3];
        for (int x = 0; x < s.width; ++x)
            image.at(x, y) = Vec3f(row[3 * x], row[3 * x + 1], row[3 * x + 2]);
    }
    return image;
}

void GlTetRenderer::bind_framebuffer() const {
    glBindFramebuffer(GL_FRAMEBUFFER, state_->volume_fbo);
    glViewport(0, 0, state_->width, state_->height);
}

void GlTetRenderer::blit_to_default(int width, int height) const {
    const State& s = *state_;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s.volume_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, s.width, s.height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace tr::gl
