#include <project/colormap.h>
#include <project/colormap_preset.h>

#include <cmath>
#include <map>

namespace tr {
namespace {

// Control points at equal spacing in [0, 1] (sampled from the published maps).
const std::map<std::string, std::vector<Vec3>>& maps() {
    static const std::map<std::string, std::vector<Vec3>> m = {
        {"viridis",
         {{0.267, 0.005, 0.329},
          {0.283, 0.141, 0.458},
          {0.254, 0.265, 0.530},
          {0.207, 0.372, 0.553},
          {0.164, 0.471, 0.558},
          {0.128, 0.567, 0.551},
          {0.135, 0.659, 0.518},
          {0.267, 0.749, 0.441},
          {0.478, 0.821, 0.318},
          {0.741, 0.873, 0.150},
          {0.993, 0.906, 0.144}}},
        {"coolwarm",
         {{0.230, 0.299, 0.754},
          {0.436, 0.571, 0.952},
          {0.667, 0.779, 0.993},
          {0.865, 0.865, 0.865},
          {0.968, 0.721, 0.612},
          {0.906, 0.455, 0.355},
          {0.706, 0.016, 0.150}}},
        {"inferno",
         {{0.001, 0.000, 0.014},
          {0.120, 0.047, 0.282},
          {0.333, 0.060, 0.429},
          {0.532, 0.134, 0.416},
          {0.729, 0.213, 0.332},
          {0.892, 0.350, 0.199},
          {0.981, 0.558, 0.035},
          {0.975, 0.800, 0.224},
          {0.988, 0.998, 0.645}}},
        {"gray", {{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}}},
    };
    return m;
}

}  // namespace

std::vector<std::string> colormap_names() {
    std::vector<std::string> names;
    for (const auto& [name, points] : maps()) names.push_back(name);
    for (const auto& name : builtin_colormap_preset_names()) names.push_back(name);
    return names;
}

Result<TransferFunction> make_quick_transfer_function(const std::string& colormap, double lo,
                                                      double hi, double max_opacity,
                                                      double unit_distance) {
    auto it = maps().find(colormap);
    if (it == maps().end() && builtin_colormap_preset(colormap).ok()) {
        if (!std::isfinite(lo) || !std::isfinite(hi)) {
            return make_error(ErrorCode::kInvalidArgument, "the scalar range is not finite");
        }
        if (!(hi > lo)) hi = lo + 1.0;
        return TransferFunction::create(preset_colors(*builtin_colormap_preset(colormap), lo, hi),
                                        {{lo, 0.0}, {hi, max_opacity}}, unit_distance);
    }
    if (it == maps().end()) {
        std::string names;
        for (const auto& n : colormap_names()) names += (names.empty() ? "" : ", ") + n;
        return make_error(ErrorCode::kInvalidArgument,
                          "unknown colour map '" + colormap + "' (known: " + names + ")");
    }
    if (!std::isfinite(lo) || !std::isfinite(hi)) {
        return make_error(ErrorCode::kInvalidArgument, "the scalar range is not finite");
    }
    if (!(hi > lo)) hi = lo + 1.0;
    std::vector<ColorPoint> color;
    const auto& points = it->second;
    for (std::size_t i = 0; i < points.size(); ++i) {
        color.push_back({lo + (hi - lo) * static_cast<double>(i) / (points.size() - 1), points[i]});
    }
    return TransferFunction::create(std::move(color), {{lo, 0.0}, {hi, max_opacity}},
                                    unit_distance);
}

}  // namespace tr
