#pragma once
// Marks placed by the scene's camera: the mesh's bounding box as 12 projected edges, and an
// axes triad in a corner showing where world x, y and z point in this view.

#include <core/camera.h>
#include <core/image.h>
#include <overlay/text.h>

namespace tr {

// A line from image point a to b (pixel units, pixel centres at half-integers), one pixel
// wide, overwriting: every pixel the segment passes through is set (walked in steps of at most
// a quarter pixel, both ends included), clipped to the image.
void draw_line(Image& image, const Vec3& a, const Vec3& b, const Vec3f& color);

// The 12 edges of `bounds` projected with `camera` at the image's size; under perspective an
// edge is cut where it passes behind the eye (depth below 1e-6 of the box's diagonal). Each
// corner in front of the eye lands on the pixel CameraFrame::project gives. Nothing for empty
// bounds.
void draw_bounding_box(Image& image, const Camera& camera, const Bounds3& bounds,
                       const Vec3f& color);

// World x (red), y (green) and z (blue) as seen by `camera`'s orientation (its right and up
// vectors; no perspective), drawn from a point in the bottom-left corner, `length` pixels for
// an axis across the view (0: an eighth of the picture's smaller side, at least 16), the
// farther axes first, each labelled at its tip when `font` is given. Returns the rectangle
// everything drawn lies in.
PixelRect draw_axes_triad(Image& image, const Camera& camera, const Font* font, int length = 0);

}  // namespace tr
