#include <tests/apps/cli_runner.h>
#include <tests/viewer/viewer_runner.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

namespace tr::testing {

bool require_xvfb() {
    if (std::system("command -v xvfb-run >/dev/null 2>&1") == 0) return true;
    const char* ci = std::getenv("CI");
    if (ci && std::string(ci) == "true") {
        ADD_FAILURE() << "CI=true but xvfb-run is missing (Debian packages xvfb and xauth)";
    }
    return false;
}

namespace {

ViewerRun run_viewer_once(const std::string& args, bool xvfb, const std::string& prefix) {
    const std::string dir = make_temp_dir();
    std::string command = prefix + " ";
    // The X authority file in our own folder: xvfb-run then makes no temporary folder of its
    // own, whose removal failed now and then on a busy machine (exit 5, "problem while
    // cleaning up temporary directory") after the viewer had run.
    if (xvfb) {
        command +=
            "xvfb-run -a -f " + shell_quote(dir + "/Xauthority") + " -s '-screen 0 1280x1024x24' ";
    }
    const ViewerRun run = run_captured(command + shell_quote(TETRENDER_VIEW_PATH) + " " + args);
    std::filesystem::remove_all(dir);
    return run;
}

// A run that failed for reasons outside the viewer: LeakSanitizer's stop-the-world tracer
// crashed at exit ("Tracer caught signal 11 ... LeakSanitizer has encountered a fatal error",
// seen once in CI with Mesa's llvmpipe threads alive: a failure of the checker, not a leak
// report), or, under xvfb-run, the X server did not start or could not be reached (a rare
// one-line failure of a viewer test on a loaded machine).
bool harness_failure(const ViewerRun& run, bool xvfb) {
    const auto has = [&](const char* text) { return run.err.find(text) != std::string::npos; };
    return has("LeakSanitizer has encountered a fatal error") ||
           (xvfb && (has("Xvfb failed to start") || has("no display:") ||
                     has("problem while cleaning up temporary directory")));
}

}  // namespace

ViewerRun run_viewer(const std::string& args, bool xvfb, const std::string& prefix) {
    // Such runs are repeated, twice at most; anything else (a leak report too) stands.
    ViewerRun run = run_viewer_once(args, xvfb, prefix);
    for (int retry = 0; retry < 2 && harness_failure(run, xvfb); ++retry) {
        run = run_viewer_once(args, xvfb, prefix);
    }
    return run;
}

double lit_fraction(const Image& image, float threshold) {
    if (image.pixels.empty()) return 0;
    std::size_t lit = 0;
    for (const Vec3f& p : image.pixels) {
        if (std::max({p.x, p.y, p.z}) > threshold) ++lit;
    }
    return static_cast<double>(lit) / static_cast<double>(image.pixels.size());
}

}  // namespace tr::testing
