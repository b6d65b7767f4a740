#pragma once
// The panel's opacity-curve widget (Dear ImGui): the transfer function's opacity points over
// its colour strip, dragged with the left button, a double click adds one, a right click
// removes one (two stay).

#include <apps/viewer/viewer_scene.h>
#include <project/transfer_function.h>

namespace tr::viewer {

class OpacityEditor {
  public:
    // Draws the widget at ImGui's cursor (inside a window) and applies this frame's clicks and
    // drags to `edit.opacity` (points stay sorted by scalar, opacities in [0, 0.99]). `tf`
    // gives the colour strip. Returns whether the points changed.
    bool draw(TransferEdit& edit, const TransferFunction& tf);

    // Whether a point is being dragged (the pre-integrated table waits for the drag's end).
    bool dragging() const { return dragging_ >= 0; }

  private:
    int dragging_ = -1;  // index of the point being dragged
};

}  // namespace tr::viewer
