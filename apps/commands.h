#pragma once
// The tetrender subcommands: each registers its options on the CLI11 app and runs.

#include <CLI/CLI.hpp>

#include <functional>

namespace tr::apps {

// Adds the subcommand to `app`; the returned function runs it (after parsing) and returns the
// exit code.
std::function<int()> add_info_command(CLI::App& app);
std::function<int()> add_tetrahedralize_command(CLI::App& app);
std::function<int()> add_demo_command(CLI::App& app);
std::function<int()> add_sort_check_command(CLI::App& app);
std::function<int()> add_sort_command(CLI::App& app);
std::function<int()> add_render_command(CLI::App& app);
std::function<int()> add_flowvol_command(CLI::App& app);
std::function<int()> add_compare_command(CLI::App& app);
std::function<int()> add_advect_command(CLI::App& app);
std::function<int()> add_spotnoise_command(CLI::App& app);
std::function<int()> add_methods_command(CLI::App& app);

}  // namespace tr::apps
