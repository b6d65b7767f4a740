// Text through FreeType: ink inside the box measure() promises, none outside it.
#include <overlay/text.h>

#include <gtest/gtest.h>

#include <cstdio>

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
    auto font = Font::shared_default();
    ASSERT_TRUE(font.ok());
    Image image(20, 10);
    (*font)->draw(image, "WWWWWW", 24, -5, -8, Vec3f(1.0f));  // mostly outside: no crash
    SUCCEED();
}

TEST(Text, MissingFontIsAOneLineError) {
    auto font = Font::load("/nonexistent/font.ttf");
    ASSERT_FALSE(font.ok());
    EXPECT_EQ(font.error().where, "/nonexistent/font.ttf");
    EXPECT_EQ(font.error().to_string().find('\n'), std::string::npos);
}

}  // namespace
}  // namespace tr
