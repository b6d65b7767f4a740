#include <apps/viewer/opacity_editor.h>

#include <imgui.h>

#include <algorithm>

namespace tr::viewer {

bool OpacityEditor::draw(TransferEdit& e, const TransferFunction& tf) {
    bool changed = false;
    const ImVec2 size(300, 120);
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("opacity_curve", size,
                           ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const double span = e.hi > e.lo ? e.hi - e.lo : 1.0;
    // Colour strip along the bottom, the curve above it.
    const int strips = 60;
    for (int i = 0; i < strips; ++i) {
        const double s = e.lo + span * (i + 0.5) / strips;
        const Vec3 c = tf.color(s);
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
            const float d = (q.x - mouse.x) * (q.x - mouse.x) + (q.y - mouse.y) * (q.y - mouse.y);
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
        changed = true;
    } else if (ImGui::IsItemHovered() && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) {
        const int i = nearest();
        if (i >= 0 && e.opacity.size() > 2) {
            e.opacity.erase(e.opacity.begin() + i);
            changed = true;
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
            changed = true;
        }
    } else {
        dragging_ = -1;
    }
    for (const OpacityPoint& p : e.opacity)
        draw->AddCircleFilled(to_screen(p), 4.0f, IM_COL32(255, 200, 60, 255));
    return changed;
}

}  // namespace tr::viewer
