#pragma once
// The viewer's window loop: input, the transfer function rebuilt when edited, the volume
// redrawn when its view changed, the panel every frame, screenshots on 's', and waiting for
// events when nothing moves.

#include <apps/viewer/viewer_panel.h>
#include <apps/viewer/volume_view.h>

struct GLFWwindow;

namespace tr::viewer {

// Runs until the window closes (or, with `exit_after_frames` > 0, after that many frames and
// any flow volume being grown: for tests). Starts from the scene's camera; prints the keys.
// `window` has a current OpenGL 3.3 core context and ImGui's GLFW and OpenGL 3 back-ends.
// Returns apps::kExitOk.
int run_interactive(GLFWwindow* window, VolumeView& view, ViewerPanel& panel,
                    int exit_after_frames);

}  // namespace tr::viewer
