// libFuzzer target: scene JSON text through parse_scene() (pipeline/scene.h). Any input must give
// a Scene or an Error; a crash, a hang, a leak or undefined behaviour is a finding.

#include <pipeline/scene.h>

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    auto scene = tr::parse_scene(text, "/nonexistent", "fuzz.json");
    if (!scene.ok()) (void)scene.error().to_string();
    return 0;
}
