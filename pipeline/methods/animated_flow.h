#pragma once
// What the animated flow-texture methods (texture-advection, spot-noise) share: the keys both
// take with the same rules, what both refuse of a scene, the flow of the scene's volume 0 and
// the frame a single render shows.

#include <pipeline/flow_volume_scene.h>
#include <pipeline/methods/method.h>

#include <cstdint>
#include <string_view>

namespace tr {

inline constexpr std::int64_t kMaxAnimationSteps = 100000;

// The keys both methods take (`dt`'s default is each method's own).
MethodKey vectors_key();
MethodKey dt_key(std::string_view default_doc);
MethodKey steps_key();
MethodKey frame_key();
MethodKey unsteady_key();
MethodKey start_time_key();

// What both methods refuse of a scene (a flow volume, the reference ray caster), and a
// `frame` past `steps`.
Status check_animated_scene(const Scene& scene, const RenderOptions& options,
                            std::string_view name);

// The domain and velocity (key `vectors`, `unsteady`) of the scene's volume 0. Errors name the
// key they are about.
struct SceneFlow {
    FlowDomain domain;
    VelocityField velocity;
};
Result<SceneFlow> scene_flow(Pipeline& pipeline, const Scene& scene);

// The note of a scene whose mesh is a planar 2D mesh (SceneFlow::domain.planar): what the flow
// is (planar_flow_note) and that the scene's volume is not drawn.
std::string planar_scene_note(const PlanarSheet& sheet);

// The key `steps`: frames after frame 0 (default 100, as steps_key() says).
int steps_of(const Scene& scene);

// The last frame a render advances to: `steps` when every frame is handed over
// (RenderOptions::on_frame), else the key `frame` (default `steps`).
int last_frame(const Scene& scene, const RenderOptions& options);

}  // namespace tr
