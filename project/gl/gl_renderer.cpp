// Projected tetrahedra with OpenGL 3.3 core: the GL half of a frame (buffers, textures,
// framebuffers, draws); the CPU half is detail/cell_stream.cpp, the GLSL is in shaders/.
#include <core/stopwatch.h>
#include <project/gl/detail/cell_stream.h>
#include <project/gl/detail/gl_program.h>
#include <project/gl/gl_renderer.h>

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>

namespace tr::gl {
namespace {

using detail::CellStream;
using detail::ExactCell;
using detail::kFloatsPerVertex;
using detail::kIndicesPerCell;
using detail::kVerticesPerCell;

constexpr int kTfSize = 4096;          // texels of the 1D colour + extinction table
constexpr float kNoSurface = 3.0e38f;  // ray parameter where no opaque surface is

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
    GLuint volume_program = 0, opaque_program = 0, exact_program = 0, image_program = 0;
    GLuint exact_vao = 0;  // no attributes: the exact and image quads come from gl_VertexID
    GLuint volume_vao = 0, volume_vbo = 0, volume_ibo = 0;
    std::size_t ibo_cells = 0;  // cells the index buffer covers
    GLuint opaque_vao = 0, opaque_vbo = 0;
    GLsizei opaque_vertices = 0;
    Bounds3 opaque_bounds;
    GLuint tf_tex = 0, exp_tex = 0, pre_tex = 0;
    GLuint color_tex = 0, t_tex = 0, depth_tex = 0;
    GLuint image_tex = 0;  // show_image's picture
    int image_width = 0, image_height = 0;
    GLuint opaque_fbo = 0, volume_fbo = 0;
    int width = 0, height = 0;
    const TetMesh* mesh = nullptr;
    std::vector<float> scalar;
    CellStream cells;  // the last frame's vertex stream and exact cells
    int mode = 0;
    SegmentShaderTables tables;
    std::unique_ptr<TransferFunction> tf;
    std::unique_ptr<SegmentShader> shader;

    void resize(int w, int h);
    // The depth scale: 1 / the farthest ray parameter anything (mesh, opaque surfaces) reaches.
    float depth_scale(const CameraFrame& camera) const;
    // The index buffer grown to cover n cell slots.
    void cover_cells(std::size_t n);
    // Background and opaque surfaces into the opaque framebuffer: colour, ray parameter, depth.
    void draw_opaque(const CameraFrame& camera, const Vec3& background, float depth_scale);
    // The n cells of the last classification, in order, over the opaque layer.
    void draw_volume(const CameraFrame& camera, float depth_scale, std::size_t n);
};

namespace {

void set_uniform3(GLuint program, const char* name, const Vec3& v) {
    glUniform3f(glGetUniformLocation(program, name), static_cast<float>(v.x),
                static_cast<float>(v.y), static_cast<float>(v.z));
}

}  // namespace

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
    using namespace detail::glsl;
    TR_TRY(s.volume_program, detail::link_program({kVolumeVs}, {kShade, kVolumeFs}, "volume"));
    TR_TRY(s.opaque_program, detail::link_program({kOpaqueVs}, {kOpaqueFs}, "opaque"));
    TR_TRY(s.exact_program, detail::link_program({kExactVs}, {kShade, kExactFs}, "exact"));
    TR_TRY(s.image_program, detail::link_program({kImageVs}, {kImageFs}, "image"));
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
    glGenTextures(1, &s.image_tex);
    glUseProgram(s.image_program);
    glUniform1i(glGetUniformLocation(s.image_program, "u_image"), 0);
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
    glDeleteProgram(s.image_program);
    const GLuint arrays[3] = {s.volume_vao, s.opaque_vao, s.exact_vao};
    glDeleteVertexArrays(3, arrays);
    const GLuint buffers[3] = {s.volume_vbo, s.volume_ibo, s.opaque_vbo};
    glDeleteBuffers(3, buffers);
    const GLuint textures[7] = {s.tf_tex, s.exp_tex,   s.pre_tex,  s.color_tex,
                                s.t_tex,  s.depth_tex, s.image_tex};
    glDeleteTextures(7, textures);
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

float GlTetRenderer::State::depth_scale(const CameraFrame& camera) const {
    Bounds3 bounds = mesh ? mesh->bounds() : Bounds3{};
    if (opaque_vertices > 0) {
        bounds.extend(opaque_bounds.lo);
        bounds.extend(opaque_bounds.hi);
    }
    const Vec3 centre = 0.5 * (bounds.lo + bounds.hi);
    const double far =
        std::max(glm::length(centre - camera.eye()) + 0.5 * bounds.diagonal(), 1e-30) * 1.01 +
        (camera.orthographic() ? 0.5 * bounds.diagonal() : 0.0);
    return static_cast<float>(1.0 / far);
}

void GlTetRenderer::State::cover_cells(std::size_t n) {
    if (ibo_cells >= n) return;
    // Four triangles (thick, hull[k], hull[k + 1]) per cell slot.
    const std::size_t slots = std::max<std::size_t>(n, 2 * ibo_cells);
    std::vector<std::uint32_t> indices(slots * kIndicesPerCell);
    for (std::size_t c = 0; c < slots; ++c) {
        const auto b = static_cast<std::uint32_t>(c * kVerticesPerCell);
        const std::uint32_t tri[kIndicesPerCell] = {b, b + 1, b + 2, b, b + 2, b + 3,
                                                    b, b + 3, b + 4, b, b + 4, b + 1};
        std::copy(tri, tri + kIndicesPerCell, &indices[c * kIndicesPerCell]);
    }
    glBindVertexArray(volume_vao);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)), indices.data(),
                 GL_STATIC_DRAW);
    glBindVertexArray(0);
    ibo_cells = slots;
}

void GlTetRenderer::State::draw_opaque(const CameraFrame& camera, const Vec3& background,
                                       float scale) {
    const int w = camera.width(), h = camera.height();
    glViewport(0, 0, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, opaque_fbo);
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
    if (opaque_vertices <= 0) return;
    const Vec3 eye = camera.eye();
    const GLuint p = opaque_program;
    glUseProgram(p);
    set_uniform3(p, "u_eye", eye);
    set_uniform3(p, "u_right", camera.right());
    set_uniform3(p, "u_up", camera.up());
    set_uniform3(p, "u_forward", camera.forward());
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
    glUniform1f(glGetUniformLocation(p, "u_depth_scale"), scale);
    glBindVertexArray(opaque_vao);
    glDrawArrays(GL_TRIANGLES, 0, opaque_vertices);
}

void GlTetRenderer::State::draw_volume(const CameraFrame& camera, float scale, std::size_t n) {
    const int w = camera.width(), h = camera.height();
    // The shading uniforms, the same in both programs.
    for (const GLuint p : {volume_program, exact_program}) {
        glUseProgram(p);
        glUniform1i(glGetUniformLocation(p, "u_mode"), mode);
        glUniform1f(glGetUniformLocation(p, "u_s_lo"), static_cast<float>(tables.s_lo));
        glUniform1f(glGetUniformLocation(p, "u_s_hi"), static_cast<float>(tables.s_hi));
        glUniform1f(glGetUniformLocation(p, "u_max_len"), static_cast<float>(tables.max_length));
        glUniform1f(glGetUniformLocation(p, "u_kappa_max"), static_cast<float>(tables.kappa_max));
        glUniform1f(glGetUniformLocation(p, "u_exp_size"), static_cast<float>(tables.exp_size));
        glUniform1f(glGetUniformLocation(p, "u_pre_scalars"),
                    static_cast<float>(tables.pre_scalars));
        glUniform1f(glGetUniformLocation(p, "u_pre_lengths"),
                    static_cast<float>(tables.pre_lengths));
        glUniform1f(glGetUniformLocation(p, "u_tf_size"), static_cast<float>(kTfSize));
    }
    GLint rect_loc = -1, plane_loc = -1, scalar_loc = -1;
    if (!cells.exact_cells.empty()) {
        // Pixel (x, y)'s ray direction, scaled to unit forward part, is linear in x and y.
        const GLuint p = exact_program;
        auto forward_scaled = [&](double x, double y) {
            const Vec3 dir = camera.ray(x, y).direction;
            return dir / glm::dot(dir, camera.forward());
        };
        const Vec3 dir0 = forward_scaled(0, 0);
        set_uniform3(p, "u_dir0", dir0);
        set_uniform3(p, "u_dir_x", (forward_scaled(w, 0) - dir0) / static_cast<double>(w));
        set_uniform3(p, "u_dir_y", (forward_scaled(0, h) - dir0) / static_cast<double>(h));
        glUniform1f(glGetUniformLocation(p, "u_height"), static_cast<float>(h));
        rect_loc = glGetUniformLocation(p, "u_rect");
        plane_loc = glGetUniformLocation(p, "u_plane");
        scalar_loc = glGetUniformLocation(p, "u_scalar");
    }
    const GLuint p = volume_program;
    glUseProgram(p);
    glUniform2f(glGetUniformLocation(p, "u_size"), static_cast<float>(w), static_cast<float>(h));
    glUniform1f(glGetUniformLocation(p, "u_depth_scale"), scale);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_1D, tf_tex);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, exp_tex);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_3D, pre_tex);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, t_tex);
    glBindVertexArray(volume_vao);
    glBindBuffer(GL_ARRAY_BUFFER, volume_vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(cells.vertices.size() * sizeof(float)),
                 cells.vertices.data(), GL_STREAM_DRAW);
    // The projected cells in batches between the exact ones, each exact cell in its place
    // (blending is order-dependent). Exact fragments sit at depth 0: the opaque surfaces cut
    // them in the shader.
    std::size_t next = 0;  // the first projected cell not yet drawn
    auto draw_projected = [&](std::size_t end) {
        if (end <= next) return;
        glUseProgram(volume_program);
        glBindVertexArray(volume_vao);
        glDrawElements(
            GL_TRIANGLES, static_cast<GLsizei>((end - next) * kIndicesPerCell), GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(next * kIndicesPerCell * sizeof(std::uint32_t)));
    };
    for (const ExactCell& cell : cells.exact_cells) {
        draw_projected(cell.index);
        glUseProgram(exact_program);
        glBindVertexArray(exact_vao);
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

GlFrameStats GlTetRenderer::render(const CameraFrame& camera, std::span<const CellId> order,
                                   const Vec3& background) {
    State& s = *state_;
    GlFrameStats stats;
    stats.cells = order.size();
    s.resize(camera.width(), camera.height());
    const float depth_scale = s.depth_scale(camera);

    // CPU: classify every cell of the order into its slot of the vertex stream.
    const auto classify_start = std::chrono::steady_clock::now();
    const std::size_t n = order.size();
    if (s.mesh) {
        detail::classify_cells(*s.mesh, s.scalar, order, camera, s.cells);
    } else {
        s.cells.vertices.assign(n * kVerticesPerCell * kFloatsPerVertex, 0.0f);
        s.cells.exact_flags.assign(n, 0);
        s.cells.exact_cells.clear();
        s.cells.projected = 0;
    }
    stats.cells_exact = s.cells.exact_cells.size();
    stats.cells_drawn = s.cells.projected + s.cells.exact_cells.size();
    stats.classify_ms = ms_since(classify_start);

    const auto raster_start = std::chrono::steady_clock::now();
    s.cover_cells(n);
    s.draw_opaque(camera, background, depth_scale);
    // The volume: depth test on, no depth write, premultiplied over.
    glBindFramebuffer(GL_FRAMEBUFFER, s.volume_fbo);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    if (s.shader && n > 0) s.draw_volume(camera, depth_scale, n);
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

void GlTetRenderer::show_image(const Image& image) {
    State& s = *state_;
    const int w = image.width, h = image.height;
    if (w <= 0 || h <= 0) return;
    s.resize(w, h);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, s.image_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    static_assert(sizeof(Vec3f) == 3 * sizeof(float), "Image pixels are packed RGB floats");
    if (w != s.image_width || h != s.image_height) {
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, w, h, 0, GL_RGB, GL_FLOAT, image.pixels.data());
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        s.image_width = w, s.image_height = h;
    } else {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RGB, GL_FLOAT, image.pixels.data());
    }
    glBindFramebuffer(GL_FRAMEBUFFER, s.volume_fbo);
    glViewport(0, 0, w, h);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(s.image_program);
    glUniform1i(glGetUniformLocation(s.image_program, "u_height"), h);
    glBindVertexArray(s.exact_vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
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
