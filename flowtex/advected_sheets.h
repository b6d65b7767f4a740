#pragma once
// Several advected sheets of one flow (seed 4.4, "several meshed sheets of semitransparent
// textured polygons"): the slices (or a sheet from a file) made once, a texture advected over
// each, frame after frame, one time step for all. What `tetrender advect` (one sheet) and the
// scene method `texture-advection` (pipeline/methods/texture_advection_method.h) run.

#include <core/result.h>
#include <flowtex/advection.h>
#include <flowtex/flow.h>
#include <flowtex/periodic_texture.h>
#include <flowtex/sheet.h>
#include <flowvol/velocity_field.h>
#include <mesh/face_adjacency.h>
#include <mesh/surface_mesh.h>
#include <mesh/tet_mesh.h>

#include <memory>
#include <optional>
#include <vector>

namespace tr {

// A slice: a plane through `point` with `normal` (not zero).
struct SlicePlane {
    Vec3 point{0.0};
    Vec3 normal{0, 0, 1};
};

inline constexpr std::size_t kMaxSheets = 16;

// The slice through the centre of `bounds`, normal along the axis of their smallest extent.
SlicePlane default_slice(const Bounds3& bounds);

struct AdvectedSheetsOptions {
    // The sheets: these slices (1 to kMaxSheets); none: one slice through the mesh bounds'
    // centre, normal along the axis of the bounds' smallest extent. Ignored when `sheet` is set.
    std::vector<SlicePlane> slices;
    // Instead: a planar triangle mesh (a 2D mesh from a file) in the mesh's space.
    std::optional<SurfaceMesh> sheet;
    int sheet_resolution = 256;  // grid squares along each slice's longer side
    int steps = 100;             // frames after frame 0 (sets the unsteady default dt)
    // Flow time per frame; 0: steady, the mean in-plane speed over every sheet's points carries
    // the texture 1/200 of the longest sheet side per frame; unsteady, the velocity's time span
    // over `steps`.
    double dt = 0;
    double start_time = 0;  // unsteady: the time of frame 0 (default the first sample's)
    bool start_time_set = false;
    AdvectionMethod method = AdvectionMethod::kBackward;
    int reinject_frames = 40;   // even; 0: off
    int texture_size = 256;     // texels a side (power of two)
    int texture_feature = 4;    // the noise's smoothing radius in texels
    double texture_period = 0;  // world units per texture repeat; 0: half each sheet's longer side
};

class AdvectedSheets {
  public:
    AdvectedSheets(const AdvectedSheets&) = delete;
    AdvectedSheets& operator=(const AdvectedSheets&) = delete;

    // Makes the sheets and frame 0 of their advection. `mesh`, `adjacency` and `velocity` must
    // outlive the object. Errors (one line): a slice that misses the mesh (with the bounds), a
    // zero normal (either with Error::about "slices[i]"), more than kMaxSheets slices, a sheet
    // file outside the mesh or not planar, bad texture options, dt < 0. Zero velocity everywhere:
    // still frames (dt 1, no re-injection). Cost: per sheet a point location per grid point.
    static Result<std::unique_ptr<AdvectedSheets>> create(const TetMesh& mesh,
                                                          const FaceAdjacency& adjacency,
                                                          const VelocityField& velocity,
                                                          const AdvectedSheetsOptions& options);

    // To the next frame: every sheet one step of dt. Cost: per sheet point and layer an RK4 step.
    void advance();
    int frame() const { return advections_.front().frame(); }

    std::size_t size() const { return sheets_.size(); }
    const Sheet& sheet(std::size_t s) const { return *sheets_[s]; }
    // Sheet s's layers to draw at this frame (flowtex/sheet_raster.h).
    std::vector<TexturedMeshView> views(std::size_t s) const { return advections_[s].views(); }
    const PeriodicTexture& texture() const { return texture_; }

    double dt() const { return dt_; }
    double mean_speed() const { return mean_speed_; }  // in-plane, over every sheet's points
    std::size_t points() const;                        // summed over the sheets
    std::size_t triangles() const;

  private:
    AdvectedSheets(const TetMesh& mesh, const FaceAdjacency& adjacency,
                   const VelocityField& velocity, PeriodicTexture texture)
        : flow_(mesh, adjacency, velocity), texture_(std::move(texture)) {}

    MeshFlow flow_;
    PeriodicTexture texture_;
    std::vector<std::unique_ptr<Sheet>> sheets_;  // stable addresses: the advections keep them
    std::vector<TextureAdvection> advections_;
    double dt_ = 0, mean_speed_ = 0;
};

}  // namespace tr
