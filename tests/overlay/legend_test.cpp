// The colour bar: its colours are the transfer function's, its ticks sit at their values, it
// stays inside its rectangle and away from the volume.
#include <overlay/legend.h>
#include <project/colormap_preset.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tr {
namespace {

// Viridis spread evenly over log10(s): what a log-scale colour map is.
TransferFunction log_viridis(double lo, double hi) {
    auto points = preset_colors(*builtin_colormap_preset("Viridis (matplotlib)"), std::log10(lo),
                                std::log10(hi));
    for (auto& p : points) p.s = std::pow(10.0, p.s);
    points.front().s = lo;
    points.back().s = hi;
    return TransferFunction::create(points, {{lo, 0.0}, {hi, 0.4}}, 1.0).value();
}

TransferFunction viridis(double lo, double hi) {
    auto preset = builtin_colormap_preset("Viridis (matplotlib)");
    return TransferFunction::create(preset_colors(*preset, lo, hi), {{lo, 0.0}, {hi, 0.4}}, 1.0)
        .value();
}

double channel_difference(const Vec3f& a, const Vec3& b) {
    return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

TEST(Legend, BarColoursAtTheTicksAreTheTransferFunctionsColours) {
    for (const auto& [lo, hi, log_scale] :
         std::vector<std::tuple<double, double, bool>>{{0.0, 10.0, false},
                                                       {-3.7, 12.2, false},
                                                       {293.15, 913.15, false},
                                                       {1e-3, 250.0, true}}) {
        SCOPED_TRACE(std::to_string(lo) + " .. " + std::to_string(hi));
        const TransferFunction tf = log_scale ? log_viridis(lo, hi) : viridis(lo, hi);
        Image image(512, 512);
        LegendSpec spec;
        spec.title = "temperature";
        spec.log_scale = log_scale;
        auto layout = draw_legend(image, tf, spec);
        ASSERT_TRUE(layout.ok()) << layout.error().to_string();
        EXPECT_DOUBLE_EQ(layout->lo, lo);
        EXPECT_DOUBLE_EQ(layout->hi, hi);
        ASSERT_GE(layout->ticks.size(), 4u);  // the ends and at least two ticks between
        const int x = (layout->bar.x0 + layout->bar.x1) / 2;
        double worst = 0;
        for (std::size_t i = 0; i < layout->ticks.size(); ++i) {
            const int row = layout->tick_rows[i];
            worst =
                std::max(worst, channel_difference(image.at(x, row), tf.color(layout->ticks[i])));
        }
        std::printf("worst tick colour difference %.5f\n", worst);
        // Measured: 0.00204, 0.00356, 0.00246, 0.00328 (a tick's value is at most half a row
        // from its row's on a 230-row bar); the bound is the brief's 1/255 = 0.00392.
        EXPECT_LE(worst, 1.0 / 255.0);
        // Every row is the colour of the value at its centre (to float precision).
        for (int row = layout->bar.y0; row < layout->bar.y1; ++row) {
            ASSERT_LE(channel_difference(image.at(x, row), tf.color(layout->value_at_row(row))),
                      1e-6);
        }
        // Linear ticks are nice numbers in the range, the ends excepted.
        for (std::size_t i = 1; i + 1 < layout->ticks.size(); ++i) {
            EXPECT_GT(layout->ticks[i], lo);
            EXPECT_LT(layout->ticks[i], hi);
        }
    }
}

TEST(Legend, DrawsOnlyInsideItsRectangleAndAvoidsTheVolume) {
    // A "volume" filling the right 60% of the picture: the legend goes left, over background.
    Image image(400, 300, Vec3f(0.1f));
    for (int y = 0; y < image.height; ++y) {
        for (int x = 160; x < image.width; ++x) image.at(x, y) = Vec3f(0.6f, 0.3f, 0.2f);
    }
    const Image before = image;
    LegendSpec spec;
    spec.title = "p";
    auto layout = draw_legend(image, viridis(0, 1), spec);
    ASSERT_TRUE(layout.ok()) << layout.error().to_string();
    EXPECT_LT(layout->whole.x1, 160);  // left of the volume
    int changed_outside = 0, changed_inside = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            if (image.at(x, y) == before.at(x, y)) continue;
            const PixelRect& w = layout->whole;
            const bool in = x >= w.x0 && x < w.x1 && y >= w.y0 && y < w.y1;
            (in ? changed_inside : changed_outside) += 1;
        }
    }
    EXPECT_EQ(changed_outside, 0);
    EXPECT_GT(changed_inside, 1000);
    // The opacity strip shows the ramp: wider at the top (hi) than at the bottom (lo).
    auto filled = [&](int row) {
        int n = 0;
        for (int x = layout->opacity_strip.x0; x < layout->opacity_strip.x1; ++x) {
            n += image.at(x, row) == Vec3f(0.8f) ? 1 : 0;  // the text colour (white) x 0.8
        }
        return n;
    };
    EXPECT_EQ(filled(layout->opacity_strip.y0), layout->opacity_strip.width());
    EXPECT_EQ(filled(layout->opacity_strip.y1 - 1), 0);
}

// The title's and the labels' pixels of a legend drawn over a uniform grey `background`: those
// that differ from it, in the title's box (above the bar) and right of the tick marks.
struct TextPixels {
    int title = 0, labels = 0;        // pixels that differ from the background
    float darkest = 1, lightest = 0;  // their extreme luminances
    int darker = 0, lighter = 0;      // how many are darker or lighter than the background
};

float luminance(const Vec3f& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

TextPixels legend_text(float background) {
    Image image(300, 300, Vec3f(background));
    LegendSpec spec;
    spec.title = "Temperature";
    spec.opacity_strip = false;
    spec.font_pixels = 16;
    auto layout = draw_legend(image, viridis(0, 1), spec);
    EXPECT_TRUE(layout.ok());
    if (!layout.ok()) return {};
    EXPECT_TRUE(layout->opacity_strip.empty());
    const PixelRect title =
        (*Font::shared_default())->measure(spec.title, 16, layout->whole.x0, layout->whole.y0);
    // At f = 16 the tick marks end 10 columns right of the bar (1 + f / 3 + f / 4) and the
    // labels start at 14 (overlay/legend.cpp): the labels' pixels counted from 16 on.
    const int labels_x0 = layout->bar.x1 + 16;
    const float bg = luminance(Vec3f(background));
    TextPixels t;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const bool in_title = x >= title.x0 && x < title.x1 && y >= title.y0 && y < title.y1;
            const bool in_labels = x >= labels_x0 && x < layout->whole.x1 &&
                                   y >= layout->bar.y0 - 16 && y < layout->bar.y1 + 16;
            const float l = luminance(image.at(x, y));
            if ((!in_title && !in_labels) || image.at(x, y) == Vec3f(background)) continue;
            (in_title ? t.title : t.labels) += 1;
            t.darkest = std::min(t.darkest, l);
            t.lightest = std::max(t.lightest, l);
            t.darker += l < bg ? 1 : 0;
            t.lighter += l > bg ? 1 : 0;
        }
    }
    std::printf("background %.2f: title %d pixels, labels %d, luminance %.3f .. %.3f\n", background,
                t.title, t.labels, t.darkest, t.lightest);
    return t;
}

TEST(Legend, LightBackgroundGivesDarkText) {
    // Over light grey the text is black: every pixel of the title and the labels is darker than
    // the background, and a fully covered one is black.
    const TextPixels t = legend_text(0.8f);
    // Measured: 525 pixels in the title, 615 in the labels (the same over dark grey); bounds
    // a quarter below.
    EXPECT_GT(t.title, 390);
    EXPECT_GT(t.labels, 460);
    EXPECT_EQ(t.lighter, 0);
    EXPECT_EQ(t.darker, t.title + t.labels);
    EXPECT_LT(t.darkest, 0.01f);
}

TEST(Legend, DarkBackgroundGivesLightText) {
    // Over dark grey the text is white: every pixel lighter than the background, a fully
    // covered one white.
    const TextPixels t = legend_text(0.2f);
    EXPECT_GT(t.title, 390);
    EXPECT_GT(t.labels, 460);
    EXPECT_EQ(t.darker, 0);
    EXPECT_EQ(t.lighter, t.title + t.labels);
    EXPECT_GT(t.lightest, 0.99f);
}

TEST(Legend, BadInputIsAOneLineError) {
    Image image(300, 300);
    LegendSpec spec;
    spec.log_scale = true;
    auto negative = draw_legend(image, viridis(-1, 1), spec);
    ASSERT_FALSE(negative.ok());
    EXPECT_NE(negative.error().message.find("log scale"), std::string::npos);
    Image tiny(40, 30);
    auto small = draw_legend(tiny, viridis(0, 1), LegendSpec{});
    ASSERT_FALSE(small.ok());
    EXPECT_NE(small.error().message.find("too small"), std::string::npos);
    EXPECT_EQ(small.error().to_string().find('\n'), std::string::npos);
    LegendSpec empty;
    empty.lo = 2.0;
    empty.hi = 2.0;
    EXPECT_FALSE(draw_legend(image, viridis(0, 1), empty).ok());
}

}  // namespace
}  // namespace tr
