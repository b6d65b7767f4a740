#include <apps/viewer/fused_worker.h>
#include <core/stopwatch.h>

#include <algorithm>
#include <chrono>

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

// pbvr-image's options: the fused worker draws no pbvr-object.
ProgressiveOptions fused_options(const PbvrSettings& settings) {
    ProgressiveOptions options;
    options.image = settings.image;
    return options;
}

}  // namespace

FusedWorker::FusedWorker(std::vector<FusedMesh> meshes, std::vector<OpaqueSurface> opaque,
                         PbvrSettings settings)
    : AccumulatingWorker(settings.repetitions, std::move(opaque), fused_options(settings),
                         "out of memory while drawing the fused picture"),
      meshes_(std::move(meshes)),
      settings_(std::move(settings)) {
    thread_ = std::thread([this] { run(); });
}

FusedWorker::~FusedWorker() { stop_and_join(); }

std::uint64_t FusedWorker::request(FusedRequest request) { return post(std::move(request)); }

bool FusedWorker::finished_at(const FusedFrame& frame, int target) const {
    if (!frame.error.empty()) return true;
    return frame.mode == FusedMode::kPbvrImage ? frame.repetitions >= target : frame.exact;
}

// Progressive: the exact picture (which cannot be interrupted) only once the camera has been
// still for kStillDelay since the quick picture, so that a drag never waits for one.
void FusedWorker::wait_before_step(std::unique_lock<std::mutex>& lock, const Job& job) {
    if (job.request.mode != FusedMode::kProgressive || render_.stats().repetitions == 0) return;
    wake_.wait_until(lock, published_ + kStillDelay, [&] { return stop_ || pending_.has_value(); });
}

FusedFrame FusedWorker::frame_of(const Job& job) const {
    FusedFrame frame;
    frame.mode = job.request.mode;
    return frame;
}

void FusedWorker::begin(const FusedRequest& r) {
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

}  // namespace tr::viewer
