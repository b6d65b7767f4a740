#pragma once
// What the viewer draws each frame: the mesh's volume in the sort worker's latest order for the
// view, or the particle-based picture the PBVR worker has accumulated for it, or the frame of
// an animated method (texture-advection, spot-noise) the animation worker has drawn, or the flow
// volume, or (a scene of several volumes) the fused picture the fused worker has drawn; the
// transfer function rebuilt when the panel changed it; the frame redrawn only when something it
// shows changed; and which GL renderer holds the last frame.

#include <apps/viewer/animation_worker.h>
#include <apps/viewer/flow_controls.h>
#include <apps/viewer/fused_worker.h>
#include <apps/viewer/pbvr_worker.h>
#include <apps/viewer/sort_worker.h>
#include <apps/viewer/viewer_scene.h>
#include <project/gl/gl_renderer.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace tr::viewer {

class VolumeView {
  public:
    // `scene` and `renderer` must outlive the view (the renderer gets the scene's mesh, scalar,
    // opaque surfaces and transfer function now). `verbose`: the flow volume prints a line per
    // grown volume (interactive mode).
    VolumeView(ViewerScene& scene, gl::GlTetRenderer& renderer, Integrator integrator,
               bool verbose);

    ViewerScene& scene() { return vs_; }
    // The flow volume's controls; null when the mesh has no 3-component point array.
    FlowControls* flow() { return flow_.get(); }
    bool flow_shown() const { return flow_ && flow_->shown(); }

    // Asks the worker for `camera`'s order when the view or the method changed; returns the
    // latest finished order (waiting only when there is none yet, or when `exact` asks for
    // this very view's).
    SortedOrder current_order(const Camera& camera, bool exact);

    // Draws the volume in `order` (frame sized as the image), or the flow volume's shown layers
    // (before the first one: the opaque surfaces alone). Records the stats for the panel.
    gl::GlFrameStats render_volume(const CameraFrame& frame, const SortedOrder& order);
    gl::GlFrameStats render_flow(const CameraFrame& frame);

    // Interactive: draws `camera`'s frame at width x height unless the last one shows the same
    // (view, order, transfer function, size, flow layers; in a particle-based mode: the same
    // accumulated picture). Returns whether the view is idle: its own order drawn, every grown
    // flow layer shown and nothing growing, or (particle-based) the latest accumulated picture
    // shown (the next batch wakes the loop through set_wake).
    bool draw(const Camera& camera, int width, int height);
    // Forgets the last frame: the next draw() draws.
    void invalidate() {
        drawn_.reset();
        pbvr_shown_.reset();
        animation_shown_id_ = 0;
    }

    // How the picture is made. The particle-based modes draw the mesh's volume and the opaque
    // surfaces on the CPU (PbvrWorker); a shown flow volume is drawn by projected tetrahedra in
    // every mode.
    ViewMethod mode() const { return mode_; }
    void set_mode(ViewMethod mode);  // the next draw() draws
    bool particle_mode() const { return mode_ != ViewMethod::kProjectedTetrahedra; }
    // splat with vector splats: the frame of the texture cycle drawn next (headless: the
    // frame's index; interactively draw() advances it kSplatCycleFps times a second).
    void set_splat_frame(std::int64_t frame) { splat_frame_ = frame; }
    bool splat_cycle() const {
        return mode_ == ViewMethod::kSplat && !vs_.pbvr.splat.vectors.empty();
    }
    static constexpr double kSplatCycleFps = 8.0;

    // texture-advection, spot-noise (the scene's method only: mode() cannot become one from
    // another; available() says which modes set_mode may take).
    bool animated() const { return animated_method(mode_); }
    bool available(ViewMethod mode) const {
        return !animated_method(mode) || (animation_ && mode == vs_.method);
    }
    // The animated method's frame of `camera` at width x height: asks the worker for this view
    // when it (or the scalar or transfer function) differs from the last one asked, which starts
    // its frames over. With `frame` >= 0, waits for that frame (mod steps + 1) and shows it;
    // with -1, shows the frame the clock is at among those arrived (kAnimationFps frames a
    // second, in a loop; all steps + 1 once every one has arrived). Until the view's frame 0
    // arrives the last picture stays. Returns the worker's frames (of the view asked for, or of
    // an older one).
    AnimationFrames draw_animation(const Camera& camera, int width, int height, int frame);
    AnimationWorker& animation() { return *animation_; }
    // The frame shown last (-1: none yet) and whether it is of the latest view asked for.
    int animation_frame_shown() const { return animation_shown_frame_; }
    bool animation_current() const {
        return animation_shown_id_ != 0 && animation_shown_id_ == animation_requested_id_;
    }
    static constexpr double kAnimationFps = 10.0;

    // The particle-based picture of `camera` at width x height: asks the worker for this view
    // when it (or the method, scalar or transfer function) differs from the last one asked,
    // which restarts the accumulation; with `min_repetitions` > 0 waits until that many are
    // accumulated (or the accumulation finished); shows the latest accumulated picture when it
    // is newer than the one shown. Returns the frame shown (none yet: nullopt).
    std::optional<PbvrFrame> draw_particles(const Camera& camera, int width, int height,
                                            int min_repetitions);
    PbvrWorker& particles() { return pbvr_; }
    // The particle-based frame shown last, and whether it answers the latest view asked for.
    const std::optional<PbvrFrame>& particles_shown() const { return pbvr_shown_; }
    bool particles_current() const {
        return pbvr_shown_ && pbvr_shown_->request_id == pbvr_requested_id_;
    }
    // Called from the worker thread when a batch is accumulated (glfwPostEmptyEvent); set
    // before the first draw.
    void set_wake(std::function<void()> wake);

    // A scene of several volumes (ViewerScene::fused): every frame is the fused worker's
    // picture, in fused_mode() (mode() and the sort are then unused).
    bool fused() const { return fused_ != nullptr; }
    FusedMode fused_mode() const { return fused_mode_; }
    void set_fused_mode(FusedMode mode);  // the next draw() asks for it
    FusedWorker& fused_worker() { return *fused_; }
    // The fused picture of `camera` at width x height: asks the worker for this view when it
    // (or the mode, a volume's scalar or transfer function) differs from the last one asked;
    // with `min_repetitions` > 0 waits for that many repetitions or the exact picture
    // (FusedWorker::kWaitFinished: the request's last picture); shows the latest picture when
    // it is newer than the one shown. Returns the frame shown (none yet: nullopt).
    std::optional<FusedFrame> draw_fused(const Camera& camera, int width, int height,
                                         int min_repetitions);
    const std::optional<FusedFrame>& fused_shown() const { return fused_shown_; }
    bool fused_current() const {
        return fused_shown_ && fused_shown_->request_id == fused_requested_id_;
    }
    // Edits of fused volume `volume`'s edit (ViewerScene::fused) mark it dirty; the next
    // rebuild_transfer_function() remakes its transfer function (and so the next draw restarts).
    void mark_dirty(std::size_t volume);
    void select_scalar(std::size_t volume, const std::string& name);

    // The renderer holding the last frame (read_image, blit_to_default, overlay).
    gl::GlTetRenderer& active() { return *active_; }

    // The transfer function: edits of scene().edit mark it dirty; rebuilt from them for the
    // current integrator (errors go to status()).
    void mark_dirty() { tf_dirty_ = true; }
    bool tf_dirty() const { return tf_dirty_; }
    // A scene of several volumes: each dirty volume's.
    void rebuild_transfer_function();

    // What the panel sets and shows.
    SortMethod method() const { return method_; }
    void set_method(SortMethod method) { method_ = method; }
    Integrator integrator() const { return integrator_; }
    void set_integrator(Integrator integrator);   // marks the transfer function dirty
    void select_scalar(const std::string& name);  // marks dirty, or says why not in status()
    const std::string& status() const { return status_; }
    double sort_ms() const { return sort_ms_; }
    bool order_current() const { return order_current_; }
    const gl::GlFrameStats& last_stats() const { return last_stats_; }

  private:
    void update_gl_transfer_function();  // when gl_tf_stale_

    ViewerScene& vs_;
    gl::GlTetRenderer& renderer_;
    gl::GlTetRenderer* active_ = &renderer_;
    SortWorker worker_;
    PbvrWorker pbvr_;
    ViewMethod mode_;
    std::unique_ptr<FlowControls> flow_;
    std::optional<Camera> requested_;  // the view of the last request
    SortMethod method_, requested_method_ = SortMethod::kMpvo;
    Integrator integrator_;
    std::uint64_t view_id_ = 0, last_order_id_ = 0;
    bool order_current_ = false;
    double sort_ms_ = 0;
    bool tf_dirty_ = false;
    int tf_version_ = 0;
    bool gl_tf_stale_ = false;  // the GL renderer's textures are of an older function
    int scalar_version_ = 0;
    // What the PBVR worker was last asked for, and the copies it draws from.
    struct ParticleKey {
        ViewMethod method;
        Camera camera;
        int width, height, tf_version, scalar_version;
        std::int64_t splat_frame;
        bool operator==(const ParticleKey& o) const;
    };
    std::optional<ParticleKey> pbvr_key_;
    std::uint64_t pbvr_requested_id_ = 0;
    std::shared_ptr<const TransferFunction> pbvr_tf_;
    std::shared_ptr<const std::vector<float>> pbvr_scalar_;
    int pbvr_tf_version_ = -1, pbvr_scalar_version_ = -1;
    std::optional<PbvrFrame> pbvr_shown_;
    std::int64_t splat_frame_ = 0;
    // The animation worker (the scene's method is texture-advection or spot-noise), what it was
    // last asked for, and the frame shown.
    std::unique_ptr<AnimationWorker> animation_;
    struct AnimationKey {
        Camera camera;
        int width, height, tf_version, scalar_version;
        bool operator==(const AnimationKey& o) const;
    };
    std::optional<AnimationKey> animation_key_;
    std::uint64_t animation_requested_id_ = 0, animation_shown_id_ = 0;
    int animation_shown_frame_ = -1;
    std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
    // The fused worker (several volumes), what it was last asked for, and the copies it draws
    // from (per volume; versions from fused_version_, increasing).
    std::unique_ptr<FusedWorker> fused_;
    FusedMode fused_mode_ = FusedMode::kProgressive;
    std::vector<FusedVolumeState> fused_state_;
    std::vector<bool> fused_dirty_;
    std::uint64_t fused_version_ = 0;  // any volume's scalar or transfer function
    struct FusedKey {
        FusedMode mode;
        Camera camera;
        int width, height;
        std::uint64_t version;
        bool operator==(const FusedKey& o) const;
    };
    std::optional<FusedKey> fused_key_;
    std::uint64_t fused_requested_id_ = 0;
    std::optional<FusedFrame> fused_shown_;
    std::string status_;
    gl::GlFrameStats last_stats_;
    // What the last interactive frame showed.
    struct DrawnKey {
        Camera camera;
        std::uint64_t order_id;
        int tf_version, width, height;
        std::uint64_t flow_id;
        std::size_t flow_layers;
        bool operator==(const DrawnKey& o) const;
    };
    std::optional<DrawnKey> drawn_;
};

}  // namespace tr::viewer
