#include <apps/cli_checks.h>
#include <apps/quick_look_args.h>
#include <core/camera.h>
#include <pipeline/paraview_camera.h>
#include <project/colormap_preset.h>

#include <stdexcept>

namespace tr::apps {
namespace {

// The options add_quick_look_options adds beyond the basics, in that order.
const std::vector<std::string>& quick_only_options() {
    static const std::vector<std::string> names = {"--point-data",
                                                   "--cell-data",
                                                   "--component",
                                                   "--view",
                                                   "--look",
                                                   "--range",
                                                   "--range-percentile",
                                                   "--log",
                                                   "--opacity-curve",
                                                   "--background",
                                                   "--azimuth",
                                                   "--elevation",
                                                   "--zoom",
                                                   "--fit-bounds",
                                                   "--camera-position",
                                                   "--camera-focal-point",
                                                   "--camera-view-up",
                                                   "--camera-view-angle",
                                                   "--camera",
                                                   "--colormap-file"};
    return names;
}

Vec3 vec3(const std::vector<double>& v) { return Vec3(v[0], v[1], v[2]); }

}  // namespace

void add_quick_look_options(CLI::App& app, QuickLookArgs& args, bool with_basics,
                            const std::string& prefix) {
    const auto help = [&](const std::string& text) { return prefix + text; };
    if (with_basics) {
        app.add_option("--scalar", args.scalar,
                       help("the array to render (default: the first point array, else the "
                            "first cell array, else where the mesh is)"));
    }
    app.add_flag("--point-data", args.point_data,
                 help("the point array of that name, when it is cell data too (default)"));
    app.add_flag("--cell-data", args.cell_data,
                 help("the cell array of that name, when it is point data too"))
        ->excludes("--point-data");
    app.add_option("--component", args.component,
                   help("'magnitude' (default) or a component index"));
    app.add_option("--view", args.view, help("iso (default), +x, -x, +y, -y, +z, -z"));
    if (with_basics) {
        app.add_option("--colormap", args.colormap,
                       help("viridis (default), coolwarm, inferno, gray, or a ParaView preset "
                            "name (Cool to Warm, Jet, Rainbow Uniform, Black-Body Radiation, "
                            "...)"));
    }
    app.add_option("--look", args.look,
                   help("fitted (default: robust range, every value visible, the object "
                        "framed) or classic (tetrender's look before 2026-11, for comparable "
                        "pictures)"));
    app.add_option("--range", args.range,
                   help("the scalar range under the colour map and opacity, lo,hi (default: "
                        "the 1st to 99th percentile of the point values)"))
        ->expected(2)
        ->delimiter(',');
    app.add_option("--range-percentile", args.range_percent,
                   help("the range from the P-th to the (100-P)-th percentile (default 1; 0: "
                        "the whole range)"))
        ->check(in_range(0.0, 49.0));
    app.add_flag("--log", args.log_scale,
                 help("a log colour scale: colours and opacity spread over log10 of the range "
                      "(of the positive values; those <= 0 take the low end's colour), the "
                      "legend's ticks at powers of ten"));
    if (with_basics) {
        app.add_option("--opacity", args.opacity,
                       help("the opacity at the range's top (default 0.5), a fifth of it at the "
                            "bottom"))
            ->check(in_range(0.001, 0.999));
    }
    app.add_option("--opacity-curve", args.opacity_curve,
                   help("opacity points t:a,... with t in [0, 1] across the range"))
        ->delimiter(',');
    if (with_basics) {
        app.add_option("--unit-distance", args.unit_distance,
                       help("the thickness a slab of the stated opacity has (default: chosen so "
                            "that a typical ray through the object reaches opacity 0.8)"))
            ->check(kPositive);
    }
    app.add_option("--background", args.background, help("background r,g,b in [0, 1]"))
        ->expected(3)
        ->delimiter(',')
        ->check(in_range(0.0, 1.0));
    app.add_option("--azimuth", args.azimuth,
                   help("turn the view about the up axis, degrees (ParaView's Azimuth)"))
        ->check(in_range(-360.0, 360.0));
    app.add_option("--elevation", args.elevation,
                   help("raise the view towards the up axis, degrees (ParaView's Elevation)"))
        ->check(in_range(-89.0, 89.0));
    app.add_option("--zoom", args.zoom, help("magnify by this factor (VTK's Zoom)"))
        ->check(in_range(0.01, 100.0));
    app.add_flag("--fit-bounds", args.fit_bounds,
                 help("frame the bounds' sphere instead of the object's projected extent"));
    app.add_option("--camera-position", args.camera_position,
                   help("the camera as ParaView gives it: position x,y,z (with "
                        "--camera-focal-point, --camera-view-up, --camera-view-angle)"))
        ->expected(3)
        ->delimiter(',');
    app.add_option("--camera-focal-point", args.camera_focal_point, help("x,y,z"))
        ->expected(3)
        ->delimiter(',');
    app.add_option("--camera-view-up", args.camera_view_up, help("x,y,z (default +z)"))
        ->expected(3)
        ->delimiter(',');
    app.add_option("--camera-view-angle", args.camera_view_angle,
                   help("vertical view angle, degrees (default 30)"))
        ->check(in_range(0.1, 179.0));
    app.add_option("--camera", args.camera_file,
                   help("a camera ParaView saved (.pvcc: Save Camera) to look from"));
    app.add_option("--colormap-file", args.colormap_file,
                   help("a ParaView colour-map preset file (JSON); --colormap names the preset "
                        "in it (default: its first)"));
}

std::vector<std::string> quick_look_options_given(const CLI::App& app,
                                                  const std::vector<std::string>& except) {
    std::vector<std::string> given;
    for (const std::string& name : quick_only_options()) {
        if (std::find(except.begin(), except.end(), name) != except.end()) continue;
        if (app.count(name) > 0) given.push_back(name);
    }
    return given;
}

Result<QuickSceneOptions> quick_scene_options(const QuickLookArgs& args) {
    if (args.look != "fitted" && args.look != "classic") {
        return make_error(ErrorCode::kInvalidArgument,
                          "--look takes fitted or classic, not '" + args.look + "'");
    }
    QuickSceneOptions options = args.look == "classic" ? classic_quick_look() : QuickSceneOptions{};
    options.scalar = args.scalar;
    if (args.component != "magnitude") {
        // A whole number >= 0: "-1" and "1.5" are not components (they used to mean the
        // magnitude and component 1).
        std::size_t used = 0;
        int component = -1;
        try {
            component = std::stoi(args.component, &used);
        } catch (...) {
            used = 0;
        }
        if (used != args.component.size() || component < 0) {
            return make_error(ErrorCode::kInvalidArgument,
                              "--component must be 'magnitude' or an index 0, 1, 2, ..., not '" +
                                  args.component + "'");
        }
        options.component = component;
    }
    options.view = args.view;
    options.colormap = args.colormap;
    if (!args.colormap_file.empty()) {
        // --colormap names the preset in the file (the first when it is the default).
        const std::string name = args.colormap == "viridis" ? "" : args.colormap;
        TR_TRY(options.colormap_preset, read_colormap_preset(args.colormap_file, name));
    }
    if (!args.range.empty()) options.range = std::array<double, 2>{args.range[0], args.range[1]};
    if (args.range_percent) options.range_percent = *args.range_percent;
    options.log_scale = args.log_scale;
    if (args.opacity) {
        options.max_opacity = *args.opacity;
        if (!options.opacity_curve.empty())
            options.opacity_curve = {{0.0, 0.0}, {1.0, *args.opacity}};
    }
    if (!args.opacity_curve.empty()) options.opacity_curve.clear();
    for (const std::string& point : args.opacity_curve) {
        const auto colon = point.find(':');
        try {
            if (colon == std::string::npos) throw std::invalid_argument(point);
            std::size_t used_t = 0, used_a = 0;
            const double t = std::stod(point.substr(0, colon), &used_t);
            const double a = std::stod(point.substr(colon + 1), &used_a);
            if (used_t != colon || used_a != point.size() - colon - 1) {
                throw std::invalid_argument(point);
            }
            options.opacity_curve.push_back({t, a});
        } catch (const std::exception&) {
            return make_error(ErrorCode::kInvalidArgument,
                              "--opacity-curve takes t:a points (t in [0, 1] across the range), "
                              "not '" +
                                  point + "'");
        }
    }
    if (args.unit_distance) options.unit_distance = *args.unit_distance;
    if (!args.background.empty()) options.background = vec3(args.background);
    options.azimuth = args.azimuth, options.elevation = args.elevation, options.zoom = args.zoom;
    if (args.fit_bounds) options.fit_extent = false;
    if (!args.camera_file.empty() && !args.camera_position.empty()) {
        return make_error(ErrorCode::kInvalidArgument,
                          "--camera takes a .pvcc file; give it or the --camera-* values, not "
                          "both");
    }
    if (!args.camera_position.empty() || !args.camera_focal_point.empty()) {
        if (args.camera_position.empty() || args.camera_focal_point.empty()) {
            return make_error(ErrorCode::kInvalidArgument,
                              "--camera-position and --camera-focal-point go together");
        }
        Camera camera;
        camera.position = vec3(args.camera_position);
        camera.focal_point = vec3(args.camera_focal_point);
        camera.view_up = args.camera_view_up.empty() ? Vec3(0, 0, 1) : vec3(args.camera_view_up);
        if (args.camera_view_angle) camera.view_angle = *args.camera_view_angle;
        TR_TRY_STATUS(check_camera(camera));
        options.camera = camera;
    }
    if (!args.camera_file.empty()) {
        TR_TRY(options.camera, read_paraview_camera(args.camera_file));
    }
    return options;
}

QuickFileOptions quick_file_options(const QuickLookArgs& args) {
    QuickFileOptions file;
    file.point_data = args.point_data;
    file.cell_data = args.cell_data;
    return file;
}

}  // namespace tr::apps
