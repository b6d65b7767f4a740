#include <core/parallel.h>
#include <flowtex/advection.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace tr {
namespace {

constexpr std::size_t kGrain = 1024;

}  // namespace

Result<TextureAdvection> TextureAdvection::create(const Sheet& sheet, const Flow& flow,
                                                  const AdvectionOptions& options) {
    if (!(options.dt > 0) || !std::isfinite(options.dt)) {
        return make_error(ErrorCode::kInvalidArgument, "advection dt must be positive");
    }
    if (!(options.texture_period > 0) || !std::isfinite(options.texture_period)) {
        return make_error(ErrorCode::kInvalidArgument, "texture period must be positive");
    }
    if (options.reinject_frames < 0 || options.reinject_frames % 2 != 0) {
        return make_error(ErrorCode::kInvalidArgument,
                          "re-injection period must be 0 or an even number of frames");
    }
    TextureAdvection advection(sheet, flow, options);
    if (options.sample_velocity_on_sheet && flow.steady() && !sheet.grid_point.empty()) {
        advection.sampled_ = std::make_unique<SheetSampledFlow>(sheet, flow);
        advection.flow_ = advection.sampled_.get();
    }
    const int num_layers = options.reinject_frames > 0 ? 2 : 1;
    for (int k = 0; k < num_layers; ++k) {
        Layer layer;
        layer.phase = k * options.reinject_frames / 2;
        // Half a period apart in both directions: an unrelated part of the noise.
        layer.offset = glm::dvec2(0.5 * k, 0.5 * k);
        advection.reset(layer);
        advection.layers_.push_back(std::move(layer));
    }
    return advection;
}

glm::dvec2 TextureAdvection::texcoord(const Layer& layer, const Vec3& q) const {
    return sheet_->plane_coordinates(q) / options_.texture_period + layer.offset;
}

void TextureAdvection::reset(Layer& layer) const {
    const std::size_t n = sheet_->points.size();
    layer.points = sheet_->points;
    layer.alive.assign(n, 1);
    layer.hints.assign(n, kNoCell);
    layer.texcoords.resize(n);
    for (std::size_t i = 0; i < n; ++i) layer.texcoords[i] = texcoord(layer, sheet_->points[i]);
}

float TextureAdvection::weight(const Layer& layer) const {
    const int period = options_.reinject_frames;
    if (period == 0) return 1.0f;
    const int age = ((frame_ - layer.phase) % period + period) % period;
    return static_cast<float>(1.0 - std::abs(2.0 * age / period - 1.0));
}

void TextureAdvection::advance() {
    const double t0 = time();
    ++frame_;
    for (Layer& layer : layers_) {
        if (options_.reinject_frames > 0 &&
            ((frame_ - layer.phase) % options_.reinject_frames) == 0) {
            reset(layer);
        } else {
            advance_layer(layer, t0);
        }
    }
}

void TextureAdvection::advance_layer(Layer& layer, double t0) {
    const Sheet& sheet = *sheet_;
    const Flow& flow = *flow_;
    const double dt = options_.dt;
    const Vec3 normal = sheet.normal;
    const std::size_t n = sheet.points.size();
    if (options_.method == AdvectionMethod::kForward) {
        parallel_for(0, n, kGrain, [&](std::size_t i) {
            if (!layer.alive[i]) return;
            const auto next = rk4_step(flow, layer.points[i], t0, dt, normal, layer.hints[i]);
            if (next) {
                layer.points[i] = *next;
            } else {
                layer.alive[i] = 0;
            }
        });
        return;
    }
    if (flow.steady() && options_.steady_streamlines) {
        // Q moves one step further back along the streamline through P (which in a steady flow
        // is the same curve every frame).
        if (const SheetSampledFlow* sampled = sampled_.get()) {
            advance_on_sheet_grid(layer, *sampled, t0);
            return;
        }
        parallel_for(0, n, kGrain, [&](std::size_t i) {
            if (!layer.alive[i]) return;
            // No end-point check: a Q that lands outside stops there at the next step's first
            // lookup, as one stopped by this step would (a fifth of the lookups saved).
            const auto back =
                rk4_step(flow, layer.points[i], t0, -dt, normal, layer.hints[i], false);
            if (back) {
                layer.points[i] = *back;
                layer.texcoords[i] = texcoord(layer, *back);
            } else {
                // The streamline ends at the domain's boundary (an inflow): Q stays, the
                // texture there stretches until the layer is re-injected; in a steady flow
                // the same step fails again, so it is not tried again (alive = 0).
                layer.alive[i] = 0;
            }
        });
        return;
    }
    // Transport equation, semi-Lagrangian: Q(P, t0 + dt) = Q(X, t0), X = P traced back.
    scratch_.resize(n);
    parallel_for(0, n, kGrain, [&](std::size_t i) {
        const Vec3& p = sheet.points[i];
        CellId hint = layer.hints[i];
        // X need not be in the flow's domain, only on the sheet: no end-point check.
        const auto back = rk4_step(flow, p, t0 + dt, -dt, normal, hint, false);
        Vec3 q = layer.points[i];
        if (back) {
            layer.hints[i] = hint;
            if (const auto where = locate_on_sheet(sheet, sheet.plane_coordinates(*back))) {
                q = Vec3(0.0);
                for (int c = 0; c < 3; ++c) q += where->weights[c] * layer.points[where->points[c]];
            } else {
                q = *back;  // from off the sheet: fresh texture flows in
            }
        } else if (const auto v = flow.at(p, t0 + dt, hint)) {
            q = p - dt * (*v - glm::dot(*v, normal) * normal);  // an Euler step back
        }
        scratch_[i] = q;
    });
    layer.points.swap(scratch_);
    parallel_for(0, n, kGrain,
                 [&](std::size_t i) { layer.texcoords[i] = texcoord(layer, layer.points[i]); });
}

void TextureAdvection::advance_on_sheet_grid(Layer& layer, const SheetSampledFlow& sampled,
                                             double t0) {
    const Sheet& sheet = *sheet_;
    const double dt = options_.dt;
    const double inv_spacing = 1.0 / sheet.spacing;
    constexpr std::size_t kChunk = 256;
    const std::size_t n = sheet.points.size();
    parallel_for(0, (n + kChunk - 1) / kChunk, 4, [&](std::size_t chunk) {
        const std::size_t first = chunk * kChunk, count = std::min(kChunk, n - first);
        std::array<glm::dvec2, kChunk> grid, back;
        for (std::size_t k = 0; k < count; ++k) {
            grid[k] = sheet.plane_coordinates(layer.points[first + k]) * inv_spacing;
        }
        sampled.grid_steps(std::span(grid.data(), count), -dt, std::span(back.data(), count));
        for (std::size_t k = 0; k < count; ++k) {
            const std::size_t i = first + k;
            if (!std::isnan(back[k].x)) {
                const glm::dvec2 st = back[k] * sheet.spacing;
                layer.points[i] = sheet.origin + st.x * sheet.axis_u + st.y * sheet.axis_v;
                layer.texcoords[i] = st / options_.texture_period + layer.offset;
                continue;
            }
            // A stage off the sheet's triangles: the flow itself, as advance_layer does.
            if (!layer.alive[i]) continue;
            const auto step =
                rk4_step(*flow_, layer.points[i], t0, -dt, sheet.normal, layer.hints[i], false);
            if (step) {
                layer.points[i] = *step;
                layer.texcoords[i] = texcoord(layer, *step);
            } else {
                layer.alive[i] = 0;  // the streamline ends here, and will next frame too
            }
        }
    });
}

std::span<const Vec3> TextureAdvection::positions(int k) const {
    if (options_.method == AdvectionMethod::kForward) return layers_[k].points;
    return sheet_->points;
}

std::vector<TexturedMeshView> TextureAdvection::views() const {
    std::vector<TexturedMeshView> out;
    for (int k = 0; k < num_layers(); ++k) {
        const Layer& layer = layers_[k];
        TexturedMeshView view;
        view.positions = positions(k);
        view.texcoords = layer.texcoords;
        view.triangles = sheet_->triangles;
        // Backward layers never lose points: no mask, so the rasteriser sees that every layer
        // shares the sheet's positions and triangles and traverses them once.
        if (options_.method == AdvectionMethod::kForward) {
            view.alive = layer.alive;
        } else if (!sheet_->grid_point.empty()) {
            view.grid = sheet_;
        }
        view.weight = weight(layer);
        out.push_back(view);
    }
    return out;
}

}  // namespace tr
