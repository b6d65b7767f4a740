// The methods of this build, by the names scenes give them (../shared/spec/scene.md, "Method").
// A new method: its own file with a make_*_method() and one line in methods() below.
#include <pipeline/methods/method.h>
#include <pipeline/methods/method_keys.h>
#include <pipeline/methods/pbvr_methods.h>
#include <pipeline/methods/projected_tetrahedra.h>
#include <pipeline/methods/splat_method.h>
#include <pipeline/methods/spot_noise_method.h>
#include <pipeline/methods/texture_advection_method.h>

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

std::string methods_markdown() {
    std::string md;
    for (const auto& m : methods()) {
        if (!md.empty()) md += '\n';
        md += method_keys_markdown(m->name(), m->keys());
    }
    return md;
}

}  // namespace tr
