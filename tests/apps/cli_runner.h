#pragma once
// Runs the tetrender executable from tests: exit code and captured stdout / stderr.

#include <string>

namespace tr::testing {

struct CliRun {
    int exit_code = -1;
    std::string out;
    std::string err;
};

// The tetrender executable under test.
std::string cli_path();

// Runs `tetrender <args>` (args is shell-quoted by the caller) and captures its output.
CliRun run_cli(const std::string& args);

// Runs a shell command line (quoted by the caller) with stdin empty, capturing its exit code
// (128 + the signal when killed), stdout and stderr.
CliRun run_captured(const std::string& command);

// Single-quotes a string for the shell.
std::string shell_quote(const std::string& s);

// A fresh empty directory under the system temp dir.
std::string make_temp_dir();

// ../shared/data beside the source tree.
std::string shared_data_dir();

// Whether the shared data is there. When it is not: false, and with CI=true also a test
// failure (realdata tests must run in CI); callers then GTEST_SKIP().
bool require_shared_data();

}  // namespace tr::testing
