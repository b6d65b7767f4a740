// Text through FreeType: ink inside the box measure() promises, none outside it.
#include <overlay/text.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace tr {
namespace {

bool lit(const Vec3f& c) { return c.r > 0.0f || c.g > 0.0f || c.b > 0.0f; }

TEST(Text, GlyphPixelsInsideTheBoxAndNothingOutside) {
    auto font = Font::shared_default();
    ASSERT_TRUE(font.ok()) << font.error().to_string();
    Image image(160, 60);
    const PixelRect box = (*font)->draw(image, "Legend 0.25", 16, 10, 20, Vec3f(1.0f));
    EXPECT_EQ(box.x0, 10);
    EXPECT_EQ(box.y0, 20);
    EXPECT_GT(box.width(), 60);  // measured: 99 px for 11 characters at 16 px
    EXPECT_GE(box.height(), 16);
    int inside = 0, outside = 0, left_quarter = 0, right_quarter = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            if (!lit(image.at(x, y))) continue;
            const bool in = x >= box.x0 && x < box.x1 && y >= box.y0 && y < box.y1;
            (in ? inside : outside) += 1;
            if (in && x < box.x0 + box.width() / 4) ++left_quarter;
            if (in && x >= box.x1 - box.width() / 4) ++right_quarter;
        }
    }
    std::printf("text box %dx%d, lit inside %d (left %d, right %d)\n", box.width(), box.height(),
                inside, left_quarter, right_quarter);
    EXPECT_EQ(outside, 0);
    // Measured: 512 lit pixels in a 99 x 19 box (left quarter 129, right 117); the text spans its
    // box (ink in both outer quarters).
    EXPECT_GT(inside, 400);
    EXPECT_GT(left_quarter, 100);
    EXPECT_GT(right_quarter, 90);
    // measure() is the box draw() returns.
    const PixelRect m = (*font)->measure("Legend 0.25", 16, 10, 20);
    EXPECT_EQ(m.x1, box.x1);
    EXPECT_EQ(m.y1, box.y1);
}

TEST(Text, ClippedAtThePictureEdge) {
    // Text mostly outside a 20 x 10 picture, over its top-left and over its bottom-right
    // corner, against the same text drawn whole in a large picture at the same place relative
    // to a 20 x 10 window: the small picture is that window, pixel for pixel (the visible part
    // is drawn, and as it would be unclipped), and the large picture has ink outside the window
    // (the text does reach past the edge). Writes outside the small picture's pixels would be
    // caught by ASan in CI (Image keeps them in one vector).
    auto font = Font::shared_default();
    ASSERT_TRUE(font.ok());
    const int ox = 80, oy = 40;  // the window's corner in the large picture
    for (const auto& [x, y] : std::vector<std::pair<int, int>>{{-5, -8}, {3, 0}}) {
        SCOPED_TRACE(std::to_string(x) + "," + std::to_string(y));
        Image small(20, 10);
        const PixelRect box = (*font)->draw(small, "WWWWWW", 24, x, y, Vec3f(1.0f));
        EXPECT_TRUE(box.x0 < 0 || box.x1 > small.width);
        EXPECT_TRUE(box.y0 < 0 || box.y1 > small.height);
        Image large(260, 100);
        (*font)->draw(large, "WWWWWW", 24, x + ox, y + oy, Vec3f(1.0f));
        int inside = 0, outside = 0, different = 0;
        for (int j = 0; j < large.height; ++j) {
            for (int i = 0; i < large.width; ++i) {
                const bool in_window =
                    i >= ox && i < ox + small.width && j >= oy && j < oy + small.height;
                if (in_window) different += small.at(i - ox, j - oy) == large.at(i, j) ? 0 : 1;
                if (lit(large.at(i, j))) (in_window ? inside : outside) += 1;
            }
        }
        std::printf("lit in the window %d, outside it %d\n", inside, outside);
        EXPECT_EQ(different, 0);
        // Measured: 105 and 43 lit pixels in the window, 1209 and 1271 outside it; bounds at
        // half the smaller.
        EXPECT_GT(inside, 21);
        EXPECT_GT(outside, 600);
    }
}

TEST(Text, MissingFontIsAOneLineError) {
    auto font = Font::load("/nonexistent/font.ttf");
    ASSERT_FALSE(font.ok());
    EXPECT_EQ(font.error().where, "/nonexistent/font.ttf");
    EXPECT_EQ(font.error().to_string().find('\n'), std::string::npos);
}

}  // namespace
}  // namespace tr
