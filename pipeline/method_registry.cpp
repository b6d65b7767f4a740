// The methods of this build, by the names scenes give them (../shared/spec/scene.md, "Method").
// A new method: its own file with a make_*_method() and one line in methods() below.
#include <memory>
#include <pipeline/method.h>
#include <pipeline/pbvr_methods.h>
#include <pipeline/projected_tetrahedra.h>

namespace tr {
namespace {

// A method the spec names that this build does not have yet: every scene asking for it gets an
// error saying so (never a picture made some other way).
class NotImplementedMethod final : public RenderMethod {
  public:
    NotImplementedMethod(std::string name, std::string issue)
        : name_(std::move(name)), issue_(std::move(issue)) {}
    std::string_view name() const override { return name_; }
    Status check(const Scene& scene, const RenderOptions&) const override {
        return make_error(ErrorCode::kUnsupported,
                          "$.method.name: '" + name_ + "' is not implemented yet (" + issue_ + ")",
                          scene.source);
    }
    Result<RenderResult> render(Pipeline&, const Scene& scene,
                                const RenderOptions& options) const override {
        return check(scene, options).error();
    }

  private:
    std::string name_;
    std::string issue_;
};

const std::vector<std::unique_ptr<RenderMethod>>& methods() {
    static const std::vector<std::unique_ptr<RenderMethod>> all = [] {
        std::vector<std::unique_ptr<RenderMethod>> m;
        m.push_back(make_projected_tetrahedra_method());
        m.push_back(make_pbvr_object_method());
        m.push_back(make_pbvr_image_method());
        m.push_back(std::make_unique<NotImplementedMethod>("splat", "issue 14"));
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

}  // namespace tr
