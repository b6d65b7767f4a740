#include <apps/viewer/view_method.h>

#include <algorithm>
#include <variant>

namespace tr::viewer {
namespace {

constexpr std::string_view kNames[] = {"projected-tetrahedra", "pbvr-image", "pbvr-object", "splat",
                                       "texture-advection",    "spot-noise"};

// The method's own option `key` (checked by Pipeline::check before it is read here).
const MethodOption* option(const MethodSpec& spec, const std::string& key) {
    auto it = spec.options.find(key);
    return it == spec.options.end() ? nullptr : &it->second;
}

}  // namespace

std::string_view view_method_name(ViewMethod method) { return kNames[static_cast<int>(method)]; }

std::optional<ViewMethod> view_method_named(std::string_view name) {
    for (int i = 0; i < kViewMethods; ++i) {
        if (kNames[i] == name) return static_cast<ViewMethod>(i);
    }
    return std::nullopt;
}

int PbvrSettings::batch_for(ViewMethod method) const {
    if (batch > 0) return batch;
    return method == ViewMethod::kPbvrObject ? 4 : 16;
}

Result<ResolvedMethod> resolve_method(const Pipeline& pipeline, const Scene& scene,
                                      const MethodArgs& args) {
    auto unknown = [](const std::string& what, const std::string& name) {
        return make_error(ErrorCode::kInvalidArgument,
                          what + "'" + name +
                              "' is not drawn by the viewer (projected-tetrahedra, pbvr-image, "
                              "pbvr-object, splat, texture-advection, spot-noise)");
    };
    // The scene's method, checked as `tetrender render` checks it (without the flow volume,
    // which the viewer draws by projected tetrahedra whatever the mode).
    Scene checked = scene;
    checked.flow_volume.reset();
    if (!args.method.empty()) {
        if (!view_method_named(args.method)) return unknown("--method ", args.method);
        if (!checked.method) checked.method.emplace();
        if (checked.method->name != args.method) {
            checked.method->name = args.method;
            checked.method->options.clear();  // the scene's method's own keys
        }
    }
    if (args.repetitions > 0) {
        if (!checked.method) checked.method.emplace();
        checked.method->repetitions = args.repetitions;
    }
    if (args.seed) {
        if (!checked.method) checked.method.emplace();
        checked.method->seed = *args.seed;
    }
    if (!args.vectors.empty() || args.cycle > 0) {
        if (checked.method_name() != "splat") {
            return make_error(ErrorCode::kInvalidArgument,
                              "--vectors and --cycle are for --method splat");
        }
        if (!args.vectors.empty()) checked.method->options["vectors"] = args.vectors;
        if (args.cycle > 0) checked.method->options["cycle"] = std::int64_t{args.cycle};
    }
    const std::optional<ViewMethod> method = view_method_named(checked.method_name());
    if (!method) return unknown(scene.source + ": $.method.name: ", checked.method_name());
    TR_TRY_STATUS(pipeline.check(checked));
    ResolvedMethod resolved;
    resolved.method = *method;
    PbvrSettings& pbvr = resolved.pbvr;
    pbvr.repetitions = args.headless ? kDefaultHeadlessRepetitions : kDefaultInteractiveRepetitions;
    pbvr.batch = std::clamp(args.batch, 0, kMaxBatch);
    if (const auto& spec = checked.method) {
        if (spec->repetitions)
            pbvr.repetitions = std::clamp(*spec->repetitions, 1, kMaxRepetitions);
        if (spec->seed) pbvr.seed = static_cast<std::uint64_t>(*spec->seed);
        if (const MethodOption* o = option(*spec, "depth")) {
            pbvr.image.depth = *parse_particle_depth(std::get<std::string>(*o));
        }
        if (const MethodOption* o = option(*spec, "stratified")) {
            pbvr.image.stratified = std::get<bool>(*o);
        }
        if (const MethodOption* o = option(*spec, "control_variate")) {
            pbvr.image.control_variate = std::get<bool>(*o);
        }
        if (const MethodOption* o = option(*spec, "subpixel_level")) {
            pbvr.object.subpixel_level = static_cast<int>(std::get<std::int64_t>(*o));
        }
        if (const MethodOption* o = option(*spec, "sampling")) {
            pbvr.object.sampling = *parse_particle_sampling(std::get<std::string>(*o));
        }
    }
    if (resolved.method == ViewMethod::kSplat) pbvr.splat = splat_settings(checked);
    if (animated_method(resolved.method)) {
        pbvr.animation = *checked.method;
        if (const MethodOption* o = option(*checked.method, "steps")) {
            pbvr.animation_steps = static_cast<int>(std::get<std::int64_t>(*o));
        }
    }
    return resolved;
}

}  // namespace tr::viewer
