#pragma once
// Rendering methods as back-ends of the pipeline: each is one class behind this interface,
// chosen by the scene's `method.name` (../shared/spec/scene.md, section "Method"). Adding a
// method is one new file in pipeline/methods/ and one line in method_registry.cpp; no other
// method changes. Its keys are a table (method_keys.h) that check(), render(), the errors and
// docs/scene-file.md all read.

#include <core/result.h>
#include <pipeline/methods/method_keys.h>
#include <pipeline/pipeline.h>
#include <pipeline/scene.h>

#include <string>
#include <string_view>
#include <vector>

namespace tr {

class RenderMethod {
  public:
    virtual ~RenderMethod() = default;

    // The name scenes give it ("projected-tetrahedra", "pbvr-object", ...).
    virtual std::string_view name() const = 0;

    // Its scene keys, each once, with type, range, default and doc line.
    virtual const MethodKeys& keys() const = 0;

    // Checks, before anything is loaded, the scene's method keys against keys() and what
    // else of the scene this method can draw (several volumes, opaque geometry, a flow volume,
    // rules between keys). Errors name the JSON path ("$.method.depth: ...").
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

// Every method's keys as docs/scene-file.md shows them, in method_names() order.
std::string methods_markdown();

}  // namespace tr
