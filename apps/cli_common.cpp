#include <apps/cli_common.h>
#include <pipeline/scene.h>

#include <nlohmann/json.hpp>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <variant>

namespace tr::apps {
namespace {

const char* g_program = "tetrender";

}  // namespace

void set_program_name(const char* name) { g_program = name; }

ProgressFn terminal_progress() {
    if (!isatty(fileno(stderr))) return {};
    struct State {
        std::string stage;
        int percent = -1;
    };
    auto state = std::make_shared<State>();
    return [state](std::string_view stage, double fraction) {
        const int percent = static_cast<int>(fraction * 100.0);
        if (stage == state->stage && percent == state->percent) return;
        state->stage = stage;
        state->percent = percent;
        std::fprintf(stderr, "\r%-20.*s %3d%%", static_cast<int>(stage.size()), stage.data(),
                     percent);
        if (percent >= 100) std::fprintf(stderr, "\r%40s\r", "");
        std::fflush(stderr);
    };
}

bool is_scene_file(const std::string& path) {
    return path.size() > 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

bool parse_image_size(const std::string& text, int& width, int& height) {
    const auto x = text.find('x');
    if (x == std::string::npos || x == 0 || x + 1 >= text.size() || x > 5 ||
        text.size() - x - 1 > 5) {
        return false;
    }
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (i != x && !std::isdigit(static_cast<unsigned char>(text[i]))) return false;
    }
    width = std::stoi(text.substr(0, x));
    height = std::stoi(text.substr(x + 1));
    return width >= 1 && height >= 1 && width <= kMaxImageSide && height <= kMaxImageSide;
}

int report_error(const Error& error) {
    std::fprintf(stderr, "%s: %s\n", g_program, error.to_string().c_str());
    return kExitError;
}

Status check_output_path(const std::string& path, const std::vector<std::string>& extensions) {
    const std::filesystem::path p(path);
    bool known = false;
    std::string list;
    for (const std::string& e : extensions) {
        known = known || p.extension() == e;
        list += (list.empty() ? "" : ", ") + e;
    }
    if (!known) {
        return make_error(
            ErrorCode::kInvalidArgument,
            "the output must end in " + list + ", not '" + p.extension().string() + "'", path);
    }
    std::error_code ec;
    const std::filesystem::path folder = p.has_parent_path() ? p.parent_path() : ".";
    if (!std::filesystem::is_directory(folder, ec)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "the output's folder '" + folder.string() + "' does not exist", path);
    }
    // A file made and removed: a folder the output cannot be written in is found now, not after
    // the work (and after any frames were written).
    const std::filesystem::path probe =
        folder / (".tetrender-write-probe-" + std::to_string(::getpid()));
    const bool made = std::ofstream(probe, std::ios::binary).is_open();
    std::filesystem::remove(probe, ec);
    if (!made) {
        return make_error(ErrorCode::kInvalidArgument,
                          "cannot write in the output's folder '" + folder.string() + "'", path);
    }
    return {};
}

int report_usage(const Error& error) {
    std::fprintf(stderr, "%s: %s\n", g_program, error.to_string().c_str());
    return kExitUsage;
}

void print_notes(const std::vector<std::string>& notes) {
    for (const std::string& note : notes)
        std::fprintf(stderr, "%s: note: %s\n", g_program, note.c_str());
}

void print_stats(const NamedStats& stats) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const auto& [key, value] : stats.entries()) {
        std::visit([&j, k = key](const auto& v) { j[k] = v; }, value);
    }
    std::printf("%s\n", j.dump().c_str());
}

}  // namespace tr::apps
