// tetrender info FILE: what a mesh file holds and what tetrahedralization makes of it.
#include <apps/cli_checks.h>
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <mesh/face_adjacency.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

namespace tr::apps {
namespace {

struct InfoArgs {
    std::string path;
    bool json = false;
    LoadOptions load;
};

nlohmann::json array_json(const Field& f) {
    nlohmann::json a;
    a["name"] = f.name;
    a["components"] = f.num_components;
    a["type"] = f.is_double() ? "float64" : "float32";
    const std::int64_t bad = first_non_finite(f);
    a["non_finite_values"] = bad >= 0;
    nlohmann::json ranges = nlohmann::json::array();
    if (bad < 0 && f.num_tuples() > 0) {
        for (int c = 0; c < f.num_components; ++c) {
            const auto [lo, hi] = field_range(f, c);
            ranges.push_back({lo, hi});
        }
        if (f.num_components > 1) {
            const auto [lo, hi] = field_range(f, -1);
            a["magnitude_range"] = {lo, hi};
        }
    }
    a["ranges"] = ranges;
    return a;
}

std::string format_range(const nlohmann::json& r) {
    std::ostringstream os;
    os << "[" << r[0].get<double>() << ", " << r[1].get<double>() << "]";
    return os.str();
}

void print_arrays(const char* title, const nlohmann::json& arrays) {
    std::printf("%s:%s\n", title, arrays.empty() ? " none" : "");
    for (const auto& a : arrays) {
        std::printf("  %-28s %d component%s %s", a["name"].get<std::string>().c_str(),
                    a["components"].get<int>(), a["components"].get<int>() == 1 ? " " : "s",
                    a["type"].get<std::string>().c_str());
        if (a["non_finite_values"].get<bool>()) {
            std::printf("  has NaN/Inf values\n");
            continue;
        }
        if (a.contains("magnitude_range")) {
            std::printf("  magnitude %s", format_range(a["magnitude_range"]).c_str());
        } else if (!a["ranges"].empty()) {
            std::printf("  range %s", format_range(a["ranges"][0]).c_str());
        }
        std::printf("\n");
    }
}

int run_info(const InfoArgs& args) {
    LoadOptions load = args.load;
    load.progress = terminal_progress();
    auto loaded_or = load_tet_mesh(args.path, load);
    if (!loaded_or.ok()) return report_error(loaded_or.error());
    const LoadedMesh& loaded = *loaded_or;
    const UnstructuredMesh& in = loaded.input;
    const TetMesh& mesh = loaded.tets;
    auto adjacency = build_face_adjacency(mesh);
    if (!adjacency.ok()) {
        Error e = adjacency.error();
        e.where = args.path + (e.where.empty() ? "" : ": " + e.where);
        return report_error(e);
    }
    const ConvexityReport convexity = check_convexity(mesh, *adjacency);
    const Bounds3 bounds = mesh.bounds();

    nlohmann::json j;
    j["file"] = args.path;
    j["format"] = in.format;
    j["points"] = in.num_points();
    j["cells"] = in.num_cells();
    nlohmann::json by_type = nlohmann::json::object();
    for (const auto& [type, count] : loaded.report.input_cells) {
        by_type[std::string(cell_type_name(type))] = count;
    }
    j["cells_by_type"] = by_type;
    j["quadratic_cells"] = loaded.report.num_quadratic_cells;
    j["time_steps"] = in.time_values.size();
    j["time_values"] = in.time_values;
    j["time_step_read"] = in.time_step;
    nlohmann::json point_arrays = nlohmann::json::array();
    for (const Field& f : in.point_fields) point_arrays.push_back(array_json(f));
    nlohmann::json cell_arrays = nlohmann::json::array();
    for (const Field& f : in.cell_fields) cell_arrays.push_back(array_json(f));
    j["point_arrays"] = point_arrays;
    j["cell_arrays"] = cell_arrays;
    j["surfaces"] = in.surfaces.size();
    j["tetrahedralization"] = {
        {"method", loaded.used_delaunay ? "delaunay" : "split"},
        {"tets", mesh.num_tets()},
        {"points", mesh.num_points()},
        {"merged_points", loaded.report.num_merged_points},
        {"inverted_cells", loaded.report.num_inverted_cells},
        {"degenerate_cells", loaded.report.num_degenerate_cells},
        {"degenerate_tets", loaded.report.num_degenerate_tets},
        {"tangled_cells", loaded.report.num_tangled_cells},
        {"skipped_cells", loaded.report.num_skipped_cells},
        {"volume", mesh.real_volume()},
    };
    j["bounds"] = {
        {bounds.lo.x, bounds.hi.x}, {bounds.lo.y, bounds.hi.y}, {bounds.lo.z, bounds.hi.z}};
    j["boundary_faces"] = adjacency->boundary_faces.size();
    j["convex"] = convexity.convex;
    j["boundary_components"] = convexity.num_boundary_components;
    j["reflex_edges"] = convexity.num_reflex_edges;
    const std::size_t bytes = mesh.byte_size() + adjacency->byte_size();
    j["memory_bytes"] = bytes;
    j["bytes_per_tet"] =
        mesh.num_tets() ? static_cast<double>(bytes) / static_cast<double>(mesh.num_tets()) : 0.0;
    j["read_ms"] = loaded.read_ms;
    j["tetrahedralize_ms"] = loaded.tetrahedralize_ms;

    if (args.json) {
        std::printf("%s\n", j.dump().c_str());
        return kExitOk;
    }
    std::printf("file:        %s\n", args.path.c_str());
    std::printf("format:      %s\n", in.format.c_str());
    std::printf("points:      %zu\n", in.num_points());
    std::printf("cells:       %zu", in.num_cells());
    const char* sep = " (";
    for (const auto& [name, count] : by_type.items()) {
        std::printf("%s%s %zu", sep, name.c_str(), count.get<std::size_t>());
        sep = ", ";
    }
    std::printf("%s\n", in.num_cells() ? ")" : " (point cloud)");
    if (loaded.report.num_quadratic_cells) {
        std::printf(
            "quadratic:   %zu cells: their corner nodes are used, mid-edge and face "
            "nodes ignored\n",
            loaded.report.num_quadratic_cells);
    }
    if (!in.time_values.empty()) {
        std::printf("time steps:  %zu (t = %g .. %g), read step %d\n", in.time_values.size(),
                    in.time_values.front(), in.time_values.back(), in.time_step);
    }
    print_arrays("point arrays", point_arrays);
    print_arrays("cell arrays", cell_arrays);
    if (!in.surfaces.empty()) {
        std::printf("surfaces:    %zu (", in.surfaces.size());
        for (std::size_t i = 0; i < in.surfaces.size(); ++i) {
            std::printf("%s%s %zu triangles", i ? ", " : "", in.surfaces[i].name.c_str(),
                        in.surfaces[i].triangles.size());
        }
        std::printf(")\n");
    }
    std::printf("tets:        %zu by %s, on %zu points; volume %.9g\n", mesh.num_tets(),
                loaded.used_delaunay ? "Delaunay tetrahedralization" : "conforming split",
                mesh.num_points(), mesh.real_volume());
    std::printf(
        "repairs:     %zu coincident points merged, %zu inverted cells re-oriented, "
        "%zu degenerate cells dropped, %zu zero-volume tets dropped",
        loaded.report.num_merged_points, loaded.report.num_inverted_cells,
        loaded.report.num_degenerate_cells, loaded.report.num_degenerate_tets);
    if (loaded.report.num_skipped_cells) {
        std::printf(", %zu unsupported cells skipped", loaded.report.num_skipped_cells);
    }
    if (loaded.report.num_tangled_cells) {
        std::printf(", %zu tangled cells (no corner sees all their faces: their tets overlap)",
                    loaded.report.num_tangled_cells);
    }
    std::printf("\n");
    std::printf("bounds:      x [%g, %g]  y [%g, %g]  z [%g, %g]\n", bounds.lo.x, bounds.hi.x,
                bounds.lo.y, bounds.hi.y, bounds.lo.z, bounds.hi.z);
    std::printf("boundary:    %zu faces in %zu component%s\n", adjacency->boundary_faces.size(),
                convexity.num_boundary_components,
                convexity.num_boundary_components == 1 ? "" : "s");
    if (convexity.convex) {
        std::printf("convex:      yes\n");
    } else {
        std::printf("convex:      no (%zu reflex edges, %zu non-manifold edges)\n",
                    convexity.num_reflex_edges, convexity.num_nonmanifold_edges);
    }
    std::printf("memory:      %.1f MB for tets, points, fields and adjacency (%.1f bytes/tet)\n",
                static_cast<double>(bytes) / 1e6, j["bytes_per_tet"].get<double>());
    std::printf("time:        read %.0f ms, tetrahedralize %.0f ms\n", loaded.read_ms,
                loaded.tetrahedralize_ms);
    return kExitOk;
}

}  // namespace

std::function<int()> add_info_command(CLI::App& app) {
    auto args = std::make_shared<InfoArgs>();
    CLI::App* cmd = app.add_subcommand(
        "info", "Describe a mesh file: cells, arrays, time steps, tets, boundary, convexity");
    cmd->add_option("file", args->path, "Mesh file (.vtu .vtk .exo .pvd ...)")->required();
    cmd->add_flag("--json", args->json, "Print one JSON object instead of text");
    cmd->add_option("--time-step", args->load.time_step, "Time step to read (default 0)")
        ->check(kNonNegativeInteger);
    cmd->add_option("--merge-tolerance", args->load.merge_tolerance,
                    "Also merge points closer than this fraction of the shortest edge at them "
                    "(default 0: exactly coincident points only)")
        ->check(kNonNegative);
    cmd->add_flag("--no-merge", args->load.no_merge, "Do not merge coincident points");
    return [args] { return run_info(*args); };
}

}  // namespace tr::apps
