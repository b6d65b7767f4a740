#include <core/stopwatch.h>
#include <flowtex/flow.h>
#include <flowtex/frame_loop.h>
#include <flowtex/sheet_raster.h>
#include <flowtex/spot_noise_frames.h>

#include <chrono>
#include <cmath>

namespace tr {
namespace {

std::string scalar_arrays(const TetMesh& mesh) {
    std::string names;
    for (const Field& f : mesh.point_fields()) {
        if (f.num_components != 1) continue;
        names += (names.empty() ? "" : ", ") + f.name;
    }
    return names.empty() ? "none" : names;
}

}  // namespace

Result<std::unique_ptr<SpotNoiseRun>> start_spot_noise(const TetMesh& mesh,
                                                       const FaceAdjacency& adjacency,
                                                       const VelocityField& velocity,
                                                       const SpotNoiseFramesOptions& options) {
    if (options.steps < 0 || options.width < 1 || options.height < 1 || options.spots.band < 0 ||
        options.spots.dt < 0 || !std::isfinite(options.spots.dt)) {
        return with_about(
            make_error(ErrorCode::kInvalidArgument,
                       "spot noise needs steps >= 0, a positive size, band >= 0 and dt >= 0"),
            "band");
    }
    auto run = std::make_unique<SpotNoiseRun>();
    SpotNoiseOptions spot_options = options.spots;
    if (options.planar) {
        std::vector<float> height(mesh.num_points());
        for (std::size_t i = 0; i < height.size(); ++i) {
            height[i] = static_cast<float>(
                glm::dot(mesh.points()[i] - options.planar->point, options.planar->normal));
        }
        run->height = make_float_field("height above the sheet", 1, std::move(height));
        spot_options.iso = 0;
        if (spot_options.band == 0) spot_options.band = 0.5 * options.planar->thickness;
    }
    const Field* scalar =
        run->height ? &*run->height : find_field(mesh.point_fields(), options.scalar);
    if (!scalar) {
        return with_about(
            make_error(ErrorCode::kNotFound, "no point array '" + options.scalar +
                                                 "' (scalar arrays: " + scalar_arrays(mesh) + ")"),
            "scalar");
    }
    if (scalar->num_components != 1) {
        return with_about(
            make_error(ErrorCode::kInvalidArgument,
                       "'" + options.scalar + "' has " + std::to_string(scalar->num_components) +
                           " components; --scalar needs a scalar (" + scalar_arrays(mesh) + ")"),
            "scalar");
    }
    const double diagonal = glm::length(mesh.bounds().size());
    if (spot_options.band == 0) spot_options.band = diagonal / 100.0;
    const bool auto_dt = spot_options.dt == 0;
    if (auto_dt) spot_options.dt = 1.0;
    const bool unsteady = !velocity.is_steady();
    if (!options.start_time_set) spot_options.start_time = unsteady ? velocity.first_time() : 0.0;
    if (!std::isfinite(spot_options.start_time)) {
        return with_about(make_error(ErrorCode::kInvalidArgument, "the start time must be finite"),
                          "start_time");
    }
    run->flow = std::make_unique<MeshFlow>(mesh, adjacency, velocity);
    const MeshFlow& flow = *run->flow;
    TR_TRY(SpotNoise created, SpotNoise::create(mesh, flow.locator(), *scalar, flow, spot_options));
    run->spots.emplace(std::move(created));
    SpotNoise& spots = *run->spots;
    SpotNoiseFramesReport& report = run->report;
    report.band_tets = spots.band_tets();
    report.spots = spots.size();
    report.band = spot_options.band;
    report.mean_speed = spots.mean_speed();
    double dt = spot_options.dt;
    int lifetime = spot_options.lifetime_frames;
    const double span = unsteady ? velocity.last_time() - spot_options.start_time : 0.0;
    if (auto_dt && unsteady && options.steps > 0 && span > 0) {
        dt = span / options.steps;  // the frames cover the series (still or not at frame 0)
    } else if (!(report.mean_speed > 0) || !std::isfinite(report.mean_speed)) {
        dt = auto_dt ? 1.0 : dt;
        if (!unsteady) lifetime = 0;  // nothing moves, ever: still frames
    } else if (auto_dt) {
        dt = diagonal / 400.0 / report.mean_speed;
    }
    spots.retime(dt, lifetime);
    report.dt = dt;
    return run;
}

Result<SpotNoiseFramesReport> spot_noise_frames(
    const TetMesh& mesh, const FaceAdjacency& adjacency, const VelocityField& velocity,
    const SpotNoiseFramesOptions& options,
    const std::function<Status(int frame, const Image& picture)>& on_frame) {
    TR_TRY(const std::unique_ptr<SpotNoiseRun> run,
           start_spot_noise(mesh, adjacency, velocity, options));
    SpotNoise& spots = *run->spots;
    SpotNoiseFramesReport report = run->report;
    const double dt = report.dt;

    Camera camera;
    if (options.camera) {
        camera = *options.camera;
    } else if (options.planar) {
        const Vec3& normal = options.planar->normal;
        const Vec3 up = upright_view_up(normal);
        camera = plane_camera(spots.positions(), options.planar->point, glm::cross(up, normal), up,
                              normal, options.width, options.height);
    } else {
        Bounds3 box{Vec3(1e300), Vec3(-1e300)};
        for (const Vec3& p : spots.positions()) {
            box.lo = glm::min(box.lo, p);
            box.hi = glm::max(box.hi, p);
        }
        camera = framing_camera(box, Vec3(1, -1.2, 0.8));
    }
    TR_TRY_STATUS(check_camera(camera));

    const CameraFrame frame(camera, options.width, options.height);
    SpotRasterOptions raster = options.raster;
    raster.dt = dt;
    View view{.camera = &frame, .background = options.background};
    OpaqueLayer opaque;
    if (!options.opaque.empty()) {
        opaque = render_opaque(options.opaque, frame, options.background);
        view.opaque_color = &opaque.color;
        view.opaque_depth = &opaque.depth;
    }
    SpotBuffers buffers;
    Image picture;
    TR_TRY(const FrameLoopTimes times, run_frame_loop(
                                           options.steps, true,
                                           [&] {
                                               spots.advance();
                                               report.reseeded += spots.reseeded();
                                           },
                                           [&](int k) {
                                               render_spots(view, spots, raster, buffers, picture);
                                               return on_frame(k, picture);
                                           }));
    report.advect_ms = times.advance_ms;
    report.raster_ms = times.draw_ms;
    report.frames = times.drawn;
    return report;
}

}  // namespace tr
