#pragma once
// The viewer's headless mode (--screenshot): frames along an orbit about the home view's up
// axis, the last one written to a file, timings on stderr; for tests and benchmarks.

#include <apps/viewer/viewer_panel.h>
#include <apps/viewer/volume_view.h>
#include <core/image.h>

#include <functional>
#include <string>

namespace tr::viewer {

struct HeadlessOptions {
    std::string screenshot;  // the picture to write (.png, or .pfm for floats)
    int frames = 1;          // frames along the orbit (at least 1)
    double orbit = 0;        // degrees the camera turns over them (the last frame: all of it)
    std::string frames_dir;  // when set, every frame also written as frame_NNNN.png there
    // When set, applied to every picture written (the screenshot and each frame): the legend
    // `tetrender render` draws (viewer_main.cpp).
    std::function<void(Image&)> annotate;
};

// Draws `options.frames` frames of `view` from its scene's camera turned by orbit * (i + 1) /
// frames degrees about the scene's up axis (the camera's view_up: no roll), the last with its own
// view's order (waited for), and a shown flow volume grown first (one layer a frame, every layer in
// the last). In a particle-based mode each frame restarts the accumulation for its view and waits
// for its first batch; the last waits for the target's repetitions (the worker's target),
// accumulated in batches as interactively. An animated method (texture-advection, spot-noise)
// shows at frame i its frame i mod (steps + 1), waited for: with no orbit, the frames of one
// render, `tetrender render SCENE --frames DIR`'s. With `panel`, the panel is drawn into the last
// frame. Writes the last frame and prints one line of timings to stderr. Returns the exit code:
// apps::kExitOk, or apps::kExitError (reported) when growth or a batch of particles fails or the
// picture cannot be written.
int run_headless_orbit(VolumeView& view, ViewerPanel* panel, const HeadlessOptions& options);

}  // namespace tr::viewer
