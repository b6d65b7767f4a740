#pragma once
// A scene for a quick look at a mesh without a scene file (`tetrender render MESH --scalar S`,
// the viewer given a mesh): a camera framing the bounds from a named direction and a colour
// map with an opacity ramp over the array's range.

#include <core/camera.h>
#include <core/result.h>
#include <pipeline/loaded_mesh.h>
#include <pipeline/scene.h>
#include <project/colormap_preset.h>

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
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
    int time_step = 0;   // recorded in the scene (the caller loads the mesh of that step)
    int width = 800, height = 600;
    std::string view = "iso";
    std::string colormap = "viridis";
    // When given, the colours of the first volume come from this preset (a ParaView colour map
    // file), spread over the range, instead of `colormap`.
    std::optional<ColormapPreset> colormap_preset;
    // The scalar range under the colour map and the opacity: `range` when given, else the
    // [range_percent, 100 - range_percent] percentiles of the finite point values (values
    // beyond take the end colours), 0: the whole range.
    std::optional<std::array<double, 2>> range;
    double range_percent = 1.0;
    // A log colour scale (`--log`): the colour map and the opacity spread evenly over log10 of
    // the range, which is then found among the positive values only (a range given must be
    // positive); values <= 0 take the low end's colour and opacity (a note counts them). The
    // transfer function stays one of the scalar (log_scaled, project/transfer_function.h), so
    // the field is interpolated linearly in each cell as always and a scene written from it
    // renders the same; the legend must be told (LegendSpec::log_scale).
    bool log_scale = false;
    // Opacity (of a slab one unit distance thick): a ramp from opacity_floor * max_opacity at
    // the range's low end to max_opacity at its high end, so that low values stay visible,
    // or, when given, `opacity_curve`: (t, a) points, t in [0, 1] across the range.
    double max_opacity = 0.5;
    double opacity_floor = 0.2;
    std::vector<std::array<double, 2>> opacity_curve;
    // 0: chosen so that a ray of the mesh's mean chord length (quick_look.h), through values
    // distributed as the mesh's points, reaches `ray_opacity` (or, when
    // unit_distance_of_diagonal > 0, that fraction of the bounds' diagonal).
    double unit_distance = 0;
    double unit_distance_of_diagonal = 0;
    double ray_opacity = 0.8;
    // A time series drawn with one transfer function (`--time-step all`): the meshes of its other
    // steps. The range, the log scale's positives, the opacity and the unit distance then come
    // from the values of every step (each step's strided to at most kSeriesValuesPerStep when
    // there are more), and an array is said to be constant only when it is over the series.
    std::vector<const TetMesh*> series;
    // The camera: `camera` when given (used as is), else one looking from `view` turned by
    // azimuth and elevation (degrees), fitting the object's projected extent (`fit_extent`;
    // false: the bounds' sphere, as before 2026-11), narrowed by `zoom`.
    std::optional<Camera> camera;
    double azimuth = 0, elevation = 0, zoom = 1;
    bool fit_extent = true;
    double view_angle = 30.0;
    Vec3 background{0.0};
};

// The array a quick look shows when none is named: the first point array, else the first cell
// array; empty when the mesh has none.
std::string default_quick_scalar(const TetMesh& mesh);

// A copy of `mesh` with a point array `name` of ones (what a quick look of a mesh without
// arrays shows: where the mesh is). Cost: a copy of the mesh.
std::shared_ptr<const TetMesh> with_constant_field(const TetMesh& mesh, const std::string& name);

// A copy of `mesh` without its point array `name`, so that a cell array of the same name is
// what `name` reads (`--cell-data`). Cost: a copy of the mesh.
std::shared_ptr<const TetMesh> without_point_field(const TetMesh& mesh, const std::string& name);

// The quick look of tetrender before 2026-11 (`--look classic`): the whole range, an opacity
// ramp 0 -> 0.3, a unit distance of a twentieth of the bounds' diagonal, the bounds' sphere
// framed. Pictures comparable with older ones; the realdata method tests keep to it.
QuickSceneOptions classic_quick_look();

// The scene: `mesh_path` (named in the scene, for --write-scene) with the array's range under the
// colour map and the opacity, the camera and unit distance as the options say.
// Errors: an unknown view or colour map, an unknown array (listing them), a component out of
// range, an array with no finite value, a bad range or opacity curve.
Result<Scene> make_quick_scene(const std::filesystem::path& mesh_path, const TetMesh& mesh,
                               const QuickSceneOptions& options);

// One more volume of a quick look at several meshes in one space.
struct QuickVolume {
    std::filesystem::path mesh_path;
    const TetMesh* mesh = nullptr;
    std::string scalar;
    int component = -1;
    std::string colormap;  // empty: the next of viridis, inferno, coolwarm, gray not yet used
    std::vector<const TetMesh*> series;  // as QuickSceneOptions::series, for this volume
};

// A time series' values per step, at most (QuickSceneOptions::series).
inline constexpr std::size_t kSeriesValuesPerStep = std::size_t{1} << 20;

// A scene of several volumes in one space (written with `volumes`): the first as above (its
// scalar, component and colour map from `options`), each of `more` with its own array and
// colour map over its own range, the camera framing the union of their bounds. Errors as
// above, the message naming the volume's index when it is not the first. The unit distance
// chosen from the first volume holds for all. `notes`, when given, receives what the user should
// know (an array that is constant, a range given outside the data's).
Result<Scene> make_quick_scene(const std::filesystem::path& mesh_path, const TetMesh& mesh,
                               const QuickSceneOptions& options,
                               const std::vector<QuickVolume>& more,
                               std::vector<std::string>* notes = nullptr);

}  // namespace tr
