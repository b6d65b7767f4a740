#include <apps/viewer/legend_overlay.h>
#include <overlay/ticks.h>

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace tr::viewer {

namespace {

ImU32 color_of(const Vec3& c, float alpha = 1.0f) {
    return ImGui::ColorConvertFloat4ToU32(ImVec4(float(c.r), float(c.g), float(c.b), alpha));
}

}  // namespace

void draw_legend_overlay(const TransferFunction& tf, const std::string& title, bool decades) {
    const double lo = tf.color_points().front().s, hi = tf.color_points().back().s;
    if (!(hi > lo)) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float font = ImGui::GetFontSize();
    const float bar_w = std::max(font, 10.0f), gap = font * 0.4f, margin = font;
    const float bar_h = display.y * 0.45f;
    if (bar_h < 3 * font || display.x < 8 * font) return;

    // Ticks where the bar's axis (the scalar, or its log10) is; labels of the values.
    Ticks ticks = linear_ticks(lo, hi, 7);
    const auto value = [&](double s) { return decades ? std::pow(10.0, s) : s; };
    if (decades) {
        const Ticks powers = log_ticks(value(lo), value(hi), 7);
        ticks.values.clear();
        for (double v : powers.values) ticks.values.push_back(std::log10(v));
    }
    std::vector<std::pair<std::string, double>> labels{{range_label(value(hi)), hi},
                                                       {range_label(value(lo)), lo}};
    for (double v : ticks.values) {
        const double t = (v - lo) / (hi - lo);
        if (t * bar_h < font * 1.1f || (1 - t) * bar_h < font * 1.1f) continue;  // touches an end
        labels.push_back({decades ? tick_label(value(v), 0) : tick_label(v, ticks.step), v});
    }
    float label_w = 0;
    for (const auto& l : labels)
        label_w = std::max(label_w, ImGui::CalcTextSize(l.first.c_str()).x);
    const float title_w = ImGui::CalcTextSize(title.c_str()).x;
    const float body_w = bar_w + gap + font * 0.4f + label_w;
    const float block_w = std::max(body_w, title_w);
    const float x0 = display.x - margin - block_w;
    const float y_title = (display.y - bar_h) * 0.5f - font * 1.6f;
    const float bar_top = y_title + font * 1.6f, bar_bottom = bar_top + bar_h;

    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    draw->AddRectFilled(ImVec2(x0 - gap, y_title - gap),
                        ImVec2(x0 + block_w + gap, bar_bottom + font * 0.6f + gap),
                        IM_COL32(0, 0, 0, 110), 4.0f);
    draw->AddText(ImVec2(x0, y_title), IM_COL32(255, 255, 255, 255), title.c_str());
    // The bar in slices, each shaded between the colours at its ends (the transfer function is
    // piecewise linear: 256 slices follow it within a slice's change).
    const int slices = 256;
    for (int i = 0; i < slices; ++i) {
        const float ya = bar_bottom - bar_h * i / slices,
                    yb = bar_bottom - bar_h * (i + 1) / slices;
        const ImU32 below = color_of(tf.color(lo + (hi - lo) * i / slices));
        const ImU32 above = color_of(tf.color(lo + (hi - lo) * (i + 1) / slices));
        draw->AddRectFilledMultiColor(ImVec2(x0, yb), ImVec2(x0 + bar_w, ya), above, above, below,
                                      below);
    }
    draw->AddRect(ImVec2(x0 - 1, bar_top - 1), ImVec2(x0 + bar_w + 1, bar_bottom + 1),
                  IM_COL32(255, 255, 255, 255));
    for (const auto& [text, value] : labels) {
        const float y = bar_bottom - float((value - lo) / (hi - lo)) * bar_h;
        draw->AddLine(ImVec2(x0 + bar_w + 1, y), ImVec2(x0 + bar_w + gap, y),
                      IM_COL32(255, 255, 255, 255));
        draw->AddText(ImVec2(x0 + bar_w + gap + font * 0.4f, y - font * 0.5f),
                      IM_COL32(255, 255, 255, 255), text.c_str());
    }
}

}  // namespace tr::viewer
