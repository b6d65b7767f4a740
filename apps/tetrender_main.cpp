// The tetrender command line: one subcommand per job; exit codes in apps/cli_common.h.
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <core/config.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    using namespace tr::apps;
    CLI::App app{"tetrender " TETRENDER_VERSION
                 ": volume rendering of unstructured FEM and CFD meshes"};
    app.set_version_flag("--version", std::string("tetrender ") + TETRENDER_VERSION);
    app.require_subcommand(1);
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
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return kExitUsage;
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
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tetrender: internal error: %s\n", e.what());
        return kExitError;
    }
    return kExitUsage;
}
