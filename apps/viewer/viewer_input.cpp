#include <apps/viewer/viewer_input.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

namespace tr::viewer {

static_assert(GLFW_KEY_LAST < 512, "keys_down_ holds every GLFW key");

ViewerInput::ViewerInput(GLFWwindow* window) : window_(window) {
    glfwSetWindowUserPointer(window_, this);
    previous_scroll_ = glfwSetScrollCallback(window_, on_scroll);
    glfwGetCursorPos(window_, &mouse_x_, &mouse_y_);
}

ViewerInput::~ViewerInput() {
    glfwSetScrollCallback(window_, previous_scroll_);
    glfwSetWindowUserPointer(window_, nullptr);
}

void ViewerInput::on_scroll(GLFWwindow* window, double dx, double dy) {
    auto* self = static_cast<ViewerInput*>(glfwGetWindowUserPointer(window));
    if (!self) return;
    self->scroll_ += dy;
    if (self->previous_scroll_) self->previous_scroll_(window, dx, dy);
}

InputActions ViewerInput::poll(CameraControl& camera) {
    InputActions actions;
    double x = 0, y = 0;
    glfwGetCursorPos(window_, &x, &y);
    const double dx = x - mouse_x_, dy = y - mouse_y_;
    mouse_x_ = x, mouse_y_ = y;
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureKeyboard) {
        auto pressed = [&](int key) {
            const bool down = glfwGetKey(window_, key) == GLFW_PRESS;
            const bool was = keys_down_[key];
            keys_down_[key] = down;
            return down && !was;
        };
        if (pressed(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(window_, GLFW_TRUE);
        if (pressed(GLFW_KEY_R)) camera.reset();
        if (pressed(GLFW_KEY_S)) actions.screenshot = true;
        if (pressed(GLFW_KEY_P)) actions.toggle_panel = true;
        if (pressed(GLFW_KEY_M)) actions.next_method = true;
        const bool shift = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                           glfwGetKey(window_, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
        // '?' is shift + slash on most layouts.
        if ((pressed(GLFW_KEY_SLASH) && shift) || pressed(GLFW_KEY_H)) actions.toggle_keys = true;
    }
    if (io.WantCaptureMouse) {
        scroll_ = 0;
        return actions;
    }
    const bool left = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    const bool middle = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    const bool shift = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
    int width = 1, height = 1;
    glfwGetWindowSize(window_, &width, &height);
    if ((left && shift) || middle) {
        camera.pan(dx, dy, width, height);
    } else if (left) {
        camera.rotate(dx, dy, width, height);
    }
    double zoom = 0;
    if (right) zoom += dy * 0.01;
    zoom -= scroll_ * 0.1;
    scroll_ = 0;
    camera.zoom(zoom);
    return actions;
}

}  // namespace tr::viewer
