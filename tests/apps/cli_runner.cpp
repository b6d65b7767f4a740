#include <tests/apps/cli_runner.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <sys/wait.h>

namespace tr::testing {

std::string shell_quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) {
        if (c == '\'') {
            q += "'\\''";
        } else {
            q += c;
        }
    }
    return q + "'";
}

std::string make_temp_dir() {
    std::random_device rd;
    auto dir = std::filesystem::temp_directory_path() /
               ("tetrender_test_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(dir);
    return dir.string();
}

std::string cli_path() { return TETRENDER_CLI_PATH; }

std::string shared_data_dir() { return TETRENDER_SHARED_DATA_DIR; }

bool require_shared_data() {
    if (std::filesystem::is_directory(shared_data_dir())) return true;
    const char* ci = std::getenv("CI");
    if (ci && std::string(ci) == "true") {
        ADD_FAILURE() << "CI=true but the shared data folder is missing: " << shared_data_dir();
    }
    return false;
}

CliRun run_captured(const std::string& command) {
    const std::string dir = make_temp_dir();
    const std::string out = dir + "/out.txt";
    const std::string err = dir + "/err.txt";
    const std::string line =
        command + " >" + shell_quote(out) + " 2>" + shell_quote(err) + " </dev/null";
    const int status = std::system(line.c_str());
    CliRun run;
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    auto slurp = [](const std::string& path) {
        std::ifstream in(path);
        std::stringstream ss;
        ss << in.rdbuf();
        return ss.str();
    };
    run.out = slurp(out);
    run.err = slurp(err);
    std::filesystem::remove_all(dir);
    return run;
}

CliRun run_cli(const std::string& args) {
    return run_captured(shell_quote(cli_path()) + " " + args);
}

}  // namespace tr::testing
