// tetrender sort-check MESH: every sorter against the independent ray verifier over random
// views. tetrender sort SCENE.json --order-out FILE: the back-to-front order for a scene.
#include <apps/cli_checks.h>
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <pipeline/pipeline.h>
#include <pipeline/scene.h>
#include <pipeline/sort_check.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

namespace tr::apps {
namespace {

inline constexpr int kExitViolations = 3;  // an exact sorter put cells in the wrong order

struct SortCheckArgs {
    std::string path;
    int views = 8;
    std::string size = "128x128";
    bool orthographic = false;
    bool inside = false;
    std::string sort = "all";
    std::uint64_t seed = 1;
    bool json = false;
    LoadOptions load;
};

int run_sort_check(const SortCheckArgs& args) {
    SortCheckOptions options;
    if (!parse_image_size(args.size, options.width, options.height)) {
        std::fprintf(stderr, "tetrender: --size must be WxH with sides in [1, %d], not '%s'\n",
                     kMaxImageSide, args.size.c_str());
        return kExitUsage;
    }
    if (args.sort != "all") {
        auto method = sort_method_named(args.sort);
        if (!method.ok()) return report_usage(method.error());
        options.methods = {*method};
    }
    options.views = args.views;
    options.orthographic = args.orthographic;
    options.inside = args.inside;
    options.seed = args.seed;
    PipelineOptions pipeline_options;
    pipeline_options.load = args.load;
    pipeline_options.progress = terminal_progress();
    Pipeline pipeline(pipeline_options);
    SceneVolume volume;
    volume.mesh = args.path;
    volume.time_step = args.load.time_step;
    auto loaded = pipeline.mesh(volume);
    if (!loaded.ok()) return report_error(loaded.error());
    if (!args.json) {
        std::printf("%s: %zu tets; %d %s views at %dx%d%s\n", args.path.c_str(),
                    (*loaded)->tets.num_real_tets(), args.views,
                    args.orthographic ? "orthographic" : "perspective", options.width,
                    options.height, args.inside ? ", eye inside" : "");
        std::printf("%-9s %5s %10s %10s %9s %9s %9s %9s %s\n", "sort", "view", "pairs",
                    "violations", "fallback", "cycles", "sort ms", "check ms", "");
    }
    auto name = [](SortMethod m) { return std::string(sort_method_name(m)); };
    const auto on_method = [&](const SortCheckMethod& m) {
        if (!m.prepared.note.empty() && !args.json) {
            std::printf("%-9s note: %s\n", name(m.method).c_str(), m.prepared.note.c_str());
        }
    };
    const auto on_row = [&](const SortCheckRow& row) {
        if (args.json) {
            nlohmann::json j = {{"sort", name(row.method)},
                                {"view", row.view},
                                {"exact", row.claims_exact},
                                {"convexified", row.convexified},
                                {"pairs", row.check.pairs},
                                {"violations", row.check.violations},
                                {"by_mpvo", row.stats.by_mpvo},
                                {"by_fallback", row.stats.by_fallback},
                                {"cells_in_cycles", row.stats.cells_in_cycles},
                                {"sort_ms", row.stats.milliseconds},
                                {"check_ms", row.check.milliseconds}};
            std::printf("%s\n", j.dump().c_str());
        } else {
            std::printf("%-9s %5d %10zu %10zu %9zu %9zu %9.2f %9.1f\n", name(row.method).c_str(),
                        row.view, row.check.pairs, row.check.violations, row.stats.by_fallback,
                        row.stats.cells_in_cycles, row.stats.milliseconds, row.check.milliseconds);
        }
    };
    auto report = check_sorts(pipeline, volume, options, on_method, on_row);
    if (!report.ok()) return report_error(report.error());
    if (!args.json) {
        for (const SortCheckMethod& m : report->methods) {
            std::printf("%-9s total %zu violations%s%s\n", name(m.method).c_str(), m.violations,
                        m.prepared.exact ? " (claims exact)" : " (approximate)",
                        m.prepared.sorted->convexified ? ", convexified" : "");
        }
    }
    if (report->exact_violated) {
        std::fprintf(stderr, "tetrender: an exact sorter put cells in the wrong order\n");
        return kExitViolations;
    }
    return kExitOk;
}

struct SortArgs {
    std::string scene;
    std::string order_out;
    std::string sort = "auto";
    bool stats = false;
};

int run_sort(const SortArgs& args) {
    const auto method = sort_method_named(args.sort);
    if (!method.ok()) return report_usage(method.error());
    auto scene = read_scene(args.scene);
    if (!scene.ok()) return report_error(scene.error());
    if (scene->volumes.size() != 1) {
        return report_error(make_error(ErrorCode::kUnsupported,
                                       "a visibility order is of one volume; this scene has " +
                                           std::to_string(scene->volumes.size()),
                                       args.scene));
    }
    PipelineOptions pipeline_options;
    pipeline_options.progress = terminal_progress();
    Pipeline pipeline(pipeline_options);
    const SceneVolume& volume = scene->volumes[0];
    auto loaded_or = pipeline.mesh(volume);
    if (!loaded_or.ok()) return report_error(loaded_or.error());
    const LoadedMesh& loaded = **loaded_or;
    const bool all_tets = !loaded.used_delaunay && loaded.report.input_cells.size() == 1 &&
                          loaded.report.input_cells.count(CellType::kTetra) == 1;
    const std::size_t num_tets = loaded.tets.num_real_tets();
    const CameraFrame frame(scene->camera, scene->width, scene->height);
    auto view = pipeline.visibility_order(volume, frame, *method);
    if (!view.ok()) return report_error(view.error());
    if (!view->prepared.note.empty()) print_notes({view->prepared.note});
    const std::vector<CellId>& order = view->order;
    const SortStats& stats = view->stats;
    const TetMesh& sorted_mesh = view->prepared.mesh();

    const std::string tmp = args.order_out + ".tmp";
    {
        std::ofstream out(tmp, std::ios::trunc);
        for (CellId t : order) out << (all_tets ? sorted_mesh.source_cell(t) : t) << '\n';
        if (!out) {
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            return report_error(make_error(ErrorCode::kIo, "cannot write", args.order_out));
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, args.order_out, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        return report_error(make_error(ErrorCode::kIo, "cannot write", args.order_out));
    }
    if (args.stats) {
        nlohmann::json j = {{"load_ms", loaded.read_ms},
                            {"tetrahedralize_ms", loaded.tetrahedralize_ms},
                            {"adjacency_ms", view->prepared.sorted->adjacency_ms},
                            {"convexify_ms", view->prepared.sorted->convexify_ms},
                            {"sort_ms", stats.milliseconds},
                            {"sort", sort_method_name(*method)},
                            {"exact", view->exact},
                            {"convexified", view->prepared.sorted->convexified},
                            {"cells", stats.cells},
                            {"tets", num_tets},
                            {"by_mpvo", stats.by_mpvo},
                            {"by_fallback", stats.by_fallback},
                            {"cells_in_cycles", stats.cells_in_cycles},
                            {"cycles_broken", stats.cycles_broken},
                            {"numbering", all_tets ? "file cells" : "tets"}};
        std::printf("%s\n", j.dump().c_str());
    }
    return kExitOk;
}

}  // namespace

std::function<int()> add_sort_check_command(CLI::App& app) {
    auto args = std::make_shared<SortCheckArgs>();
    CLI::App* cmd = app.add_subcommand(
        "sort-check",
        "Check visibility orders against brute-force rays over random views (exit 3 when a "
        "sorter that claims exactness is wrong)");
    cmd->add_option("mesh", args->path, "Mesh file")->required();
    cmd->add_option("--views", args->views, "Random views per sorter (default 8)")
        ->check(in_range(1, 100000));
    cmd->add_option("--size", args->size, "Rays per view as WxH (default 128x128)");
    cmd->add_flag("--orthographic", args->orthographic, "Orthographic views");
    cmd->add_flag("--inside", args->inside, "Put the eye inside the mesh's bounds");
    cmd->add_option("--sort", args->sort,
                    "auto, mpvo, mpvonc, exact, centroid, or all (default all)");
    cmd->add_option("--seed", args->seed, "Seed of the random views (default 1)");
    cmd->add_flag("--json", args->json, "One JSON line per sorter and view");
    cmd->add_option("--time-step", args->load.time_step, "Time step to read (default 0)")
        ->check(kNonNegativeInteger);
    return [args] { return run_sort_check(*args); };
}

std::function<int()> add_sort_command(CLI::App& app) {
    auto args = std::make_shared<SortArgs>();
    CLI::App* cmd = app.add_subcommand(
        "sort", "Write the back-to-front cell order for a scene's camera, one index a line");
    cmd->add_option("scene", args->scene, "Scene file (.json)")->required();
    cmd->add_option("--order-out", args->order_out,
                    "Output: cell indices back to front, one a line (the file's own cell "
                    "numbers when it is all tets, otherwise the tets of `tetrender "
                    "tetrahedralize`)")
        ->required();
    cmd->add_option("--sort", args->sort, "auto (default), mpvo, mpvonc, exact, centroid");
    cmd->add_flag("--stats", args->stats,
                  "Print one JSON line: time of each phase (ms) and the sort's counts");
    return [args] { return run_sort(*args); };
}

}  // namespace tr::apps
