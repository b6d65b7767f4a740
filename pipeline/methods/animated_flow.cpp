#include <pipeline/methods/animated_flow.h>

#include <string>

namespace tr {

MethodKey vectors_key() {
    return {.key = "vectors",
            .type = KeyType::kString,
            .doc = "a 3-component point array of volume 0's mesh: the flow",
            .required = true,
            .expected = "the name of a 3-component point array"};
}

MethodKey dt_key(std::string_view default_doc) {
    return {.key = "dt",
            .type = KeyType::kNumber,
            .default_value = "from the flow",
            .doc = default_doc,
            .lo = 0,
            .open_lo = true};
}

MethodKey steps_key() {
    return {.key = "steps",
            .type = KeyType::kInteger,
            .default_value = "100",
            .doc = "frames after frame 0",
            .lo = 0,
            .hi = static_cast<double>(kMaxAnimationSteps)};
}

MethodKey frame_key() {
    return {.key = "frame",
            .type = KeyType::kInteger,
            .default_value = "`steps`",
            .doc = "the frame a render shows (advecting from frame 0 up to it)",
            .lo = 0,
            .hi = static_cast<double>(kMaxAnimationSteps),
            .expected = "an integer from 0 to steps"};
}

MethodKey unsteady_key() {
    return {
        .key = "unsteady",
        .type = KeyType::kBool,
        .default_value = "false",
        .doc = "false: the velocity of `time_step`; true: linear in time over the file's steps"};
}

MethodKey start_time_key() {
    return {.key = "start_time",
            .type = KeyType::kNumber,
            .default_value = "the first step's",
            .doc = "the flow time of frame 0 (unsteady)"};
}

Status check_animated_scene(const Scene& scene, const RenderOptions& options,
                            std::string_view name) {
    const int steps = steps_of(scene);
    if (const MethodOption* o = option(scene, "frame")) {
        const std::int64_t frame = *std::get_if<std::int64_t>(o);
        if (frame > steps) {
            return method_option_error(scene, "frame",
                                       "frame " + std::to_string(frame) + " is past steps (" +
                                           std::to_string(steps) + ")");
        }
    }
    auto refuse = [&](const std::string& what) {
        return make_error(ErrorCode::kUnsupported, std::string(name) + ": " + what, scene.source);
    };
    if (scene.flow_volume) return refuse("does not draw flow volumes");
    if (options.reference) {
        return refuse(
            "the reference ray caster draws no opaque stops (the sheets split the "
            "volume's integral); use preintegrated or exact");
    }
    return {};
}

Result<SceneFlow> scene_flow(Pipeline& pipeline, const Scene& scene) {
    TR_TRY(FlowDomain domain, pipeline.flow_domain(scene.volumes[0]));
    auto velocity = load_velocity(domain, string_key(scene, "vectors"),
                                  bool_key(scene, "unsteady", false), pipeline.options().load);
    if (!velocity.ok()) {
        // "--unsteady" is the command line's word; a scene says it with the key.
        return method_key_error(scene, velocity.error(),
                                option(scene, "unsteady") ? "unsteady" : "vectors");
    }
    return SceneFlow{std::move(domain), std::move(velocity).value()};
}

std::string planar_scene_note(const PlanarSheet& sheet) {
    return planar_flow_note(sheet) + "; the scene's volume is not drawn (a 2D mesh has none)";
}

int steps_of(const Scene& scene) { return static_cast<int>(integer_key(scene, "steps", 100)); }

int last_frame(const Scene& scene, const RenderOptions& options) {
    const int steps = steps_of(scene);
    return options.on_frame ? steps : static_cast<int>(integer_key(scene, "frame", steps));
}

}  // namespace tr
