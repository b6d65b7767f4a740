#pragma once
// Rendering methods as back-ends of the pipeline: each is one class behind this interface,
// chosen by the scene's `method.name` (../shared/spec/scene.md, section "Method"). Adding a
// method is one new file and one line in method_registry.cpp; no other method changes.

#include <core/result.h>
#include <pipeline/pipeline.h>
#include <pipeline/scene.h>

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace tr {

class RenderMethod {
  public:
    virtual ~RenderMethod() = default;

    // The name scenes give it ("projected-tetrahedra", "pbvr-object", ...).
    virtual std::string_view name() const = 0;

    // Checks, before anything is loaded, the scene's method keys (its own options, repetitions,
    // seed) and what else of the scene this method can draw (several volumes, opaque geometry,
    // a flow volume). Errors name the JSON path ("$.method.depth: ...").
    virtual Status check(const Scene& scene, const RenderOptions& options) const = 0;

    // Whether it draws RenderOptions::transparent (premultiplied RGBA over transparent black).
    virtual bool draws_transparent() const { return false; }

    // Renders the scene, taking meshes, orders and shaders from `pipeline`. Precondition:
    // check() passed.
    virtual Result<RenderResult> render(Pipeline& pipeline, const Scene& scene,
                                        const RenderOptions& options) const = 0;
};

// The method called `name` in this build, or nullptr.
const RenderMethod* find_method(std::string_view name);

// Every method name the spec knows, in its order (those not built yet answer with an error).
std::vector<std::string> method_names();

// An error for a method option at `$.method.<key>` of the scene (its file in `where`).
Error method_option_error(const Scene& scene, const std::string& key, const std::string& message);

// The method's own option `key`, if the scene gives it.
const MethodOption* option(const Scene& scene, const std::string& key);

// An error unless every option of the scene's method is among `keys` (or name, repetitions,
// seed), listing those `name` takes.
Status only_keys(const Scene& scene, std::string_view name,
                 std::initializer_list<std::string_view> keys);

}  // namespace tr
