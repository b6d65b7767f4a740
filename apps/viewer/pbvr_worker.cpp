#include <apps/viewer/pbvr_worker.h>
#include <pipeline/methods/splat_method.h>

#include <algorithm>

namespace tr::viewer {

PbvrWorker::PbvrWorker(const TetMesh& mesh, std::vector<OpaqueSurface> opaque, double longest_edge,
                       PbvrSettings settings)
    : AccumulatingWorker(settings.repetitions, std::move(opaque),
                         ProgressiveOptions{.image = settings.image,
                                            .object = settings.object,
                                            .max_kept_bytes = settings.max_kept_bytes},
                         "out of memory while rendering particles"),
      mesh_(mesh),
      longest_edge_(longest_edge),
      settings_(std::move(settings)) {
    thread_ = std::thread([this] { run(); });
}

PbvrWorker::~PbvrWorker() { stop_and_join(); }

std::uint64_t PbvrWorker::request(PbvrRequest request) { return post(std::move(request)); }

bool PbvrWorker::finished_at(const PbvrFrame& frame, int target) const {
    return frame.repetitions >= target;
}

void PbvrWorker::begin(const PbvrRequest& r) {
    render_.begin(ProgressiveView{
        .camera = r.camera,
        .width = r.width,
        .height = r.height,
        .background = r.background,
        .volumes = {{&mesh_, longest_edge_, r.scalar, r.scalar_version, r.tf, r.tf_version}}});
}

PbvrFrame PbvrWorker::frame_of(const Job& job) const {
    PbvrFrame frame;
    frame.method = job.request.method;
    return frame;
}

void PbvrWorker::step(Job& job, int target) {
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

}  // namespace tr::viewer
