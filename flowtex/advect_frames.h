#pragma once
// Texture advection from a mesh's vector field to pictures, frame by frame: what
// `tetrender advect` runs (the app only parses arguments and writes files).

#include <core/image.h>
#include <core/result.h>
#include <flowtex/advection.h>
#include <flowtex/sheet_raster.h>
#include <flowvol/velocity_field.h>
#include <mesh/face_adjacency.h>
#include <mesh/planar_slab.h>
#include <mesh/surface_mesh.h>
#include <mesh/tet_mesh.h>

#include <functional>
#include <optional>

namespace tr {

struct AdvectFramesOptions {
    // The slice: a point and a normal. Default: the mesh bounds' centre, normal along the axis
    // of the bounds' smallest extent.
    std::optional<Vec3> slice_point;
    std::optional<Vec3> slice_normal;
    int sheet_resolution = 256;  // grid squares along the sheet's longer side
    // Instead of a slice: a planar triangle mesh (a 2D mesh from a file) in the mesh's space.
    std::optional<SurfaceMesh> sheet;
    int steps = 100;  // frames after frame 0
    // Flow time per frame; 0: steady, the mean in-plane speed over the sheet carries the
    // texture 1/200 of the sheet's longer side per frame; unsteady, the velocity's time span
    // over `steps`.
    double dt = 0;
    double start_time = 0;  // unsteady: the time of frame 0 (default the first sample's)
    bool start_time_set = false;
    AdvectionMethod method = AdvectionMethod::kBackward;
    int reinject_frames = 40;  // even; 0: off
    int width = 512, height = 512;
    // The picture's up, made tangent to the sheet (sheet_camera); default the sheet's axis_v,
    // or upright (upright_view_up) with `planar`.
    std::optional<Vec3> view_up;
    // The mesh is a planar 2D mesh's slab (mesh/planar_slab.h, FlowDomain::planar): the slice
    // defaults to its plane (unless a slice or sheet is given) and the picture is upright.
    std::optional<PlanarSheet> planar;
    int texture_size = 256;     // texels a side (power of two)
    int texture_feature = 4;    // the noise's smoothing radius in texels
    double texture_period = 0;  // world units per texture repeat; 0: half the longer side
    SheetRasterOptions raster;
};

struct AdvectFramesReport {
    std::size_t sheet_points = 0, sheet_triangles = 0;
    double dt = 0;
    double mean_speed = 0;                // in the plane, over the sheet's points at frame 0's time
    int frames = 0;                       // pictures handed to on_frame (steps + 1)
    double advect_ms = 0, raster_ms = 0;  // summed over the frames
};

// Slices the mesh (or takes options.sheet), advects a noise texture over the slice `steps` frames
// and hands each frame's picture (frame 0 first) to on_frame, which may fail (a write) and stop the
// run. Zero velocity everywhere gives still frames (dt 1, no re-injection). Errors: the slice's
// (misses the mesh, bad normal), bad options, on_frame's. Cost: per frame one RK4 step per sheet
// point and layer, and a raster.
Result<AdvectFramesReport> advect_frames(
    const TetMesh& mesh, const FaceAdjacency& adjacency, const VelocityField& velocity,
    const AdvectFramesOptions& options,
    const std::function<Status(int frame, const Image& picture)>& on_frame);

}  // namespace tr
