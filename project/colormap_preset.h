#pragma once
// ParaView's colour-map presets (the JSON ParaView's "Choose Preset" dialog imports and
// exports): a list of objects with "Name", "ColorSpace", "RGBPoints" (x r g b, ...), optional
// "Points" (opacity: x a midpoint sharpness, ...) and "NanColor"; other keys are ignored.
// Presets are read into the transfer function's colour points (RGB, piecewise linear), and a
// scene's transfer function is written back as one. A few published maps are built in under
// their ParaView names (builtin_colormap_presets).

#include <core/result.h>
#include <project/transfer_function.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tr {

struct ColormapPreset {
    std::string name;
    // ParaView's interpolation space: "RGB", "Lab" (or "CIELAB"), "Diverging" (Moreland's Msh),
    // "HSV"; colours between control points are interpolated in it (preset_colors).
    std::string color_space = "RGB";
    std::vector<ColorPoint> rgb_points;  // at least one; x non-decreasing, rgb in [0, 1]
    // "Points" as (x, a), when the preset has them. ParaView's midpoint and sharpness are read
    // as 0.5 and 0 (linear between points): a note in `notes` says when they were not.
    std::vector<OpacityPoint> opacity_points;
    std::optional<Vec3> nan_color;
    std::vector<std::string> notes;  // what reading approximated
};

// Parses preset JSON: a list of presets or one preset object. `source` names the text in
// errors, which say where: "file.json:12:5: ..." for malformed JSON, "file.json: $[1].RGBPoints:
// ..." for a bad value (a count not a multiple of 4, a colour outside [0, 1], decreasing x, a
// missing Name or RGBPoints, an unknown ColorSpace).
Result<std::vector<ColormapPreset>> parse_colormap_presets(const std::string& text,
                                                           const std::string& source);

// Reads `file` and picks the preset called `name` (exact, then case-insensitive); an empty
// name picks the only preset, or the first when there are several. Errors: parse's, a name
// not in the file (listing the names in it).
Result<ColormapPreset> read_colormap_preset(const std::filesystem::path& file,
                                            const std::string& name = {});

// The presets as ParaView JSON (a list; RGBPoints, Points with midpoint 0.5 and sharpness 0,
// NanColor when set; numbers written to round-trip exactly).
std::string colormap_presets_json(const std::vector<ColormapPreset>& presets);
// Writes them to `file`. Errors: kIo naming the file.
Status write_colormap_presets(const std::vector<ColormapPreset>& presets,
                              const std::filesystem::path& file);

// A transfer function as a preset (ColorSpace "RGB", so reading it back gives the same points).
ColormapPreset preset_from_transfer_function(const TransferFunction& tf, const std::string& name);

// The preset's colours as RGB-linear control points over [lo, hi]: its x range mapped
// linearly onto [lo, hi] (ParaView's "rescale to data range"); a preset in another colour space
// is interpolated in that space, each piece split so that the whole has about 256 pieces (a
// 256-point map is kept as it is). lo == hi, or a one-point preset, gives one point.
std::vector<ColorPoint> preset_colors(const ColormapPreset& preset, double lo, double hi);
// Its opacity points mapped the same way (empty when it has none); opacities are clamped to
// 0.999 (the transfer function's opacity is below 1).
std::vector<OpacityPoint> preset_opacity(const ColormapPreset& preset, double lo, double hi);

// A transfer function from a preset over [lo, hi]: preset_colors, and preset_opacity when the
// preset has opacity points, else `opacity` (e.g. the quick mode's ramp). Errors: those of
// TransferFunction::create (naming the point), a range that is not finite.
Result<TransferFunction> preset_transfer_function(const ColormapPreset& preset, double lo,
                                                  double hi, std::vector<OpacityPoint> opacity,
                                                  double unit_distance);

// Built-in presets by ParaView name: "Cool to Warm", "Viridis (matplotlib)", "Jet",
// "Rainbow Uniform", "Black-Body Radiation", "Inferno (matplotlib)", "Grayscale".
std::vector<std::string> builtin_colormap_preset_names();
// A built-in preset by name, case-insensitive; "Viridis" and "Inferno" are also accepted without
// " (matplotlib)". Errors: kNotFound listing the names.
Result<ColormapPreset> builtin_colormap_preset(const std::string& name);

}  // namespace tr
