#pragma once
// Runs tetrender-view from the viewer tests, under `xvfb-run -a` (Mesa's llvmpipe gives an
// OpenGL 4.5 core context on the CPU); its PFM screenshots are read and compared with
// tests/support/image_check.h (read_pfm, images_match).

#include <core/image.h>
#include <tests/apps/cli_runner.h>
#include <tests/support/image_check.h>

#include <string>

namespace tr::testing {

using ViewerRun = CliRun;

// Whether xvfb-run is on the PATH. When it is not: false, and with CI=true also a test failure
// (the viewer tests must run in CI); callers then GTEST_SKIP().
bool require_xvfb();

// Runs `[prefix] tetrender-view <args>` (args shell-quoted by the caller); with `xvfb`, under
// `xvfb-run -a`. `prefix` is put in front (e.g. "env -u DISPLAY").
ViewerRun run_viewer(const std::string& args, bool xvfb = true, const std::string& prefix = "");

// Fraction of pixels whose largest channel exceeds `threshold`.
double lit_fraction(const Image& image, float threshold = 0.02f);

}  // namespace tr::testing
