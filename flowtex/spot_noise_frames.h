#pragma once
// Spot noise from a mesh's scalar and vector fields to pictures, frame by frame: what
// `tetrender spotnoise` runs (the app only parses arguments and writes files).

#include <core/camera.h>
#include <core/image.h>
#include <core/result.h>
#include <flowtex/flow.h>
#include <flowtex/spot_noise.h>
#include <flowtex/spot_raster.h>
#include <flowvol/velocity_field.h>
#include <mesh/face_adjacency.h>
#include <mesh/planar_slab.h>
#include <mesh/tet_mesh.h>
#include <project/opaque_geometry.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tr {

struct SpotNoiseFramesOptions {
    std::string scalar;  // a 1-component point array of the mesh (ignored with `planar`)
    // The mesh is a planar 2D mesh's slab (mesh/planar_slab.h): the spots lie on the whole
    // sheet (their scalar the height above its plane, iso 0, band half the slab's thickness
    // unless given), and the default camera looks at the plane, upright (upright_view_up).
    std::optional<PlanarSheet> planar;
    // iso, count, seed, lifetime as given; band 0: the mesh bounds' diagonal / 100; dt 0: the
    // mean speed over the spots at frame 0 carries a spot 1/400 of the diagonal per frame, or,
    // for an unsteady velocity, the frames span its times from the start to the last sample.
    // spots.start_time is used when start_time_set; else 0 for a steady velocity and the first
    // sample's time for an unsteady one.
    SpotNoiseOptions spots;
    bool start_time_set = false;
    int steps = 100;  // frames after frame 0
    int width = 512, height = 512;
    // Default: a perspective view (30 degrees) from (1, -1.2, 0.8) framing the spots of frame 0.
    std::optional<Camera> camera;
    // Opaque surfaces drawn under the spots, which are depth-tested against them, over the
    // background.
    std::vector<OpaqueSurface> opaque;
    Vec3 background{0.0};
    SpotRasterOptions raster;  // its dt is set to the spots' dt
};

struct SpotNoiseFramesReport {
    std::size_t band_tets = 0, spots = 0;
    double band = 0, dt = 0;
    double mean_speed = 0;                // over the spots at frame 0
    int frames = 0;                       // pictures handed to on_frame (steps + 1)
    std::size_t reseeded = 0;             // summed over the frames
    double advect_ms = 0, raster_ms = 0;  // summed over the frames
};

// Spots seeded and timed as spot_noise_frames does, before its frames: the flow they follow,
// the spots at frame 0 (their dt and lifetime set) and the report's band, dt, counts and mean
// speed. Errors: spot_noise_frames' (but the camera's and on_frame's), Error::about naming the
// option ("scalar", "count", "band", "iso", "start_time").
struct SpotNoiseRun {
    std::unique_ptr<MeshFlow> flow;  // the spots keep a reference
    std::optional<Field> height;     // a planar slab's height above its plane (the spots' scalar)
    std::optional<SpotNoise> spots;
    SpotNoiseFramesReport report;
};
Result<std::unique_ptr<SpotNoiseRun>> start_spot_noise(const TetMesh& mesh,
                                                       const FaceAdjacency& adjacency,
                                                       const VelocityField& velocity,
                                                       const SpotNoiseFramesOptions& options);

// Seeds spots in the band around `scalar` = iso, advects them `steps` frames and hands each
// frame's picture (frame 0 first) to on_frame, which may fail (a write) and stop the run. Zero
// velocity everywhere gives still frames (dt 1, no reseeding by age). Errors (one line): no such
// scalar array (the message lists the scalar arrays), a vector array given as the scalar, those
// of SpotNoise::create (iso outside the range, with it; bad count), bad sizes or steps, the
// camera's, on_frame's. Cost: per frame an RK4 step per spot and a raster.
Result<SpotNoiseFramesReport> spot_noise_frames(
    const TetMesh& mesh, const FaceAdjacency& adjacency, const VelocityField& velocity,
    const SpotNoiseFramesOptions& options,
    const std::function<Status(int frame, const Image& picture)>& on_frame);

}  // namespace tr
