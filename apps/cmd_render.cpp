// tetrender render: a scene file, or a mesh with --scalar for a quick look, to PNG or PFM.
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <apps/flowvol_render.h>
#include <apps/flowvol_setup.h>
#include <apps/sort_setup.h>
#include <core/parallel.h>
#include <io/read_surface.h>
#include <io/write_image.h>
#include <mesh/point_data.h>
#include <project/colormap.h>
#include <project/cpu_renderer.h>
#include <project/opaque_geometry.h>
#include <project/reference_raycaster.h>
#include <project/scene.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>

namespace tr::apps {
namespace {

struct RenderArgs {
    std::string input;
    std::string output;
    std::string sort = "auto";
    std::string integrator = "preintegrated";
    int threads = 0;
    bool stats = false;
    // Quick mode (input is a mesh).
    std::string scalar;
    std::string component = "magnitude";
    std::string size = "800x600";
    std::string view = "iso";
    std::string colormap = "viridis";
    std::string write_scene_path;
};

bool is_scene_file(const std::string& path) {
    return path.size() > 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

Result<Vec3> view_direction(const std::string& view) {
    static const std::map<std::string, Vec3> views = {
        {"iso", {1.0, -1.2, 0.8}}, {"+x", {1, 0, 0}}, {"-x", {-1, 0, 0}}, {"+y", {0, 1, 0}},
        {"-y", {0, -1, 0}},        {"+z", {0, 0, 1}}, {"-z", {0, 0, -1}}};
    auto it = views.find(view);
    if (it == views.end()) {
        return make_error(ErrorCode::kInvalidArgument,
                          "unknown --view '" + view + "' (iso, +x, -x, +y, -y, +z, -z)");
    }
    return it->second;
}

// The scene for a quick look at `mesh`: camera framing the bounds, colour map over the range.
Result<Scene> quick_scene(const RenderArgs& args, const TetMesh& mesh) {
    Scene scene;
    scene.mesh = std::filesystem::absolute(args.input);
    scene.scalar = args.scalar;
    if (args.component != "magnitude") {
        try {
            scene.component = std::stoi(args.component);
        } catch (...) {
            return make_error(ErrorCode::kInvalidArgument,
                              "--component must be 'magnitude' or an index");
        }
    }
    if (!parse_image_size(args.size, scene.width, scene.height)) {
        return make_error(ErrorCode::kInvalidArgument, "--size must be WxH with sides in [1, " +
                                                           std::to_string(kMaxImageSide) +
                                                           "], not " + args.size);
    }
    TR_TRY(const Vec3 from, view_direction(args.view));
    const Bounds3 bounds = mesh.bounds();
    scene.camera = framing_camera(bounds, from);
    scene.camera.view_angle = 30.0;
    TR_TRY(const std::vector<float> values, point_scalar(mesh, scene.scalar, scene.component));
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (float v : values) {
        if (!std::isfinite(v)) continue;
        lo = std::min<double>(lo, v);
        hi = std::max<double>(hi, v);
    }
    TR_TRY(scene.transfer_function,
           make_quick_transfer_function(args.colormap, lo, hi, 0.3, bounds.diagonal() / 20.0));
    return scene;
}

// The scene's opaque surfaces: files read here, side sets taken from the mesh as read.
Result<std::vector<SurfaceMesh>> opaque_surfaces(const Scene& scene, const UnstructuredMesh& input,
                                                 const TetMesh& mesh,
                                                 const FaceAdjacency& adjacency,
                                                 std::vector<Vec3>& colors) {
    std::vector<SurfaceMesh> surfaces;
    for (const OpaqueSpec& spec : scene.opaque) {
        if (spec.boundary) {
            surfaces.push_back(boundary_surface(mesh, adjacency));
            colors.push_back(spec.color);
            continue;
        }
        if (!spec.file.empty()) {
            TR_TRY(SurfaceMesh surface, read_surface(spec.file));
            surfaces.push_back(std::move(surface));
            colors.push_back(spec.color);
            continue;
        }
        bool found = false;
        for (const SurfaceMesh& s : input.surfaces) {
            if (spec.side_set == "*" || s.name == spec.side_set) {
                surfaces.push_back(s);
                colors.push_back(spec.color);
                found = true;
            }
        }
        if (!found) {
            std::string names;
            for (const SurfaceMesh& s : input.surfaces)
                names += (names.empty() ? "" : ", ") + s.name;
            return make_error(ErrorCode::kNotFound,
                              "no side set '" + spec.side_set + "' in the mesh (it has: " +
                                  (names.empty() ? std::string("none") : names) + ")",
                              scene.mesh.string());
        }
    }
    return surfaces;
}

// A scene with a flow volume: the dye grown from the scene's mesh, drawn without sorting over
// the opaque geometry (the scene's scalar is checked but not drawn).
int render_flow_volume(const Scene& scene, const LoadedMesh& loaded, const RenderArgs& args) {
    const std::string mesh_name = scene.mesh.string();
    FlowVolumeSpec spec = *scene.flow_volume;
    const std::vector<double>& times = loaded.input.time_values;
    if (spec.unsteady && !spec.start_time && times.size() > 1) {
        spec.start_time = times[static_cast<std::size_t>(scene.time_step)];
    }
    auto adjacency = build_face_adjacency(loaded.tets);
    if (!adjacency.ok()) return report_error(with_where(adjacency.error(), mesh_name));
    auto velocity = load_velocity(mesh_name, loaded, spec.vectors, spec.unsteady);
    if (!velocity.ok()) return report_error(velocity.error());
    const auto start = std::chrono::steady_clock::now();
    auto fv = grow_flow_volume(loaded.tets, *adjacency, *velocity, dye_seed(spec),
                               flow_volume_options(spec), terminal_progress());
    if (!fv.ok()) return report_error(with_where(fv.error(), args.input));
    const double grow_ms = ms_since(start);
    std::vector<Vec3> opaque_colors;
    auto surfaces = opaque_surfaces(scene, loaded.input, loaded.tets, *adjacency, opaque_colors);
    if (!surfaces.ok()) return report_error(surfaces.error());
    FlowVolumeView view{scene.camera, scene.width, scene.height, scene.background, {}};
    for (std::size_t i = 0; i < surfaces->size(); ++i) {
        view.opaque.push_back({&(*surfaces)[i], opaque_colors[i]});
    }
    view.dye_color = spec.color;
    view.dye_opacity = spec.opacity;
    view.unit_distance = spec.unit_distance.value_or(0.0);
    SurfaceMesh boundary;
    if (spec.context) {
        boundary = boundary_surface(loaded.tets, *adjacency);
        view.context = &boundary;
    }
    const auto render_start = std::chrono::steady_clock::now();
    FlowVolumeRenderer renderer(*fv, loaded.tets, view);
    const Image image = renderer.render_up_to(fv->mesh.num_tets());
    const double render_ms = ms_since(render_start);
    const Status written = write_image(image, args.output);
    if (!written.ok()) return report_error(written.error());
    if (args.stats) {
        nlohmann::json j = {{"load_ms", loaded.read_ms},
                            {"tetrahedralize_ms", loaded.tetrahedralize_ms},
                            {"grow_ms", grow_ms},
                            {"render_ms", render_ms},
                            {"layers", fv->layer_tets.size()},
                            {"flow_volume_tets", fv->mesh.num_tets()},
                            {"particles_inserted", fv->particles_inserted},
                            {"particles_stopped", fv->particles_stopped},
                            {"width", scene.width},
                            {"height", scene.height}};
        std::printf("%s\n", j.dump().c_str());
    }
    return kExitOk;
}

int run_render(const RenderArgs& args) {
    const auto method = parse_sort_method(args.sort);
    if (!method) {
        std::fprintf(stderr,
                     "tetrender: unknown --sort '%s' (auto, mpvo, mpvonc, exact, "
                     "centroid)\n",
                     args.sort.c_str());
        return kExitUsage;
    }
    const bool reference = args.integrator == "reference";
    const auto integrator =
        reference ? std::optional(Integrator::kExact) : parse_integrator(args.integrator);
    if (!integrator) {
        std::fprintf(stderr,
                     "tetrender: unknown --integrator '%s' (exact, preintegrated, "
                     "exp-texture, reference)\n",
                     args.integrator.c_str());
        return kExitUsage;
    }
    const bool scene_mode = is_scene_file(args.input);
    if (!scene_mode && args.scalar.empty()) {
        std::fprintf(stderr,
                     "tetrender: rendering a mesh file needs --scalar NAME (or give a "
                     "scene .json)\n");
        return kExitUsage;
    }
    if (args.threads > 0) set_thread_count(args.threads);

    Scene scene;
    if (scene_mode) {
        auto read = read_scene(args.input);
        if (!read.ok()) return report_error(read.error());
        scene = std::move(read).value();
    }
    LoadOptions load;
    load.time_step = scene.time_step;
    auto loaded = load_tet_mesh(scene_mode ? scene.mesh.string() : args.input, load);
    if (!loaded.ok()) return report_error(loaded.error());
    if (!scene_mode) {
        auto quick = quick_scene(args, loaded->tets);
        if (!quick.ok()) return report_error(with_where(quick.error(), args.input));
        scene = std::move(quick).value();
        if (!args.write_scene_path.empty()) {
            const Status written = write_scene(scene, args.write_scene_path);
            if (!written.ok()) return report_error(written.error());
        }
    }
    const std::string mesh_name = scene.mesh.string();
    auto scalar = point_scalar(loaded->tets, scene.scalar, scene.component);
    if (!scalar.ok()) return report_error(with_where(scalar.error(), mesh_name));
    for (std::size_t p = 0; p < scalar->size(); ++p) {
        if (!std::isfinite((*scalar)[p])) {
            return report_error(make_error(
                ErrorCode::kInvalidMesh,
                "array '" + scene.scalar + "' is not finite at point " + std::to_string(p),
                mesh_name));
        }
    }
    if (scene.flow_volume) {
        if (reference) {
            return report_error(make_error(ErrorCode::kUnsupported,
                                           "--integrator reference does not draw flow volumes",
                                           args.input));
        }
        return render_flow_volume(scene, *loaded, args);
    }
    const std::size_t cells = loaded->tets.num_real_tets();
    if (reference) {
        // The brute-force reference ray caster: no sort, no opaque geometry.
        if (!scene.opaque.empty()) {
            return report_error(make_error(ErrorCode::kUnsupported,
                                           "--integrator reference draws no opaque geometry",
                                           args.input));
        }
        const auto start = std::chrono::steady_clock::now();
        const Image image = render_reference(loaded->tets, *scalar, scene.transfer_function,
                                             CameraFrame(scene.camera, scene.width, scene.height),
                                             scene.background);
        const double raster_ms = ms_since(start);
        const Status written = write_image(image, args.output);
        if (!written.ok()) return report_error(written.error());
        if (args.stats) {
            nlohmann::json j = {{"load_ms", loaded->read_ms},
                                {"tetrahedralize_ms", loaded->tetrahedralize_ms},
                                {"raster_ms", raster_ms},
                                {"cells", cells},
                                {"integrator", "reference"}};
            std::printf("%s\n", j.dump().c_str());
        }
        return kExitOk;
    }
    auto setup = prepare_sort(std::move(loaded->tets), *method);
    if (!setup.ok()) return report_error(with_where(setup.error(), mesh_name));
    if (!setup->note.empty()) std::fprintf(stderr, "tetrender: note: %s\n", setup->note.c_str());
    // Virtual points (convexification) get scalar 0: they are never drawn.
    scalar->resize(setup->mesh.num_points(), 0.0f);

    const CameraFrame frame(scene.camera, scene.width, scene.height);
    VisibilitySorter sorter;
    std::vector<CellId> order;
    const SortStats sort_stats = sorter.sort(setup->mesh, setup->adjacency,
                                             SortView::from_camera(frame), setup->method, order);
    const auto shader_start = std::chrono::steady_clock::now();
    const SegmentShader shader(scene.transfer_function, *integrator, longest_edge(setup->mesh));
    const double shader_ms = ms_since(shader_start);
    std::vector<Vec3> opaque_colors;
    auto surfaces =
        opaque_surfaces(scene, loaded->input, setup->mesh, setup->adjacency, opaque_colors);
    if (!surfaces.ok()) return report_error(surfaces.error());
    std::vector<OpaqueSurface> opaque;
    for (std::size_t i = 0; i < surfaces->size(); ++i) {
        opaque.push_back({&(*surfaces)[i], opaque_colors[i]});
    }
    const auto opaque_start = std::chrono::steady_clock::now();
    const OpaqueLayer layer =
        opaque.empty() ? OpaqueLayer{} : render_opaque(opaque, frame, scene.background);
    const double opaque_ms = ms_since(opaque_start);
    RenderInputs in;
    if (!opaque.empty()) {
        in.opaque_color = &layer.color;
        in.opaque_depth = &layer.depth;
    }
    in.mesh = &setup->mesh;
    in.scalar = *scalar;
    in.order = order;
    in.shader = &shader;
    in.camera = &frame;
    in.background = scene.background;
    RenderStats render_stats;
    const Image image = render_projected_tetrahedra(in, &render_stats);
    const Status written = write_image(image, args.output);
    if (!written.ok()) return report_error(written.error());
    if (args.stats) {
        nlohmann::json j = {{"load_ms", loaded->read_ms},
                            {"tetrahedralize_ms", loaded->tetrahedralize_ms},
                            {"adjacency_ms", setup->adjacency_ms},
                            {"convexify_ms", setup->convexify_ms},
                            {"sort_ms", sort_stats.milliseconds},
                            {"shader_ms", shader_ms},
                            {"opaque_ms", opaque_ms},
                            {"raster_ms", render_stats.raster_ms},
                            {"cells", cells},
                            {"cells_drawn", render_stats.cells_drawn},
                            {"fragments", render_stats.fragments},
                            {"sort", sort_method_name(*method)},
                            {"sort_exact", setup->exact},
                            {"integrator", integrator_name(*integrator)},
                            {"threads", thread_count()},
                            {"width", scene.width},
                            {"height", scene.height}};
        std::printf("%s\n", j.dump().c_str());
    }
    return kExitOk;
}

}  // namespace

std::function<int()> add_render_command(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand(
        "render", "Render a scene file, or a mesh with --scalar for a quick look, to PNG/PFM");
    cmd->add_option("input", args->input, "Scene file (.json) or mesh file")->required();
    cmd->add_option("-o,--output", args->output, "Output image (.png, or .pfm for floats)")
        ->required();
    cmd->add_option("--sort", args->sort, "auto (default), mpvo, mpvonc, exact, centroid");
    cmd->add_option("--integrator", args->integrator,
                    "preintegrated (default), exact, exp-texture, or reference (the slow "
                    "brute-force ray caster the others are tested against)");
    cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    cmd->add_flag("--stats", args->stats,
                  "Print one JSON line: time of each phase (ms), cells drawn, fragments");
    cmd->add_option("--scalar", args->scalar, "Quick mode: the array to render");
    cmd->add_option("--component", args->component,
                    "Quick mode: 'magnitude' (default) or a component index");
    cmd->add_option("--size", args->size, "Quick mode: image size WxH (default 800x600)");
    cmd->add_option("--view", args->view, "Quick mode: iso (default), +x, -x, +y, -y, +z, -z");
    cmd->add_option("--colormap", args->colormap,
                    "Quick mode: viridis (default), coolwarm, inferno, gray");
    cmd->add_option("--write-scene", args->write_scene_path,
                    "Quick mode: save the scene used, to edit and re-render");
    return [args] { return run_render(*args); };
}

}  // namespace tr::apps
