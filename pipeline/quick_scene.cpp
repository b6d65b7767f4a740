#include <mesh/point_data.h>
#include <project/colormap.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <pipeline/quick_scene.h>
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

// One volume's array range under a colour map, the opacity ramp of the options.
Result<SceneVolume> quick_volume(const std::filesystem::path& mesh_path, const TetMesh& mesh,
                                 const std::string& scalar, int component,
                                 const std::string& colormap, const QuickSceneOptions& options,
                                 double unit_distance) {
    SceneVolume volume;
    volume.mesh = mesh_path;
    volume.scalar = scalar;
    volume.component = component;
    TR_TRY(const std::vector<float> values, point_scalar(mesh, scalar, component));
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (float v : values) {
        if (!std::isfinite(v)) continue;
        lo = std::min<double>(lo, v);
        hi = std::max<double>(hi, v);
    }
    if (!(hi >= lo)) {
        return make_error(ErrorCode::kInvalidMesh, "array '" + scalar + "' has no finite value",
                          mesh_path.string());
    }
    TR_TRY(volume.transfer_function,
           make_quick_transfer_function(colormap, lo, hi, options.max_opacity, unit_distance));
    return volume;
}

}  // namespace

Result<Scene> make_quick_scene(const std::filesystem::path& mesh_path, const TetMesh& mesh,
                               const QuickSceneOptions& options) {
    return make_quick_scene(mesh_path, mesh, options, {});
}

Result<Scene> make_quick_scene(const std::filesystem::path& mesh_path, const TetMesh& mesh,
                               const QuickSceneOptions& options,
                               const std::vector<QuickVolume>& more) {
    Scene scene;
    scene.width = options.width;
    scene.height = options.height;
    TR_TRY(const Vec3 from, view_direction(options.view));
    Bounds3 bounds = mesh.bounds();
    for (const QuickVolume& v : more) {
        const Bounds3 b = v.mesh->bounds();
        if (!b.empty()) bounds.extend(b.lo), bounds.extend(b.hi);
    }
    scene.camera = framing_camera(bounds, from, options.view_angle);
    const double unit =
        options.unit_distance > 0 ? options.unit_distance : bounds.diagonal() / 20.0;
    TR_TRY(SceneVolume first, quick_volume(mesh_path, mesh, options.scalar, options.component,
                                           options.colormap, options, unit));
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
        auto volume =
            quick_volume(v.mesh_path, *v.mesh, v.scalar, v.component, colormap, options, unit);
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
