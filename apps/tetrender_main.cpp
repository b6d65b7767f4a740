// The tetrender command line: one subcommand per job; exit codes in apps/cli_common.h.
#include <apps/cli_checks.h>
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <core/config.h>
#include <core/memory_budget.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

// Edit distance (insertions, deletions, substitutions, adjacent swaps) between a and b.
std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        for (std::size_t j = 1; j <= b.size(); ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1,
                                d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
            }
        }
    }
    return d[a.size()][b.size()];
}

// When `word` (the first argument, not an option) names no subcommand: one line saying so,
// with the nearest subcommand when one is within a third of its length (at least 2 edits),
// else the list of subcommands. Empty when `word` is a subcommand.
std::string unknown_subcommand_message(const CLI::App& app, const std::string& word) {
    std::string names;
    std::string nearest;
    std::size_t best = std::string::npos;
    for (const CLI::App* sub : app.get_subcommands({})) {
        const std::string& name = sub->get_name();
        if (name == word) return {};
        names += (names.empty() ? "" : ", ") + name;
        const std::size_t distance = edit_distance(word, name);
        if (distance < best) {
            best = distance;
            nearest = name;
        }
    }
    std::string message = "tetrender: unknown subcommand '" + word + "'";
    if (best <= std::max<std::size_t>(2, nearest.size() / 3)) {
        return message + " (did you mean '" + nearest + "'?)";
    }
    return message + "; subcommands: " + names;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace tr::apps;
    CLI::App app{"tetrender " TETRENDER_VERSION
                 ": volume rendering of unstructured FEM and CFD meshes"};
    app.set_version_flag("--version", std::string("tetrender ") + TETRENDER_VERSION);
    app.require_subcommand(1);
    // Every subcommand takes it (options a subcommand does not know fall through to here).
    std::string max_memory;
    app.add_option("--max-memory", max_memory,
                   "The most memory to take, e.g. 8G or 512M: a mesh or picture that would "
                   "need more is refused up front, saying what it would take (default: 80% of "
                   "this machine's memory)");
    app.fallthrough();
    auto info = add_info_command(app);
    auto tetrahedralize = add_tetrahedralize_command(app);
    auto demo = add_demo_command(app);
    auto sort_check = add_sort_check_command(app);
    auto sort = add_sort_command(app);
    auto render = add_render_command(app);
    auto flowvol = add_flowvol_command(app);
    auto compare = add_compare_command(app);
    auto advect = add_advect_command(app);
    auto spotnoise = add_spotnoise_command(app);
    auto methods = add_methods_command(app);
    for (CLI::App* sub : app.get_subcommands({})) {
        sub->footer(
            "Also: --max-memory SIZE (e.g. 8G): refuse up front what would need more "
            "(default: 80% of this machine's memory)");
    }
    if (argc > 1 && argv[1][0] != '-') {
        const std::string message = unknown_subcommand_message(app, argv[1]);
        if (!message.empty()) {
            std::fprintf(stderr, "%s\n", message.c_str());
            return kExitUsage;
        }
    }
    if (const auto code = parse_command_line(app, argc, argv, "tetrender")) return *code;
    if (!max_memory.empty()) {
        const auto budget = tr::parse_byte_size(max_memory);
        if (!budget.ok()) {
            std::fprintf(stderr, "tetrender: --max-memory: %s\n", budget.error().message.c_str());
            return kExitUsage;
        }
        tr::set_memory_budget(*budget);
    }
    try {
        if (app.got_subcommand("info")) return info();
        if (app.got_subcommand("tetrahedralize")) return tetrahedralize();
        if (app.got_subcommand("demo")) return demo();
        if (app.got_subcommand("sort-check")) return sort_check();
        if (app.got_subcommand("sort")) return sort();
        if (app.got_subcommand("render")) return render();
        if (app.got_subcommand("flowvol")) return flowvol();
        if (app.got_subcommand("compare")) return compare();
        if (app.got_subcommand("advect")) return advect();
        if (app.got_subcommand("spotnoise")) return spotnoise();
        if (app.got_subcommand("methods")) return methods();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tetrender: internal error: %s\n", e.what());
        return kExitError;
    }
    return kExitUsage;
}
