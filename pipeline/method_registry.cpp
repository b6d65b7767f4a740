// The methods of this build, by the names scenes give them (../shared/spec/scene.md, "Method").
// A new method: its own file with a make_*_method() and one line in methods() below.
#include <pipeline/method.h>
#include <pipeline/pbvr_methods.h>
#include <pipeline/projected_tetrahedra.h>
#include <pipeline/splat_method.h>
#include <pipeline/texture_advection_method.h>

#include <memory>

namespace tr {
namespace {

const std::vector<std::unique_ptr<RenderMethod>>& methods() {
    static const std::vector<std::unique_ptr<RenderMethod>> all = [] {
        std::vector<std::unique_ptr<RenderMethod>> m;
        m.push_back(make_projected_tetrahedra_method());
        m.push_back(make_pbvr_object_method());
        m.push_back(make_pbvr_image_method());
        m.push_back(make_splat_method());
        m.push_back(make_texture_advection_method());
        m.push_back(make_spot_noise_method());
        return m;
    }();
    return all;
}

}  // namespace

const RenderMethod* find_method(std::string_view name) {
    for (const auto& m : methods()) {
        if (m->name() == name) return m.get();
    }
    return nullptr;
}

std::vector<std::string> method_names() {
    std::vector<std::string> names;
    for (const auto& m : methods()) names.emplace_back(m->name());
    return names;
}

Error method_option_error(const Scene& scene, const std::string& key, const std::string& message) {
    return make_error(ErrorCode::kInvalidArgument, "$.method." + key + ": " + message,
                      scene.source);
}

const MethodOption* option(const Scene& scene, const std::string& key) {
    if (!scene.method) return nullptr;
    auto it = scene.method->options.find(key);
    return it == scene.method->options.end() ? nullptr : &it->second;
}

Status only_keys(const Scene& scene, std::string_view name,
                 std::initializer_list<std::string_view> keys) {
    if (!scene.method) return {};
    for (const auto& [key, value] : scene.method->options) {
        bool known = false;
        std::string list = "name, repetitions, seed";
        for (std::string_view k : keys) {
            known = known || k == key;
            list += ", " + std::string(k);
        }
        if (!known) {
            return method_option_error(
                scene, key, "unknown key for " + std::string(name) + " (it takes " + list + ")");
        }
    }
    return {};
}

}  // namespace tr
