// tetrender-view: the interactive viewer (GLFW window, OpenGL 3.3 core, Dear ImGui panel), and
// its headless screenshot mode for tests and benchmarks.
#include <apps/cli_common.h>
#include <apps/viewer/sort_worker.h>
#include <apps/viewer/viewer_flow.h>
#include <apps/viewer/viewer_scene.h>
#include <core/image.h>
#include <io/write_image.h>
#include <project/colormap.h>
#include <project/gl/gl_renderer.h>

#include <CLI/CLI.hpp>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui/backends/imgui_impl_glfw.h>
#include <imgui/backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <memory>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tr::viewer {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kKeys =
    "keys: left drag rotate | right drag or wheel zoom | middle drag or shift+left drag pan | "
    "r reset view | s screenshot | p panel on/off | ? or h this list | Esc quit";

struct Args {
    std::string input;
    std::string scalar;
    std::string screenshot;
    int frames = 1;
    double orbit = 0;
    std::string size;
    std::string integrator = "exp-texture";
    std::string sort = "auto";
    std::string colormap;
    double opacity = 0;
    double unit_distance = 0;
    bool panel_in_screenshot = false;
    int exit_after_frames = 0;  // interactive mode: quit after this many frames (tests)
    // A flow volume from the command line (as `tetrender flowvol` names the options).
    std::string flowvol_vectors;
    std::vector<double> seed_center, seed_size, seed_normal;
    FlowVolumeSpec flow;  // resolution, steps, dt, split threshold
};

std::string glfw_error_text;
void on_glfw_error(int, const char* description) { glfw_error_text = description; }

double scroll_accumulated = 0;
void on_scroll(GLFWwindow*, double, double dy) { scroll_accumulated += dy; }

Vec3 rotate_about(const Vec3& v, const Vec3& axis, double angle) {
    const Vec3 k = glm::normalize(axis);
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1 - c);
}

// Rolling means of the last frames, for the panel.
struct Rolling {
    std::deque<double> values;
    void add(double v) {
        values.push_back(v);
        if (values.size() > 30) values.pop_front();
    }
    double mean() const {
        double sum = 0;
        for (double v : values) sum += v;
        return values.empty() ? 0 : sum / static_cast<double>(values.size());
    }
};

class Viewer {
  public:
    Viewer(ViewerScene& scene, GLFWwindow* window, gl::GlTetRenderer& renderer,
           Integrator integrator)
        : vs_(scene),
          window_(window),
          renderer_(renderer),
          worker_(scene.sort.mesh(), scene.sort.adjacency()),
          camera_(scene.scene.camera),
          home_(scene.scene.camera),
          method_(scene.sort.method),
          integrator_(integrator) {
        renderer_.set_mesh(&vs_.sort.mesh(), vs_.scalar);
        renderer_.set_opaque(vs_.opaque.layers());
        renderer_.set_transfer_function(vs_.volume().transfer_function, integrator_,
                                        vs_.longest_edge);
        if (vs_.flow) {
            grower_ = std::make_unique<FlowGrower>(*vs_.flow);
            flow_spec_ = vs_.scene.flow_volume.value_or(default_flow_spec(*vs_.flow));
            show_flow_ = vs_.scene.flow_volume.has_value();
        }
    }

    // Headless: N frames along an orbit, the last one written. Returns the exit code.
    int screenshot(const Args& args) {
        const int frames = std::max(args.frames, 1);
        const CameraFrame start(home_, vs_.scene.width, vs_.scene.height);
        const Vec3 axis = start.up();
        double frame_ms = 0, sort_ms = 0, classify_ms = 0, raster_ms = 0;
        std::size_t sorts = 0, drawn = 0;
        std::uint64_t last_seen = 0;
        if (show_flow_) {
            // Grown before the frames; they show it growing, one layer a frame, and the last
            // frame shows all of it.
            request_flow();
            install_flow(grower_->wait_for(flow_request_));
            if (!flow_) return apps::report_error(*flow_error_);
        }
        for (int i = 0; i < frames; ++i) {
            const auto frame_start = Clock::now();
            const double angle = glm::radians(args.orbit) * (i + 1) / frames;
            camera_ = home_;
            camera_.position =
                home_.focal_point + rotate_about(home_.position - home_.focal_point, axis, angle);
            camera_.view_up = rotate_about(home_.view_up, axis, angle);
            const bool last = i + 1 == frames;
            const CameraFrame frame(camera_, vs_.scene.width, vs_.scene.height);
            gl::GlFrameStats stats;
            if (show_flow_) {
                layers_shown_ =
                    last ? flow_->volume->layer_tets.size()
                         : std::min<std::size_t>(i + 1, flow_->volume->layer_tets.size());
                stats = render_flow(frame);
            } else {
                const SortedOrder order = current_order(last);
                if (order.view_id != last_seen) {
                    last_seen = order.view_id;
                    sort_ms += order.stats.milliseconds;
                    ++sorts;
                }
                stats = renderer_.render(frame, *order.order, vs_.scene.background);
                active_ = &renderer_;
            }
            classify_ms += stats.classify_ms;
            raster_ms += stats.raster_ms;
            drawn = stats.cells_drawn;
            if (last && args.panel_in_screenshot) {
                active_->bind_framebuffer();
                last_stats_ = stats;
                frame_ms_.add(ms_since(frame_start));
                // Auto-sized windows appear on ImGui's second frame: lay out twice first.
                draw_ui(false);
                draw_ui(false);
                draw_ui();
            }
            frame_ms += ms_since(frame_start);
        }
        const Image image = active_->read_image();
        const Status written = write_image(image, args.screenshot);
        if (!written.ok()) return apps::report_error(written.error());
        std::string flow;
        if (show_flow_) {
            char text[160];
            std::snprintf(text, sizeof(text),
                          ", flow volume: %zu layers, %zu particles inserted, grown in %.1f ms",
                          flow_->volume->layer_tets.size(), flow_->volume->particles_inserted,
                          flow_->grow_ms);
            flow = text;
        }
        const std::size_t cells =
            show_flow_ ? flow_->volume->mesh.num_tets() : vs_.sort.mesh().num_real_tets();
        std::fprintf(stderr,
                     "tetrender-view: frames %d, %.1f ms/frame mean (%.1f fps), sort %.1f ms mean "
                     "(%zu sorts), classify %.1f ms, raster %.1f ms, %zu cells (%zu drawn), "
                     "%dx%d, %s%s\n",
                     frames, frame_ms / frames, 1000.0 * frames / frame_ms,
                     sorts ? sort_ms / static_cast<double>(sorts) : 0.0, sorts,
                     classify_ms / frames, raster_ms / frames, cells, drawn, vs_.scene.width,
                     vs_.scene.height, integrator_name(integrator_).data(), flow.c_str());
        return apps::kExitOk;
    }

    int interactive(int exit_after_frames) {
        headless_ = false;
        glfwSetScrollCallback(window_, on_scroll);
        std::printf("%s\n", kKeys);
        glfwGetCursorPos(window_, &mouse_x_, &mouse_y_);
        int frames = 0;
        if (show_flow_) request_flow();
        while (!glfwWindowShouldClose(window_)) {
            // (Tests: a flow volume being grown is waited for.)
            if (exit_after_frames > 0 && frames++ >= exit_after_frames &&
                !(show_flow_ && grower_ && grower_->busy()))
                break;
            const auto frame_start = Clock::now();
            glfwPollEvents();
            handle_input();
            // The pre-integrated table takes 0.1-0.3 s: rebuilt when a drag ends, not during it.
            if (tf_dirty_ && (dragging_ < 0 || integrator_ == Integrator::kExpTexture)) {
                rebuild_transfer_function();
            }
            int fw = 0, fh = 0;
            glfwGetFramebufferSize(window_, &fw, &fh);
            if (fw <= 0 || fh <= 0) {  // minimized
                glfwWaitEvents();
                continue;
            }
            bool idle = false;
            if (show_flow_) {
                // The dye, unsorted; a new flow volume appears one layer a frame.
                if (auto grown = grower_->take()) install_flow(std::move(grown));
                if (flow_ && layers_shown_ < flow_->volume->layer_tets.size()) ++layers_shown_;
                const VolumeKey key{camera_,      0, tf_version_, fw, fh, flow_ ? flow_->id : 0,
                                    layers_shown_};
                if (!drawn_ || !(key == *drawn_)) {
                    last_stats_ = render_flow(CameraFrame(camera_, fw, fh));
                    drawn_ = key;
                }
                idle = !grower_->busy() &&
                       (!flow_ || layers_shown_ == flow_->volume->layer_tets.size());
            } else {
                const SortedOrder order = current_order(false);
                // The volume is drawn again only when something it shows changed; the panel is
                // drawn every frame so that it stays responsive.
                const VolumeKey key{camera_, order.view_id, tf_version_, fw, fh, 0, 0};
                if (!drawn_ || !(key == *drawn_)) {
                    const CameraFrame frame(camera_, fw, fh);
                    last_stats_ = renderer_.render(frame, *order.order, vs_.scene.background);
                    active_ = &renderer_;
                    drawn_ = key;
                }
                idle = order_current_;
            }
            if (screenshot_requested_) {
                screenshot_requested_ = false;
                const std::string name =
                    "tetrender-view-" + std::to_string(++screenshots_) + ".png";
                const Status written = write_image(active_->read_image(), name);
                if (written.ok()) {
                    std::printf("screenshot: %s\n", name.c_str());
                } else {
                    std::fprintf(stderr, "tetrender-view: %s\n", written.error().message.c_str());
                }
            }
            active_->blit_to_default(fw, fh);
            draw_ui();
            glfwSwapBuffers(window_);
            frame_ms_.add(ms_since(frame_start));
            // Idle (nothing moving, the sort done): wait for events instead of spinning.
            if (idle && !tf_dirty_) glfwWaitEventsTimeout(0.1);
        }
        return apps::kExitOk;
    }

  private:
    // Asks the worker for the current view's order; returns the latest finished one (waiting
    // only when there is none yet, or when `exact` asks for this very view's).
    SortedOrder current_order(bool exact) {
        const bool changed = !requested_ || camera_.position != requested_->position ||
                             camera_.focal_point != requested_->focal_point ||
                             camera_.view_up != requested_->view_up || method_ != requested_method_;
        if (changed) {
            ++view_id_;
            requested_ = camera_;
            requested_method_ = method_;
            const CameraFrame frame(camera_, 16, 16);
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

    void handle_input() {
        double x = 0, y = 0;
        glfwGetCursorPos(window_, &x, &y);
        const double dx = x - mouse_x_, dy = y - mouse_y_;
        mouse_x_ = x, mouse_y_ = y;
        const ImGuiIO& io = ImGui::GetIO();
        if (!io.WantCaptureKeyboard) {
            auto pressed = [&](int key) {
                const bool down = glfwGetKey(window_, key) == GLFW_PRESS;
                const bool was = keys_down_[key];
                keys_down_[key] = down;
                return down && !was;
            };
            if (pressed(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(window_, GLFW_TRUE);
            if (pressed(GLFW_KEY_R)) camera_ = home_;
            if (pressed(GLFW_KEY_S)) screenshot_requested_ = true;
            if (pressed(GLFW_KEY_P)) show_panel_ = !show_panel_;
            const bool shift = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                               glfwGetKey(window_, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
            // '?' is shift + slash on most layouts.
            if ((pressed(GLFW_KEY_SLASH) && shift) || pressed(GLFW_KEY_H)) {
                show_keys_ = !show_keys_;
                std::printf("%s\n", kKeys);
            }
        }
        if (io.WantCaptureMouse) {
            scroll_accumulated = 0;
            return;
        }
        const bool left = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        const bool right = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
        const bool middle = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
        const bool shift = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
        int ww = 1, wh = 1;
        glfwGetWindowSize(window_, &ww, &wh);
        const CameraFrame frame(camera_, std::max(ww, 1), std::max(wh, 1));
        const Vec3 offset = camera_.position - camera_.focal_point;
        const double distance = glm::length(offset);
        if ((left && shift) || middle) {
            const double scale =
                camera_.parallel
                    ? 2 * camera_.parallel_scale / wh
                    : 2 * distance * std::tan(glm::radians(camera_.view_angle) / 2) / wh;
            const Vec3 shift_by = (-dx * frame.right() + dy * frame.up()) * scale;
            camera_.position += shift_by;
            camera_.focal_point += shift_by;
        } else if (left && (dx != 0 || dy != 0)) {
            // Trackball: horizontal motion about the view's up, vertical about its right.
            Vec3 o = rotate_about(offset, frame.up(), -dx * 0.01);
            Vec3 up = frame.up();
            const Vec3 right = glm::normalize(glm::cross(-o, up));
            o = rotate_about(o, right, -dy * 0.01);
            up = rotate_about(up, right, -dy * 0.01);
            camera_.position = camera_.focal_point + o;
            camera_.view_up = up;
        }
        double zoom = 0;
        if (right) zoom += dy * 0.01;
        zoom -= scroll_accumulated * 0.1;
        scroll_accumulated = 0;
        if (zoom != 0) {
            const double factor = std::exp(zoom);
            camera_.position = camera_.focal_point + offset * factor;
            camera_.parallel_scale *= factor;
        }
    }

    void rebuild_transfer_function() {
        tf_dirty_ = false;
        auto tf = make_transfer_function(vs_.edit);
        if (!tf.ok()) {
            status_ = tf.error().message;
            return;
        }
        vs_.volume().transfer_function = std::move(tf).value();
        ++tf_version_;
        renderer_.set_transfer_function(vs_.volume().transfer_function, integrator_,
                                        vs_.longest_edge);
        if (flow_) set_dye_transfer_function();
    }

    // Asks the grower for the panel's flow volume (a newer request replaces a pending one).
    void request_flow() {
        grower_->request(flow_spec_, ++flow_request_);
        flow_error_.reset();
    }

    // Puts a grown flow volume on screen (from its first layer), or keeps the one there and
    // shows why growth failed. While a drag asks for new ones, each finished one is shown.
    void install_flow(std::shared_ptr<GrownFlowVolume> grown) {
        if (!grown || (flow_ && grown->id <= flow_->id)) return;
        if (grown->error) {
            flow_error_ = grown->error;
            return;
        }
        if (!dye_renderer_) {
            auto created = gl::GlTetRenderer::create();
            if (!created.ok()) {
                flow_error_ = created.error();
                return;
            }
            dye_renderer_ = std::move(created).value();
            dye_renderer_->set_opaque(opaque_surfaces());
        }
        if (!headless_) {
            std::printf(
                "flow volume: %zu layers, %zu tets, %zu particles inserted, grown in %.0f ms\n",
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

    void set_dye_transfer_function() {
        dye_renderer_->set_transfer_function(dye_transfer_function(flow_->spec, vs_.flow->mesh()),
                                             integrator_, flow_->longest_edge);
        ++tf_version_;
    }

    // The dye's first layers_shown_ layers over the opaque surfaces, in any order (one glow
    // colour: compositing commutes); before the first flow volume, the opaque surfaces alone.
    gl::GlFrameStats render_flow(const CameraFrame& frame) {
        if (!flow_ || layers_shown_ == 0) {
            active_ = &renderer_;
            return renderer_.render(frame, {}, vs_.scene.background);
        }
        const std::size_t end = flow_->volume->layer_tets[layers_shown_ - 1];
        active_ = dye_renderer_.get();
        return dye_renderer_->render(frame, std::span<const CellId>(dye_order_).first(end),
                                     vs_.scene.background);
    }

    std::vector<OpaqueSurface> opaque_surfaces() const { return vs_.opaque.layers(); }

    // The panel's flow-volume section: the seed polygon and growth options (a change regrows),
    // what was grown and how long it took.
    void flow_panel() {
        if (!ImGui::CollapsingHeader("flow volume", ImGuiTreeNodeFlags_DefaultOpen)) return;
        if (!vs_.flow) {
            ImGui::TextDisabled("(the mesh has no 3-component point array)");
            return;
        }
        if (ImGui::Checkbox("show flow volume", &show_flow_)) {
            drawn_.reset();
            if (show_flow_ && !flow_ && !grower_->busy()) request_flow();
        }
        bool changed = false;
        FlowVolumeSpec& spec = flow_spec_;
        if (ImGui::BeginCombo("vectors", spec.vectors.c_str())) {
            for (const std::string& name : vs_.flow->vector_arrays) {
                if (ImGui::Selectable(name.c_str(), name == spec.vectors) && name != spec.vectors) {
                    spec.vectors = name;
                    changed = true;
                }
            }
            ImGui::EndCombo();
        }
        const Bounds3 bounds = vs_.flow->mesh().bounds();
        const double diag = std::max(bounds.diagonal(), 1e-30);
        const double lo = std::min({bounds.lo.x, bounds.lo.y, bounds.lo.z});
        const double hi = std::max({bounds.hi.x, bounds.hi.y, bounds.hi.z});
        if (ImGui::DragScalarN("seed centre", ImGuiDataType_Double, &spec.seed_center.x, 3,
                               static_cast<float>(diag * 2e-3), &lo, &hi, "%.4g")) {
            spec.seed_center = glm::clamp(spec.seed_center, bounds.lo, bounds.hi);
            changed = true;
        }
        const double size_lo = diag * 1e-3, size_hi = diag;
        changed |= ImGui::SliderScalar("seed width", ImGuiDataType_Double, &spec.seed_width,
                                       &size_lo, &size_hi, "%.4g", ImGuiSliderFlags_Logarithmic);
        changed |= ImGui::SliderScalar("seed height", ImGuiDataType_Double, &spec.seed_height,
                                       &size_lo, &size_hi, "%.4g", ImGuiSliderFlags_Logarithmic);
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
            show_flow_ = true;
            request_flow();
        }
        if (grower_->busy()) {
            ImGui::Text("growing...");
        } else if (flow_) {
            const FlowVolume& fv = *flow_->volume;
            ImGui::Text("layers %zu / %zu, %zu tets", layers_shown_, fv.layer_tets.size(),
                        fv.mesh.num_tets());
            ImGui::Text("%zu particles inserted, %zu stopped; grown in %.0f ms",
                        fv.particles_inserted, fv.particles_stopped, flow_->grow_ms);
        }
        if (flow_error_) {
            ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 400);
            ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", flow_error_->message.c_str());
            ImGui::PopTextWrapPos();
        }
    }

    // The panel's dye polygon, outlined in yellow over the picture (drawn with the panel).
    void seed_outline() {
        if (!locator_)
            locator_ = std::make_unique<PointLocator>(vs_.flow->mesh(), *vs_.flow->adjacency);
        const auto corners = seed_polygon(*vs_.flow, *locator_, flow_spec_);
        if (!corners) return;
        const ImVec2 display = ImGui::GetIO().DisplaySize;
        const CameraFrame frame(camera_, std::max(1, int(display.x)), std::max(1, int(display.y)));
        ImVec2 points[4];
        for (int i = 0; i < 4; ++i) {
            const Vec3 p = frame.project((*corners)[i]);
            if (!frame.orthographic() && !(p.z > 0)) return;  // behind the eye
            points[i] = ImVec2(float(p.x), float(p.y));
        }
        ImGui::GetBackgroundDrawList()->AddPolyline(points, 4, IM_COL32(255, 230, 80, 255),
                                                    ImDrawFlags_Closed, 2.0f);
    }

    // The opacity curve: points dragged with the left button, a double click adds one, a right
    // click removes one (two stay).
    void opacity_editor() {
        TransferEdit& e = vs_.edit;
        const ImVec2 size(300, 120);
        const ImVec2 p0 = ImGui::GetCursorScreenPos();
        ImGui::InvisibleButton(
            "opacity_curve", size,
            ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
        ImDrawList* draw = ImGui::GetWindowDrawList();
        const double span = e.hi > e.lo ? e.hi - e.lo : 1.0;
        // Colour strip along the bottom, the curve above it.
        const int strips = 60;
        for (int i = 0; i < strips; ++i) {
            const double s = e.lo + span * (i + 0.5) / strips;
            const Vec3 c = vs_.volume().transfer_function.color(s);
            draw->AddRectFilled(
                ImVec2(p0.x + size.x * i / strips, p0.y + size.y - 10),
                ImVec2(p0.x + size.x * (i + 1) / strips, p0.y + size.y),
                ImGui::ColorConvertFloat4ToU32(ImVec4(float(c.x), float(c.y), float(c.z), 1.0f)));
        }
        draw->AddRect(p0, ImVec2(p0.x + size.x, p0.y + size.y), IM_COL32(200, 200, 200, 255));
        const float plot_h = size.y - 12;
        auto to_screen = [&](const OpacityPoint& p) {
            return ImVec2(p0.x + float((p.s - e.lo) / span) * size.x,
                          p0.y + plot_h * (1.0f - float(p.a)));
        };
        for (std::size_t i = 0; i + 1 < e.opacity.size(); ++i) {
            draw->AddLine(to_screen(e.opacity[i]), to_screen(e.opacity[i + 1]),
                          IM_COL32(255, 255, 255, 255), 2.0f);
        }
        const ImVec2 mouse = ImGui::GetIO().MousePos;
        auto nearest = [&]() {
            int best = -1;
            float best_d = 10 * 10;
            for (std::size_t i = 0; i < e.opacity.size(); ++i) {
                const ImVec2 q = to_screen(e.opacity[i]);
                const float d =
                    (q.x - mouse.x) * (q.x - mouse.x) + (q.y - mouse.y) * (q.y - mouse.y);
                if (d < best_d) best_d = d, best = static_cast<int>(i);
            }
            return best;
        };
        auto from_screen = [&](ImVec2 m) {
            const double s = e.lo + std::clamp((m.x - p0.x) / size.x, 0.0f, 1.0f) * span;
            const double a = std::clamp(1.0 - (m.y - p0.y) / plot_h, 0.0, 0.99);
            return OpacityPoint{s, a};
        };
        if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) {
            const OpacityPoint p = from_screen(mouse);
            auto at = std::lower_bound(e.opacity.begin(), e.opacity.end(), p.s,
                                       [](const OpacityPoint& q, double s) { return q.s < s; });
            e.opacity.insert(at, p);
            tf_dirty_ = true;
        } else if (ImGui::IsItemHovered() && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) {
            const int i = nearest();
            if (i >= 0 && e.opacity.size() > 2) {
                e.opacity.erase(e.opacity.begin() + i);
                tf_dirty_ = true;
            }
        } else if (ImGui::IsItemActivated()) {
            dragging_ = nearest();
        }
        if (dragging_ >= 0 && ImGui::IsItemActive()) {
            OpacityPoint p = from_screen(mouse);
            const std::size_t i = static_cast<std::size_t>(dragging_);
            const double lo = i > 0 ? e.opacity[i - 1].s : e.lo;
            const double hi = i + 1 < e.opacity.size() ? e.opacity[i + 1].s : e.hi;
            p.s = std::clamp(p.s, lo, hi);
            if (p.s != e.opacity[i].s || p.a != e.opacity[i].a) {
                e.opacity[i] = p;
                tf_dirty_ = true;
            }
        } else {
            dragging_ = -1;
        }
        for (const OpacityPoint& p : e.opacity)
            draw->AddCircleFilled(to_screen(p), 4.0f, IM_COL32(255, 200, 60, 255));
    }

    void panel() {
        ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowBgAlpha(0.85f);
        ImGui::Begin("tetrender-view", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
        ImGui::Text("%s", vs_.volume().mesh.filename().string().c_str());
        ImGui::Text("%zu cells%s", vs_.sort.mesh().num_real_tets(),
                    vs_.sort.sorted->convexified ? " (+ convexification for the sort)" : "");
        // Scalar array.
        if (ImGui::BeginCombo("scalar", vs_.scalar_name.c_str())) {
            for (const std::string& name : vs_.arrays) {
                if (ImGui::Selectable(name.c_str(), name == vs_.scalar_name) &&
                    name != vs_.scalar_name) {
                    const Status s = select_scalar(vs_, name);
                    if (s.ok()) {
                        renderer_.set_scalar(vs_.scalar);
                        tf_dirty_ = true;
                        status_.clear();
                    } else {
                        status_ = s.error().message;
                    }
                }
            }
            ImGui::EndCombo();
        }
        // Colour map.
        const std::string current = vs_.edit.colormap.empty() ? "scene" : vs_.edit.colormap;
        if (ImGui::BeginCombo("colour map", current.c_str())) {
            if (!vs_.edit.scene_colors.empty() &&
                ImGui::Selectable("scene", vs_.edit.colormap.empty())) {
                vs_.edit.colormap.clear();
                tf_dirty_ = true;
            }
            for (const std::string& name : colormap_names()) {
                if (ImGui::Selectable(name.c_str(), name == vs_.edit.colormap)) {
                    vs_.edit.colormap = name;
                    tf_dirty_ = true;
                }
            }
            ImGui::EndCombo();
        }
        ImGui::Text("opacity (drag points; double-click adds, right-click removes)");
        opacity_editor();
        float unit = static_cast<float>(vs_.edit.unit_distance);
        const double diag = std::max(vs_.sort.mesh().bounds().diagonal(), 1e-30);
        if (ImGui::SliderFloat("unit distance", &unit, float(diag * 1e-3), float(diag * 10), "%.4g",
                               ImGuiSliderFlags_Logarithmic)) {
            vs_.edit.unit_distance = std::max(static_cast<double>(unit), 1e-30);
            tf_dirty_ = true;
        }
        // Sort and integrator.
        const SortMethod methods[] = {SortMethod::kMpvo, SortMethod::kMpvoNonConvex,
                                      SortMethod::kCentroid};
        if (ImGui::BeginCombo("sort", sort_method_name(method_).data())) {
            for (SortMethod m : methods) {
                if (ImGui::Selectable(sort_method_name(m).data(), m == method_)) method_ = m;
            }
            ImGui::EndCombo();
        }
        if (ImGui::BeginCombo("integrator", integrator_name(integrator_).data())) {
            for (Integrator i : {Integrator::kExpTexture, Integrator::kPreintegrated}) {
                if (ImGui::Selectable(integrator_name(i).data(), i == integrator_) &&
                    i != integrator_) {
                    integrator_ = i;
                    tf_dirty_ = true;
                }
            }
            ImGui::EndCombo();
        }
        flow_panel();
        ImGui::Separator();
        const double frame = frame_ms_.mean();
        ImGui::Text("frame %.1f ms (%.1f fps)", frame, frame > 0 ? 1000.0 / frame : 0.0);
        if (show_flow_) {
            ImGui::Text("no sort (one dye colour)  classify %.1f ms  raster %.1f ms",
                        last_stats_.classify_ms, last_stats_.raster_ms);
        } else {
            ImGui::Text("sort %.1f ms (%s)  classify %.1f ms  raster %.1f ms", sort_ms_,
                        order_current_ ? "current" : "previous view", last_stats_.classify_ms,
                        last_stats_.raster_ms);
        }
        ImGui::Text("cells %zu, drawn %zu", last_stats_.cells, last_stats_.cells_drawn);
        if (!status_.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", status_.c_str());
        ImGui::TextDisabled("? lists the keys");
        ImGui::End();
    }

    // One ImGui frame; drawn into the bound framebuffer unless `submit` is false (layout only).
    void draw_ui(bool submit = true) {
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        if (show_panel_) panel();
        if (show_panel_ && show_flow_ && show_outline_ && vs_.flow) seed_outline();
        if (show_keys_) {
            ImGui::SetNextWindowPos(ImVec2(10, ImGui::GetIO().DisplaySize.y - 40),
                                    ImGuiCond_Always);
            ImGui::Begin("keys", nullptr,
                         ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize);
            ImGui::TextUnformatted(kKeys);
            ImGui::End();
        }
        ImGui::Render();
        if (submit) ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    }

    ViewerScene& vs_;
    GLFWwindow* window_;
    gl::GlTetRenderer& renderer_;
    gl::GlTetRenderer* active_ = &renderer_;  // the renderer whose frame is on screen
    SortWorker worker_;
    Camera camera_, home_;
    std::optional<Camera> requested_;
    SortMethod method_, requested_method_ = SortMethod::kMpvo;
    Integrator integrator_;
    std::uint64_t view_id_ = 0, last_order_id_ = 0;
    bool order_current_ = false;
    double sort_ms_ = 0;
    gl::GlFrameStats last_stats_;
    Rolling frame_ms_;
    bool tf_dirty_ = false, screenshot_requested_ = false, show_panel_ = true, show_keys_ = false;
    int screenshots_ = 0;
    int dragging_ = -1;
    double mouse_x_ = 0, mouse_y_ = 0;
    bool keys_down_[GLFW_KEY_LAST + 1] = {};
    std::string status_;
    // Flow volumes (when the mesh has a vector array): the panel's spec, the grower, the one on
    // screen and its renderer, how many of its layers are drawn.
    std::unique_ptr<FlowGrower> grower_;
    FlowVolumeSpec flow_spec_;
    bool show_flow_ = false, regrow_on_change_ = true;
    std::uint64_t flow_request_ = 0;
    std::shared_ptr<GrownFlowVolume> flow_;
    std::optional<Error> flow_error_;
    std::unique_ptr<gl::GlTetRenderer> dye_renderer_;
    std::vector<CellId> dye_order_;  // 0..n-1
    std::size_t layers_shown_ = 0;
    bool show_outline_ = true;
    bool headless_ = true;
    std::unique_ptr<PointLocator> locator_;  // for the outline, made when first drawn
    // What the last volume frame showed.
    struct VolumeKey {
        Camera camera;
        std::uint64_t order_id;
        int tf_version, width, height;
        std::uint64_t flow_id;
        std::size_t flow_layers;
        bool operator==(const VolumeKey& o) const {
            return camera.position == o.camera.position &&
                   camera.focal_point == o.camera.focal_point &&
                   camera.view_up == o.camera.view_up &&
                   camera.parallel_scale == o.camera.parallel_scale && order_id == o.order_id &&
                   tf_version == o.tf_version && width == o.width && height == o.height &&
                   flow_id == o.flow_id && flow_layers == o.flow_layers;
        }
    };
    std::optional<VolumeKey> drawn_;
    int tf_version_ = 0;
};

// What the display offers when a 3.3 core context cannot be had: a default context's version.
std::string available_gl() {
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    GLFWwindow* probe = glfwCreateWindow(16, 16, "probe", nullptr, nullptr);
    if (!probe) return "no OpenGL context at all";
    glfwMakeContextCurrent(probe);
    using GetString = const unsigned char* (*)(unsigned int);
    auto get_string = reinterpret_cast<GetString>(glfwGetProcAddress("glGetString"));
    std::string text = "?";
    if (get_string) {
        const auto* version = reinterpret_cast<const char*>(get_string(0x1F02));   // GL_VERSION
        const auto* renderer = reinterpret_cast<const char*>(get_string(0x1F01));  // GL_RENDERER
        text =
            std::string("OpenGL ") + (version ? version : "?") + ", " + (renderer ? renderer : "?");
    }
    glfwMakeContextCurrent(nullptr);
    glfwDestroyWindow(probe);
    return text;
}

int fail(const std::string& message) {
    std::fprintf(stderr, "tetrender-view: %s\n", message.c_str());
    return apps::kExitError;
}

int run(const Args& args) {
    ViewerOptions options;
    options.input = args.input;
    options.scalar = args.scalar;
    options.colormap = args.colormap;
    options.max_opacity = args.opacity;
    options.unit_distance = args.unit_distance;
    if (!args.flowvol_vectors.empty()) {
        FlowVolumeSpec spec = args.flow;
        spec.vectors = args.flowvol_vectors;
        spec.seed_center = Vec3(args.seed_center[0], args.seed_center[1], args.seed_center[2]);
        spec.seed_width = args.seed_size[0];
        spec.seed_height = args.seed_size[1];
        if (!args.seed_normal.empty()) {
            spec.seed_normal = Vec3(args.seed_normal[0], args.seed_normal[1], args.seed_normal[2]);
        }
        options.flow_volume = spec;
    }
    const auto integrator = integrator_named(args.integrator);
    if (!integrator.ok() || *integrator == Integrator::kExact) {
        std::fprintf(stderr,
                     "tetrender-view: unknown --integrator '%s' (exp-texture, "
                     "preintegrated)\n",
                     args.integrator.c_str());
        return apps::kExitUsage;
    }
    const auto method = sort_method_named(args.sort);
    if (!method.ok()) {
        std::fprintf(stderr, "tetrender-view: %s\n", method.error().message.c_str());
        return apps::kExitUsage;
    }
    options.sort = *method;
    if (!args.size.empty()) {
        if (!apps::parse_image_size(args.size, options.width, options.height)) {
            std::fprintf(stderr,
                         "tetrender-view: --size must be WxH with sides in [1, %d], not %s\n",
                         kMaxImageSide, args.size.c_str());
            return apps::kExitUsage;
        }
        options.size_given = true;
    }
    if (!args.colormap.empty()) {
        const auto names = colormap_names();
        if (std::find(names.begin(), names.end(), args.colormap) == names.end()) {
            std::fprintf(stderr, "tetrender-view: unknown --colormap '%s'\n",
                         args.colormap.c_str());
            return apps::kExitUsage;
        }
    }
    const bool headless = !args.screenshot.empty();

    auto loaded = load_viewer_scene(options);
    if (!loaded.ok()) return apps::report_error(loaded.error());
    ViewerScene vs = std::move(loaded).value();
    if (!vs.sort.note.empty())
        std::fprintf(stderr, "tetrender-view: note: %s\n", vs.sort.note.c_str());
    if (vs.scene.flow_volume && vs.scene.flow_volume->context) {
        std::fprintf(stderr, "tetrender-view: note: the flow volume's context veil is not drawn\n");
    }

    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland)) {
        return fail("no display: run under xvfb-run or set DISPLAY");
    }
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        return fail("no display: run under xvfb-run or set DISPLAY (GLFW: " + glfw_error_text +
                    ")");
    }
    struct Terminate {
        ~Terminate() {
#if !defined(__SANITIZE_ADDRESS__)
            glfwTerminate();
#endif
            // Under AddressSanitizer the display stays open until exit: closing it unloads
            // Mesa's driver, and LeakSanitizer could then not name the module of the driver's
            // own never-freed allocations (scripts/lsan.supp suppresses them by module).
        }
    } terminate;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, headless ? GLFW_FALSE : GLFW_TRUE);
    GLFWwindow* window = glfwCreateWindow(
        vs.scene.width, vs.scene.height,
        ("tetrender-view: " + vs.volume().mesh.filename().string()).c_str(), nullptr, nullptr);
    if (!window) {
        const std::string why = glfw_error_text;
        return fail("no OpenGL 3.3 core context (GLFW: " + why + "); the display offers " +
                    available_gl());
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(headless ? 0 : 1);
    auto info = gl::check_gl_context();
    if (!info.ok()) {
        glfwDestroyWindow(window);
        return fail(info.error().message);
    }
    int code = apps::kExitOk;
    {
        auto renderer = gl::GlTetRenderer::create();
        if (!renderer.ok()) {
            glfwDestroyWindow(window);
            return fail(renderer.error().message);
        }
        const bool ui = !headless || args.panel_in_screenshot;
        if (ui) {
            IMGUI_CHECKVERSION();
            ImGui::CreateContext();
            ImGui::GetIO().IniFilename = nullptr;
            ImGui_ImplGlfw_InitForOpenGL(window, true);
            ImGui_ImplOpenGL3_Init("#version 330 core");
        }
        {
            Viewer viewer(vs, window, **renderer, *integrator);
            code = headless ? viewer.screenshot(args) : viewer.interactive(args.exit_after_frames);
        }
        if (ui) {
            ImGui_ImplOpenGL3_Shutdown();
            ImGui_ImplGlfw_Shutdown();
            ImGui::DestroyContext();
        }
    }
    glfwDestroyWindow(window);
    return code;
}

}  // namespace
}  // namespace tr::viewer

int main(int argc, char** argv) {
    tr::viewer::Args args;
    CLI::App app{
        "tetrender-view: interactive projected-tetrahedra viewer (OpenGL 3.3). Keys: left drag "
        "rotate, right drag / wheel zoom, middle drag / shift+left pan, r reset, s screenshot, "
        "p panel, ? keys, Esc quit."};
    app.add_option("input", args.input, "Scene file (.json) or mesh file")->required();
    app.add_option("--scalar", args.scalar,
                   "Mesh mode: the array to show (default: the first point array, else the "
                   "first cell array)");
    app.add_option("--screenshot", args.screenshot,
                   "Headless: render --frames frames, write the last (.png or .pfm), exit");
    app.add_option("--frames", args.frames, "Headless: frames along the orbit (default 1)")
        ->check(CLI::Range(1, 100000));
    app.add_option("--orbit", args.orbit,
                   "Headless: degrees the camera turns about the view's up axis over the frames");
    app.add_option("--size", args.size, "Window / image size WxH (default 960x600 or the scene's)");
    app.add_option("--integrator", args.integrator, "exp-texture (default) or preintegrated");
    app.add_option("--sort", args.sort, "auto (default), mpvo, mpvonc, exact, centroid");
    app.add_option("--colormap", args.colormap,
                   "viridis, coolwarm, inferno, gray (default: the scene's colours, or viridis)");
    app.add_option(
           "--opacity", args.opacity,
           "Largest opacity: of the ramp (default 0.3), or a scene's opacity points scaled to it")
        ->check(CLI::Range(0.0, 0.999));
    app.add_option("--unit-distance", args.unit_distance,
                   "Unit distance of the opacities (default: the scene's, or diagonal / 20)")
        ->check(CLI::PositiveNumber);
    auto* vectors = app.add_option("--flowvol-vectors", args.flowvol_vectors,
                                   "Flow volume: grow the dye through this 3-component point "
                                   "array (replaces a scene's flow_volume)");
    auto* center =
        app.add_option("--seed-center", args.seed_center, "Flow volume: dye polygon centre x,y,z")
            ->expected(3)
            ->delimiter(',')
            ->needs(vectors);
    auto* size =
        app.add_option("--seed-size", args.seed_size, "Flow volume: dye polygon width,height")
            ->expected(2)
            ->delimiter(',')
            ->check(CLI::PositiveNumber)
            ->needs(vectors);
    vectors->needs(center)->needs(size);
    app.add_option("--seed-normal", args.seed_normal,
                   "Flow volume: dye polygon normal x,y,z (default: the flow at its centre)")
        ->expected(3)
        ->delimiter(',')
        ->needs(vectors);
    app.add_option("--seed-res", args.flow.seed_resolution,
                   "Flow volume: quads per side of the polygon (default 32)")
        ->check(CLI::Range(1, 4096))
        ->needs(vectors);
    app.add_option("--steps", args.flow.steps, "Flow volume: layers (default 50)")
        ->check(CLI::Range(1, 100000))
        ->needs(vectors);
    app.add_option("--dt", args.flow.dt, "Flow volume: time per layer (default 0.05)")
        ->check(CLI::PositiveNumber)
        ->needs(vectors);
    app.add_option("--split-threshold", args.flow.split_threshold,
                   "Flow volume: split front edges longer than this many seed spacings "
                   "(default 2; 0: off)")
        ->check(CLI::Number)
        ->needs(vectors);
    app.add_flag("--panel-in-screenshot", args.panel_in_screenshot,
                 "Headless: draw the ImGui panel into the screenshot");
    app.add_option("--exit-after-frames", args.exit_after_frames,
                   "Interactive mode: quit after N frames and any flow volume grown (for tests)")
        ->group("");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : tr::apps::kExitUsage;
    }
    try {
        return tr::viewer::run(args);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tetrender-view: %s\n", e.what());
        return tr::apps::kExitError;
    }
}
