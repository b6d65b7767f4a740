#pragma once
// Projected tetrahedra with OpenGL 3.3 core: the texture-mapping paper's section 3.2 on the
// GPU. Each frame, the cells of a back-to-front order are classified on the CPU (Shirley and
// Tuchman, project/tet_projection.h, the same code as the CPU renderer's exp-texture path,
// parallel over cells), streamed to a vertex buffer as 3 or 4 triangles around the thick
// vertex, and rasterized by GL with thickness, front and back scalar and front ray parameter
// interpolated `noperspective` (screen-linear, as on the CPU). Per pixel:
// - exp texture: opacity 1 - exp(-u v) from a real 2D texture (u the thickness, v the mean
//   extinction of the two ends), colour from the transfer function at the mean scalar;
// - pre-integrated: a 3D texture over (front scalar, back scalar, length) made from the
//   SegmentShader's table.
// Opaque surfaces are drawn first into the z-buffer (and the ray parameter of the nearest one
// per pixel into a float texture, so each segment is cut where the surface is); the volume is
// drawn with the depth test on, no depth write, premultiplied blending (ONE,
// ONE_MINUS_SRC_ALPHA), into an offscreen float framebuffer.
//
// Cells reaching behind a perspective eye (a corner at or behind the eye's plane, the test that
// sends a cell to the CPU renderer's exact path) or too close to it to project (a corner more
// than 16 (width + height) pixels from the image) are drawn exactly per pixel instead, in their
// place in the order (the projected cells are drawn in batches between them): a rectangle
// covering the screen where the cell's part in front of the eye may be (all of it when the
// cell holds the eye), and per fragment the pixel centre's ray (CameraFrame::pixel_ray)
// clipped against the cell's four face planes, at the eye and at the opaque surface, the
// scalar linear along it, shaded with the same textures. Cost: a draw call and a fragment per
// pixel of the rectangle for each such cell (the cells around the eye; none orthographic).
//
// Every call needs a current OpenGL >= 3.3 core context (GLFW or any other); GL headers stay
// in the .cpp. Not thread-safe: use from the context's thread.

#include <core/camera.h>
#include <core/image.h>
#include <core/result.h>
#include <mesh/tet_mesh.h>
#include <project/opaque_geometry.h>
#include <project/segment_shader.h>
#include <project/transfer_function.h>

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace tr::gl {

// What the current context is.
struct GlContextInfo {
    std::string version;   // GL_VERSION
    std::string renderer;  // GL_RENDERER
    int major = 0, minor = 0;
    bool core = false;  // a core profile (or a version >= 3.2 without compatibility bit)
};

// Reads the current context's version. Error kUnsupported when it is older than 3.3 or not a
// core profile, saying what it is.
Result<GlContextInfo> check_gl_context();

struct GlFrameStats {
    std::size_t cells = 0;        // cells in the order
    std::size_t cells_drawn = 0;  // classified with area on screen, or drawn exactly
    std::size_t cells_exact = 0;  // of those, drawn exactly per pixel (around the eye)
    double classify_ms = 0;       // CPU: projection, classification, vertex streaming
    double raster_ms = 0;         // GL: upload and draw, until finished (glFinish)
};

class GlTetRenderer {
  public:
    // Compiles the shaders and makes the buffers. Errors: shader compile or link failures
    // (with the driver's log).
    static Result<std::unique_ptr<GlTetRenderer>> create();
    ~GlTetRenderer();
    GlTetRenderer(const GlTetRenderer&) = delete;
    GlTetRenderer& operator=(const GlTetRenderer&) = delete;

    // The mesh (kept by pointer: it must outlive the renderer or the next set_mesh) and one
    // scalar per mesh point (copied). Virtual cells are never drawn.
    void set_mesh(const TetMesh* mesh, std::span<const float> scalar);
    void set_scalar(std::span<const float> scalar);

    // Builds the textures of `tf` for `integrator` (kExpTexture or kPreintegrated; kExact is
    // drawn as kPreintegrated). `max_length`: the longest segment (longest_edge(mesh)).
    // Cost: a SegmentShader's construction (pre-integrated: 0.1-0.3 s).
    void set_transfer_function(const TransferFunction& tf, Integrator integrator,
                               double max_length);

    // Triangle surfaces drawn opaque before the volume, shaded as render_opaque shades them
    // (copied to GL buffers).
    void set_opaque(const std::vector<OpaqueSurface>& surfaces);

    // Draws one frame into the offscreen framebuffer (resized to the camera's image size):
    // background, opaque surfaces, then the cells of `order` (back to front, real cells).
    GlFrameStats render(const CameraFrame& camera, std::span<const CellId> order,
                        const Vec3& background);

    // Makes `image` (row 0 at the top) the frame, as a textured quad over the offscreen
    // framebuffer (resized to the image's size), each pixel its own texel: what read_image,
    // blit_to_default and overlays then see. For pictures made elsewhere (the viewer's
    // particle-based modes, on the CPU). Cost: one upload of 12 bytes a pixel and one draw.
    void show_image(const Image& image);

    // The last frame as a float image (row 0 at the top), read with glReadPixels.
    Image read_image() const;

    // Binds the offscreen framebuffer (holding the last frame) for drawing on top of it, with
    // the viewport over it: an overlay drawn then is part of read_image().
    void bind_framebuffer() const;

    // Copies the last frame to the default framebuffer (window), scaled to width x height, and
    // leaves that framebuffer bound with the viewport over it.
    void blit_to_default(int width, int height) const;

  private:
    GlTetRenderer() = default;
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace tr::gl
