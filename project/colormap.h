#pragma once
// Named colour maps and a default transfer function over a scalar range, for quick looks.

#include <core/result.h>
#include <project/transfer_function.h>

#include <string>
#include <vector>

namespace tr {

// Names accepted by make_quick_transfer_function: "viridis", "coolwarm", "inferno", "gray", then
// the built-in ParaView presets by their names (project/colormap_preset.h: "Cool to Warm",
// "Viridis (matplotlib)", "Jet", ...; those also case-insensitive).
std::vector<std::string> colormap_names();

// A colour map spread over [lo, hi]; opacity rising linearly from 0 at lo to `max_opacity` at
// hi; unit_distance as given. Errors on an unknown name or a non-finite range.
Result<TransferFunction> make_quick_transfer_function(const std::string& colormap, double lo,
                                                      double hi, double max_opacity,
                                                      double unit_distance);

}  // namespace tr
