#include <flowtex/advected_sheets.h>

#include <algorithm>
#include <cmath>

namespace tr {

SlicePlane default_slice(const Bounds3& bounds) {
    const Vec3 size = bounds.size();
    SlicePlane plane{0.5 * (bounds.lo + bounds.hi), Vec3(0, 0, 1)};
    if (size.x <= size.y && size.x <= size.z) {
        plane.normal = Vec3(1, 0, 0);
    } else if (size.y <= size.z) {
        plane.normal = Vec3(0, 1, 0);
    }
    return plane;
}

Result<std::unique_ptr<AdvectedSheets>> AdvectedSheets::create(
    const TetMesh& mesh, const FaceAdjacency& adjacency, const VelocityField& velocity,
    const AdvectedSheetsOptions& options) {
    if (options.steps < 0 || options.dt < 0 || !std::isfinite(options.dt)) {
        return make_error(ErrorCode::kInvalidArgument, "advection needs steps >= 0 and dt >= 0");
    }
    const int tex = options.texture_size;
    if (tex < 8 || tex > 4096 || (tex & (tex - 1)) != 0 || options.texture_feature < 1) {
        return make_error(ErrorCode::kInvalidArgument,
                          "texture size must be a power of two in 8..4096, feature >= 1");
    }
    if (options.slices.size() > kMaxSheets) {
        return make_error(ErrorCode::kInvalidArgument, std::to_string(options.slices.size()) +
                                                           " slices: at most " +
                                                           std::to_string(kMaxSheets));
    }
    std::unique_ptr<AdvectedSheets> out(
        new AdvectedSheets(mesh, adjacency, velocity,
                           PeriodicTexture::filtered_noise(tex, 0x5eed, options.texture_feature)));
    const MeshFlow& flow = out->flow_;
    const Bounds3 bounds = mesh.bounds();
    if (options.sheet) {
        TR_TRY(Sheet sheet, sheet_from_triangles(options.sheet->points, options.sheet->triangles));
        CellId hint = kNoCell;
        const bool any_inside =
            std::any_of(sheet.points.begin(), sheet.points.end(),
                        [&](const Vec3& p) { return flow.locator().locate(p, hint).has_value(); });
        if (!any_inside) {
            return make_error(ErrorCode::kInvalidArgument,
                              "the sheet lies outside the mesh: none of its " +
                                  std::to_string(sheet.points.size()) + " points is inside");
        }
        out->sheets_.push_back(std::make_unique<Sheet>(std::move(sheet)));
    } else {
        std::vector<SlicePlane> slices = options.slices;
        if (slices.empty()) slices.push_back(default_slice(bounds));
        for (std::size_t i = 0; i < slices.size(); ++i) {
            auto sheet = slice_sheet(flow.locator(), bounds, slices[i].point, slices[i].normal,
                                     options.sheet_resolution);
            if (!sheet.ok()) {
                Error error = sheet.error();
                error.about = "slices[" + std::to_string(i) + "]";
                return error;
            }
            out->sheets_.push_back(std::make_unique<Sheet>(std::move(sheet).value()));
        }
    }

    const double start_time = options.start_time_set ? options.start_time
                              : velocity.is_steady() ? 0.0
                                                     : velocity.first_time();
    double speed_sum = 0, extent = 0;
    std::size_t counted = 0;
    for (const auto& sheet : out->sheets_) {
        CellId hint = kNoCell;
        for (const Vec3& p : sheet->points) {
            if (const auto v = flow.at(p, start_time, hint)) {
                const Vec3 t = *v - glm::dot(*v, sheet->normal) * sheet->normal;
                const double s = glm::length(t);
                if (std::isfinite(s)) {
                    speed_sum += s;
                    ++counted;
                }
            }
        }
        extent = std::max(extent, sheet->spacing * std::max(sheet->nu, sheet->nv));
    }
    out->mean_speed_ = counted > 0 ? speed_sum / counted : 0.0;
    double dt = options.dt;
    if (dt == 0) {
        if (!velocity.is_steady() && options.steps > 0) {
            dt = std::max(velocity.last_time() - start_time, 0.0) / options.steps;
        } else if (out->mean_speed_ > 0) {
            dt = extent / 200.0 / out->mean_speed_;
        }
        if (!(dt > 0) || !std::isfinite(dt)) dt = 1.0;  // zero velocity: still frames
    }
    out->dt_ = dt;

    for (const auto& sheet : out->sheets_) {
        AdvectionOptions advection_options;
        advection_options.dt = dt;
        advection_options.start_time = start_time;
        advection_options.texture_period =
            options.texture_period > 0 ? options.texture_period
                                       : sheet->spacing * std::max(sheet->nu, sheet->nv) / 2.0;
        // Nothing moves anywhere: no re-injection either, so the frames are still.
        advection_options.reinject_frames = out->mean_speed_ > 0 ? options.reinject_frames : 0;
        advection_options.method = options.method;
        TR_TRY(TextureAdvection advection,
               TextureAdvection::create(*sheet, flow, advection_options));
        out->advections_.push_back(std::move(advection));
    }
    return out;
}

void AdvectedSheets::advance() {
    for (TextureAdvection& a : advections_) a.advance();
}

std::size_t AdvectedSheets::points() const {
    std::size_t n = 0;
    for (const auto& s : sheets_) n += s->points.size();
    return n;
}

std::size_t AdvectedSheets::triangles() const {
    std::size_t n = 0;
    for (const auto& s : sheets_) n += s->triangles.size();
    return n;
}

}  // namespace tr
