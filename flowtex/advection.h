#pragma once
// Texture advection on a sheet (seed section 4.4; Max and Becker, "Flow visualization using
// moving textures", 1995, the seed's reference [28]): frame after frame, texture coordinates
// on the sheet's polygons that make a periodic texture move with the flow.
//
// Methods (AdvectionMethod):
// - kBackward: the sheet's points stay put; each carries Q(P, t), the point at the start time
//   that the flow carries to P at time t, and draws the texture at Q (its plane coordinates
//   over the texture period). Steady flow: Q is pushed one RK4 step further back along the
//   streamline through P each frame (exact up to RK4). Unsteady flow: Q solves the transport
//   equation dQ/dt + (v . grad) Q = 0 semi-Lagrangian, frame to frame: Q(P, t + dt) =
//   Q(X, t), X the RK4 step back from P over [t, t + dt], Q(X, t) interpolated linearly on the
//   sheet's triangles; where X is off the sheet the flow brings in fresh texture: Q = X.
//   On a grid sheet a steady flow's velocity is sampled once at the sheet's points and
//   interpolated on its triangles (AdvectionOptions::sample_velocity_on_sheet), and a point
//   whose streamline has ended (at an inflow boundary) is not traced again until its layer is
//   reset.
// - kForward: the points move forward along particle paths and keep their texture
//   coordinates; a point that leaves the flow's domain dies and its triangles are not drawn.
//
// Re-injection (reinject_frames = T > 0): two layers, each reset to the unadvected texture
// every T frames, half a period apart, blended with triangle weights 1 - |2 age / T - 1|
// (0 just before and after its reset, 1 half way) that sum to 1. A layer is never shown
// stretched over more than T frames; with kForward a reset layer is the whole sheet again,
// which is how new polygons appear where the flow enters. T = 0: one layer, never reset.
//
// Velocities are projected onto the sheet's plane (the component along its normal removed).

#include <core/result.h>
#include <flowtex/flow.h>
#include <flowtex/sheet.h>
#include <flowtex/sheet_sampled_flow.h>

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace tr {

enum class AdvectionMethod { kBackward, kForward };

struct AdvectionOptions {
    double dt = 0.05;             // flow time per frame (> 0)
    double start_time = 0;        // the time of frame 0 (unsteady flows)
    double texture_period = 1.0;  // world units the texture takes to repeat in the plane (> 0)
    int reinject_frames = 0;      // T (even, >= 2), or 0 for no re-injection
    AdvectionMethod method = AdvectionMethod::kBackward;
    // kBackward on a steady flow: per-point streamlines (true, the default) or the transport
    // equation as for unsteady flow (false; for comparisons). Ignored otherwise.
    bool steady_streamlines = true;
    // Steady flow on a grid sheet: the velocity is looked up once at the sheet's points and
    // interpolated linearly on its triangles (SheetSampledFlow; Max and Becker's velocities at
    // the polygons' vertices) instead of being located in the flow's mesh at every RK4 stage.
    bool sample_velocity_on_sheet = true;
};

// What a rasteriser draws: a triangle mesh with per-point texture coordinates (in periods),
// the points whose triangles are drawn, and the layer's blend weight.
struct TexturedMeshView {
    std::span<const Vec3> positions;
    std::span<const glm::dvec2> texcoords;
    std::span<const std::array<std::uint32_t, 3>> triangles;
    std::span<const std::uint8_t> alive;  // per point, 0: its triangles are skipped; empty: all
    float weight = 1.0f;
    // When set, positions and triangles are this grid sheet's points and triangles (nothing
    // skipped): a rasteriser may find each pixel's triangle on the grid instead of visiting
    // every triangle.
    const Sheet* grid = nullptr;
};

class TextureAdvection {
  public:
    // Frame 0: every layer unadvected (texture coordinates = plane coordinates / period, plus
    // the layer's offset). `sheet` and `flow` must outlive the advection. Errors: dt or period
    // not positive and finite, reinject_frames odd or negative.
    static Result<TextureAdvection> create(const Sheet& sheet, const Flow& flow,
                                           const AdvectionOptions& options);

    // To the next frame (time + dt). Cost: per point and layer one RK4 step (four velocity
    // lookups: on a sampled sheet velocity three grid points each, otherwise the flow's own,
    // a point location in its mesh), parallel over points.
    void advance();

    int frame() const { return frame_; }
    double time() const { return options_.start_time + frame_ * options_.dt; }

    // The layers to draw at this frame (1, or 2 with re-injection).
    std::vector<TexturedMeshView> views() const;

    // Layer k's texture coordinates per sheet point (tests). Precondition: k < layers.
    std::span<const glm::dvec2> texcoords(int k) const { return layers_[k].texcoords; }
    // Layer k's drawn points: the sheet's (kBackward) or the moved ones (kForward).
    std::span<const Vec3> positions(int k) const;
    int num_layers() const { return static_cast<int>(layers_.size()); }

  private:
    struct Layer {
        int phase = 0;             // the frame (mod T) at which it is reset
        glm::dvec2 offset{0.0};    // added to its texture coordinates
        std::vector<Vec3> points;  // kBackward: Q per point; kForward: moved positions
        std::vector<glm::dvec2> texcoords;
        // kForward: 0 once the point has left the flow; kBackward on a steady flow: 0 once
        // its streamline has ended (Q stays until the layer is reset).
        std::vector<std::uint8_t> alive;
        std::vector<CellId> hints;
    };

    TextureAdvection(const Sheet& sheet, const Flow& flow, const AdvectionOptions& options)
        : sheet_(&sheet), flow_(&flow), options_(options) {}
    void reset(Layer& layer) const;
    void advance_layer(Layer& layer, double t0);
    // advance_layer's steady backward step on the velocity sampled at a grid sheet's points.
    void advance_on_sheet_grid(Layer& layer, const SheetSampledFlow& sampled, double t0);
    float weight(const Layer& layer) const;
    glm::dvec2 texcoord(const Layer& layer, const Vec3& q) const;

    const Sheet* sheet_;
    const Flow* flow_;  // the flow given, or *sampled_
    std::unique_ptr<const SheetSampledFlow> sampled_;
    AdvectionOptions options_;
    int frame_ = 0;
    std::vector<Layer> layers_;
    std::vector<Vec3> scratch_;
};

}  // namespace tr
