#pragma once
// Runs tetrender-view from the viewer tests, under `xvfb-run -a` (Mesa's llvmpipe gives an
// OpenGL 4.5 core context on the CPU), and reads the PFM screenshots it writes.

#include <core/image.h>
#include <tests/apps/cli_runner.h>

#include <string>

namespace tr::testing {

using ViewerRun = CliRun;

// Whether xvfb-run is on the PATH. When it is not: false, and with CI=true also a test failure
// (the viewer tests must run in CI); callers then GTEST_SKIP().
bool require_xvfb();

// Runs `[prefix] tetrender-view <args>` (args shell-quoted by the caller); with `xvfb`, under
// `xvfb-run -a`. `prefix` is put in front (e.g. "env -u DISPLAY").
ViewerRun run_viewer(const std::string& args, bool xvfb = true, const std::string& prefix = "");

// Reads a PFM written by tetrender's image writer (little-endian RGB floats, bottom row first).
// An empty image when the file is missing or malformed.
Image read_pfm(const std::string& path);

// Fraction of pixels whose largest channel exceeds `threshold`.
double lit_fraction(const Image& image, float threshold = 0.02f);

}  // namespace tr::testing
