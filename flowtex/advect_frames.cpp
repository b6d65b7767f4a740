#include <core/stopwatch.h>
#include <flowtex/advect_frames.h>
#include <flowtex/advected_sheets.h>
#include <flowtex/frame_loop.h>

#include <chrono>
#include <cmath>

namespace tr {
namespace {

// The sheets' options of `options`; a slice with only its point or its normal given takes the
// other from the default slice (the bounds' centre; the normal along their thinnest axis).
AdvectedSheetsOptions advected_sheets_options(const AdvectFramesOptions& options,
                                              const Bounds3& bounds) {
    AdvectedSheetsOptions out;
    if (options.planar && !options.slice_point && !options.slice_normal && !options.sheet) {
        out.slices.push_back({options.planar->point, options.planar->normal});
    } else if (options.slice_point || options.slice_normal) {
        const SlicePlane fallback = default_slice(bounds);
        out.slices.push_back({options.slice_point.value_or(fallback.point),
                              options.slice_normal.value_or(fallback.normal)});
    }
    out.sheet = options.sheet;
    out.sheet_resolution = options.sheet_resolution;
    out.steps = options.steps;
    out.dt = options.dt;
    out.start_time = options.start_time;
    out.start_time_set = options.start_time_set;
    out.method = options.method;
    out.reinject_frames = options.reinject_frames;
    out.texture_size = options.texture_size;
    out.texture_feature = options.texture_feature;
    out.texture_period = options.texture_period;
    return out;
}

}  // namespace

Result<AdvectFramesReport> advect_frames(
    const TetMesh& mesh, const FaceAdjacency& adjacency, const VelocityField& velocity,
    const AdvectFramesOptions& options,
    const std::function<Status(int frame, const Image& picture)>& on_frame) {
    if (options.steps < 0 || options.width < 1 || options.height < 1 || options.dt < 0 ||
        !std::isfinite(options.dt)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "advection needs steps >= 0, a positive size and dt >= 0");
    }
    TR_TRY(const std::unique_ptr<AdvectedSheets> sheets,
           AdvectedSheets::create(mesh, adjacency, velocity,
                                  advected_sheets_options(options, mesh.bounds())));
    const std::optional<Vec3> view_up = options.view_up || !options.planar
                                            ? options.view_up
                                            : upright_view_up(options.planar->normal);
    AdvectFramesReport report;
    report.sheet_points = sheets->points();
    report.sheet_triangles = sheets->triangles();
    report.mean_speed = sheets->mean_speed();
    report.dt = sheets->dt();
    const CameraFrame frame(sheet_camera(sheets->sheet(0), options.width, options.height, view_up),
                            options.width, options.height);
    Image picture;
    TR_TRY(const FrameLoopTimes times, run_frame_loop(
                                           options.steps, true, [&] { sheets->advance(); },
                                           [&](int k) {
                                               rasterize_sheet(frame, sheets->views(0),
                                                               sheets->texture(), options.raster,
                                                               picture);
                                               return on_frame(k, picture);
                                           }));
    report.advect_ms = times.advance_ms;
    report.raster_ms = times.draw_ms;
    report.frames = times.drawn;
    return report;
}

}  // namespace tr
