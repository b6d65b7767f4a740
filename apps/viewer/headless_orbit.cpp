#include <apps/cli_common.h>
#include <apps/viewer/camera_control.h>
#include <apps/viewer/headless_orbit.h>
#include <core/stopwatch.h>
#include <io/write_image.h>
#include <pipeline/loaded_mesh.h>
#include <pipeline/movie.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <optional>

namespace tr::viewer {
namespace {

// The picture shown, annotated as asked.
Image picture_of(VolumeView& view, const HeadlessOptions& options) {
    Image image = view.active().read_image();
    if (options.annotate) options.annotate(image);
    return image;
}

// What the orbit's frames drew and how long they took, for the line it prints.
struct OrbitTotals {
    int frames = 0;
    double frame_ms = 0, sort_ms = 0, classify_ms = 0, raster_ms = 0;
    std::size_t sorts = 0, drawn = 0;
    std::optional<PbvrFrame> shown;   // particle-based: the last picture
    std::optional<FusedFrame> fused;  // several volumes: the last picture
    AnimationFrames animation;        // an animated method's last view's frames
};

// The orbit's one line of figures, for what the view drew.
void print_orbit_stats(VolumeView& view, const OrbitTotals& totals, FlowControls* flow,
                       bool animated, bool particles, int batch) {
    const ViewerScene& vs = view.scene();
    const int width = vs.scene.width, height = vs.scene.height;
    const int frames = totals.frames;
    const double frame_ms = totals.frame_ms;
    std::string flow_text;
    std::size_t cells = vs.sort.mesh().num_real_tets();
    if (flow) {
        const GrownFlowVolume& grown = *flow->grown();
        char text[160];
        std::snprintf(text, sizeof(text),
                      ", flow volume: %zu layers, %zu particles inserted, grown in %.1f ms",
                      grown.volume->layer_tets.size(), grown.volume->particles_inserted,
                      grown.grow_ms);
        flow_text = text;
        cells = grown.volume->mesh.num_tets();
    }
    if (totals.fused) {
        const FusedFrame& f = *totals.fused;
        std::fprintf(stderr,
                     "tetrender-view: frames %d, %.1f ms/frame mean (%.1f fps), %zu volumes fused "
                     "(%s): %s, %d pbvr-image repetitions in %d batches, %.1f ms/batch mean, exact "
                     "%.1f ms, setup %.1f ms, %zu particles, %zu fragments, %zu overlap "
                     "intervals, %dx%d\n",
                     frames, frame_ms / frames, 1000.0 * frames / frame_ms, vs.fused.size(),
                     fused_mode_name(view.fused_mode()).data(),
                     f.exact ? "exact picture" : "pbvr-image picture", f.repetitions, f.batches,
                     f.mean_batch_ms, f.exact_ms, f.setup_ms, f.particles, f.fragments,
                     f.overlap_intervals, width, height);
        return;
    }
    if (animated) {
        const AnimationFrames& animation = totals.animation;
        std::fprintf(stderr,
                     "tetrender-view: frames %d, %.1f ms/frame mean (%.1f fps), %s: frame i of "
                     "its %d frames at frame i, %zu rendered for the last view, the first in "
                     "%.1f ms (setup), %.1f ms a frame after it, %dx%d\n",
                     frames, frame_ms / frames, 1000.0 * frames / frame_ms,
                     view_method_name(view.mode()).data(), animation.total, animation.frames.size(),
                     animation.first_ms, animation.frame_ms, width, height);
        return;
    }
    if (particles && view.mode() == ViewMethod::kSplat) {
        const PbvrFrame& f = *totals.shown;
        std::fprintf(stderr,
                     "tetrender-view: frames %d, %.1f ms/frame mean (%.1f fps), splat: %.1f ms "
                     "the last picture%s, %dx%d\n",
                     frames, frame_ms / frames, 1000.0 * frames / frame_ms, f.batch_ms,
                     view.splat_cycle() ? " (vector splats, frame i of the cycle at frame i)" : "",
                     width, height);
        return;
    }
    if (particles) {
        const PbvrFrame& f = *totals.shown;
        std::fprintf(stderr,
                     "tetrender-view: frames %d, %.1f ms/frame mean (%.1f fps), %s: %d "
                     "repetitions in %d batches (%d a batch), %.1f ms/batch mean, setup %.1f "
                     "ms, %zu particles, %d repetitions from kept particles, retarget %zu "
                     "cells, %zu cells, %dx%d\n",
                     frames, frame_ms / frames, 1000.0 * frames / frame_ms,
                     view_method_name(view.mode()).data(), f.repetitions, f.batches, batch,
                     f.mean_batch_ms, f.setup_ms, f.particles, f.reused_repetitions,
                     f.retargeted_cells, f.cells, width, height);
        return;
    }
    std::fprintf(stderr,
                 "tetrender-view: frames %d, %.1f ms/frame mean (%.1f fps), sort %.1f ms mean "
                 "(%zu sorts), classify %.1f ms, raster %.1f ms, %zu cells (%zu drawn), "
                 "%dx%d, %s%s\n",
                 frames, frame_ms / frames, 1000.0 * frames / frame_ms,
                 totals.sorts ? totals.sort_ms / static_cast<double>(totals.sorts) : 0.0,
                 totals.sorts, totals.classify_ms / frames, totals.raster_ms / frames, cells,
                 totals.drawn, width, height, integrator_name(view.integrator()).data(),
                 flow_text.c_str());
}

}  // namespace

int run_headless_orbit(VolumeView& view, ViewerPanel* panel, const HeadlessOptions& options) {
    const ViewerScene& vs = view.scene();
    const int width = vs.scene.width, height = vs.scene.height;
    const Camera& home = vs.scene.camera;
    const int frames = std::max(options.frames, 1);
    // The scene's up axis, not the picture's: a camera looking down turns as on a turntable.
    const Vec3 axis = glm::normalize(home.view_up);
    FlowControls* flow = view.flow_shown() ? view.flow() : nullptr;
    // Particle-based: each frame waits for its view's first batch, the last for all of them.
    const bool animated = view.animated() && !flow && !view.fused();
    const bool particles = view.particle_mode() && !flow && !view.fused() && !animated;
    const int target = view.particles().target();
    const int batch = std::min(vs.pbvr.batch_for(view.mode()), target);
    OrbitTotals totals;
    totals.frames = frames;
    std::optional<PbvrFrame>& shown = totals.shown;
    std::optional<FusedFrame>& fused = totals.fused;
    AnimationFrames& animation = totals.animation;
    std::uint64_t last_seen = 0;
    if (flow) {
        // Grown before the frames; they show it growing, one layer a frame, and the last frame
        // shows all of it.
        if (const auto error = flow->grow_and_wait()) return apps::report_error(*error);
    }
    for (int i = 0; i < frames; ++i) {
        const auto frame_start = std::chrono::steady_clock::now();
        const double angle = glm::radians(options.orbit) * (i + 1) / frames;
        const Camera camera = orbit_camera(home, axis, angle);
        const bool last = i + 1 == frames;
        const CameraFrame frame(camera, width, height);
        gl::GlFrameStats stats;
        if (flow) {
            flow->show_layers(last ? flow->num_layers() : static_cast<std::size_t>(i + 1));
            stats = view.render_flow(frame);
        } else if (view.fused()) {
            fused = view.draw_fused(camera, width, height, last ? FusedWorker::kWaitFinished : 1);
            if (!fused || !fused->error.empty()) {
                return apps::report_error(
                    make_error(ErrorCode::kInternal, fused ? fused->error : "no fused picture"));
            }
        } else if (animated) {
            // Frame i of the method's frames 0 .. steps (i mod steps + 1), from one render while
            // the camera stays (a turning camera starts the frames over at each view).
            animation = view.draw_animation(camera, width, height, i);
            if (static_cast<int>(animation.frames.size()) <= i % animation.total) {
                return apps::report_error(
                    make_error(ErrorCode::kInternal,
                               animation.error.empty() ? "no animation frame" : animation.error));
            }
        } else if (particles) {
            view.set_splat_frame(i);  // vector splats: frame i of the texture cycle
            shown = view.draw_particles(camera, width, height, last ? target : batch);
            if (!shown || !shown->error.empty()) {
                return apps::report_error(make_error(
                    ErrorCode::kInternal, shown ? shown->error : "no particle-based picture"));
            }
        } else {
            const SortedOrder order = view.current_order(camera, last);
            if (order.view_id != last_seen) {
                last_seen = order.view_id;
                totals.sort_ms += order.stats.milliseconds;
                ++totals.sorts;
            }
            stats = view.render_volume(frame, order);
        }
        totals.classify_ms += stats.classify_ms;
        totals.raster_ms += stats.raster_ms;
        totals.drawn = stats.cells_drawn;
        if (last && panel) {
            view.active().bind_framebuffer();
            panel->add_frame_ms(ms_since(frame_start));
            // Auto-sized windows appear on ImGui's second frame: lay out twice first.
            panel->draw(camera, false);
            panel->draw(camera, false);
            panel->draw(camera);
        }
        totals.frame_ms += ms_since(frame_start);
        if (!options.frames_dir.empty()) {
            const Status frame_written =
                write_image(picture_of(view, options), frame_path(options.frames_dir, i));
            if (!frame_written.ok()) return apps::report_error(frame_written.error());
        }
    }
    const Status written = write_image(picture_of(view, options), options.screenshot);
    if (!written.ok()) return apps::report_error(written.error());
    print_orbit_stats(view, totals, flow, animated, particles, batch);
    return apps::kExitOk;
}

}  // namespace tr::viewer
