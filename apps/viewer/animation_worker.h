#pragma once
// The viewer's animated flow-texture modes (texture-advection, spot-noise) in a worker thread:
// for the requested view, one render of the scene through the library (Pipeline::render, as
// `tetrender render SCENE --frames DIR` draws it) hands over the method's frames 0 .. steps in
// order (RenderOptions::on_frame); each finished frame is kept and published at once, so that
// the window plays the frames that have arrived while the rest are computed. A new request
// (camera, size, scalar or transfer function changed) stops the render in progress at its next
// frame and starts over. The method's setup (the sheets, or the spots, and the volume split at
// their depths) is not interrupted.
//
// Cost: the render's (docs/flowtex.md), again for every new view; memory: every frame kept, 12
// bytes a pixel and frame ((steps + 1) x width x height x 12 bytes: 101 frames of 960x600 are
// 0.7 GB), checked against the memory budget (core/memory_budget.h) before the render.

#include <apps/viewer/request_worker.h>
#include <core/camera.h>
#include <core/image.h>
#include <pipeline/pipeline.h>
#include <pipeline/scene.h>
#include <project/transfer_function.h>

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace tr::viewer {

// The view to animate.
struct AnimationRequest {
    Camera camera;
    int width = 0, height = 0;  // the picture, >= 1 each
    std::shared_ptr<const TransferFunction> tf;
    // Volume 0's scalar: a point or cell array of its mesh, and its component (-1: magnitude).
    std::string scalar;
    int component = -1;
};

// The frames of one request so far.
struct AnimationFrames {
    std::uint64_t request_id = 0;                      // the request they answer (0: none yet)
    std::vector<std::shared_ptr<const Image>> frames;  // frames 0, 1, ... arrived, in order
    int total = 0;                                     // steps + 1
    double first_ms = 0;    // from the request to frame 0 (the method's setup and frame 0)
    double frame_ms = 0;    // mean time of each later frame
    bool finished = false;  // every frame arrived, or the render failed
    std::string error;      // the render failed: the frames before it stay
};

class AnimationWorker : private RequestWorker<AnimationRequest> {
  public:
    // Renders `scene` (one volume; its method texture-advection or spot-noise, with its keys,
    // and `steps`: frames 0 .. steps) through `pipeline`, which the worker thread then uses
    // alone: `pipeline` must outlive the worker and no one else may render with it meanwhile.
    AnimationWorker(Pipeline& pipeline, Scene scene, int steps);
    ~AnimationWorker();  // stops the render in progress at its next frame, and waits for it
    AnimationWorker(const AnimationWorker&) = delete;
    AnimationWorker& operator=(const AnimationWorker&) = delete;

    // Asks for `request`'s frames: it replaces a request not yet started, and the render in
    // progress stops at its next frame. Returns the request's id (increasing from 1).
    std::uint64_t request(AnimationRequest request);

    // The frames of the latest request that has begun (none yet: request_id 0).
    AnimationFrames latest() const;

    // Blocks until frame `frame` of request `request_id` has arrived (or that render finished or
    // failed), or a later request has begun; returns its frames.
    AnimationFrames wait_for(std::uint64_t request_id, int frame);

    // Called from the worker thread after each frame arrives (glfwPostEmptyEvent, to wake the
    // window loop). Set before the first request.
    void set_on_frame(std::function<void()> on_frame) { on_frame_ = std::move(on_frame); }

    int total() const { return steps_ + 1; }

  private:
    void run();
    void render(const AnimationRequest& request, std::uint64_t id);

    Pipeline& pipeline_;
    const Scene scene_;
    const int steps_;
    std::function<void()> on_frame_;

    AnimationFrames latest_;
};

}  // namespace tr::viewer
