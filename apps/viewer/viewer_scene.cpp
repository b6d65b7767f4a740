#include <apps/cli_common.h>
#include <apps/viewer/viewer_scene.h>
#include <mesh/point_data.h>
#include <pipeline/quick_scene.h>
#include <project/colormap.h>
#include <project/cpu_renderer.h>

#include <cmath>
#include <limits>

namespace tr::viewer {
namespace {

constexpr const char* kConstant = "(constant)";

// log10 of each value, those <= 0 given the smallest positive one's. Error when none is
// positive. `where`: the file, for errors.
Status to_decades(std::vector<float>& values, const std::string& name, const std::string& where) {
    float smallest = std::numeric_limits<float>::infinity();
    for (float v : values) {
        if (v > 0.0f) smallest = std::min(smallest, v);
    }
    if (!std::isfinite(smallest)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "--log: array '" + name + "' has no positive value", where);
    }
    for (float& v : values) {
        if (std::isfinite(v)) v = std::log10(std::max(v, smallest));
    }
    return {};
}

// The scalar `name` on `mesh` (virtual points get 0), in decades when `log_scale`, and its
// finite range over the points real tets use. `where`: the file, for errors.
Result<std::vector<float>> scalar_values(const TetMesh& mesh, const std::string& where,
                                         const std::string& name, int component, double& lo,
                                         double& hi, bool log_scale = false) {
    std::vector<float> values;
    if (name == kConstant) {
        values.assign(mesh.num_points(), 1.0f);
    } else {
        TR_TRY(values, point_scalar(mesh, name, component));
    }
    if (log_scale) TR_TRY_STATUS(to_decades(values, name, where));
    lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t p = 0; p < values.size(); ++p) {
        if (!std::isfinite(values[p])) {
            return make_error(ErrorCode::kInvalidMesh,
                              "array '" + name + "' is not finite at point " + std::to_string(p),
                              where);
        }
        if (p < mesh.num_points() && mesh.num_virtual_tets() == 0) {
            lo = std::min<double>(lo, values[p]);
            hi = std::max<double>(hi, values[p]);
        }
    }
    if (mesh.num_virtual_tets() > 0) {
        // Only the points real tets use count for the range.
        for (CellId t = 0; t < mesh.num_real_tets(); ++t) {
            for (PointId p : mesh.tet(t)) {
                lo = std::min<double>(lo, values[p]);
                hi = std::max<double>(hi, values[p]);
            }
        }
    }
    if (!(hi >= lo)) lo = 0, hi = 1;
    if (hi == lo) lo = hi - 1;  // a constant: opacity ramps up to it
    return values;
}

Result<std::vector<float>> scalar_values(const ViewerScene& vs, const std::string& name,
                                         int component, double& lo, double& hi) {
    return scalar_values(vs.sort.mesh(), vs.volume().mesh.string(), name, component, lo, hi,
                         vs.log_scale);
}

// The panel's edit of a scene's volume's transfer function over its scalar's range [lo, hi]:
// the scene's own points (with --opacity scaling them), or --colormap's ramp; --unit-distance
// over all.
TransferEdit initial_edit(const ViewerOptions& options, const TransferFunction& tf, double lo,
                          double hi) {
    TransferEdit edit;
    edit.lo = lo, edit.hi = hi;
    if (options.colormap.empty()) {
        edit.scene_colors = tf.color_points();
        edit.opacity = tf.opacity_points();
        edit.unit_distance = tf.unit_distance();
        edit.lo = std::min(lo, tf.s_min());  // the editor's axis covers the points too
        edit.hi = std::max(hi, tf.s_max());
        double largest = 0;
        for (const OpacityPoint& p : edit.opacity) largest = std::max(largest, p.a);
        if (options.max_opacity > 0 && largest > 0) {
            for (OpacityPoint& p : edit.opacity) p.a *= options.max_opacity / largest;
        }
    } else {
        edit.colormap = options.colormap;
        edit.opacity = ramp_opacity(lo, hi, options.max_opacity > 0 ? options.max_opacity : 0.3);
        edit.unit_distance = tf.unit_distance();
    }
    if (options.unit_distance > 0) edit.unit_distance = options.unit_distance;
    if (!(edit.unit_distance > 0)) edit.unit_distance = 1;
    return edit;
}

// `points` less those on the line through their neighbours (a ramp sampled densely).
std::vector<OpacityPoint> without_collinear(const std::vector<OpacityPoint>& points) {
    if (points.size() < 3) return points;
    std::vector<OpacityPoint> kept{points.front()};
    for (std::size_t i = 1; i + 1 < points.size(); ++i) {
        const OpacityPoint &a = kept.back(), &b = points[i + 1], &p = points[i];
        const double t = b.s > a.s ? (p.s - a.s) / (b.s - a.s) : 0.0;
        if (std::abs(p.a - (a.a + t * (b.a - a.a))) > 1e-9) kept.push_back(p);
    }
    kept.push_back(points.back());
    return kept;
}

// The panel's edit of a quick look's transfer function `tf` (pipeline/quick_scene.h): its
// colour map by name (a preset file's colours as the scene's own), opacity points, unit
// distance and colour range; in decades when `decades` (tf then spreads its points at 10^x,
// project/transfer_function.h log_scaled, and the viewer shows log10 of the scalar).
TransferEdit quick_edit(const TransferFunction& tf, const QuickSceneOptions& quick, bool decades) {
    const auto axis = [&](double s) { return decades ? std::log10(s) : s; };
    TransferEdit edit;
    edit.colormap = quick.colormap_preset ? "" : quick.colormap;
    for (const ColorPoint& p : tf.color_points()) edit.scene_colors.push_back({axis(p.s), p.rgb});
    for (const OpacityPoint& p : tf.opacity_points()) edit.opacity.push_back({axis(p.s), p.a});
    if (decades) edit.opacity = without_collinear(edit.opacity);
    edit.unit_distance = tf.unit_distance();
    edit.lo = edit.scene_colors.front().s;
    edit.hi = edit.scene_colors.back().s;
    return edit;
}

// Each volume of a scene of several: its mesh as loaded, scalar, arrays and edit; each
// volume's transfer function made from its edit.
Status load_fused_volumes(ViewerScene& vs, const ViewerOptions& options) {
    for (std::size_t v = 0; v < vs.scene.volumes.size(); ++v) {
        SceneVolume& volume = vs.scene.volumes[v];
        auto name = [&](Error e) {
            e.message = "volume " + std::to_string(v) + ": " + e.message;
            return e;
        };
        FusedVolume fv;
        auto loaded = vs.pipeline->mesh(volume);
        if (!loaded.ok()) return name(loaded.error());
        fv.loaded = std::move(loaded).value();
        for (const Field& f : fv.mesh().point_fields()) fv.arrays.push_back(f.name);
        for (const Field& f : fv.mesh().cell_fields()) fv.arrays.push_back(f.name);
        fv.arrays.push_back(kConstant);
        fv.scalar_name = volume.scalar;
        double lo = 0, hi = 1;
        auto values =
            scalar_values(fv.mesh(), volume.mesh.string(), volume.scalar, volume.component, lo, hi);
        if (!values.ok()) return name(with_where(values.error(), volume.mesh.string()));
        fv.scalar = std::move(values).value();
        fv.longest_edge = longest_edge(fv.mesh());
        fv.edit = initial_edit(options, volume.transfer_function, lo, hi);
        auto tf = make_transfer_function(fv.edit);
        if (!tf.ok()) return name(tf.error());
        volume.transfer_function = std::move(tf).value();
        vs.fused.push_back(std::move(fv));
    }
    return {};
}

double remap(double s, double lo, double hi, double new_lo, double new_hi) {
    return hi > lo ? new_lo + (s - lo) / (hi - lo) * (new_hi - new_lo) : new_hi;
}

}  // namespace

std::vector<OpacityPoint> ramp_opacity(double lo, double hi, double max_opacity, double floor) {
    const double bottom = floor * max_opacity, step = (max_opacity - bottom) / 3;
    return {{lo, bottom},
            {lo + (hi - lo) / 3, bottom + step},
            {lo + 2 * (hi - lo) / 3, bottom + 2 * step},
            {hi, max_opacity}};
}

Result<TransferFunction> make_transfer_function(const TransferEdit& edit) {
    std::vector<ColorPoint> colors = edit.scene_colors;
    if (!edit.colormap.empty()) {
        TR_TRY(
            const TransferFunction quick,
            make_quick_transfer_function(edit.colormap, edit.lo, edit.hi, 0.5, edit.unit_distance));
        colors = quick.color_points();
    }
    return TransferFunction::create(colors, edit.opacity, edit.unit_distance);
}

Result<ViewerScene> load_viewer_scene(const ViewerOptions& options) {
    ViewerScene vs;
    std::vector<std::string>& notes = vs.notes;
    const bool scene_mode = apps::is_scene_file(options.input);
    if (scene_mode && options.quick.log_scale) {
        return make_error(ErrorCode::kInvalidArgument,
                          "--log is for a mesh file; a scene's transfer function is its own",
                          options.input);
    }
    PipelineOptions pipeline_options;
    pipeline_options.progress = apps::terminal_progress();
    vs.pipeline = std::make_unique<Pipeline>(pipeline_options);
    Pipeline& pipeline = *vs.pipeline;
    if (scene_mode) {
        TR_TRY(vs.scene, read_scene(options.input));
    } else {
        // The quick look `tetrender render MESH` makes, at the window's size.
        QuickSceneOptions quick = options.quick;
        quick.width = options.width, quick.height = options.height;
        TR_TRY(vs.scene, quick_scene_of_file(pipeline, options.input, quick, options.file, &notes));
        vs.log_scale = quick.log_scale;
    }
    const bool fused = vs.scene.volumes.size() > 1;
    if (fused) {
        if (options.flow_volume || vs.scene.flow_volume) {
            return make_error(ErrorCode::kUnsupported,
                              "a flow volume grows through one mesh; this scene has " +
                                  std::to_string(vs.scene.volumes.size()) + " volumes",
                              options.input);
        }
        TR_TRY_STATUS(load_fused_volumes(vs, options));
    }
    TR_TRY(const std::shared_ptr<const LoadedMesh> loaded, pipeline.mesh(vs.volume()));
    const std::string mesh_name = vs.volume().mesh.string();
    for (const Field& f : loaded->tets.point_fields()) vs.arrays.push_back(f.name);
    for (const Field& f : loaded->tets.cell_fields()) vs.arrays.push_back(f.name);
    vs.arrays.push_back(kConstant);
    if (options.flow_volume) vs.scene.flow_volume = options.flow_volume;
    if (!fused && !vector_arrays(loaded->tets).empty()) {
        TR_TRY(FlowDomain domain, pipeline.flow_domain(vs.volume()));
        vs.flow = std::make_unique<FlowDomain>(std::move(domain));
    }
    if (vs.scene.flow_volume) {
        if (!vs.flow) {
            return make_error(ErrorCode::kNotFound,
                              "no 3-component point array '" + vs.scene.flow_volume->vectors +
                                  "' (vector arrays: none)",
                              mesh_name);
        }
        TR_TRY_STATUS(check_flow_spec(*vs.flow, *vs.scene.flow_volume));
        // What the scene or the command line left to the data is chosen, and said.
        TR_TRY(vs.scene.flow_volume, resolve_flow_spec(*vs.flow, *vs.scene.flow_volume, &notes));
    }
    // Several volumes: volume 0 for the GL renderer only, never convexified.
    TR_TRY(vs.sort, pipeline.prepared_sort(vs.volume(), fused ? SortMethod::kMpvo : options.sort));
    vs.longest_edge = longest_edge(vs.sort.mesh());
    if (options.size_given || !scene_mode) {
        vs.scene.width = options.width;
        vs.scene.height = options.height;
    }
    vs.scalar_name = vs.volume().scalar;
    double lo = 0, hi = 1;
    auto values = scalar_values(vs, vs.scalar_name, vs.volume().component, lo, hi);
    if (!values.ok()) return with_where(values.error(), mesh_name);
    vs.scalar = std::move(values).value();
    vs.edit = scene_mode ? initial_edit(options, vs.volume().transfer_function, lo, hi)
                         : quick_edit(vs.volume().transfer_function, options.quick, vs.log_scale);
    TR_TRY(vs.volume().transfer_function, make_transfer_function(vs.edit));
    TR_TRY(vs.opaque, pipeline.opaque(vs.scene));
    return vs;
}

Status select_scalar(ViewerScene& vs, const std::string& name) {
    double lo = 0, hi = 1;
    TR_TRY(std::vector<float> values, scalar_values(vs, name, -1, lo, hi));
    TransferEdit& edit = vs.edit;
    for (OpacityPoint& p : edit.opacity) p.s = remap(p.s, edit.lo, edit.hi, lo, hi);
    for (ColorPoint& p : edit.scene_colors) p.s = remap(p.s, edit.lo, edit.hi, lo, hi);
    edit.lo = lo, edit.hi = hi;
    vs.scalar = std::move(values);
    vs.scalar_name = name;
    return {};
}

Status select_fused_scalar(ViewerScene& vs, std::size_t volume, const std::string& name) {
    FusedVolume& fv = vs.fused.at(volume);
    double lo = 0, hi = 1;
    TR_TRY(std::vector<float> values,
           scalar_values(fv.mesh(), vs.scene.volumes[volume].mesh.string(), name, -1, lo, hi));
    TransferEdit& edit = fv.edit;
    for (OpacityPoint& p : edit.opacity) p.s = remap(p.s, edit.lo, edit.hi, lo, hi);
    for (ColorPoint& p : edit.scene_colors) p.s = remap(p.s, edit.lo, edit.hi, lo, hi);
    edit.lo = lo, edit.hi = hi;
    fv.scalar = std::move(values);
    fv.scalar_name = name;
    return {};
}

}  // namespace tr::viewer
