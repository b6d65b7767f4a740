#pragma once
// The quick look's command-line options, one definition shared by `tetrender render MESH` and
// `tetrender-view MESH`: their names, help, parsing and error wording, turned into the
// library's QuickSceneOptions and QuickFileOptions (pipeline/quick_scene.h,
// pipeline/quick_file_scene.h). Image size, time step and what else a program takes are its own.

#include <core/result.h>
#include <pipeline/quick_file_scene.h>
#include <pipeline/quick_scene.h>

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace tr::apps {

struct QuickLookArgs {
    // The basics (added only when asked: the viewer defines its own, which apply to scene files
    // too).
    std::string scalar;
    std::string colormap = "viridis";
    std::optional<double> opacity;
    std::optional<double> unit_distance;
    // The rest.
    bool point_data = false, cell_data = false;
    std::string component = "magnitude";
    std::string view = "iso";
    std::string colormap_file;
    std::string look = "fitted";
    std::vector<double> range;  // lo, hi
    std::optional<double> range_percent;
    bool log_scale = false;
    std::vector<std::string> opacity_curve;  // t:a each
    std::vector<double> background;          // r, g, b
    double azimuth = 0, elevation = 0, zoom = 1;
    bool fit_bounds = false;
    std::vector<double> camera_position, camera_focal_point, camera_view_up;
    std::optional<double> camera_view_angle;
    std::string camera_file;  // a ParaView .pvcc camera
};

// Adds the options to `app` (--scalar, --colormap, --opacity and --unit-distance too when
// `with_basics`); `prefix` starts each help line ("Quick mode: ").
void add_quick_look_options(CLI::App& app, QuickLookArgs& args, bool with_basics,
                            const std::string& prefix);

// The options given on the command line that only a quick look takes, in the order added
// (for "--range is for a mesh file"), less those named in `except`.
std::vector<std::string> quick_look_options_given(const CLI::App& app,
                                                  const std::vector<std::string>& except = {});

// QuickSceneOptions from the arguments (width, height and time step left at their defaults
// for the caller). Errors (kInvalidArgument), each naming its option: --look, --component,
// --opacity-curve, --camera-* given in part, a camera that cannot look, a .pvcc file that
// does not read, both --camera and --camera-position.
Result<QuickSceneOptions> quick_scene_options(const QuickLookArgs& args);

// QuickFileOptions from the arguments (no more volumes).
QuickFileOptions quick_file_options(const QuickLookArgs& args);

}  // namespace tr::apps
