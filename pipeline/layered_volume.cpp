#include <core/memory_budget.h>
#include <core/parallel.h>
#include <core/stopwatch.h>
#include <pipeline/layered_volume.h>
#include <pipeline/methods/projected_tetrahedra.h>
#include <pipeline/scene_volumes.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace tr {

std::vector<double> plane_depths(const CameraFrame& frame, const Vec3& point, const Vec3& normal) {
    const int w = frame.width(), h = frame.height();
    std::vector<double> depth(static_cast<std::size_t>(w) * h,
                              std::numeric_limits<double>::infinity());
    parallel_for(0, static_cast<std::size_t>(h), 1, [&](std::size_t j) {
        for (int i = 0; i < w; ++i) {
            const Ray ray = frame.pixel_ray(i, static_cast<int>(j));
            const double facing = glm::dot(normal, ray.direction);
            if (facing == 0) continue;
            const double t = glm::dot(normal, point - ray.origin) / facing;
            if (t > 0 && std::isfinite(t)) depth[j * w + i] = t;
        }
    });
    return depth;
}

Status check_layers_memory(const Scene& scene, std::size_t surfaces) {
    // Per surface its depths (8 bytes a pixel), a place in each pixel's order (1) and, per
    // fragment rank, two pictures and a rank map (25); the full picture and the opaque layer.
    const double pixels = static_cast<double>(scene.width) * scene.height;
    const Status fits =
        check_memory(pixels * (34.0 * static_cast<double>(surfaces) + 32.0),
                     std::to_string(surfaces) + " layers over a " + std::to_string(scene.width) +
                         "x" + std::to_string(scene.height) + " picture");
    if (!fits.ok()) return make_error(fits.error().code, fits.error().message, scene.source);
    return {};
}

Result<LayeredVolume> LayeredVolume::create(Pipeline& pipeline, const Scene& scene,
                                            const RenderOptions& options,
                                            std::span<const std::vector<double>> depths,
                                            NamedStats& stats, std::vector<std::string>& notes,
                                            bool volume_drawn) {
    LayeredVolume out;
    out.width_ = scene.width;
    out.height_ = scene.height;
    const std::size_t num_pixels = static_cast<std::size_t>(scene.width) * scene.height;
    const std::size_t num_surfaces = depths.size();
    TR_TRY_STATUS(check_layers_memory(scene, num_surfaces));
    const CameraFrame frame(scene.camera, scene.width, scene.height);
    TR_TRY(out.opaque_, opaque_layer(pipeline, scene, frame, stats));
    const auto start = std::chrono::steady_clock::now();

    // The volume alone, over the opaque geometry: R.
    Scene volume = scene;
    volume.method.reset();
    RenderOptions plain = options;
    plain.on_frame = nullptr;
    plain.on_flow_volume_layer = nullptr;
    int renders = 0;
    if (volume_drawn) {
        TR_TRY(RenderResult full, pipeline.render(volume, plain));
        out.full_ = std::move(full.image);
        for (std::string& note : full.notes) {
            // The volume alone may well be clear: the sheets or spots are the picture.
            if (note.rfind("the picture is empty", 0) != 0) notes.push_back(std::move(note));
        }
        renders = 1;
    } else {
        out.full_ = out.opaque_.color.pixels.empty()
                        ? Image(scene.width, scene.height, Vec3f(scene.background))
                        : out.opaque_.color;
    }

    // Each pixel's fragments in front of the opaque geometry, nearest first (ties: the earlier
    // surface).
    std::vector<std::int8_t> order(num_pixels * num_surfaces, -1);
    std::vector<int> count(num_pixels, 0);
    parallel_for(0, num_pixels, 4096, [&](std::size_t p) {
        const double hidden = out.opaque_.depth.empty() ? std::numeric_limits<double>::infinity()
                                                        : out.opaque_.depth[p];
        std::int8_t* list = &order[p * num_surfaces];
        int n = 0;
        for (std::size_t s = 0; s < num_surfaces; ++s) {
            const double d = depths[s][p];
            if (!(d > 0) || !(d < hidden)) continue;
            int at = n++;
            while (at > 0 && depths[list[at - 1]][p] > d) {
                list[at] = list[at - 1];
                --at;
            }
            list[at] = static_cast<std::int8_t>(s);
        }
        count[p] = n;
    });
    const int num_ranks = num_pixels ? *std::max_element(count.begin(), count.end()) : 0;

    // Per rank: the volume up to that fragment, with a black and with a white stop there.
    Scene under = volume;
    under.opaque.clear();
    for (int k = 0; k < num_ranks; ++k) {
        std::vector<std::int8_t> rank(num_pixels, -1);
        OpaqueLayer stop;
        stop.depth.assign(num_pixels, 0.0);  // no fragment of this rank: nothing to integrate
        for (std::size_t p = 0; p < num_pixels; ++p) {
            if (k < count[p]) {
                rank[p] = order[p * num_surfaces + k];
                stop.depth[p] = depths[rank[p]][p];
            }
        }
        out.rank_.push_back(std::move(rank));
        if (!volume_drawn) {  // nothing in front: no light, full transmittance
            out.front_.emplace_back(scene.width, scene.height, Vec3f(0.0f));
            out.transmittance_.emplace_back(scene.width, scene.height, Vec3f(1.0f));
            continue;
        }
        stop.color = Image(scene.width, scene.height, Vec3f(0.0f));
        TR_TRY(RenderResult black, render_projected_volume(pipeline, under, plain, &stop));
        stop.color = Image(scene.width, scene.height, Vec3f(1.0f));
        TR_TRY(RenderResult white, render_projected_volume(pipeline, under, plain, &stop));
        renders += 2;
        Image transmittance = std::move(white.image);
        for (std::size_t p = 0; p < num_pixels; ++p) {
            transmittance.pixels[p] -= black.image.pixels[p];
        }
        out.front_.push_back(std::move(black.image));
        out.transmittance_.push_back(std::move(transmittance));
    }
    stats.set("volume_renders", renders);
    stats.set("volume_ms", ms_since(start));
    stats.set("layers", num_ranks);
    return out;
}

Image LayeredVolume::composite(std::span<const SurfaceFragments> surfaces) const {
    Image image(width_, height_);
    const std::size_t num_pixels = static_cast<std::size_t>(width_) * height_;
    parallel_for(0, num_pixels, 4096, [&](std::size_t p) {
        Vec3f sum(0.0f);
        float through = 1.0f;
        for (std::size_t k = 0; k < rank_.size(); ++k) {
            const int s = rank_[k][p];
            if (s < 0) break;
            const float a = surfaces[s].alpha[p];
            if (!(a > 0)) continue;
            sum += (through * a) *
                   (front_[k].pixels[p] + transmittance_[k].pixels[p] * surfaces[s].color[p]);
            through *= 1.0f - a;
        }
        image.pixels[p] = sum + through * full_.pixels[p];
    });
    return image;
}

}  // namespace tr
