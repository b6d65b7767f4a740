#include <apps/viewer/viewer_input.h>
#include <apps/viewer/viewer_panel.h>
#include <project/colormap.h>

#include <imgui.h>
#include <imgui/backends/imgui_impl_glfw.h>
#include <imgui/backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <string>

namespace tr::viewer {

void ViewerPanel::add_frame_ms(double ms) {
    frame_ms_.push_back(ms);
    if (frame_ms_.size() > 30) frame_ms_.pop_front();
}

void ViewerPanel::draw(const Camera& camera, bool submit) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
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

void ViewerPanel::draw_panel() {
    ViewerScene& vs = view_.scene();
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("tetrender-view", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::Text("%s", vs.volume().mesh.filename().string().c_str());
    ImGui::Text("%zu cells%s", vs.sort.mesh().num_real_tets(),
                vs.sort.sorted->convexified ? " (+ convexification for the sort)" : "");
    // Scalar array.
    if (ImGui::BeginCombo("scalar", vs.scalar_name.c_str())) {
        for (const std::string& name : vs.arrays) {
            if (ImGui::Selectable(name.c_str(), name == vs.scalar_name) && name != vs.scalar_name) {
                view_.select_scalar(name);
            }
        }
        ImGui::EndCombo();
    }
    // Colour map.
    const std::string current = vs.edit.colormap.empty() ? "scene" : vs.edit.colormap;
    if (ImGui::BeginCombo("colour map", current.c_str())) {
        if (!vs.edit.scene_colors.empty() && ImGui::Selectable("scene", vs.edit.colormap.empty())) {
            vs.edit.colormap.clear();
            view_.mark_dirty();
        }
        for (const std::string& name : colormap_names()) {
            if (ImGui::Selectable(name.c_str(), name == vs.edit.colormap)) {
                vs.edit.colormap = name;
                view_.mark_dirty();
            }
        }
        ImGui::EndCombo();
    }
    ImGui::Text("opacity (drag points; double-click adds, right-click removes)");
    if (opacity_.draw(vs.edit, vs.volume().transfer_function)) view_.mark_dirty();
    float unit = static_cast<float>(vs.edit.unit_distance);
    const double diag = std::max(vs.sort.mesh().bounds().diagonal(), 1e-30);
    if (ImGui::SliderFloat("unit distance", &unit, float(diag * 1e-3), float(diag * 10), "%.4g",
                           ImGuiSliderFlags_Logarithmic)) {
        vs.edit.unit_distance = std::max(static_cast<double>(unit), 1e-30);
        view_.mark_dirty();
    }
    // How the picture is made; projected tetrahedra's sort and integrator.
    if (ImGui::BeginCombo("method", view_method_name(view_.mode()).data())) {
        for (ViewMethod m :
             {ViewMethod::kProjectedTetrahedra, ViewMethod::kPbvrImage, ViewMethod::kPbvrObject}) {
            if (ImGui::Selectable(view_method_name(m).data(), m == view_.mode())) view_.set_mode(m);
        }
        ImGui::EndCombo();
    }
    if (view_.particle_mode()) {
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
