#include <algorithm>
#include <chrono>
#include <cmath>
#include <flowtex/advect_frames.h>
#include <flowtex/flow.h>
#include <flowtex/periodic_texture.h>
#include <flowtex/sheet.h>

namespace tr {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
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
    const int tex = options.texture_size;
    if (tex < 8 || tex > 4096 || (tex & (tex - 1)) != 0 || options.texture_feature < 1) {
        return make_error(ErrorCode::kInvalidArgument,
                          "texture size must be a power of two in 8..4096, feature >= 1");
    }
    const Bounds3 bounds = mesh.bounds();
    const Vec3 size = bounds.size();
    const Vec3 point = options.slice_point.value_or(0.5 * (bounds.lo + bounds.hi));
    Vec3 normal(0, 0, 1);
    if (options.slice_normal) {
        normal = *options.slice_normal;
    } else if (size.x <= size.y && size.x <= size.z) {
        normal = Vec3(1, 0, 0);
    } else if (size.y <= size.z) {
        normal = Vec3(0, 1, 0);
    }
    const MeshFlow flow(mesh, adjacency, velocity);
    Sheet sheet;
    if (options.sheet) {
        TR_TRY(sheet, sheet_from_triangles(options.sheet->points, options.sheet->triangles));
        CellId hint = kNoCell;
        const bool any_inside =
            std::any_of(sheet.points.begin(), sheet.points.end(),
                        [&](const Vec3& p) { return flow.locator().locate(p, hint).has_value(); });
        if (!any_inside) {
            return make_error(ErrorCode::kInvalidArgument,
                              "the sheet lies outside the mesh: none of its " +
                                  std::to_string(sheet.points.size()) + " points is inside");
        }
    } else {
        TR_TRY(sheet, slice_sheet(flow.locator(), bounds, point, normal, options.sheet_resolution));
    }

    AdvectFramesReport report;
    report.sheet_points = sheet.points.size();
    report.sheet_triangles = sheet.triangles.size();
    const double start_time = options.start_time_set ? options.start_time
                              : velocity.is_steady() ? 0.0
                                                     : velocity.first_time();
    double speed_sum = 0;
    std::size_t counted = 0;
    CellId hint = kNoCell;
    for (const Vec3& p : sheet.points) {
        if (const auto v = flow.at(p, start_time, hint)) {
            const Vec3 t = *v - glm::dot(*v, sheet.normal) * sheet.normal;
            const double s = glm::length(t);
            if (std::isfinite(s)) {
                speed_sum += s;
                ++counted;
            }
        }
    }
    report.mean_speed = counted > 0 ? speed_sum / counted : 0.0;
    const double extent = sheet.spacing * std::max(sheet.nu, sheet.nv);
    double dt = options.dt;
    if (dt == 0) {
        if (!velocity.is_steady() && options.steps > 0) {
            dt = std::max(velocity.last_time() - start_time, 0.0) / options.steps;
        } else if (report.mean_speed > 0) {
            dt = extent / 200.0 / report.mean_speed;
        }
        if (!(dt > 0) || !std::isfinite(dt)) dt = 1.0;  // zero velocity: still frames
    }
    report.dt = dt;

    AdvectionOptions advection_options;
    advection_options.dt = dt;
    advection_options.start_time = start_time;
    advection_options.texture_period =
        options.texture_period > 0 ? options.texture_period : extent / 2.0;
    // Nothing moves anywhere: no re-injection either, so the frames are still.
    advection_options.reinject_frames = report.mean_speed > 0 ? options.reinject_frames : 0;
    advection_options.method = options.method;
    TR_TRY(TextureAdvection advection, TextureAdvection::create(sheet, flow, advection_options));
    const PeriodicTexture texture =
        PeriodicTexture::filtered_noise(tex, 0x5eed, options.texture_feature);
    const CameraFrame frame(sheet_camera(sheet, options.width, options.height), options.width,
                            options.height);
    Image picture;
    for (int k = 0; k <= options.steps; ++k) {
        if (k > 0) {
            const auto start = std::chrono::steady_clock::now();
            advection.advance();
            report.advect_ms += ms_since(start);
        }
        const auto start = std::chrono::steady_clock::now();
        const std::vector<TexturedMeshView> views = advection.views();
        rasterize_sheet(frame, views, texture, options.raster, picture);
        report.raster_ms += ms_since(start);
        TR_TRY_STATUS(on_frame(k, picture));
        ++report.frames;
    }
    return report;
}

}  // namespace tr
