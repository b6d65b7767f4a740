// tetrender tetrahedralize IN -o OUT.vtu: split cells, Delaunay a point cloud, mesh a closed
// surface with TetGen, or fill a non-convex mesh's concavities with virtual tets.
#include <apps/cli_checks.h>
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <core/config.h>
#include <io/write_vtu.h>
#include <mesh/face_adjacency.h>

#if TETRENDER_HAS_TETGEN
#include <io/read_surface.h>
#include <mesh/copyleft/convexify.h>
#include <mesh/copyleft/tetgen_mesher.h>
#endif

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace tr::apps {
namespace {

struct TetrahedralizeArgs {
    std::string input;
    std::string output;
    bool delaunay = false;
    std::string tetgen_switches;
    bool tetgen = false;
    double quality = 2.0;
    double max_volume = 0.0;
    bool convexify = false;
    LoadOptions load;
};

// Surfaces TetGen meshes (io/read_surface.h), by extension, whatever the case.
bool is_surface_file(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".stl" || ext == ".off" || ext == ".ply" || ext == ".obj" || ext == ".poly";
}

int run_tetrahedralize(const TetrahedralizeArgs& args) {
    if (static_cast<int>(args.delaunay) + static_cast<int>(args.tetgen) +
            static_cast<int>(args.convexify) >
        1) {
        std::fprintf(stderr,
                     "tetrender: --delaunay, --tetgen and --convexify exclude each other\n");
        return kExitUsage;
    }
    if (const Status ok = check_output_path(args.output, {".vtu"}); !ok.ok()) {
        return report_usage(ok.error());
    }
    TetMesh mesh;
    WriteVtuOptions write_options;
    if (args.tetgen) {
#if TETRENDER_HAS_TETGEN
        auto surface = read_surface(args.input);
        if (!surface.ok()) return report_error(surface.error());
        TetgenOptions options;
        options.quality_ratio = args.quality;
        options.max_volume = args.max_volume;
        options.extra_switches = args.tetgen_switches;
        auto meshed = tetgen_mesh_surface(*surface, options);
        if (!meshed.ok()) return report_error(with_where(meshed.error(), args.input));
        mesh = std::move(meshed).value();
#else
        return report_error(make_error(ErrorCode::kUnsupported,
                                       "this build has no TetGen (TETRENDER_WITH_TETGEN=OFF)"));
#endif
    } else {
        if (is_surface_file(args.input)) {
            return report_error(make_error(ErrorCode::kUnsupported,
                                           "a surface: --tetgen meshes the inside of a closed one",
                                           args.input));
        }
        LoadOptions load = args.load;
        load.delaunay = args.delaunay;
        load.progress = terminal_progress();
        auto loaded = load_tet_mesh(args.input, load);
        if (!loaded.ok()) return report_error(loaded.error());
        mesh = std::move(loaded->tets);
    }
    std::size_t num_virtual = 0;
    if (args.convexify) {
#if TETRENDER_HAS_TETGEN
        auto adjacency = build_face_adjacency(mesh);
        if (!adjacency.ok()) return report_error(with_where(adjacency.error(), args.input));
        auto report = convexify(mesh, *adjacency);
        if (!report.ok()) return report_error(with_where(report.error(), args.input));
        num_virtual = report->num_virtual_tets;
        write_options.include_virtual = true;
#else
        return report_error(make_error(ErrorCode::kUnsupported,
                                       "this build has no TetGen (TETRENDER_WITH_TETGEN=OFF)"));
#endif
    }
    const Status written = write_vtu(mesh, args.output, write_options);
    if (!written.ok()) return report_error(written.error());
    std::printf("wrote %s: %zu tets", args.output.c_str(), mesh.num_real_tets());
    if (args.convexify) std::printf(" + %zu virtual tets (cell array \"virtual\")", num_virtual);
    std::printf(", %zu points\n", mesh.num_points());
    return kExitOk;
}

}  // namespace

std::function<int()> add_tetrahedralize_command(CLI::App& app) {
    auto args = std::make_shared<TetrahedralizeArgs>();
    CLI::App* cmd = app.add_subcommand(
        "tetrahedralize", "Turn a mesh, point cloud or closed surface into tets, written as .vtu");
    cmd->add_option("input", args->input,
                    "Mesh, point cloud (.csv, points-only .vtu/.vtp) or, "
                    "with --tetgen, a closed surface (.stl .off .ply .poly)")
        ->required();
    cmd->add_option("-o,--output", args->output, "Output .vtu")->required();
    cmd->add_flag("--delaunay", args->delaunay,
                  "Delaunay tetrahedralization of the points, ignoring any cells (CGAL)");
    // Given at all (no value, '' or switches) it asks for TetGen: counted after parsing, since
    // CLI11 calls `each` for no value and for '' with nothing.
    CLI::Option* tetgen = cmd->add_option("--tetgen", args->tetgen_switches,
                                          "Mesh a closed surface with TetGen; extra TetGen "
                                          "switches (may be none: --tetgen, or --tetgen '')")
                              ->expected(0, 1);
    cmd->add_option("--quality", args->quality,
                    "With --tetgen: radius-edge ratio bound (-q), 0 for none (default 2)")
        ->check(kNonNegative);
    cmd->add_option("--max-volume", args->max_volume,
                    "With --tetgen: largest tet volume (-a), 0 for none (default)")
        ->check(kNonNegative);
    cmd->add_flag("--convexify", args->convexify,
                  "Add virtual tets filling the space between the mesh and a box around it "
                  "(TetGen), marked by the cell array \"virtual\"");
    cmd->add_option("--merge-tolerance", args->load.merge_tolerance,
                    "Also merge points closer than this fraction of the shortest edge at them")
        ->check(kNonNegative);
    cmd->add_option("--time-step", args->load.time_step, "Time step to read (default 0)")
        ->check(kNonNegativeInteger);
    return [args, tetgen] {
        args->tetgen = tetgen->count() > 0;
        return run_tetrahedralize(*args);
    };
}

}  // namespace tr::apps
