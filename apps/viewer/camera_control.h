#pragma once
// The viewer's camera moves, without a window: trackball rotation, pan and zoom from mouse
// motion, the home view, and the turn of the headless orbit.

#include <core/camera.h>
#include <core/math.h>

namespace tr::viewer {

// `v` turned by `angle` radians about `axis` (any length > 0), right-handed (Rodrigues).
Vec3 rotate_about(const Vec3& v, const Vec3& axis, double angle);

// `home` turned by `angle` radians about `axis` through its focal point: position and view_up
// turn, the rest is kept. The headless orbit turns about the home view's up.
Camera orbit_camera(const Camera& home, const Vec3& axis, double angle);

// The interactive camera and the view that `r` returns to. Mouse motion is in window pixels,
// x to the right, y down; `width` x `height` is the window (sides clamped to at least 1).
class CameraControl {
  public:
    explicit CameraControl(const Camera& home) : camera_(home), home_(home) {}

    const Camera& camera() const { return camera_; }
    const Camera& home() const { return home_; }
    void reset() { camera_ = home_; }

    // Trackball: horizontal motion turns about the view's up, vertical about its right, 0.01
    // radians a pixel, about the focal point.
    void rotate(double dx, double dy, int width, int height);

    // Moves position and focal point with the picture: the point under the cursor stays under
    // it at the focal point's depth (orthographic: at any depth).
    void pan(double dx, double dy, int width, int height);

    // Scales the distance to the focal point (and an orthographic view's parallel scale) by
    // exp(amount): amount > 0 moves away.
    void zoom(double amount);

  private:
    Camera camera_, home_;
};

}  // namespace tr::viewer
