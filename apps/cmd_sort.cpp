// tetrender sort-check MESH: every sorter against the independent ray verifier over random
// views. tetrender sort SCENE.json --order-out FILE: the back-to-front order for a scene.
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <apps/sort_setup.h>
#include <project/scene.h>
#include <sort/order_verifier.h>

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
    int width = 0, height = 0;
    if (!parse_image_size(args.size, width, height)) {
        std::fprintf(stderr, "tetrender: --size must be WxH with sides in [1, %d], not '%s'\n",
                     kMaxImageSide, args.size.c_str());
        return kExitUsage;
    }
    std::vector<SortMethod> methods;
    if (args.sort == "all") {
        methods = {SortMethod::kMpvo, SortMethod::kMpvoNonConvex, SortMethod::kExact,
                   SortMethod::kCentroid};
    } else if (auto m = parse_sort_method(args.sort)) {
        methods = {*m};
    } else {
        std::fprintf(stderr,
                     "tetrender: unknown --sort '%s' (auto, mpvo, mpvonc, exact, "
                     "centroid, all)\n",
                     args.sort.c_str());
        return kExitUsage;
    }
    auto loaded = load_tet_mesh(args.path, args.load);
    if (!loaded.ok()) return report_error(loaded.error());
    const Bounds3 bounds = loaded->tets.bounds();
    bool exact_violated = false;
    if (!args.json) {
        std::printf("%s: %zu tets; %d %s views at %dx%d%s\n", args.path.c_str(),
                    loaded->tets.num_real_tets(), args.views,
                    args.orthographic ? "orthographic" : "perspective", width, height,
                    args.inside ? ", eye inside" : "");
        std::printf("%-9s %5s %10s %10s %9s %9s %9s %9s %s\n", "sort", "view", "pairs",
                    "violations", "fallback", "cycles", "sort ms", "check ms", "");
    }
    for (SortMethod method : methods) {
        auto setup_or = prepare_sort(loaded->tets, method);
        if (!setup_or.ok()) return report_error(setup_or.error());
        SortSetup& setup = *setup_or;
        if (!setup.note.empty() && !args.json) {
            std::printf("%-9s note: %s\n", std::string(sort_method_name(method)).c_str(),
                        setup.note.c_str());
        }
        VisibilitySorter sorter;
        std::vector<CellId> order;
        std::size_t total_violations = 0;
        for (int v = 0; v < args.views; ++v) {
            const Camera camera =
                random_view(bounds, args.seed * 7919 + static_cast<std::uint64_t>(v),
                            args.orthographic, args.inside);
            const CameraFrame frame(camera, width, height);
            const SortStats stats = sorter.sort(setup.mesh, setup.adjacency,
                                                SortView::from_camera(frame), setup.method, order);
            const OrderCheck check = check_order(setup.mesh, order, frame);
            total_violations += check.violations;
            if (args.json) {
                nlohmann::json j = {{"sort", sort_method_name(method)},
                                    {"view", v},
                                    {"exact", setup.exact},
                                    {"convexified", setup.convexified},
                                    {"pairs", check.pairs},
                                    {"violations", check.violations},
                                    {"by_mpvo", stats.by_mpvo},
                                    {"by_fallback", stats.by_fallback},
                                    {"cells_in_cycles", stats.cells_in_cycles},
                                    {"sort_ms", stats.milliseconds},
                                    {"check_ms", check.milliseconds}};
                std::printf("%s\n", j.dump().c_str());
            } else {
                std::printf("%-9s %5d %10zu %10zu %9zu %9zu %9.2f %9.1f\n",
                            std::string(sort_method_name(method)).c_str(), v, check.pairs,
                            check.violations, stats.by_fallback, stats.cells_in_cycles,
                            stats.milliseconds, check.milliseconds);
            }
        }
        if (setup.exact && total_violations > 0) exact_violated = true;
        if (!args.json) {
            std::printf("%-9s total %zu violations%s%s\n",
                        std::string(sort_method_name(method)).c_str(), total_violations,
                        setup.exact ? " (claims exact)" : " (approximate)",
                        setup.convexified ? ", convexified" : "");
        }
    }
    if (exact_violated) {
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
    const auto method = parse_sort_method(args.sort);
    if (!method) {
        std::fprintf(stderr,
                     "tetrender: unknown --sort '%s' (auto, mpvo, mpvonc, exact, "
                     "centroid)\n",
                     args.sort.c_str());
        return kExitUsage;
    }
    auto scene = read_scene(args.scene);
    if (!scene.ok()) return report_error(scene.error());
    LoadOptions load;
    load.time_step = scene->time_step;
    auto loaded = load_tet_mesh(scene->mesh.string(), load);
    if (!loaded.ok()) return report_error(loaded.error());
    const bool all_tets = !loaded->used_delaunay && loaded->report.input_cells.size() == 1 &&
                          loaded->report.input_cells.count(CellType::kTetra) == 1;
    const std::size_t num_tets = loaded->tets.num_real_tets();
    auto setup = prepare_sort(std::move(loaded->tets), *method);
    if (!setup.ok()) return report_error(setup.error());
    if (!setup->note.empty()) std::fprintf(stderr, "tetrender: note: %s\n", setup->note.c_str());
    const CameraFrame frame(scene->camera, scene->width, scene->height);
    VisibilitySorter sorter;
    std::vector<CellId> order;
    const SortStats stats = sorter.sort(setup->mesh, setup->adjacency, SortView::from_camera(frame),
                                        setup->method, order);

    const std::string tmp = args.order_out + ".tmp";
    {
        std::ofstream out(tmp, std::ios::trunc);
        for (CellId t : order) out << (all_tets ? setup->mesh.source_cell(t) : t) << '\n';
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
        nlohmann::json j = {{"load_ms", loaded->read_ms},
                            {"tetrahedralize_ms", loaded->tetrahedralize_ms},
                            {"adjacency_ms", setup->adjacency_ms},
                            {"convexify_ms", setup->convexify_ms},
                            {"sort_ms", stats.milliseconds},
                            {"sort", sort_method_name(*method)},
                            {"exact", setup->exact},
                            {"convexified", setup->convexified},
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
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--size", args->size, "Rays per view as WxH (default 128x128)");
    cmd->add_flag("--orthographic", args->orthographic, "Orthographic views");
    cmd->add_flag("--inside", args->inside, "Put the eye inside the mesh's bounds");
    cmd->add_option("--sort", args->sort,
                    "auto, mpvo, mpvonc, exact, centroid, or all (default all)");
    cmd->add_option("--seed", args->seed, "Seed of the random views (default 1)");
    cmd->add_flag("--json", args->json, "One JSON line per sorter and view");
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
