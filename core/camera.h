#pragma once
// The camera of a scene file (../shared/spec/scene.md, VTK's conventions): rays through pixel
// centres and the projection of points to the image.
//
// Image coordinates: pixel (i, j) is column i, row j, row 0 at the top; it covers
// [i, i + 1) x [j, j + 1) and its ray passes through (i + 0.5, j + 0.5).

#include <core/math.h>
#include <core/result.h>

#include <cstdint>

namespace tr {

struct Camera {
    Vec3 position{0, 0, 1};
    Vec3 focal_point{0, 0, 0};
    Vec3 view_up{0, 1, 0};
    double view_angle = 30.0;     // vertical field of view in degrees (perspective)
    bool parallel = false;        // true: orthographic
    double parallel_scale = 1.0;  // orthographic: half the view's height in world units
};

struct Ray {
    Vec3 origin;
    Vec3 direction;  // unit length
};

// The camera's frame and the image size, ready for rays and projections.
class CameraFrame {
  public:
    // Preconditions: width, height >= 1; position != focal_point; view_up not parallel to
    // the view direction (validated where scenes are read).
    CameraFrame(const Camera& camera, int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }
    bool orthographic() const { return camera_.parallel; }
    const Vec3& eye() const { return camera_.position; }
    const Vec3& forward() const { return forward_; }  // unit, towards the focal point
    const Vec3& right() const { return right_; }
    const Vec3& up() const { return up_; }

    // The ray through image point (x, y) in pixel units (pixel centres at half-integers).
    Ray ray(double x, double y) const;
    Ray pixel_ray(int i, int j) const { return ray(i + 0.5, j + 0.5); }

    // Perspective: the direction of pixel (i, j)'s ray before it is normalized,
    // forward + nx right + ny up, is affine in the pixel: at_origin + i per_column + j per_row
    // (pixel (0, 0)'s centre at the origin). What a rasterizer steps along a row.
    struct PixelDirections {
        Vec3 at_origin, per_column, per_row;
    };
    PixelDirections pixel_directions() const;

    // Image position (x, y in pixel units) and depth (distance along `forward`) of a world
    // point. For a perspective camera, depth <= 0 means behind the eye: x, y are meaningless.
    Vec3 project(const Vec3& world) const;

  private:
    Camera camera_;
    int width_, height_;
    Vec3 forward_, right_, up_;
    double half_height_;  // perspective: tan(angle / 2); orthographic: parallel_scale
    double aspect_;
};

// Whether `camera` can make rays: every number finite, the eye away from the focal point (by
// more than 1e-12 of their size), view_up not zero nor parallel to the view direction, the view
// angle in (0, 180), the parallel scale positive. Error kInvalidArgument saying what is wrong.
Status check_camera(const Camera& camera);

// A perspective camera (view_angle degrees) looking at the centre of `bounds` from direction
// `from` (the eye lies at centre + k * from), far enough that the bounding sphere fills the
// view; view_up is +z unless `from` is nearly along z (then +y).
Camera framing_camera(const Bounds3& bounds, const Vec3& from, double view_angle = 30.0);

// A random camera for tests and checks: looking at the centre of `bounds` from a random
// direction outside them (perspective, 45 degrees, or orthographic framing the bounds), or,
// with `inside`, from a random point in the middle 60% of the bounds looking in a random
// direction (90 degrees). The same seed gives the same camera.
Camera random_view(const Bounds3& bounds, std::uint64_t seed, bool orthographic, bool inside);

}  // namespace tr
