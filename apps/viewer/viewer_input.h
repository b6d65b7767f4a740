#pragma once
// The viewer's keys and mouse (GLFW): drags and the wheel move the camera, keys ask for
// actions; what Dear ImGui wants (the panel under the cursor, a text field) is left to it.

#include <apps/viewer/camera_control.h>

struct GLFWwindow;

namespace tr::viewer {

// The list printed at start and on '?', and shown in the keys window.
constexpr const char* kKeyHelp =
    "keys: left drag rotate | right drag or wheel zoom | middle drag or shift+left drag pan | "
    "r reset view | m next method (projected tetrahedra, pbvr-image, pbvr-object, splat, and the "
    "scene's texture-advection or spot-noise; several volumes: progressive, pbvr-image, exact) | "
    "s screenshot | p panel on/off | ? or h this list "
    "| Esc quit";

// What the keys asked for since the last poll (each on the frame its key went down).
struct InputActions {
    bool screenshot = false;    // s
    bool toggle_panel = false;  // p
    bool toggle_keys = false;   // ? or h
    bool next_method = false;   // m
};

class ViewerInput {
  public:
    // Takes `window`'s scroll callback (calling the one installed before, ImGui's, too) and its
    // user pointer; reads the cursor's position. Create it after ImGui's GLFW back-end.
    explicit ViewerInput(GLFWwindow* window);
    ~ViewerInput();
    ViewerInput(const ViewerInput&) = delete;
    ViewerInput& operator=(const ViewerInput&) = delete;

    // Reads keys and mouse (after glfwPollEvents): Esc closes the window, r resets `camera`,
    // left drag rotates it, right drag and the wheel zoom, middle or shift+left drag pan.
    InputActions poll(CameraControl& camera);

  private:
    static void on_scroll(GLFWwindow* window, double dx, double dy);

    GLFWwindow* window_;
    void (*previous_scroll_)(GLFWwindow*, double, double) = nullptr;
    double scroll_ = 0;  // wheel steps since the last poll
    double mouse_x_ = 0, mouse_y_ = 0;
    bool keys_down_[512] = {};  // by GLFW key code (GLFW_KEY_LAST is 348)
};

}  // namespace tr::viewer
