#pragma once
// A picture of loaded volumes made progressively, as `tetrender render` draws the same scene:
// particle-based batches (pbvr-image over every volume, pbvr-object over one) accumulated into
// one mean while the view stays, or the exact fused picture (the segment merge of every volume,
// project/segment_merge.h) in one step. The viewer's particle and fused workers
// (apps/viewer/pbvr_worker.h, fused_worker.h) draw through it; it holds no thread.
//
// Per view: begin() makes the frame and the opaque layer; then batches, an exact picture or
// pictures drawn elsewhere (splat) are added; picture() is the mean so far (or the exact
// picture). Across views it keeps what still holds:
// - the shaders (pre-integrated tables) of each volume while its transfer function stays:
// pbvr-image
//   of one volume draws its segments' mean colours with it (inverse-CDF depth, pbvr_image.h), the
//   exact picture shades every volume with them;
// - pbvr-object's particles of a view's first batches (ObjectParticleSet, up to max_kept_bytes):
//   a view with the same scalar and a camera they are reusable for (an orthographic turn, the same
//   camera) draws them again, after retarget() when the transfer function changed, before new
//   batches are generated; the kept sets are dropped by a pbvr-image batch or a view they do not
//   fit.

#include <core/camera.h>
#include <core/image.h>
#include <core/result.h>
#include <mesh/tet_mesh.h>
#include <project/opaque_geometry.h>
#include <project/pbvr/pbvr_image.h>
#include <project/pbvr/pbvr_object.h>
#include <project/transfer_function.h>
#include <project/volume_scene.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace tr {

// One volume of a view. The mesh must outlive the render; scalar and transfer function are
// shared so that the caller may replace its own meanwhile.
struct ProgressiveVolume {
    const TetMesh* mesh = nullptr;  // its real tets are drawn
    double longest_edge = 1;        // the mesh's (cpu_renderer.h), for the shaders
    std::shared_ptr<const std::vector<float>> scalar;  // one per mesh point
    std::uint64_t scalar_version = 0;                  // changes whenever `scalar` does
    std::shared_ptr<const TransferFunction> tf;
    std::uint64_t tf_version = 0;  // changes whenever `tf` does
};

struct ProgressiveView {
    Camera camera;
    int width = 0, height = 0;  // the picture, >= 1 each
    Vec3 background{0.0};
    std::vector<ProgressiveVolume> volumes;  // >= 1
};

struct ProgressiveOptions {
    ImagePbvrOptions image;    // depth, stratified, control variate (repetitions, seed: per batch)
    ObjectPbvrOptions object;  // subpixel_level, sampling (repetitions, seed: per batch)
    std::size_t max_kept_bytes = std::size_t{512} << 20;  // pbvr-object's kept particles
};

enum class ParticleMethod { kPbvrImage, kPbvrObject };

// What the view's picture is made of so far, and what it cost.
struct ProgressiveStats {
    int repetitions = 0;    // accumulated (a picture added counts for its repetitions)
    int batches = 0;        // particle batches and pictures added
    bool exact = false;     // the picture is the exact fused one
    int preview_scale = 1;  // the last batch was drawn at 1 / this of the size
    double setup_ms = 0;    // begin(): the opaque layer
    double batch_ms = 0;    // the last batch: drawing and accumulating
    double mean_batch_ms = 0;
    double exact_ms = 0;                // the exact picture: shaders made and segments merged
    std::size_t particles = 0;          // drawn (pbvr-image) or kept and generated (pbvr-object)
    std::size_t fragments = 0;          // the last batch's or the exact picture's
    std::size_t overlap_intervals = 0;  // the exact picture's
    // pbvr-object: repetitions drawn from kept particles, the most cells retarget() regenerated
    // in one kept set, and the bytes and sets kept.
    int reused_repetitions = 0;
    std::size_t retargeted_cells = 0;
    std::size_t kept_bytes = 0;
    int kept_sets = 0;
    std::size_t cells = 0;  // the view's real tets, all volumes
};

class ProgressiveRender {
  public:
    // The surfaces `opaque` points to must outlive the render.
    ProgressiveRender(std::vector<OpaqueSurface> opaque, ProgressiveOptions options);
    ~ProgressiveRender();
    ProgressiveRender(const ProgressiveRender&) = delete;
    ProgressiveRender& operator=(const ProgressiveRender&) = delete;

    // Starts `view`'s picture afresh (nothing accumulated): its frame and opaque layer; drops the
    // kept particles that do not fit it.
    void begin(ProgressiveView view);

    // The most repetitions one batch of `method` may draw at the view's size (the library's limit
    // on work, kMaxParticleSamples), and at most `cap`.
    int most_repetitions(ParticleMethod method, int cap) const;

    // Draws `repetitions` (1 .. most_repetitions) more with `seed` and adds them to the mean.
    // pbvr-image at preview_scale > 1: drawn at 1 / scale of the size (its opaque layer too) and
    // nearest-upsampled (a quick picture; its cost is mostly the segments on the pixel rays).
    // pbvr-object draws a kept set instead while the view has one not yet drawn (its own
    // repetitions count). Errors: kInvalidArgument when pbvr-object would generate more than
    // kMaxObjectCandidates particles a repetition (the camera inside or near the volume).
    Status add_batch(ParticleMethod method, int repetitions, std::uint64_t seed,
                     int preview_scale = 1);

    // Adds a picture drawn elsewhere (the view's size), counting for `repetitions`.
    void add_picture(const Image& image, int repetitions);

    // The exact fused picture of every volume: picture() is it from now on.
    void draw_exact();

    // The exact picture, else the mean of the repetitions so far (null before any).
    std::shared_ptr<const Image> picture() const;

    const ProgressiveStats& stats() const { return stats_; }
    const CameraFrame& frame() const { return *frame_; }
    // The view's camera, background and opaque layer (valid until the next begin()).
    View view() const;

    // After std::bad_alloc: drops the kept particles and the shaders.
    void release_memory();

  private:
    struct Shader;
    struct KeptSet;
    const SegmentShader& shader_of(std::size_t volume);
    Image draw_image_batch(const ImagePbvrOptions& options, int preview_scale);
    Result<Image> draw_object_batch(int repetitions, std::uint64_t seed, int& drawn);
    void accumulate(const Image& image, int repetitions);
    void count_kept();

    const std::vector<OpaqueSurface> opaque_;
    const ProgressiveOptions options_;

    ProgressiveView view_;
    std::optional<CameraFrame> frame_;
    OpaqueLayer layer_;
    VolumeScene scene_;        // points into view_ and layer_
    std::vector<double> sum_;  // over batches: the batch's mean x its repetitions
    std::shared_ptr<const Image> exact_;
    ProgressiveStats stats_;
    double total_batch_ms_ = 0;

    std::vector<std::unique_ptr<Shader>> shaders_;  // per volume
    std::vector<KeptSet> kept_;
    std::uint64_t kept_scalar_version_ = 0;
    std::size_t replayed_ = 0;  // kept sets drawn for this view
};

}  // namespace tr
