#include <mesh/point_data.h>
#include <project/colormap.h>

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

Result<Scene> make_quick_scene(const std::filesystem::path& mesh_path, const TetMesh& mesh,
                               const QuickSceneOptions& options) {
    Scene scene;
    SceneVolume volume;
    volume.mesh = mesh_path;
    volume.scalar = options.scalar;
    volume.component = options.component;
    scene.width = options.width;
    scene.height = options.height;
    TR_TRY(const Vec3 from, view_direction(options.view));
    const Bounds3 bounds = mesh.bounds();
    scene.camera = framing_camera(bounds, from, options.view_angle);
    TR_TRY(const std::vector<float> values, point_scalar(mesh, volume.scalar, volume.component));
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (float v : values) {
        if (!std::isfinite(v)) continue;
        lo = std::min<double>(lo, v);
        hi = std::max<double>(hi, v);
    }
    if (!(hi >= lo)) {
        return make_error(ErrorCode::kInvalidMesh,
                          "array '" + volume.scalar + "' has no finite value", mesh_path.string());
    }
    const double unit =
        options.unit_distance > 0 ? options.unit_distance : bounds.diagonal() / 20.0;
    TR_TRY(volume.transfer_function,
           make_quick_transfer_function(options.colormap, lo, hi, options.max_opacity, unit));
    scene.volumes.push_back(std::move(volume));
    return scene;
}

}  // namespace tr
