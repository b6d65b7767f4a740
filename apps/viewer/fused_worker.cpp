#include <apps/viewer/fused_worker.h>
#include <core/stopwatch.h>

#include <algorithm>
#include <chrono>
#include <new>

namespace tr::viewer {

std::string_view fused_mode_name(FusedMode mode) {
    switch (mode) {
        case FusedMode::kProgressive:
            return "progressive";
        case FusedMode::kPbvrImage:
            return "pbvr-image";
        case FusedMode::kExact:
            return "exact";
    }
    return "?";
}

namespace {

// Whether a request in `mode` has nothing more to draw at `target` repetitions.
bool drawn_all(FusedMode mode, const ProgressiveStats& stats, bool failed, int target) {
    if (failed) return true;
    return mode == FusedMode::kPbvrImage ? stats.repetitions >= target : stats.exact;
}

// pbvr-image's options: the fused worker draws no pbvr-object.
ProgressiveOptions fused_options(const PbvrSettings& settings) {
    ProgressiveOptions options;
    options.image = settings.image;
    return options;
}

}  // namespace

// The request being drawn.
struct FusedWorker::Job {
    FusedRequest request;
    std::uint64_t id = 0;
    bool fresh = false;   // begin() not yet called
    bool active = false;  // a request has begun
    std::string error;    // a step failed: nothing more for this request
    std::chrono::steady_clock::time_point published;  // the last picture
};

FusedWorker::FusedWorker(std::vector<FusedMesh> meshes, std::vector<OpaqueSurface> opaque,
                         PbvrSettings settings)
    : AccumulatingWorker(settings.repetitions),
      meshes_(std::move(meshes)),
      settings_(std::move(settings)),
      render_(std::move(opaque), fused_options(settings_)) {
    thread_ = std::thread([this] { run(); });
}

FusedWorker::~FusedWorker() { stop_and_join(); }

std::uint64_t FusedWorker::request(FusedRequest request) { return post(std::move(request)); }

bool FusedWorker::finished_at(const FusedFrame& frame, int target) const {
    return drawn_all(frame.mode, frame, !frame.error.empty(), target);
}

void FusedWorker::run() {
    Job job;
    const auto has_work = [&](int target) {
        return job.active &&
               !drawn_all(job.request.mode, render_.stats(), !job.error.empty(), target);
    };
    for (;;) {
        int target = 0;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || pending_.has_value() || has_work(target_); });
            // Progressive: the exact picture (which cannot be interrupted) only once the camera
            // has been still for kStillDelay since the quick picture, so that a drag never
            // waits for one.
            if (!stop_ && !pending_ && job.request.mode == FusedMode::kProgressive &&
                render_.stats().repetitions > 0) {
                wake_.wait_until(lock, job.published + kStillDelay,
                                 [&] { return stop_ || pending_.has_value(); });
            }
            if (stop_) return;
            if (pending_) {
                job.request = std::move(pending_->first);
                job.id = pending_->second;
                job.fresh = true;
                pending_.reset();
            }
            target = target_;
        }
        try {
            if (job.fresh) begin(job);
            step(job, target);
        } catch (const std::bad_alloc&) {
            render_.release_memory();
            job.error = "out of memory while drawing the fused picture";
        }
        publish(job);
    }
}

void FusedWorker::begin(Job& job) {
    job.fresh = false;
    job.active = true;
    job.error.clear();
    const FusedRequest& r = job.request;
    ProgressiveView view;
    view.camera = r.camera;
    view.width = r.width;
    view.height = r.height;
    view.background = r.background;
    for (std::size_t v = 0; v < meshes_.size(); ++v) {
        ProgressiveVolume& volume = view.volumes.emplace_back();
        volume.mesh = meshes_[v].mesh;
        volume.longest_edge = meshes_[v].longest_edge;
        volume.scalar = r.volumes[v].scalar;
        volume.tf = r.volumes[v].tf;
        volume.tf_version = r.volumes[v].tf_version;
    }
    render_.begin(std::move(view));
}

void FusedWorker::step(Job& job, int target) {
    const auto start = std::chrono::steady_clock::now();
    const FusedRequest& r = job.request;
    const ProgressiveStats& stats = render_.stats();
    if (r.mode == FusedMode::kExact || (r.mode == FusedMode::kProgressive && stats.repetitions > 0))
        return render_.draw_exact();
    // pbvr-image batches, as the pipeline renders several volumes.
    const int most = render_.most_repetitions(ParticleMethod::kPbvrImage, kMaxBatch);
    const int batch = settings_.batch_for(ViewMethod::kPbvrImage);
    const int repetitions = r.mode == FusedMode::kProgressive
                                ? std::clamp(batch, 1, most)
                                : std::clamp(std::min(batch, target - stats.repetitions), 1, most);
    // Progressive: the quick picture at 1 / scale of the size, so that it costs about
    // kPreviewBudget at the last one's rate (its cost is mostly the segments on the pixel rays).
    int scale = 1;
    if (r.mode == FusedMode::kProgressive) {
        const double full_ms = preview_ms_per_pixel_ * r.width * r.height;
        for (int f : {2, 3, 4, 6, 8}) {
            if (full_ms / (scale * scale) <= kPreviewBudget.count()) break;
            scale = f;
        }
    }
    const std::uint64_t seed = settings_.seed + static_cast<std::uint64_t>(stats.batches);
    const Status drawn = render_.add_batch(ParticleMethod::kPbvrImage, repetitions, seed, scale);
    if (!drawn.ok()) job.error = drawn.error().message;
    if (r.mode == FusedMode::kProgressive) {
        preview_ms_per_pixel_ =
            ms_since(start) * scale * scale / (static_cast<double>(r.width) * r.height);
    }
}

void FusedWorker::publish(Job& job) {
    job.published = std::chrono::steady_clock::now();
    FusedFrame frame;
    frame.mode = job.request.mode;
    publish_frame(render_, job.id, job.error, std::move(frame));
}

}  // namespace tr::viewer
