#include <mesh/point_data.h>
#include <pipeline/quick_look.h>
#include <pipeline/quick_scene.h>
#include <project/colormap.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <utility>

namespace tr {
namespace {

const std::vector<std::pair<std::string, Vec3>>& views() {
    static const std::vector<std::pair<std::string, Vec3>> v = {{"iso", kDefaultViewDirection},
                                                                {"+x", {1, 0, 0}},
                                                                {"-x", {-1, 0, 0}},
                                                                {"+y", {0, 1, 0}},
                                                                {"-y", {0, -1, 0}},
                                                                {"+z", {0, 0, 1}},
                                                                {"-z", {0, 0, -1}}};
    return v;
}

}  // namespace

std::vector<std::string> view_names() {
    std::vector<std::string> names;
    for (const auto& [name, dir] : views()) names.push_back(name);
    return names;
}

Result<Vec3> view_direction(const std::string& name) {
    for (const auto& [n, dir] : views()) {
        if (n == name) return dir;
    }
    std::string list;
    for (const auto& [n, dir] : views()) list += (list.empty() ? "" : ", ") + n;
    return make_error(ErrorCode::kInvalidArgument, "unknown view '" + name + "' (" + list + ")");
}

namespace {

// The opacity points of the options over [lo, hi] (a ramp, or the curve given).
Result<std::vector<OpacityPoint>> quick_opacity(const QuickSceneOptions& options, double lo,
                                                double hi) {
    std::vector<OpacityPoint> points;
    if (options.opacity_curve.empty()) {
        if (!(options.max_opacity > 0.0 && options.max_opacity < 1.0)) {
            return make_error(ErrorCode::kInvalidArgument, "the opacity must lie in (0, 1), not " +
                                                               std::to_string(options.max_opacity));
        }
        const double floor = std::clamp(options.opacity_floor, 0.0, 1.0);
        points = {{lo, floor * options.max_opacity}, {hi, options.max_opacity}};
        return points;
    }
    double last_t = -1.0;
    for (const auto& [t, a] : options.opacity_curve) {
        if (!(t >= 0.0 && t <= 1.0) || !(a >= 0.0 && a < 1.0) || t < last_t) {
            return make_error(
                ErrorCode::kInvalidArgument,
                "the opacity curve takes t:a points with t in [0, 1], non-decreasing, "
                "and a in [0, 1)");
        }
        last_t = t;
        points.push_back({lo + (hi - lo) * t, a});
    }
    return points;
}

// The values the range, opacity and unit distance come from: the mesh's, or with a series those
// of every step, each strided to at most kSeriesValuesPerStep.
Result<std::vector<float>> quick_values(const TetMesh& mesh,
                                        const std::vector<const TetMesh*>& series,
                                        const std::string& scalar, int component) {
    TR_TRY(std::vector<float> values, point_scalar(mesh, scalar, component));
    if (series.empty()) return values;
    const auto strided = [](const std::vector<float>& step, std::vector<float>& into) {
        const std::size_t stride = (step.size() + kSeriesValuesPerStep - 1) / kSeriesValuesPerStep;
        for (std::size_t i = 0; i < step.size(); i += std::max<std::size_t>(stride, 1))
            into.push_back(step[i]);
    };
    std::vector<float> all;
    strided(values, all);
    for (const TetMesh* step : series) {
        TR_TRY(const std::vector<float> more, point_scalar(*step, scalar, component));
        strided(more, all);
    }
    return all;
}

// One volume: its array's range under a colour map, the opacity of the options, the unit
// distance given or chosen from the mesh (and the other steps of its series, when given).
Result<SceneVolume> quick_volume(const std::filesystem::path& mesh_path, const TetMesh& mesh,
                                 const std::string& scalar, int component,
                                 const std::string& colormap, const QuickSceneOptions& options,
                                 std::vector<std::string>* notes) {
    SceneVolume volume;
    volume.mesh = mesh_path;
    volume.scalar = scalar;
    volume.component = component;
    volume.time_step = options.time_step;
    volume.log_scale = options.log_scale;
    TR_TRY(const std::vector<float> values, quick_values(mesh, options.series, scalar, component));
    // With a log scale, the range is found in log10 of the positive values.
    std::vector<float> logs;
    if (options.log_scale) {
        std::size_t not_positive = 0;
        for (float v : values) {
            if (v > 0.0f && std::isfinite(v)) {
                logs.push_back(static_cast<float>(std::log10(static_cast<double>(v))));
            } else if (std::isfinite(v)) {
                ++not_positive;
            }
        }
        if (logs.empty()) {
            return make_error(ErrorCode::kInvalidArgument,
                              "--log: array '" + scalar + "' has no positive value",
                              mesh_path.string());
        }
        if (not_positive > 0 && notes) {
            notes->push_back("--log: " + std::to_string(not_positive) + " of " +
                             std::to_string(values.size()) + " values of '" + scalar +
                             "' are <= 0 and take the low end's colour");
        }
    }
    const std::span<const float> ranged = options.log_scale ? std::span<const float>(logs) : values;
    auto whole = robust_range(ranged, 0.0);
    if (!whole.ok()) {
        return make_error(ErrorCode::kInvalidMesh, "array '" + scalar + "' has no finite value",
                          mesh_path.string());
    }
    std::array<double, 2> range = (*whole);
    if (options.range) {
        range = *options.range;
        if (!std::isfinite(range[0]) || !std::isfinite(range[1]) || !(range[1] > range[0])) {
            return make_error(ErrorCode::kInvalidArgument,
                              "the range must be two finite values lo < hi");
        }
        if (options.log_scale) {
            if (!(range[0] > 0.0)) {
                return make_error(
                    ErrorCode::kInvalidArgument,
                    "--log needs a positive range, not starting at " + std::to_string(range[0]));
            }
            range = {std::log10(range[0]), std::log10(range[1])};
        }
        if (notes && (range[0] > (*whole)[1] || range[1] < (*whole)[0])) {
            const auto real = [&](double x) { return options.log_scale ? std::pow(10.0, x) : x; };
            notes->push_back("the range given lies outside the values of '" + scalar + "' (" +
                             std::to_string(real((*whole)[0])) + " to " +
                             std::to_string(real((*whole)[1])) + ")");
        }
    } else if (options.range_percent > 0.0) {
        TR_TRY(range, robust_range(ranged, options.range_percent));
        if (!(range[1] > range[0])) range = *whole;  // most values equal: the whole range
    }
    if (!(range[1] > range[0]) && notes) {
        const double value = options.log_scale ? std::pow(10.0, range[0]) : range[0];
        const std::string over =
            options.series.empty()
                ? std::string()
                : " over all " + std::to_string(options.series.size() + 1) + " time steps";
        notes->push_back("array '" + scalar + "' is constant" + over + " (" +
                         std::to_string(value) +
                         "): the picture shows where the mesh is, in one colour");
    }
    // A constant sits in the middle of the colour map and of the opacity ramp.
    const double half = 0.5 * std::max(1.0, std::abs(range[0]));
    const double lo = range[1] > range[0] ? range[0] : range[0] - half;
    const double hi = range[1] > range[0] ? range[1] : range[0] + half;
    TR_TRY(const std::vector<OpacityPoint> opacity, quick_opacity(options, lo, hi));
    TR_TRY(TransferFunction colors, make_quick_transfer_function(colormap, lo, hi, 0.5, 1.0));
    if (options.colormap_preset) {
        TR_TRY(colors,
               preset_transfer_function(*options.colormap_preset, lo, hi, {{lo, 0.5}}, 1.0));
    }
    // Colours and opacity over log10 of the scalar, as a function of the scalar itself.
    TR_TRY(TransferFunction shape, TransferFunction::create(colors.color_points(), opacity, 1.0));
    if (options.log_scale) {
        TR_TRY(shape, log_scaled(shape));
    }
    // The unit distance: given, or the one that brings the mean chord to options.ray_opacity.
    double unit = options.unit_distance;
    if (!(unit > 0.0) && options.unit_distance_of_diagonal > 0.0) {
        unit = options.unit_distance_of_diagonal * mesh.bounds().diagonal();
    }
    if (!(unit > 0.0)) {
        const double target = std::clamp(options.ray_opacity, 0.01, 0.99);
        unit = unit_distance_for_opacity(
            values, [&](double s) { return shape.opacity(s); }, mean_chord_length(mesh), target);
        if (!(unit > 0.0)) unit = std::max(mesh.bounds().diagonal(), 1e-12) / 20.0;
    }
    TR_TRY(volume.transfer_function,
           TransferFunction::create(shape.color_points(), shape.opacity_points(), unit));
    return volume;
}

}  // namespace

std::string default_quick_scalar(const TetMesh& mesh) {
    if (!mesh.point_fields().empty()) return mesh.point_fields().front().name;
    if (!mesh.cell_fields().empty()) return mesh.cell_fields().front().name;
    return {};
}

std::shared_ptr<const TetMesh> with_constant_field(const TetMesh& mesh, const std::string& name) {
    auto copy = std::make_shared<TetMesh>(mesh);
    Field ones;
    ones.name = name;
    ones.values = std::vector<float>(mesh.num_points(), 1.0f);
    // One tuple a point, a new name: cannot fail.
    (void)copy->add_point_field(std::move(ones));
    return copy;
}

std::shared_ptr<const TetMesh> without_point_field(const TetMesh& mesh, const std::string& name) {
    auto copy = std::make_shared<TetMesh>(mesh);
    auto& fields = copy->point_fields();
    std::erase_if(fields, [&](const Field& f) { return f.name == name; });
    return copy;
}

QuickSceneOptions classic_quick_look() {
    QuickSceneOptions options;
    options.range_percent = 0.0;
    options.opacity_curve = {{0.0, 0.0}, {1.0, 0.3}};
    options.unit_distance_of_diagonal = 1.0 / 20.0;
    options.fit_extent = false;
    return options;
}

Result<Scene> make_quick_scene(const std::filesystem::path& mesh_path, const TetMesh& mesh,
                               const QuickSceneOptions& options) {
    return make_quick_scene(mesh_path, mesh, options, {});
}

Result<Scene> make_quick_scene(const std::filesystem::path& mesh_path, const TetMesh& mesh,
                               const QuickSceneOptions& options,
                               const std::vector<QuickVolume>& more,
                               std::vector<std::string>* notes) {
    Scene scene;
    scene.width = options.width;
    scene.height = options.height;
    scene.background = options.background;
    TR_TRY(const Vec3 from, view_direction(options.view));
    std::vector<const TetMesh*> meshes = {&mesh};
    for (const QuickVolume& v : more) meshes.push_back(v.mesh);
    if (options.camera) {
        scene.camera = *options.camera;
    } else if (options.fit_extent) {
        CameraFit fit;
        fit.from = from;
        fit.width = options.width, fit.height = options.height;
        fit.view_angle = options.view_angle;
        fit.azimuth = options.azimuth, fit.elevation = options.elevation, fit.zoom = options.zoom;
        scene.camera = fitting_camera(meshes, fit);
    } else {
        Bounds3 bounds;
        for (const TetMesh* m : meshes) {
            const Bounds3 b = m->bounds();
            if (!b.empty()) bounds.extend(b.lo), bounds.extend(b.hi);
        }
        scene.camera = framing_camera(bounds, from, options.view_angle);
    }
    TR_TRY(SceneVolume first, quick_volume(mesh_path, mesh, options.scalar, options.component,
                                           options.colormap, options, notes));
    scene.volumes.push_back(std::move(first));
    std::vector<std::string> used = {options.colormap};
    for (std::size_t i = 0; i < more.size(); ++i) {
        const QuickVolume& v = more[i];
        std::string colormap = v.colormap;
        if (colormap.empty()) {
            for (const char* name : {"viridis", "inferno", "coolwarm", "gray"}) {
                if (std::find(used.begin(), used.end(), name) == used.end()) {
                    colormap = name;
                    break;
                }
            }
            if (colormap.empty()) colormap = used[(i + 1) % used.size()];
        }
        used.push_back(colormap);
        QuickSceneOptions own = options;
        own.range.reset();  // each volume over its own range, in its own colours
        own.colormap_preset.reset();
        own.series = v.series;
        auto volume =
            quick_volume(v.mesh_path, *v.mesh, v.scalar, v.component, colormap, own, notes);
        if (!volume.ok()) {
            Error e = volume.error();
            e.message = "volume " + std::to_string(i + 1) + ": " + e.message;
            if (e.where.empty()) e.where = v.mesh_path.string();
            return e;
        }
        scene.volumes.push_back(std::move(volume).value());
    }
    scene.volumes_key = scene.volumes.size() > 1;
    return scene;
}

}  // namespace tr
