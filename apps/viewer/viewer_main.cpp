// tetrender-view: the interactive viewer (GLFW window, OpenGL 3.3 core, Dear ImGui panel), and
// its headless screenshot mode for tests and benchmarks. This file: the command line and the
// start-up (display, GL context, ImGui); the rest of the viewer is in its neighbours.
#include <apps/cli_checks.h>
#include <apps/cli_common.h>
#include <apps/quick_look_args.h>
#include <apps/viewer/headless_orbit.h>
#include <apps/viewer/interactive_loop.h>
#include <apps/viewer/viewer_panel.h>
#include <apps/viewer/viewer_scene.h>
#include <apps/viewer/volume_view.h>
#include <core/memory_budget.h>
#include <pipeline/annotations.h>
#include <project/colormap.h>
#include <project/gl/gl_renderer.h>

#include <CLI/CLI.hpp>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui/backends/imgui_impl_glfw.h>
#include <imgui/backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tr::viewer {
namespace {

struct Args {
    std::string input;
    std::string scalar;
    std::string screenshot;
    std::string frames_dir;
    int frames = 1;
    double orbit = 0;
    std::string size;
    std::string integrator = "exp-texture";
    std::string sort = "auto";
    // How the picture is made (overriding the scene's `method` key) and the particle-based
    // modes' accumulation.
    std::string method;
    int repetitions = 0;
    std::optional<std::int64_t> seed;
    int batch = 0;
    std::string colormap;
    double opacity = 0;
    double unit_distance = 0;
    int time_step = 0;
    std::string max_memory;
    std::string vectors;        // splat: textured vector splats of this point array
    int cycle = 0;              // splat: textures in their cycle
    apps::QuickLookArgs quick;  // mesh mode: the quick look's options beyond the four above
    std::vector<std::string> quick_given;  // those given (refused with a scene file)
    bool panel_in_screenshot = false;
    std::string legend = "auto";  // on, off, or auto: on for a mesh, off for a scene file
    int exit_after_frames = 0;    // interactive mode: quit after this many frames (tests)
    // A flow volume from the command line (as `tetrender flowvol` names the options).
    std::string flowvol_vectors;
    std::vector<double> seed_center, seed_size, seed_normal;
    FlowVolumeSpec flow;  // resolution, steps, split threshold
    double flow_dt = 0;   // 0: chosen from the flow (resolve_flow_spec)
};

std::string glfw_error_text;
void on_glfw_error(int, const char* description) { glfw_error_text = description; }

// What the display offers when a 3.3 core context cannot be had: a default context's version.
std::string available_gl() {
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    GLFWwindow* probe = glfwCreateWindow(16, 16, "probe", nullptr, nullptr);
    if (!probe) return "no OpenGL context at all";
    glfwMakeContextCurrent(probe);
    using GetString = const unsigned char* (*)(unsigned int);
    auto get_string = reinterpret_cast<GetString>(glfwGetProcAddress("glGetString"));
    std::string text = "?";
    if (get_string) {
        const auto* version = reinterpret_cast<const char*>(get_string(0x1F02));   // GL_VERSION
        const auto* renderer = reinterpret_cast<const char*>(get_string(0x1F01));  // GL_RENDERER
        text =
            std::string("OpenGL ") + (version ? version : "?") + ", " + (renderer ? renderer : "?");
    }
    glfwMakeContextCurrent(nullptr);
    glfwDestroyWindow(probe);
    return text;
}

int fail(const std::string& message) {
    std::fprintf(stderr, "tetrender-view: %s\n", message.c_str());
    return apps::kExitError;
}

// The viewer's options from the command line, checked: kExitOk, or the exit code of a message
// already printed.
int viewer_options(const Args& args, ViewerOptions& options, Integrator& integrator) {
    if (!args.max_memory.empty()) {
        const auto budget = parse_byte_size(args.max_memory);
        if (!budget.ok()) {
            std::fprintf(stderr, "tetrender-view: --max-memory: %s\n",
                         budget.error().message.c_str());
            return apps::kExitUsage;
        }
        set_memory_budget(*budget);
    }
    options.input = args.input;
    options.colormap = args.colormap;
    options.max_opacity = args.opacity;
    options.unit_distance = args.unit_distance;
    if (!apps::is_scene_file(args.input)) {
        // A mesh: the quick look `tetrender render` makes, with the same options.
        apps::QuickLookArgs quick = args.quick;
        quick.scalar = args.scalar;
        if (!args.colormap.empty()) quick.colormap = args.colormap;
        if (args.opacity > 0) quick.opacity = args.opacity;
        if (args.unit_distance > 0) quick.unit_distance = args.unit_distance;
        auto made = apps::quick_scene_options(quick);
        if (!made.ok()) return apps::report_error(made.error());
        options.quick = std::move(made).value();
        options.quick.time_step = args.time_step;
        options.file = apps::quick_file_options(quick);
    } else if (!args.quick_given.empty()) {
        std::fprintf(stderr, "tetrender-view: %s is for a mesh file; a scene file says it itself\n",
                     args.quick_given.front().c_str());
        return apps::kExitUsage;
    }
    if (!args.flowvol_vectors.empty()) {
        FlowVolumeSpec spec = args.flow;
        spec.vectors = args.flowvol_vectors;
        // What is not given is chosen from the flow, as `tetrender flowvol` chooses it.
        spec.choose = {.seed_center = args.seed_center.empty(),
                       .seed_size = args.seed_size.empty(),
                       .dt = args.flow_dt == 0};
        if (!spec.choose.seed_center) {
            spec.seed_center = Vec3(args.seed_center[0], args.seed_center[1], args.seed_center[2]);
        }
        if (!spec.choose.seed_size) {
            spec.seed_width = args.seed_size[0];
            spec.seed_height = args.seed_size[1];
        }
        if (!spec.choose.dt) spec.dt = args.flow_dt;
        if (!args.seed_normal.empty()) {
            spec.seed_normal = Vec3(args.seed_normal[0], args.seed_normal[1], args.seed_normal[2]);
        }
        options.flow_volume = spec;
    }
    const auto named = integrator_named(args.integrator);
    if (!named.ok() || *named == Integrator::kExact) {
        std::fprintf(stderr,
                     "tetrender-view: unknown --integrator '%s' (exp-texture, "
                     "preintegrated)\n",
                     args.integrator.c_str());
        return apps::kExitUsage;
    }
    integrator = *named;
    const auto method = sort_method_named(args.sort);
    if (!method.ok()) {
        std::fprintf(stderr, "tetrender-view: %s\n", method.error().message.c_str());
        return apps::kExitUsage;
    }
    options.sort = *method;
    if (!args.method.empty() && !view_method_named(args.method)) {
        std::fprintf(stderr,
                     "tetrender-view: unknown --method '%s' (projected-tetrahedra, pbvr-image, "
                     "pbvr-object, splat, texture-advection, spot-noise)\n",
                     args.method.c_str());
        return apps::kExitUsage;
    }
    if (!args.size.empty()) {
        if (!apps::parse_image_size(args.size, options.width, options.height)) {
            std::fprintf(stderr,
                         "tetrender-view: --size must be WxH with sides in [1, %d], not %s\n",
                         kMaxImageSide, args.size.c_str());
            return apps::kExitUsage;
        }
        options.size_given = true;
    }
    if (!args.colormap.empty()) {
        const auto names = colormap_names();
        if (std::find(names.begin(), names.end(), args.colormap) == names.end()) {
            std::fprintf(stderr, "tetrender-view: unknown --colormap '%s'\n",
                         args.colormap.c_str());
            return apps::kExitUsage;
        }
    }
    const bool headless = !args.screenshot.empty();
    if (headless) {
        if (const Status ok = apps::check_output_path(args.screenshot, {".png", ".pfm"});
            !ok.ok()) {
            return apps::report_usage(ok.error());
        }
    }
    if (!args.frames_dir.empty()) {
        std::error_code made;
        std::filesystem::create_directories(args.frames_dir, made);
        if (!headless || made || !std::filesystem::is_directory(args.frames_dir)) {
            return fail(headless ? args.frames_dir + ": cannot make the frames folder"
                                 : "--frames-dir writes the frames of a --screenshot orbit");
        }
    }
    return apps::kExitOk;
}

// The scene loaded and its method resolved (several volumes: how they are drawn fused):
// kExitOk, or the exit code of a message already printed.
int load_scene(const Args& args, const ViewerOptions& options, bool headless, ViewerScene& vs) {
    auto loaded = load_viewer_scene(options);
    if (!loaded.ok()) return apps::report_error(loaded.error());
    vs = std::move(loaded).value();
    MethodArgs method_args{args.method, args.repetitions, args.seed, args.batch,
                           headless,    args.vectors,     args.cycle};
    auto resolved = resolve_method(*vs.pipeline, vs.scene, method_args);
    if (!resolved.ok()) return apps::report_error(resolved.error());
    vs.method = resolved->method;
    vs.pbvr = resolved->pbvr;
    // Splats are of the file's points: the convexification's (appended) are not drawn.
    if (auto loaded = vs.pipeline->mesh(vs.volume()); loaded.ok()) {
        vs.pbvr.splat_points = (*loaded)->tets.num_points();
    }
    if (!vs.fused.empty()) {
        // Several volumes: drawn fused on the CPU. projected-tetrahedra (the default) is the
        // exact fused picture, as `tetrender render` draws such a scene.
        if (animated_method(vs.method)) {
            return fail(std::string(view_method_name(vs.method)) +
                        ": the viewer draws it for a scene of one volume; use `tetrender render`");
        }
        if (vs.method == ViewMethod::kPbvrObject) {
            return fail(
                "pbvr-object: the viewer draws a scene of several volumes with pbvr-image or "
                "the exact fused picture (projected-tetrahedra); use `tetrender render` for "
                "pbvr-object");
        }
        vs.fused_mode = vs.method == ViewMethod::kPbvrImage ? FusedMode::kPbvrImage
                        : headless                          ? FusedMode::kExact
                                                            : FusedMode::kProgressive;
        std::fprintf(stderr,
                     "tetrender-view: note: %zu volumes, drawn fused on the CPU (%s): projected "
                     "tetrahedra cannot order the cells of intersecting meshes\n",
                     vs.fused.size(), fused_mode_name(vs.fused_mode).data());
    }
    return apps::kExitOk;
}

// `tetrender render`'s legend of the scene onto a screenshot of it (pipeline/annotations.h); a
// picture too small for it is still written, with a note.
void draw_legend(ViewerScene& vs, Image& image) {
    Scene scene = vs.scene;
    scene.width = image.width;
    scene.height = image.height;
    AnnotationOptions legend;
    const Status drawn = annotate(image, scene, *vs.pipeline, legend);
    if (!drawn.ok()) {
        std::fprintf(stderr, "tetrender-view: note: no legend: %s\n",
                     drawn.error().message.c_str());
    }
}

// The window (hidden when headless), its OpenGL context and the ImGui panel; the view drawn in
// it, interactively or along the headless orbit. Returns the exit code.
int run_on_display(const Args& args, ViewerScene& vs, Integrator integrator, bool headless) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland)) {
        return fail("no display: run under xvfb-run or set DISPLAY");
    }
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        return fail("no display: run under xvfb-run or set DISPLAY (GLFW: " + glfw_error_text +
                    ")");
    }
    struct Terminate {
        ~Terminate() {
#if !defined(__SANITIZE_ADDRESS__)
            glfwTerminate();
#endif
            // Under AddressSanitizer the display stays open until exit: closing it unloads
            // Mesa's driver, and LeakSanitizer could then not name the module of the driver's
            // own never-freed allocations (scripts/lsan.supp suppresses them by module).
        }
    } terminate;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, headless ? GLFW_FALSE : GLFW_TRUE);
    std::string title = "tetrender-view: " + vs.volume().mesh.filename().string();
    for (std::size_t v = 1; v < vs.scene.volumes.size(); ++v)
        title += " + " + vs.scene.volumes[v].mesh.filename().string();
    GLFWwindow* window =
        glfwCreateWindow(vs.scene.width, vs.scene.height, title.c_str(), nullptr, nullptr);
    if (!window) {
        const std::string why = glfw_error_text;
        return fail("no OpenGL 3.3 core context (GLFW: " + why + "); the display offers " +
                    available_gl());
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(headless ? 0 : 1);
    auto info = gl::check_gl_context();
    if (!info.ok()) {
        glfwDestroyWindow(window);
        return fail(info.error().message);
    }
    int code = apps::kExitOk;
    {
        auto renderer = gl::GlTetRenderer::create();
        if (!renderer.ok()) {
            glfwDestroyWindow(window);
            return fail(renderer.error().message);
        }
        const bool ui = !headless || args.panel_in_screenshot;
        if (ui) {
            IMGUI_CHECKVERSION();
            ImGui::CreateContext();
            ImGui::GetIO().IniFilename = nullptr;
            ImGui_ImplGlfw_InitForOpenGL(window, true);
            ImGui_ImplOpenGL3_Init("#version 330 core");
        }
        {
            VolumeView view(vs, **renderer, integrator, !headless);
            // The legend: render's in a screenshot, the panel's (ImGui) in the window.
            const bool legend =
                args.legend == "on" ||
                (args.legend == "auto" &&
                 legend_by_default(apps::is_scene_file(args.input), args.quick.look == "classic"));
            std::optional<ViewerPanel> panel;
            if (ui) {
                panel.emplace(view);
                panel->set_legend(legend);
            }
            if (headless) {
                HeadlessOptions shot{args.screenshot, args.frames, args.orbit, args.frames_dir, {}};
                if (legend && !panel)
                    shot.annotate = [&vs](Image& image) { draw_legend(vs, image); };
                code = run_headless_orbit(view, panel ? &*panel : nullptr, shot);
            } else {
                code = run_interactive(window, view, *panel, args.exit_after_frames);
            }
        }
        if (ui) {
            ImGui_ImplOpenGL3_Shutdown();
            ImGui_ImplGlfw_Shutdown();
            ImGui::DestroyContext();
        }
    }
    glfwDestroyWindow(window);
    return code;
}

int run(const Args& args) {
    ViewerOptions options;
    Integrator integrator = Integrator::kExpTexture;
    if (const int code = viewer_options(args, options, integrator); code != apps::kExitOk) {
        return code;
    }
    const bool headless = !args.screenshot.empty();
    ViewerScene vs;
    if (const int code = load_scene(args, options, headless, vs); code != apps::kExitOk) {
        return code;
    }
    // Headless, the quick look's notes come after the picture, so that an error found while
    // drawing (a seed outside the mesh) stays one line.
    const std::vector<std::string> notes = std::move(vs.notes);
    if (!headless) apps::print_notes(notes);
    if (!vs.sort.note.empty() && vs.fused.empty())
        std::fprintf(stderr, "tetrender-view: note: %s\n", vs.sort.note.c_str());
    if (vs.scene.flow_volume && vs.scene.flow_volume->context) {
        std::fprintf(stderr, "tetrender-view: note: the flow volume's context veil is not drawn\n");
    }
    const int code = run_on_display(args, vs, integrator, headless);
    if (headless && code == apps::kExitOk) apps::print_notes(notes);
    return code;
}

}  // namespace
}  // namespace tr::viewer

int main(int argc, char** argv) {
    tr::viewer::Args args;
    tr::apps::set_program_name("tetrender-view");
    CLI::App app{
        "tetrender-view: interactive viewer: projected tetrahedra (OpenGL 3.3) or particle-based "
        "volume rendering (CPU, progressive). Keys: left drag rotate, right drag / wheel zoom, "
        "middle drag / shift+left pan, r reset, m next method, s screenshot, p panel, ? keys, "
        "Esc quit."};
    app.add_option("input", args.input, "Scene file (.json) or mesh file")->required();
    app.add_option("--scalar", args.scalar,
                   "Mesh mode: the array to show (default: the first point array, else the "
                   "first cell array)");
    app.add_option("--screenshot", args.screenshot,
                   "Headless: render --frames frames, write the last (.png or .pfm), exit");
    app.add_option("--frames", args.frames, "Headless: frames along the orbit (default 1)")
        ->check(tr::apps::in_range(1, 100000));
    app.add_option("--orbit", args.orbit,
                   "Headless: degrees the camera turns about the scene's up axis (view_up) over "
                   "the frames, without rolling")
        ->check(tr::apps::kFinite);
    app.add_option("--frames-dir", args.frames_dir,
                   "Headless: also write every frame as DIR/frame_0000.png, ... (a movie: "
                   "ffmpeg -i DIR/frame_%04d.png out.mp4)");
    app.add_option("--size", args.size, "Window / image size WxH (default 960x600 or the scene's)");
    app.add_option("--integrator", args.integrator, "exp-texture (default) or preintegrated");
    app.add_option("--sort", args.sort, "auto (default), mpvo, mpvonc, exact, centroid");
    app.add_option("--method", args.method,
                   "projected-tetrahedra (default, OpenGL), pbvr-image or pbvr-object (particles "
                   "on the CPU, accumulated while the camera is still), splat (the mesh's points "
                   "splatted on the CPU), texture-advection or spot-noise (the scene's "
                   "frames, looping; their keys are the scene's) (default: the scene's). A "
                   "scene of several volumes is "
                   "drawn fused on the CPU: projected-tetrahedra is then the exact fused "
                   "picture, pbvr-image fused particles");
    app.add_option("--vectors", args.vectors,
                   "Splat: textured vector splats along this 3-component point array, their "
                   "texture cycle playing (headless: frame i of --frames draws cycle frame i)");
    app.add_option("--cycle", args.cycle, "Splat: textures in the vector splats' cycle (default 8)")
        ->check(tr::apps::in_range(1, tr::kMaxSplatCycle));
    app.add_option("--repetitions", args.repetitions,
                   "Particle-based: repetitions to accumulate (default: the scene's, else 64 "
                   "headless, 1024 interactively)")
        ->check(tr::apps::in_range(1, tr::viewer::kMaxRepetitions));
    app.add_option("--seed", args.seed,
                   "Particle-based: the seed (batch b of a view uses seed + b; default: the "
                   "scene's, else 1)");
    app.add_option("--batch", args.batch,
                   "Particle-based: repetitions per batch (default 16 for pbvr-image, 4 for "
                   "pbvr-object)")
        ->check(tr::apps::in_range(1, tr::viewer::kMaxBatch));
    app.add_option("--colormap", args.colormap,
                   "viridis, coolwarm, inferno, gray or a ParaView preset name (default: the "
                   "scene's colours, or viridis)");
    app.add_option(
           "--opacity", args.opacity,
           "Largest opacity: a mesh's ramp's top (default 0.5, as `tetrender render`), or a "
           "scene's opacity points scaled to it")
        ->check(tr::apps::in_range(0.0, 0.999));
    app.add_option("--max-memory", args.max_memory,
                   "The most memory to take, e.g. 8G: a mesh that would need more is refused up "
                   "front (default: 80% of this machine's memory)");
    app.add_option("--time-step", args.time_step, "Mesh mode: the time step to read (default 0)")
        ->check(tr::apps::kNonNegativeInteger);
    tr::apps::add_quick_look_options(app, args.quick, false, "Mesh mode: ");
    app.add_option("--unit-distance", args.unit_distance,
                   "Unit distance of the opacities (default: the scene's, or for a mesh the "
                   "quick look's: a typical ray through the object reaches opacity 0.8)")
        ->check(tr::apps::kPositive);
    auto* vectors = app.add_option("--flowvol-vectors", args.flowvol_vectors,
                                   "Flow volume: grow the dye through this 3-component point "
                                   "array (replaces a scene's flow_volume)");
    app.add_option("--seed-center", args.seed_center,
                   "Flow volume: dye polygon centre x,y,z (default: where the flow is fastest)")
        ->expected(3)
        ->delimiter(',')
        ->check(tr::apps::kFinite)
        ->needs(vectors);
    app.add_option("--seed-size", args.seed_size,
                   "Flow volume: dye polygon width,height (default: an eighth of the diagonal)")
        ->expected(2)
        ->delimiter(',')
        ->check(tr::apps::kPositive)
        ->needs(vectors);
    app.add_option("--seed-normal", args.seed_normal,
                   "Flow volume: dye polygon normal x,y,z (default: the flow at its centre)")
        ->expected(3)
        ->delimiter(',')
        ->check(tr::apps::kFinite)
        ->needs(vectors);
    app.add_option("--seed-res", args.flow.seed_resolution,
                   "Flow volume: quads per side of the polygon (default 32)")
        ->check(tr::apps::in_range(1, 4096))
        ->needs(vectors);
    app.add_option("--steps", args.flow.steps, "Flow volume: layers (default 50)")
        ->check(tr::apps::in_range(1, 100000))
        ->needs(vectors);
    app.add_option("--dt", args.flow_dt,
                   "Flow volume: time per layer (default: the front travels 40% of the diagonal "
                   "over the steps)")
        ->check(tr::apps::kPositive)
        ->needs(vectors);
    app.add_option("--split-threshold", args.flow.split_threshold,
                   "Flow volume: split front edges longer than this many seed spacings "
                   "(default 2; 0: off)")
        ->check(tr::apps::kFinite)
        ->needs(vectors);
    app.add_option("--legend", args.legend,
                   "The colour legend (name, range, ticks): on, off, or auto (default: on for a "
                   "mesh, off for a scene file); a screenshot carries render's, the window (and "
                   "--panel-in-screenshot) the panel's")
        ->check(CLI::IsMember({"auto", "on", "off"}));
    app.add_flag("--panel-in-screenshot", args.panel_in_screenshot,
                 "Headless: draw the ImGui panel into the screenshot");
    app.add_option("--exit-after-frames", args.exit_after_frames,
                   "Interactive mode: quit after N frames and any flow volume grown (for tests)")
        ->group("");
    if (const auto code = tr::apps::parse_command_line(app, argc, argv, "tetrender-view")) {
        return *code;
    }
    args.quick_given = tr::apps::quick_look_options_given(app);
    if (app.count("--time-step") > 0) args.quick_given.push_back("--time-step");
    try {
        return tr::viewer::run(args);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tetrender-view: %s\n", e.what());
        return tr::apps::kExitError;
    }
}
