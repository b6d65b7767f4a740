#pragma once
// A scene for a quick look at a mesh without a scene file (`tetrender render MESH --scalar S`,
// the viewer given a mesh): a camera framing the bounds from a named direction and a colour
// map with an opacity ramp over the array's range.

#include <core/camera.h>
#include <core/result.h>
#include <project/scene.h>

#include <filesystem>
#include <pipeline/loaded_mesh.h>
#include <string>
#include <vector>

namespace tr {

// The direction quick looks come from: above, in front and to the right.
inline constexpr Vec3 kDefaultViewDirection{1.0, -1.2, 0.8};

// "iso" (kDefaultViewDirection), "+x", "-x", "+y", "-y", "+z", "-z": where the eye lies from the
// centre. Error kInvalidArgument naming the choices.
Result<Vec3> view_direction(const std::string& name);
std::vector<std::string> view_names();

struct QuickSceneOptions {
    std::string scalar;  // required: a point or cell array of the mesh
    int component = -1;  // -1: magnitude
    int width = 800, height = 600;
    std::string view = "iso";
    std::string colormap = "viridis";
    double max_opacity = 0.3;  // the ramp's top, at the range's high end
    double unit_distance = 0;  // 0: the bounds' diagonal / 20
    double view_angle = 30.0;
};

// The scene: `mesh_path` (named in the scene, for --write-scene) with the array's finite range
// under the colour map and an opacity ramp 0 -> max_opacity, the camera framing the bounds.
// Errors: an unknown view or colour map, an unknown array (listing them), a component out of
// range, an array with no finite value.
Result<Scene> make_quick_scene(const std::filesystem::path& mesh_path, const TetMesh& mesh,
                               const QuickSceneOptions& options);

// One more volume of a quick look at several meshes in one space.
struct QuickVolume {
    std::filesystem::path mesh_path;
    const TetMesh* mesh = nullptr;
    std::string scalar;
    int component = -1;
    std::string colormap;  // empty: the next of viridis, inferno, coolwarm, gray not yet used
};

// A scene of several volumes in one space (written with `volumes`): the first as above (its
// scalar, component and colour map from `options`), each of `more` with its own array and
// colour map over its own range, the camera framing the union of their bounds. Errors as
// above, the message naming the volume's index when it is not the first.
Result<Scene> make_quick_scene(const std::filesystem::path& mesh_path, const TetMesh& mesh,
                               const QuickSceneOptions& options,
                               const std::vector<QuickVolume>& more);

}  // namespace tr
