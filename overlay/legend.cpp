#include <overlay/legend.h>
#include <overlay/ticks.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tr {
namespace {

double to_axis(double v, bool log_scale) { return log_scale ? std::log10(v) : v; }
double from_axis(double t, bool log_scale) { return log_scale ? std::pow(10.0, t) : t; }

bool differs(const Vec3f& a, const Vec3f& b) {
    const Vec3f d = glm::abs(a - b);
    return std::max({d.x, d.y, d.z}) > 0.5f / 255.0f;
}

std::size_t covered(const Image& image, const PixelRect& r, const Vec3f& background) {
    std::size_t n = 0;
    for (int y = std::max(r.y0, 0); y < std::min(r.y1, image.height); ++y) {
        for (int x = std::max(r.x0, 0); x < std::min(r.x1, image.width); ++x) {
            if (differs(image.at(x, y), background)) ++n;
        }
    }
    return n;
}

void fill(Image& image, const PixelRect& r, const Vec3f& color) {
    for (int y = std::max(r.y0, 0); y < std::min(r.y1, image.height); ++y) {
        for (int x = std::max(r.x0, 0); x < std::min(r.x1, image.width); ++x)
            image.at(x, y) = color;
    }
}

void frame(Image& image, const PixelRect& r, const Vec3f& color) {
    fill(image, {r.x0 - 1, r.y0 - 1, r.x1 + 1, r.y0}, color);
    fill(image, {r.x0 - 1, r.y1, r.x1 + 1, r.y1 + 1}, color);
    fill(image, {r.x0 - 1, r.y0, r.x0, r.y1}, color);
    fill(image, {r.x1, r.y0, r.x1 + 1, r.y1}, color);
}

struct Label {
    std::string text;
    int row;  // the row the label is centred on
};

}  // namespace

double LegendLayout::value_at_row(int row) const {
    const double t = bar.height() > 1 ? (bar.y1 - 1.0 - row) / (bar.height() - 1.0) : 0.0;
    const double a = to_axis(lo, log_scale), b = to_axis(hi, log_scale);
    if (row >= bar.y1 - 1) return lo;
    if (row <= bar.y0) return hi;
    return from_axis(a + t * (b - a), log_scale);
}

int LegendLayout::row_of(double value) const {
    const double a = to_axis(lo, log_scale), b = to_axis(hi, log_scale);
    const double t = b > a ? (to_axis(value, log_scale) - a) / (b - a) : 0.0;
    const int row = static_cast<int>(std::lround(bar.y1 - 1.0 - t * (bar.height() - 1.0)));
    return std::clamp(row, bar.y0, bar.y1 - 1);
}

Result<LegendLayout> draw_legend(Image& image, const TransferFunction& tf, const LegendSpec& spec) {
    auto font = Font::shared_default();
    if (!font) return font.error();
    return draw_legend(image, tf, spec, **font);
}

Result<LegendLayout> draw_legend(Image& image, const TransferFunction& tf, const LegendSpec& spec,
                                 const Font& font) {
    LegendLayout L;
    L.lo = spec.lo.value_or(tf.color_points().front().s);
    L.hi = spec.hi.value_or(tf.color_points().back().s);
    L.log_scale = spec.log_scale;
    if (!std::isfinite(L.lo) || !std::isfinite(L.hi) || !(L.hi > L.lo)) {
        return make_error(ErrorCode::kInvalidArgument, "legend: the range [" + range_label(L.lo) +
                                                           ", " + range_label(L.hi) +
                                                           "] is empty or not finite");
    }
    if (L.log_scale && !(L.lo > 0)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "legend: a log scale needs a positive range, not [" + range_label(L.lo) +
                              ", " + range_label(L.hi) + "]");
    }
    const Vec3f background =
        spec.background.value_or(image.pixels.empty() ? Vec3f(0.0f) : image.at(0, 0));
    const float luminance =
        0.2126f * background.r + 0.7152f * background.g + 0.0722f * background.b;
    const Vec3f text_color = spec.text_color.value_or(luminance > 0.5f ? Vec3f(0.0f) : Vec3f(1.0f));
    const int f = spec.font_pixels > 0 ? spec.font_pixels : std::clamp(image.height / 40, 10, 28);

    // Labels: the ends and the ticks strictly inside, a tick dropped when it would touch an end.
    const Ticks ticks = L.log_scale ? log_ticks(L.lo, L.hi, spec.max_ticks)
                                    : linear_ticks(L.lo, L.hi, spec.max_ticks);
    const int bar_w = std::max(f, 8);
    const int strip_w = spec.opacity_strip ? std::max(bar_w * 2 / 3, 5) : 0;
    const int gap = std::max(f / 3, 3);
    const int bar_h = std::max(image.height * 9 / 20, 4 * f);
    const int text_h = font.ascent(f) + font.descent(f);

    std::vector<std::string> tick_texts;
    int label_w = font.measure(range_label(L.lo), f).width();
    label_w = std::max(label_w, font.measure(range_label(L.hi), f).width());
    for (double v : ticks.values) {
        tick_texts.push_back(L.log_scale ? tick_label(v, 0) : tick_label(v, ticks.step));
        label_w = std::max(label_w, font.measure(tick_texts.back(), f).width());
    }
    const int title_w = font.measure(spec.title, f).width();
    // The frames take a pixel on each side of the bar and the strip.
    const int body_w = 1 + bar_w + (strip_w > 0 ? gap + strip_w : 0) + 2 + gap + f / 2 + label_w;
    const int block_w = std::max(body_w, title_w);
    const int block_h = text_h + gap + text_h / 2 + bar_h + text_h / 2;
    const int margin = std::max(f / 2, 4);
    if (block_w + 2 * margin > image.width || block_h + 2 * margin > image.height) {
        return make_error(ErrorCode::kInvalidArgument,
                          "legend: the picture (" + std::to_string(image.width) + "x" +
                              std::to_string(image.height) + ") is too small for it (needs " +
                              std::to_string(block_w + 2 * margin) + "x" +
                              std::to_string(block_h + 2 * margin) + ")");
    }

    // Candidate places, in order of preference for ties.
    const int right_x = image.width - margin - block_w, left_x = margin;
    const int centre_y = (image.height - block_h) / 2, top_y = margin;
    const int bottom_y = image.height - margin - block_h;
    std::vector<std::pair<int, int>> places;
    const bool right = spec.place != LegendPlace::kLeft, left = spec.place != LegendPlace::kRight;
    if (right) places.push_back({right_x, centre_y});
    if (left) places.push_back({left_x, centre_y});
    if (spec.place == LegendPlace::kAuto) {
        for (int x : {right_x, left_x}) {
            places.emplace_back(x, top_y);
            places.emplace_back(x, bottom_y);
        }
    }
    std::size_t best = std::numeric_limits<std::size_t>::max();
    int bx = places.front().first, by = places.front().second;
    for (const auto& [x, y] : places) {
        const std::size_t n = covered(image, {x, y, x + block_w, y + block_h}, background);
        if (n < best) {
            best = n;
            bx = x;
            by = y;
        }
    }
    L.whole = {bx, by, bx + block_w, by + block_h};
    const int bar_top = by + text_h + gap + text_h / 2;
    L.bar = {bx + 1, bar_top, bx + 1 + bar_w, bar_top + bar_h};
    if (strip_w > 0)
        L.opacity_strip = {L.bar.x1 + gap, bar_top, L.bar.x1 + gap + strip_w, bar_top + bar_h};

    // Title, bar, strip.
    font.draw(image, spec.title, f, bx, by, text_color);
    for (int y = L.bar.y0; y < L.bar.y1; ++y) {
        const Vec3 c = tf.color(L.value_at_row(y));
        fill(image, {L.bar.x0, y, L.bar.x1, y + 1}, Vec3f(c));
    }
    frame(image, L.bar, text_color);
    if (strip_w > 0) {
        double max_a = 0;
        for (int y = L.opacity_strip.y0; y < L.opacity_strip.y1; ++y) {
            max_a = std::max(max_a, tf.opacity(L.value_at_row(y)));
        }
        const Vec3f strip_bg = background * 0.6f + Vec3f(0.5f) * 0.4f;
        fill(image, L.opacity_strip, strip_bg);
        for (int y = L.opacity_strip.y0; y < L.opacity_strip.y1 && max_a > 0; ++y) {
            const double share = tf.opacity(L.value_at_row(y)) / max_a;
            const int w = static_cast<int>(std::lround(share * strip_w));
            fill(image, {L.opacity_strip.x0, y, L.opacity_strip.x0 + w, y + 1}, text_color * 0.8f);
        }
        frame(image, L.opacity_strip, text_color);
    }

    // Ticks and labels to the right of the bar (and strip).
    const int tick_x0 = (strip_w > 0 ? L.opacity_strip.x1 : L.bar.x1) + 1;
    const int label_x = tick_x0 + gap + f / 2;
    std::vector<Label> labels{{range_label(L.hi), L.bar.y0}, {range_label(L.lo), L.bar.y1 - 1}};
    L.ticks = {L.lo};
    L.tick_rows = {L.bar.y1 - 1};
    for (std::size_t i = 0; i < ticks.values.size(); ++i) {
        const int row = L.row_of(ticks.values[i]);
        if (row - L.bar.y0 < text_h || L.bar.y1 - 1 - row < text_h) continue;  // touches an end
        labels.push_back({tick_texts[i], row});
        L.ticks.push_back(ticks.values[i]);
        L.tick_rows.push_back(row);
    }
    L.ticks.push_back(L.hi);
    L.tick_rows.push_back(L.bar.y0);
    for (const Label& label : labels) {
        fill(image, {tick_x0, label.row, tick_x0 + gap + f / 4, label.row + 1}, text_color);
        font.draw(image, label.text, f, label_x, label.row - text_h / 2, text_color);
    }
    return L;
}

}  // namespace tr
