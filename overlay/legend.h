#pragma once
// A colour bar for a picture: the array's name above a vertical bar drawn with the transfer
// function's own colours (each row the colour of its value, LegendLayout::value_at_row, exactly
// as TransferFunction::color gives it), the range's ends and nicely rounded ticks beside it
// (overlay/ticks.h, linear or log), and beside the bar a strip with the opacity's shape.
//
// Why opacity is a separate strip and not blended into the bar: the bar is for reading values
// off colours, so it shows the colours unaltered; an opacity is per unit distance, so what a
// viewer sees of it depends on the thickness crossed, and only its shape says something
// general. The strip fills, row by row, a width proportional to a(s) / max a.
//
// Placement: on the right or the left, centred or at the top or bottom, wherever it covers the
// fewest pixels of the picture that differ from the background (the volume); ties go, in
// order, to the right centre, the left centre, then the right and the left corners.

#include <core/image.h>
#include <overlay/text.h>
#include <project/transfer_function.h>

#include <optional>
#include <string>
#include <vector>

namespace tr {

enum class LegendPlace { kAuto, kRight, kLeft };

struct LegendSpec {
    std::string title;             // the array's name
    std::optional<double> lo, hi;  // the range shown; default: the colour points' range
    bool log_scale = false;        // needs 0 < lo < hi
    bool opacity_strip = true;
    LegendPlace place = LegendPlace::kAuto;
    std::optional<Vec3f> background;  // what is not volume; default: the top-left pixel
    std::optional<Vec3f> text_color;  // default: white on a dark background, else black
    int font_pixels = 0;              // 0: the picture's height / 40, in [10, 28]
    int max_ticks = 7;
};

struct LegendLayout {
    PixelRect whole;          // everything drawn lies inside
    PixelRect bar;            // the colour bar; its top row is `hi`, its bottom row `lo`
    PixelRect opacity_strip;  // empty when not drawn
    double lo = 0, hi = 1;
    bool log_scale = false;
    std::vector<double> ticks;   // labelled values strictly inside (lo, hi) plus lo and hi
    std::vector<int> tick_rows;  // the bar row each tick is drawn at

    // The value whose colour row `row` of the bar shows: the rows' centres sample [lo, hi]
    // evenly (linearly or in log10), the bottom row exactly lo and the top row exactly hi.
    double value_at_row(int row) const;
    // The row whose value is nearest to `value` (clamped to the bar).
    int row_of(double value) const;
};

// Draws the legend. Errors (kInvalidArgument): a range that is not finite or empty after
// defaults, a log scale over a range that is not positive, a picture too small to hold it
// (the message says the size it needs).
Result<LegendLayout> draw_legend(Image& image, const TransferFunction& tf, const LegendSpec& spec);

// The same with a given font (the default: Font::shared_default()).
Result<LegendLayout> draw_legend(Image& image, const TransferFunction& tf, const LegendSpec& spec,
                                 const Font& font);

}  // namespace tr
