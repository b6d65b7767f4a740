#include <apps/cli_common.h>
#include <apps/viewer/interactive_loop.h>
#include <apps/viewer/viewer_input.h>
#include <core/stopwatch.h>
#include <io/write_image.h>

#define GLFW_INCLUDE_NONE
#include <pipeline/loaded_mesh.h>

#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace tr::viewer {

int run_interactive(GLFWwindow* window, VolumeView& view, ViewerPanel& panel,
                    int exit_after_frames) {
    CameraControl camera(view.scene().scene.camera);
    ViewerInput input(window);
    std::printf("%s\n", kKeyHelp);
    int frames = 0, screenshots = 0;
    bool screenshot_requested = false;  // kept while minimized
    FlowControls* flow = view.flow();
    if (view.flow_shown()) flow->request();
    // A batch of particles accumulated: wake the loop to show it.
    view.set_wake([] { glfwPostEmptyEvent(); });
    while (!glfwWindowShouldClose(window)) {
        // (Tests: a flow volume being grown is waited for.)
        if (exit_after_frames > 0 && frames++ >= exit_after_frames &&
            !(view.flow_shown() && flow->busy()))
            break;
        const auto frame_start = std::chrono::steady_clock::now();
        glfwPollEvents();
        const InputActions actions = input.poll(camera);
        screenshot_requested |= actions.screenshot;
        if (actions.toggle_panel) panel.toggle_panel();
        if (actions.next_method && view.fused()) {
            view.set_fused_mode(
                static_cast<FusedMode>((static_cast<int>(view.fused_mode()) + 1) % 3));
        } else if (actions.next_method) {
            // The next method the view can draw (an animated one only when it is the scene's).
            int next = static_cast<int>(view.mode());
            do {
                next = (next + 1) % kViewMethods;
            } while (!view.available(static_cast<ViewMethod>(next)));
            view.set_mode(static_cast<ViewMethod>(next));
        }
        if (actions.toggle_keys) {
            panel.toggle_keys();
            std::printf("%s\n", kKeyHelp);
        }
        // The pre-integrated table takes 0.1-0.3 s: rebuilt when a drag ends, not during it
        // (the particle-based modes rebuild during drags: their worker takes the latest).
        if (view.tf_dirty() && (!panel.dragging() || view.integrator() == Integrator::kExpTexture ||
                                view.particle_mode() || view.fused())) {
            view.rebuild_transfer_function();
        }
        int fw = 0, fh = 0;
        glfwGetFramebufferSize(window, &fw, &fh);
        if (fw <= 0 || fh <= 0) {  // minimized
            glfwWaitEvents();
            continue;
        }
        const bool idle = view.draw(camera.camera(), fw, fh);
        if (screenshot_requested) {
            screenshot_requested = false;
            const std::string name = "tetrender-view-" + std::to_string(++screenshots) + ".png";
            const Status written = write_image(view.active().read_image(), name);
            if (written.ok()) {
                std::printf("screenshot: %s\n", name.c_str());
            } else {
                std::fprintf(stderr, "tetrender-view: %s\n", written.error().message.c_str());
            }
        }
        view.active().blit_to_default(fw, fh);
        panel.draw(camera.camera());
        glfwSwapBuffers(window);
        panel.add_frame_ms(ms_since(frame_start));
        // Idle (nothing moving, the sort done): wait for events instead of spinning.
        if (idle && !view.tf_dirty()) glfwWaitEventsTimeout(0.1);
    }
    return apps::kExitOk;
}

}  // namespace tr::viewer
