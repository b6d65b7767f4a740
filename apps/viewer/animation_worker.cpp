#include <apps/viewer/animation_worker.h>
#include <core/memory_budget.h>
#include <core/stopwatch.h>
#include <pipeline/loaded_mesh.h>

#include <algorithm>
#include <chrono>

namespace tr::viewer {

AnimationWorker::AnimationWorker(Pipeline& pipeline, Scene scene, int steps)
    : pipeline_(pipeline), scene_(std::move(scene)), steps_(std::max(steps, 0)) {
    thread_ = std::thread([this] { run(); });
}

AnimationWorker::~AnimationWorker() { stop_and_join(); }

std::uint64_t AnimationWorker::request(AnimationRequest request) {
    return post(std::move(request));
}

AnimationFrames AnimationWorker::latest() const {
    std::lock_guard lock(mutex_);
    return latest_;
}

AnimationFrames AnimationWorker::wait_for(std::uint64_t request_id, int frame) {
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] {
        if (latest_.request_id > request_id) return true;
        return latest_.request_id == request_id &&
               (static_cast<int>(latest_.frames.size()) > frame || latest_.finished);
    });
    return latest_;
}

void AnimationWorker::run() {
    for (;;) {
        std::optional<std::pair<AnimationRequest, std::uint64_t>> job;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || pending_.has_value(); });
            if (stop_) return;
            job = std::move(pending_);
            pending_.reset();
        }
        render(job->first, job->second);
    }
}

void AnimationWorker::render(const AnimationRequest& request, std::uint64_t id) {
    const auto start = std::chrono::steady_clock::now();
    {
        std::lock_guard lock(mutex_);
        latest_ = AnimationFrames{};
        latest_.request_id = id;
        latest_.total = total();
    }
    done_.notify_all();
    const auto fail = [&](const std::string& error) {
        {
            std::lock_guard lock(mutex_);
            latest_.error = error;
            latest_.finished = true;
        }
        done_.notify_all();
        if (on_frame_) on_frame_();
    };
    const double bytes = 12.0 * request.width * request.height * total();
    if (const Status fits = check_memory(
            bytes, "the animation's " + std::to_string(total()) + " frames (steps + 1)");
        !fits.ok()) {
        fail(fits.error().message);
        return;
    }
    Scene scene = scene_;
    scene.camera = request.camera;
    scene.width = request.width;
    scene.height = request.height;
    SceneVolume& volume = scene.volumes[0];
    volume.transfer_function = *request.tf;
    volume.scalar = request.scalar;
    volume.component = request.component;
    RenderOptions options;
    bool stopped = false;
    options.on_frame = [&](int k, const Image& picture) -> Status {
        auto frame = std::make_shared<const Image>(picture);
        {
            std::lock_guard lock(mutex_);
            latest_.frames.push_back(std::move(frame));
            const double ms = ms_since(start);
            if (k == 0) {
                latest_.first_ms = ms;
            } else {
                latest_.frame_ms = (ms - latest_.first_ms) / k;
            }
            latest_.finished = k >= steps_;
            stopped = stop_ || pending_.has_value();
        }
        done_.notify_all();
        if (on_frame_) on_frame_();
        if (stopped) return make_error(ErrorCode::kInternal, "a newer view was asked for");
        return Status{};
    };
    const Result<RenderResult> rendered = pipeline_.render(scene, options);
    if (stopped) return;
    if (!rendered.ok()) {
        fail(rendered.error().to_string());
        return;
    }
    {
        std::lock_guard lock(mutex_);
        latest_.finished = true;
    }
    done_.notify_all();
}

}  // namespace tr::viewer
