#include <apps/viewer/legend_overlay.h>
#include <apps/viewer/viewer_input.h>
#include <apps/viewer/viewer_panel.h>
#include <project/colormap.h>

#include <imgui.h>
#include <imgui/backends/imgui_impl_glfw.h>
#include <imgui/backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <string>

namespace tr::viewer {

namespace {

// The scalar, colour map, opacity curve and unit distance of one volume's transfer function;
// `select` switches the scalar. Returns whether the edit changed.
template <class Select>
bool draw_transfer_section(const std::vector<std::string>& arrays, const std::string& scalar_name,
                           TransferEdit& edit, const TransferFunction& tf, const Bounds3& bounds,
                           OpacityEditor& opacity, Select select) {
    bool changed = false;
    if (ImGui::BeginCombo("scalar", scalar_name.c_str())) {
        for (const std::string& name : arrays) {
            if (ImGui::Selectable(name.c_str(), name == scalar_name) && name != scalar_name) {
                select(name);
            }
        }
        ImGui::EndCombo();
    }
    const std::string current = edit.colormap.empty() ? "scene" : edit.colormap;
    if (ImGui::BeginCombo("colour map", current.c_str())) {
        if (!edit.scene_colors.empty() && ImGui::Selectable("scene", edit.colormap.empty())) {
            edit.colormap.clear();
            changed = true;
        }
        for (const std::string& name : colormap_names()) {
            if (ImGui::Selectable(name.c_str(), name == edit.colormap)) {
                edit.colormap = name;
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    ImGui::Text("opacity (drag points; double-click adds, right-click removes)");
    if (opacity.draw(edit, tf)) changed = true;
    float unit = static_cast<float>(edit.unit_distance);
    const double diag = std::max(bounds.diagonal(), 1e-30);
    if (ImGui::SliderFloat("unit distance", &unit, float(diag * 1e-3), float(diag * 10), "%.4g",
                           ImGuiSliderFlags_Logarithmic)) {
        edit.unit_distance = std::max(static_cast<double>(unit), 1e-30);
        changed = true;
    }
    return changed;
}

}  // namespace

void ViewerPanel::add_frame_ms(double ms) {
    frame_ms_.push_back(ms);
    if (frame_ms_.size() > 30) frame_ms_.pop_front();
}

void ViewerPanel::draw(const Camera& camera, bool submit) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (show_legend_) {
        ViewerScene& vs = view_.scene();
        const std::string& name = vs.fused.empty() ? vs.scalar_name : vs.fused[0].scalar_name;
        draw_legend_overlay(vs.volume().transfer_function, name, vs.log_scale);
    }
    if (show_panel_) draw_panel();
    if (show_panel_ && view_.flow()) view_.flow()->draw_seed_outline(camera);
    if (show_keys_) {
        ImGui::SetNextWindowPos(ImVec2(10, ImGui::GetIO().DisplaySize.y - 40), ImGuiCond_Always);
        ImGui::Begin("keys", nullptr,
                     ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize);
        ImGui::TextUnformatted(kKeyHelp);
        ImGui::End();
    }
    ImGui::Render();
    if (submit) ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

bool ViewerPanel::dragging() const {
    if (opacity_.dragging()) return true;
    for (const OpacityEditor& e : fused_opacity_) {
        if (e.dragging()) return true;
    }
    return false;
}

void ViewerPanel::draw_panel() {
    if (view_.fused()) {
        draw_fused_panel();
        return;
    }
    ViewerScene& vs = view_.scene();
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("tetrender-view", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::Text("%s", vs.volume().mesh.filename().string().c_str());
    ImGui::Text("%zu cells%s", vs.sort.mesh().num_real_tets(),
                vs.sort.sorted->convexified ? " (+ convexification for the sort)" : "");
    ImGui::Checkbox("colour legend", &show_legend_);
    if (draw_transfer_section(vs.arrays, vs.scalar_name, vs.edit, vs.volume().transfer_function,
                              vs.sort.mesh().bounds(), opacity_,
                              [&](const std::string& name) { view_.select_scalar(name); })) {
        view_.mark_dirty();
    }
    // How the picture is made; projected tetrahedra's sort and integrator.
    if (ImGui::BeginCombo("method", view_method_name(view_.mode()).data())) {
        for (int i = 0; i < kViewMethods; ++i) {
            const ViewMethod m = static_cast<ViewMethod>(i);
            if (!view_.available(m)) continue;
            if (ImGui::Selectable(view_method_name(m).data(), m == view_.mode())) view_.set_mode(m);
        }
        ImGui::EndCombo();
    }
    if (view_.animated()) {
        draw_animation_section();
    } else if (view_.particle_mode()) {
        draw_particle_section();
    } else {
        const SortMethod methods[] = {SortMethod::kMpvo, SortMethod::kMpvoNonConvex,
                                      SortMethod::kCentroid};
        if (ImGui::BeginCombo("sort", sort_method_name(view_.method()).data())) {
            for (SortMethod m : methods) {
                if (ImGui::Selectable(sort_method_name(m).data(), m == view_.method()))
                    view_.set_method(m);
            }
            ImGui::EndCombo();
        }
        if (ImGui::BeginCombo("integrator", integrator_name(view_.integrator()).data())) {
            for (Integrator i : {Integrator::kExpTexture, Integrator::kPreintegrated}) {
                if (ImGui::Selectable(integrator_name(i).data(), i == view_.integrator()))
                    view_.set_integrator(i);
            }
            ImGui::EndCombo();
        }
    }
    if (ImGui::CollapsingHeader("flow volume", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (FlowControls* flow = view_.flow()) {
            if (flow->draw_section()) view_.invalidate();
        } else {
            ImGui::TextDisabled("(the mesh has no 3-component point array)");
        }
    }
    ImGui::Separator();
    const gl::GlFrameStats& stats = view_.last_stats();
    double frame = 0;
    for (double ms : frame_ms_) frame += ms;
    if (!frame_ms_.empty()) frame /= static_cast<double>(frame_ms_.size());
    ImGui::Text("frame %.1f ms (%.1f fps)", frame, frame > 0 ? 1000.0 / frame : 0.0);
    if (view_.flow_shown()) {
        ImGui::Text("no sort (one dye colour)  classify %.1f ms  raster %.1f ms", stats.classify_ms,
                    stats.raster_ms);
        if (view_.particle_mode()) {
            ImGui::TextDisabled("(the flow volume is drawn by projected tetrahedra)");
        }
    } else if (view_.animated()) {
        ImGui::Text("frames on the CPU (%zu cells)", vs.sort.mesh().num_real_tets());
    } else if (view_.particle_mode()) {
        ImGui::Text("particles on the CPU (%zu cells)", vs.sort.mesh().num_real_tets());
    } else {
        ImGui::Text("sort %.1f ms (%s)  classify %.1f ms  raster %.1f ms", view_.sort_ms(),
                    view_.order_current() ? "current" : "previous view", stats.classify_ms,
                    stats.raster_ms);
    }
    if (!view_.particle_mode() || view_.flow_shown())
        ImGui::Text("cells %zu, drawn %zu", stats.cells, stats.cells_drawn);
    if (!view_.status().empty())
        ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", view_.status().c_str());
    ImGui::TextDisabled("? lists the keys");
    ImGui::End();
}

void ViewerPanel::draw_animation_section() {
    const AnimationFrames f = view_.animation().latest();
    const int arrived = static_cast<int>(f.frames.size());
    if (!f.error.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", f.error.c_str());
    if (view_.animation_frame_shown() < 0) {
        ImGui::Text("rendering frame 0 of %d (setup)", f.total);
        return;
    }
    ImGui::Text("frame %d of %d, %.0f a second%s", view_.animation_frame_shown(), f.total,
                VolumeView::kAnimationFps, !view_.animation_current() ? " (previous view)" : "");
    ImGui::Text("%d of %d rendered%s", arrived, f.total,
                arrived < f.total && f.error.empty() ? " (rendering)" : "");
    ImGui::Text("frame 0 in %.1f ms, then %.1f ms a frame", f.first_ms, f.frame_ms);
}

void ViewerPanel::draw_particle_section() {
    PbvrWorker& worker = view_.particles();
    int target = worker.target();
    if (ImGui::InputInt("repetitions", &target, 64, 256)) worker.set_target(target);
    const std::optional<PbvrFrame>& f = view_.particles_shown();
    const int batch = worker.settings().batch_for(view_.mode());
    if (!f) {
        ImGui::Text("accumulating: the first batch of %d repetitions", batch);
        return;
    }
    if (!f->error.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", f->error.c_str());
    ImGui::Text("%d repetitions accumulated%s", f->repetitions,
                !view_.particles_current() ? " (previous view)"
                : f->finished              ? " (done)"
                                           : "");
    ImGui::Text("batch %.1f ms (mean %.1f, %d batches of %d)", f->batch_ms, f->mean_batch_ms,
                f->batches, batch);
    ImGui::Text("%zu particles, seed %llu + batch", f->particles,
                static_cast<unsigned long long>(worker.settings().seed));
    if (f->method == ViewMethod::kPbvrObject) {
        ImGui::Text("kept: %d particle sets, %.1f MB", f->kept_sets,
                    static_cast<double>(f->kept_bytes) / (1 << 20));
        ImGui::Text("reused %d repetitions; retarget regenerated %zu of %zu cells",
                    f->reused_repetitions, f->retargeted_cells, f->cells);
    }
}

}  // namespace tr::viewer

namespace tr::viewer {

void ViewerPanel::draw_fused_panel() {
    ViewerScene& vs = view_.scene();
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("tetrender-view", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    std::size_t cells = 0;
    for (const FusedVolume& fv : vs.fused) cells += fv.mesh().num_real_tets();
    ImGui::Text("%zu volumes in one space, %zu cells", vs.fused.size(), cells);
    fused_opacity_.resize(vs.fused.size());
    for (std::size_t v = 0; v < vs.fused.size(); ++v) {
        FusedVolume& fv = vs.fused[v];
        ImGui::PushID(static_cast<int>(v));
        const std::string header = "volume " + std::to_string(v) + ": " +
                                   vs.scene.volumes[v].mesh.filename().string() + "###volume";
        if (ImGui::CollapsingHeader(header.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) {
            ImGui::Text("%zu cells", fv.mesh().num_real_tets());
            if (draw_transfer_section(
                    fv.arrays, fv.scalar_name, fv.edit, vs.scene.volumes[v].transfer_function,
                    fv.mesh().bounds(), fused_opacity_[v],
                    [&](const std::string& name) { view_.select_scalar(v, name); })) {
                view_.mark_dirty(v);
            }
        }
        ImGui::PopID();
    }
    ImGui::Separator();
    if (ImGui::BeginCombo("method", fused_mode_name(view_.fused_mode()).data())) {
        for (FusedMode m : {FusedMode::kProgressive, FusedMode::kPbvrImage, FusedMode::kExact}) {
            if (ImGui::Selectable(fused_mode_name(m).data(), m == view_.fused_mode()))
                view_.set_fused_mode(m);
        }
        ImGui::EndCombo();
    }
    ImGui::TextDisabled("progressive: a pbvr-image batch while moving, exact when still");
    ImGui::TextDisabled("(projected tetrahedra cannot draw them: the cells of intersecting");
    ImGui::TextDisabled(" meshes have no visibility order; exact merges each pixel's segments)");
    FusedWorker& worker = view_.fused_worker();
    if (view_.fused_mode() == FusedMode::kPbvrImage) {
        int target = worker.target();
        if (ImGui::InputInt("repetitions", &target, 64, 256)) worker.set_target(target);
    }
    ImGui::Separator();
    double frame = 0;
    for (double ms : frame_ms_) frame += ms;
    if (!frame_ms_.empty()) frame /= static_cast<double>(frame_ms_.size());
    ImGui::Text("frame %.1f ms (%.1f fps)", frame, frame > 0 ? 1000.0 / frame : 0.0);
    const std::optional<FusedFrame>& f = view_.fused_shown();
    if (!f) {
        ImGui::Text("drawing the first picture");
    } else {
        if (!f->error.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", f->error.c_str());
        const char* state = !view_.fused_current() ? " (previous view)"
                            : f->finished          ? " (done)"
                                                   : "";
        if (f->exact) {
            ImGui::Text("exact fused picture%s: %.1f ms", state, f->exact_ms);
            ImGui::Text("%zu fragments, %zu overlap intervals", f->fragments, f->overlap_intervals);
        } else {
            if (f->preview_scale > 1) {
                ImGui::Text("pbvr-image: %d repetitions at 1/%d of the size%s", f->repetitions,
                            f->preview_scale, state);
            } else {
                ImGui::Text("pbvr-image: %d repetitions%s", f->repetitions, state);
            }
            ImGui::Text("batch %.1f ms (mean %.1f, %d batches)", f->batch_ms, f->mean_batch_ms,
                        f->batches);
            ImGui::Text("%zu particles, seed %llu + batch", f->particles,
                        static_cast<unsigned long long>(worker.settings().seed));
        }
    }
    if (!view_.status().empty())
        ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", view_.status().c_str());
    ImGui::TextDisabled("? lists the keys");
    ImGui::End();
}

}  // namespace tr::viewer
