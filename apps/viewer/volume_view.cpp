#include <apps/viewer/volume_view.h>
#include <core/stopwatch.h>

#include <utility>

namespace tr::viewer {

VolumeView::VolumeView(ViewerScene& scene, gl::GlTetRenderer& renderer, Integrator integrator,
                       bool verbose)
    : vs_(scene),
      renderer_(renderer),
      worker_(scene.sort.mesh(), scene.sort.adjacency()),
      pbvr_(scene.sort.mesh(), scene.opaque.layers(), scene.longest_edge, scene.pbvr),
      mode_(scene.method),
      method_(scene.sort.method),
      integrator_(integrator) {
    renderer_.set_mesh(&vs_.sort.mesh(), vs_.scalar);
    renderer_.set_opaque(vs_.opaque.layers());
    renderer_.set_transfer_function(vs_.volume().transfer_function, integrator_, vs_.longest_edge);
    if (vs_.flow) {
        flow_ = std::make_unique<FlowControls>(*vs_.flow, vs_.opaque, vs_.scene.flow_volume,
                                               integrator_, verbose);
    }
    if (!vs_.fused.empty()) {
        std::vector<FusedMesh> meshes;
        for (const FusedVolume& fv : vs_.fused) {
            meshes.push_back({&fv.mesh(), fv.longest_edge});
            fused_state_.push_back(
                {std::make_shared<const std::vector<float>>(fv.scalar), nullptr, 0});
        }
        for (std::size_t v = 0; v < vs_.fused.size(); ++v) {
            fused_state_[v].tf =
                std::make_shared<const TransferFunction>(vs_.scene.volumes[v].transfer_function);
        }
        fused_dirty_.assign(vs_.fused.size(), false);
        fused_mode_ = scene.fused_mode;
        fused_ = std::make_unique<FusedWorker>(std::move(meshes), vs_.opaque.layers(), vs_.pbvr);
    }
    if (animated_method(vs_.method) && vs_.fused.empty()) {
        // The library's render of the scene, with the method as resolved; no flow volume (the
        // methods refuse one: a shown flow volume is drawn by projected tetrahedra).
        Scene scene = vs_.scene;
        scene.method = vs_.pbvr.animation;
        scene.flow_volume.reset();
        animation_ = std::make_unique<AnimationWorker>(*vs_.pipeline, std::move(scene),
                                                       vs_.pbvr.animation_steps);
    }
}

void VolumeView::set_wake(std::function<void()> wake) {
    if (fused_) fused_->set_on_frame(wake);
    if (animation_) animation_->set_on_frame(wake);
    pbvr_.set_on_frame(std::move(wake));
}

void VolumeView::set_fused_mode(FusedMode mode) {
    if (mode == fused_mode_) return;
    fused_mode_ = mode;
    invalidate();
}

void VolumeView::mark_dirty(std::size_t volume) {
    fused_dirty_.at(volume) = true;
    tf_dirty_ = true;
}

void VolumeView::select_scalar(std::size_t volume, const std::string& name) {
    const Status s = select_fused_scalar(vs_, volume, name);
    if (s.ok()) {
        fused_state_[volume].scalar =
            std::make_shared<const std::vector<float>>(vs_.fused[volume].scalar);
        ++fused_version_;
        mark_dirty(volume);
        status_.clear();
    } else {
        status_ = s.error().message;
    }
}

bool VolumeView::FusedKey::operator==(const FusedKey& o) const {
    const Camera &a = camera, &b = o.camera;
    return mode == o.mode && a.position == b.position && a.focal_point == b.focal_point &&
           a.view_up == b.view_up && a.view_angle == b.view_angle && a.parallel == b.parallel &&
           a.parallel_scale == b.parallel_scale && width == o.width && height == o.height &&
           version == o.version;
}

std::optional<FusedFrame> VolumeView::draw_fused(const Camera& camera, int width, int height,
                                                 int min_repetitions) {
    const FusedKey key{fused_mode_, camera, width, height, fused_version_};
    if (!fused_key_ || !(key == *fused_key_)) {
        FusedRequest request;
        request.mode = fused_mode_;
        request.camera = camera;
        request.width = width;
        request.height = height;
        request.volumes = fused_state_;
        request.background = vs_.scene.background;
        fused_requested_id_ = fused_->request(std::move(request));
        fused_key_ = key;
    }
    std::optional<FusedFrame> latest = min_repetitions > 0
                                           ? fused_->wait_for(fused_requested_id_, min_repetitions)
                                           : fused_->latest();
    const bool newer =
        latest && (!fused_shown_ || latest->request_id != fused_shown_->request_id ||
                   latest->repetitions != fused_shown_->repetitions ||
                   latest->exact != fused_shown_->exact || latest->error != fused_shown_->error);
    if (newer) {
        if (latest->image) {
            renderer_.show_image(*latest->image);
            active_ = &renderer_;
        }
        fused_shown_ = std::move(latest);
    }
    return fused_shown_;
}

SortedOrder VolumeView::current_order(const Camera& camera, bool exact) {
    const bool changed = !requested_ || camera.position != requested_->position ||
                         camera.focal_point != requested_->focal_point ||
                         camera.view_up != requested_->view_up || method_ != requested_method_;
    if (changed) {
        ++view_id_;
        requested_ = camera;
        requested_method_ = method_;
        const CameraFrame frame(camera, 16, 16);
        worker_.request(SortView::from_camera(frame), method_, view_id_);
    }
    std::optional<SortedOrder> latest = exact ? std::nullopt : worker_.latest();
    if (!latest) latest = worker_.wait_for(view_id_);
    if (latest->view_id != last_order_id_) {
        last_order_id_ = latest->view_id;
        sort_ms_ = latest->stats.milliseconds;
    }
    order_current_ = latest->view_id == view_id_;
    return *latest;
}

gl::GlFrameStats VolumeView::render_volume(const CameraFrame& frame, const SortedOrder& order) {
    update_gl_transfer_function();
    active_ = &renderer_;
    last_stats_ = renderer_.render(frame, *order.order, vs_.scene.background);
    return last_stats_;
}

gl::GlFrameStats VolumeView::render_flow(const CameraFrame& frame) {
    update_gl_transfer_function();
    if (!flow_ || flow_->layers_shown() == 0) {
        active_ = &renderer_;
        last_stats_ = renderer_.render(frame, {}, vs_.scene.background);
    } else {
        active_ = &flow_->renderer();
        last_stats_ = flow_->render(frame, vs_.scene.background);
    }
    return last_stats_;
}

void VolumeView::update_gl_transfer_function() {
    if (!gl_tf_stale_) return;
    gl_tf_stale_ = false;
    renderer_.set_transfer_function(vs_.volume().transfer_function, integrator_, vs_.longest_edge);
}

bool VolumeView::ParticleKey::operator==(const ParticleKey& o) const {
    const Camera &a = camera, &b = o.camera;
    return method == o.method && a.position == b.position && a.focal_point == b.focal_point &&
           a.view_up == b.view_up && a.view_angle == b.view_angle && a.parallel == b.parallel &&
           a.parallel_scale == b.parallel_scale && width == o.width && height == o.height &&
           tf_version == o.tf_version && scalar_version == o.scalar_version &&
           splat_frame == o.splat_frame;
}

void VolumeView::set_mode(ViewMethod mode) {
    if (mode == mode_ || !available(mode)) return;
    mode_ = mode;
    invalidate();
}

std::optional<PbvrFrame> VolumeView::draw_particles(const Camera& camera, int width, int height,
                                                    int min_repetitions) {
    // The worker draws from copies: the panel may change the scalar and the function meanwhile.
    if (pbvr_tf_version_ != tf_version_) {
        pbvr_tf_ = std::make_shared<const TransferFunction>(vs_.volume().transfer_function);
        pbvr_tf_version_ = tf_version_;
    }
    if (pbvr_scalar_version_ != scalar_version_) {
        pbvr_scalar_ = std::make_shared<const std::vector<float>>(vs_.scalar);
        pbvr_scalar_version_ = scalar_version_;
    }
    const std::int64_t splat_frame = splat_cycle() ? splat_frame_ : 0;
    const ParticleKey key{mode_, camera, width, height, tf_version_, scalar_version_, splat_frame};
    if (!pbvr_key_ || !(key == *pbvr_key_)) {
        PbvrRequest request;
        request.method = mode_;
        request.camera = camera;
        request.width = width;
        request.height = height;
        request.scalar = pbvr_scalar_;
        request.scalar_version = static_cast<std::uint64_t>(scalar_version_);
        request.tf = pbvr_tf_;
        request.tf_version = static_cast<std::uint64_t>(tf_version_);
        request.background = vs_.scene.background;
        request.splat_frame = splat_frame;
        pbvr_requested_id_ = pbvr_.request(std::move(request));
        pbvr_key_ = key;
    }
    std::optional<PbvrFrame> latest =
        min_repetitions > 0 ? pbvr_.wait_for(pbvr_requested_id_, min_repetitions) : pbvr_.latest();
    const bool newer = latest && (!pbvr_shown_ || latest->request_id != pbvr_shown_->request_id ||
                                  latest->repetitions != pbvr_shown_->repetitions ||
                                  latest->error != pbvr_shown_->error);
    if (newer) {
        if (latest->image) {
            renderer_.show_image(*latest->image);
            active_ = &renderer_;
        }
        pbvr_shown_ = std::move(latest);
    }
    return pbvr_shown_;
}

bool VolumeView::AnimationKey::operator==(const AnimationKey& o) const {
    const Camera &a = camera, &b = o.camera;
    return a.position == b.position && a.focal_point == b.focal_point && a.view_up == b.view_up &&
           a.view_angle == b.view_angle && a.parallel == b.parallel &&
           a.parallel_scale == b.parallel_scale && width == o.width && height == o.height &&
           tf_version == o.tf_version && scalar_version == o.scalar_version;
}

AnimationFrames VolumeView::draw_animation(const Camera& camera, int width, int height, int frame) {
    const AnimationKey key{camera, width, height, tf_version_, scalar_version_};
    if (!animation_key_ || !(key == *animation_key_)) {
        AnimationRequest request;
        request.camera = camera;
        request.width = width;
        request.height = height;
        request.tf = std::make_shared<const TransferFunction>(vs_.volume().transfer_function);
        // The panel's scalar (the scene's own component while it is the scene's array).
        request.scalar = vs_.scalar_name;
        request.component = vs_.scalar_name == vs_.volume().scalar ? vs_.volume().component : -1;
        animation_requested_id_ = animation_->request(std::move(request));
        animation_key_ = key;
    }
    const int total = animation_->total();
    AnimationFrames frames = frame >= 0
                                 ? animation_->wait_for(animation_requested_id_, frame % total)
                                 : animation_->latest();
    const int arrived = static_cast<int>(frames.frames.size());
    if (arrived == 0) return frames;
    int shown = 0;
    if (frame >= 0) {
        shown = frame % total;
        if (shown >= arrived) return frames;  // the render failed before it
    } else {
        const double seconds = seconds_since(started_);
        shown = static_cast<int>(static_cast<std::int64_t>(seconds * kAnimationFps) % arrived);
    }
    if (frames.request_id != animation_shown_id_ || shown != animation_shown_frame_) {
        renderer_.show_image(*frames.frames[static_cast<std::size_t>(shown)]);
        active_ = &renderer_;
        animation_shown_id_ = frames.request_id;
        animation_shown_frame_ = shown;
    }
    return frames;
}

bool VolumeView::DrawnKey::operator==(const DrawnKey& o) const {
    return camera.position == o.camera.position && camera.focal_point == o.camera.focal_point &&
           camera.view_up == o.camera.view_up && camera.parallel_scale == o.camera.parallel_scale &&
           order_id == o.order_id && tf_version == o.tf_version && width == o.width &&
           height == o.height && flow_id == o.flow_id && flow_layers == o.flow_layers;
}

bool VolumeView::draw(const Camera& camera, int width, int height) {
    if (flow_shown()) {
        // The dye, unsorted; a new flow volume appears one layer a frame.
        flow_->advance();
        const GrownFlowVolume* grown = flow_->grown();
        const DrawnKey key{
            camera, 0, tf_version_, width, height, grown ? grown->id : 0, flow_->layers_shown()};
        if (!drawn_ || !(key == *drawn_)) {
            render_flow(CameraFrame(camera, width, height));
            drawn_ = key;
        }
        return flow_->settled();
    }
    if (fused()) {
        // The worker's next picture wakes the window loop (set_wake).
        draw_fused(camera, width, height, 0);
        return true;
    }
    if (animated()) {
        // The frames that have arrived play in a loop; the worker's next frame wakes the window
        // loop (set_wake), which looks at least every 0.1 s.
        draw_animation(camera, width, height, -1);
        return true;
    }
    if (particle_mode()) {
        // Vector splats play their texture cycle: the frame follows the clock (the loop looks
        // at least every 0.1 s).
        if (splat_cycle()) {
            const double seconds = seconds_since(started_);
            splat_frame_ = static_cast<std::int64_t>(seconds * kSplatCycleFps);
        }
        // The worker's next batch wakes the window loop (set_wake).
        draw_particles(camera, width, height, 0);
        return true;
    }
    const SortedOrder order = current_order(camera, false);
    // The volume is drawn again only when something it shows changed (the panel is drawn
    // every frame so that it stays responsive).
    const DrawnKey key{camera, order.view_id, tf_version_, width, height, 0, 0};
    if (!drawn_ || !(key == *drawn_)) {
        render_volume(CameraFrame(camera, width, height), order);
        drawn_ = key;
    }
    return order_current_;
}

void VolumeView::rebuild_transfer_function() {
    tf_dirty_ = false;
    if (fused()) {
        for (std::size_t v = 0; v < fused_dirty_.size(); ++v) {
            if (!fused_dirty_[v]) continue;
            fused_dirty_[v] = false;
            auto tf = make_transfer_function(vs_.fused[v].edit);
            if (!tf.ok()) {
                status_ = "volume " + std::to_string(v) + ": " + tf.error().message;
                continue;
            }
            vs_.scene.volumes[v].transfer_function = std::move(tf).value();
            fused_state_[v].tf =
                std::make_shared<const TransferFunction>(vs_.scene.volumes[v].transfer_function);
            fused_state_[v].tf_version = ++fused_version_;
        }
        return;
    }
    auto tf = make_transfer_function(vs_.edit);
    if (!tf.ok()) {
        status_ = tf.error().message;
        return;
    }
    vs_.volume().transfer_function = std::move(tf).value();
    ++tf_version_;
    // The GL textures (the pre-integrated table: 0.1-0.3 s) when projected tetrahedra draw.
    gl_tf_stale_ = true;
    if (!particle_mode()) update_gl_transfer_function();
    if (flow_) flow_->set_integrator(integrator_);
}

void VolumeView::set_integrator(Integrator integrator) {
    if (integrator == integrator_) return;
    integrator_ = integrator;
    tf_dirty_ = true;
}

void VolumeView::select_scalar(const std::string& name) {
    const Status s = viewer::select_scalar(vs_, name);
    if (s.ok()) {
        renderer_.set_scalar(vs_.scalar);
        ++scalar_version_;
        tf_dirty_ = true;
        status_.clear();
    } else {
        status_ = s.error().message;
    }
}

}  // namespace tr::viewer
