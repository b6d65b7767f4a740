// libFuzzer target: ParaView colour-map preset JSON through parse_colormap_presets()
// (project/colormap_preset.h), then each preset parsed made into a transfer function over [0, 1]
// and written back as JSON, which must parse
// again into as many presets.

#include <project/colormap_preset.h>

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    auto presets = tr::parse_colormap_presets(text, "fuzz.json");
    if (!presets.ok()) {
        (void)presets.error().to_string();
        return 0;
    }
    for (const tr::ColormapPreset& preset : presets.value()) {
        auto tf = tr::preset_transfer_function(preset, 0.0, 1.0, {}, 1.0);
        if (!tf.ok()) (void)tf.error().to_string();
    }
    // What was read, written back, reads again (the writer's JSON is the parser's language).
    auto again = tr::parse_colormap_presets(tr::colormap_presets_json(presets.value()), "again");
    if (!again.ok() || again.value().size() != presets.value().size()) __builtin_trap();
    return 0;
}
