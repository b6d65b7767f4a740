#pragma once
// The CPU projected-tetrahedra renderer: cells composited in a given visibility order with the
// premultiplied over operator (equation 1b of the texture-mapping paper), each cell's fragment
// per pixel the exact segment of that pixel's ray through the tet (right under perspective),
// clipped at the eye and at opaque depth, shaded by a SegmentShader. Each screen tile takes
// its cells front to back (the order reversed, the same operator written as "under"), so a
// pixel whose transmittance falls below 2^-24 takes no more fragments (what lies behind could
// add no more than a float's rounding); cells whose scalar range the transfer function leaves
// clear (SegmentShader::clear_between) are not drawn at all, which changes no bit.
//
// With the exp-texture integrator, cells are drawn as the paper draws them instead: each
// projected tet split by Shirley and Tuchman's classification into 3 or 4 triangles around the
// thick vertex (whose thickness and front and back scalars come from the exact chord there),
// those attributes interpolated linearly across the triangles (exact under orthographic
// projection, an approximation under perspective), and pixel centres on triangle edges decided
// by the exact ray test. Cells reaching behind the eye always take the exact path.
//
// Pixel rays pass through pixel centres. A centre on a face shared by two tets belongs to
// exactly one of them (the one whose outward normal is "positive"), so shared edges are
// neither skipped nor blended twice. Threads work on fixed screen tiles, each compositing its
// cells in the given order: the image is bit-identical whatever the thread count.

#include <core/camera.h>
#include <core/image.h>
#include <mesh/tet_mesh.h>
#include <project/segment_shader.h>
#include <project/view.h>

#include <cstddef>
#include <span>
#include <vector>

namespace tr {

struct RenderStats {
    std::size_t cells_drawn = 0;  // cells reaching the image, less those left clear
    std::size_t fragments = 0;    // (cell, pixel) pairs with a segment of positive length
    double raster_ms = 0;
};

// The view (camera, background, opaque layer: project/view.h) and what is drawn in it.
struct RenderInputs : View {
    const TetMesh* mesh = nullptr;
    std::span<const float> scalar;  // one per mesh point
    std::span<const CellId> order;  // back to front, real cells
    const SegmentShader* shader = nullptr;
};

// Renders the volume over the background (or opaque geometry): camera.width() x height() pixels.
// Preconditions, checked (TR_CHECK, core/check.h: a failure aborts with the check that failed,
// as a wrong call would read or write out of bounds): mesh, shader and camera set; one scalar
// per mesh point; every order id a real tet (< mesh.num_real_tets()); opaque colour and depth,
// when given, the image's size. Cost: O(cells + fragments), threaded over screen tiles.
//
// `alpha`, when given, is resized to width x height (row-major, row 0 at the top, as Image) and
// receives per pixel the opacity of the volume drawn there, 1 - the product of its fragments'
// transmittances (composited alongside the colour by the same over operator; 0 where no
// fragment was drawn): the returned picture is then, up to float rounding, the picture the same
// call returns over black with no opaque colour plus (1 - alpha) times the background or opaque
// colour — the premultiplied RGBA a compositor blends. An opaque depth without an opaque
// colour stops the segments there (a rank's part over transparent black). Asking for alpha
// changes no bit of the picture; without it the raster costs what it did.
Image render_projected_tetrahedra(const RenderInputs& inputs, RenderStats* stats = nullptr,
                                  std::vector<float>* alpha = nullptr);

// The longest segment a ray can have through any real tet (its longest edge): what a
// SegmentShader's tables must cover.
double longest_edge(const TetMesh& mesh);

}  // namespace tr
