#include <apps/viewer/pbvr_worker.h>
#include <pipeline/methods/splat_method.h>

#include <algorithm>
#include <new>

namespace tr::viewer {

// The request being accumulated.
struct PbvrWorker::Job {
    PbvrRequest request;
    std::uint64_t id = 0;
    bool fresh = false;   // begin() not yet called
    bool active = false;  // a request has begun
    std::string error;    // a batch failed: nothing more for this request
};

PbvrWorker::PbvrWorker(const TetMesh& mesh, std::vector<OpaqueSurface> opaque, double longest_edge,
                       PbvrSettings settings)
    : AccumulatingWorker(settings.repetitions),
      mesh_(mesh),
      longest_edge_(longest_edge),
      settings_(std::move(settings)),
      render_(std::move(opaque), ProgressiveOptions{.image = settings_.image,
                                                    .object = settings_.object,
                                                    .max_kept_bytes = settings_.max_kept_bytes}) {
    thread_ = std::thread([this] { run(); });
}

PbvrWorker::~PbvrWorker() { stop_and_join(); }

std::uint64_t PbvrWorker::request(PbvrRequest request) { return post(std::move(request)); }

bool PbvrWorker::finished_at(const PbvrFrame& frame, int target) const {
    return frame.repetitions >= target;
}

void PbvrWorker::run() {
    Job job;
    for (;;) {
        int target = 0;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] {
                return stop_ || pending_.has_value() ||
                       (job.active && job.error.empty() && render_.stats().repetitions < target_);
            });
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
            run_batch(job, target);
        } catch (const std::bad_alloc&) {
            render_.release_memory();
            job.error = "out of memory while rendering particles";
        }
        publish(job);
    }
}

void PbvrWorker::begin(Job& job) {
    job.fresh = false;
    job.active = true;
    job.error.clear();
    const PbvrRequest& r = job.request;
    render_.begin(ProgressiveView{
        .camera = r.camera,
        .width = r.width,
        .height = r.height,
        .background = r.background,
        .volumes = {{&mesh_, longest_edge_, r.scalar, r.scalar_version, r.tf, r.tf_version}}});
}

void PbvrWorker::run_batch(Job& job, int target) {
    const PbvrRequest& r = job.request;
    if (r.method == ViewMethod::kSplat) return draw_splat(job, target);
    const ParticleMethod method = r.method == ViewMethod::kPbvrObject ? ParticleMethod::kPbvrObject
                                                                      : ParticleMethod::kPbvrImage;
    const ProgressiveStats& stats = render_.stats();
    // The repetitions of a new batch: up to the target, within the library's limit on work.
    const int repetitions =
        std::clamp(std::min(settings_.batch_for(r.method), target - stats.repetitions), 1,
                   render_.most_repetitions(method, kMaxBatch));
    const std::uint64_t seed = settings_.seed + static_cast<std::uint64_t>(stats.batches);
    const Status drawn = render_.add_batch(method, repetitions, seed);
    if (!drawn.ok()) job.error = drawn.error().message;
}

// One picture is the whole of it (as `tetrender render --method splat` draws it): it counts for
// every repetition still wanted.
void PbvrWorker::draw_splat(Job& job, int target) {
    const PbvrRequest& r = job.request;
    SplatPicture picture;
    picture.mesh = &mesh_;
    picture.points = settings_.splat_points;
    picture.scalar = *r.scalar;
    picture.tf = r.tf.get();
    picture.view = render_.view();
    picture.where = "splat";
    SplatSettings splat = settings_.splat;
    splat.frame = r.splat_frame;
    auto made = render_splat_picture(picture, splat);
    if (!made.ok()) {
        job.error = made.error().to_string();
        return;
    }
    render_.add_picture(made.value(), std::max(target - render_.stats().repetitions, 1));
}

void PbvrWorker::publish(Job& job) {
    PbvrFrame frame;
    frame.method = job.request.method;
    publish_frame(render_, job.id, job.error, std::move(frame));
}

}  // namespace tr::viewer
