#include <apps/viewer/flow_controls.h>

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <span>
#include <string>

namespace tr::viewer {

FlowControls::FlowControls(const FlowDomain& domain, const OpaqueSet& opaque,
                           const std::optional<FlowVolumeSpec>& initial, Integrator integrator,
                           bool verbose)
    : domain_(domain),
      opaque_(opaque),
      integrator_(integrator),
      verbose_(verbose),
      grower_(std::make_unique<FlowGrower>(domain)),
      spec_(initial.value_or(default_flow_spec(domain))),
      shown_(initial.has_value()) {}

void FlowControls::request() {
    grower_->request(spec_, ++request_);
    error_.reset();
}

std::optional<Error> FlowControls::grow_and_wait() {
    request();
    install(grower_->wait_for(request_));
    if (flow_) return std::nullopt;
    return error_ ? *error_ : make_error(ErrorCode::kUnsupported, "the flow volume did not grow");
}

void FlowControls::advance() {
    if (auto grown = grower_->take()) install(std::move(grown));
    if (flow_ && layers_shown_ < num_layers()) ++layers_shown_;
}

void FlowControls::show_layers(std::size_t n) { layers_shown_ = std::min(n, num_layers()); }

// Puts a grown flow volume on screen (from its first layer), or keeps the one there and shows
// why growth failed. While a drag asks for new ones, each finished one is shown.
void FlowControls::install(std::shared_ptr<GrownFlowVolume> grown) {
    if (!grown || (flow_ && grown->id <= flow_->id)) return;
    if (grown->error) {
        error_ = grown->error;
        return;
    }
    if (!dye_renderer_) {
        auto created = gl::GlTetRenderer::create();
        if (!created.ok()) {
            error_ = created.error();
            return;
        }
        dye_renderer_ = std::move(created).value();
        dye_renderer_->set_opaque(opaque_.layers());
    }
    if (verbose_) {
        std::printf("flow volume: %zu layers, %zu tets, %zu particles inserted, grown in %.0f ms\n",
                    grown->volume->layer_tets.size(), grown->volume->mesh.num_tets(),
                    grown->volume->particles_inserted, grown->grow_ms);
    }
    dye_renderer_->set_mesh(&grown->volume->mesh, grown->concentration);
    flow_ = std::move(grown);  // after set_mesh: the previous mesh is no longer referenced
    set_dye_transfer_function();
    dye_order_.resize(flow_->volume->mesh.num_tets());
    std::iota(dye_order_.begin(), dye_order_.end(), CellId{0});
    layers_shown_ = 0;
}

void FlowControls::set_integrator(Integrator integrator) {
    integrator_ = integrator;
    if (flow_) set_dye_transfer_function();
}

void FlowControls::set_dye_transfer_function() {
    dye_renderer_->set_transfer_function(dye_transfer_function(flow_->spec, domain_.mesh()),
                                         integrator_, flow_->longest_edge);
}

gl::GlFrameStats FlowControls::render(const CameraFrame& frame, const Vec3& background) {
    const std::size_t end = flow_->volume->layer_tets[layers_shown_ - 1];
    return dye_renderer_->render(frame, std::span<const CellId>(dye_order_).first(end), background);
}

bool FlowControls::draw_section() {
    bool switched = false;
    if (ImGui::Checkbox("show flow volume", &shown_)) {
        switched = true;
        if (shown_ && !flow_ && !grower_->busy()) request();
    }
    bool changed = false;
    FlowVolumeSpec& spec = spec_;
    if (ImGui::BeginCombo("vectors", spec.vectors.c_str())) {
        for (const std::string& name : domain_.vector_arrays) {
            if (ImGui::Selectable(name.c_str(), name == spec.vectors) && name != spec.vectors) {
                spec.vectors = name;
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    const Bounds3 bounds = domain_.mesh().bounds();
    const double diag = std::max(bounds.diagonal(), 1e-30);
    const double lo = std::min({bounds.lo.x, bounds.lo.y, bounds.lo.z});
    const double hi = std::max({bounds.hi.x, bounds.hi.y, bounds.hi.z});
    if (ImGui::DragScalarN("seed centre", ImGuiDataType_Double, &spec.seed_center.x, 3,
                           static_cast<float>(diag * 2e-3), &lo, &hi, "%.4g")) {
        spec.seed_center = glm::clamp(spec.seed_center, bounds.lo, bounds.hi);
        changed = true;
    }
    const double size_lo = diag * 1e-3, size_hi = diag;
    changed |= ImGui::SliderScalar("seed width", ImGuiDataType_Double, &spec.seed_width, &size_lo,
                                   &size_hi, "%.4g", ImGuiSliderFlags_Logarithmic);
    changed |= ImGui::SliderScalar("seed height", ImGuiDataType_Double, &spec.seed_height, &size_lo,
                                   &size_hi, "%.4g", ImGuiSliderFlags_Logarithmic);
    changed |= ImGui::SliderInt("resolution", &spec.seed_resolution, 1, 256);
    changed |= ImGui::SliderInt("steps", &spec.steps, 1, 1000);
    const double dt_lo = 1e-6 * diag, dt_hi = diag;
    changed |= ImGui::SliderScalar("dt", ImGuiDataType_Double, &spec.dt, &dt_lo, &dt_hi, "%.4g",
                                   ImGuiSliderFlags_Logarithmic);
    const double split_lo = 0, split_hi = 8;
    if (ImGui::SliderScalar("split threshold", ImGuiDataType_Double, &spec.split_threshold,
                            &split_lo, &split_hi, "%.2f")) {
        // 0 turns adaptive subdivision off; otherwise at least 1.5.
        if (spec.split_threshold > 0 && spec.split_threshold < 1.5)
            spec.split_threshold = spec.split_threshold < 0.75 ? 0.0 : 1.5;
        changed = true;
    }
    ImGui::Checkbox("outline", &show_outline_);
    ImGui::SameLine();
    ImGui::Checkbox("regrow on change", &regrow_on_change_);
    ImGui::SameLine();
    if (ImGui::Button("grow") || (changed && regrow_on_change_)) {
        shown_ = true;
        request();
    }
    if (grower_->busy()) {
        ImGui::Text("growing...");
    } else if (flow_) {
        const FlowVolume& fv = *flow_->volume;
        ImGui::Text("layers %zu / %zu, %zu tets", layers_shown_, fv.layer_tets.size(),
                    fv.mesh.num_tets());
        ImGui::Text("%zu particles inserted, %zu stopped; grown in %.0f ms", fv.particles_inserted,
                    fv.particles_stopped, flow_->grow_ms);
    }
    if (error_) {
        ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 400);
        ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error_->message.c_str());
        ImGui::PopTextWrapPos();
    }
    return switched;
}

void FlowControls::draw_seed_outline(const Camera& camera) {
    if (!shown_ || !show_outline_) return;
    if (!locator_) locator_ = std::make_unique<PointLocator>(domain_.mesh(), *domain_.adjacency);
    const auto corners = seed_polygon(domain_, *locator_, spec_);
    if (!corners) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const CameraFrame frame(camera, std::max(1, int(display.x)), std::max(1, int(display.y)));
    ImVec2 points[4];
    for (int i = 0; i < 4; ++i) {
        const Vec3 p = frame.project((*corners)[i]);
        if (!frame.orthographic() && !(p.z > 0)) return;  // behind the eye
        points[i] = ImVec2(float(p.x), float(p.y));
    }
    ImGui::GetBackgroundDrawList()->AddPolyline(points, 4, IM_COL32(255, 230, 80, 255),
                                                ImDrawFlags_Closed, 2.0f);
}

}  // namespace tr::viewer
