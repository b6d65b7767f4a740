#include <apps/cli_common.h>
#include <apps/viewer/viewer_scene.h>
#include <io/read_surface.h>
#include <mesh/point_data.h>
#include <project/colormap.h>
#include <project/cpu_renderer.h>

#include <cmath>
#include <limits>

namespace tr::viewer {
namespace {

constexpr const char* kConstant = "(constant)";

bool is_scene_file(const std::string& path) {
    return path.size() > 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

// The scalar `name` on the sorted mesh (virtual points get 0), and its finite range.
Result<std::vector<float>> scalar_values(const ViewerScene& vs, const std::string& name,
                                         int component, double& lo, double& hi) {
    std::vector<float> values;
    if (name == kConstant) {
        values.assign(vs.setup.mesh.num_points(), 1.0f);
    } else {
        TR_TRY(values, point_scalar(vs.setup.mesh, name, component));
    }
    lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t p = 0; p < values.size(); ++p) {
        if (!std::isfinite(values[p])) {
            return make_error(ErrorCode::kInvalidMesh,
                              "array '" + name + "' is not finite at point " + std::to_string(p),
                              vs.scene.mesh.string());
        }
        if (p < vs.setup.mesh.num_points() && vs.setup.mesh.num_virtual_tets() == 0) {
            lo = std::min<double>(lo, values[p]);
            hi = std::max<double>(hi, values[p]);
        }
    }
    if (vs.setup.mesh.num_virtual_tets() > 0) {
        // Only the points real tets use count for the range.
        for (CellId t = 0; t < vs.setup.mesh.num_real_tets(); ++t) {
            for (PointId p : vs.setup.mesh.tet(t)) {
                lo = std::min<double>(lo, values[p]);
                hi = std::max<double>(hi, values[p]);
            }
        }
    }
    if (!(hi >= lo)) lo = 0, hi = 1;
    if (hi == lo) lo = hi - 1;  // a constant: opacity ramps up to it
    return values;
}

double remap(double s, double lo, double hi, double new_lo, double new_hi) {
    return hi > lo ? new_lo + (s - lo) / (hi - lo) * (new_hi - new_lo) : new_hi;
}

}  // namespace

std::vector<OpacityPoint> ramp_opacity(double lo, double hi, double max_opacity) {
    return {{lo, 0.0},
            {lo + (hi - lo) / 3, max_opacity / 3},
            {lo + 2 * (hi - lo) / 3, 2 * max_opacity / 3},
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
    const bool scene_mode = is_scene_file(options.input);
    if (scene_mode) {
        TR_TRY(vs.scene, read_scene(options.input));
    } else {
        vs.scene.mesh = std::filesystem::absolute(options.input);
    }
    apps::LoadOptions load;
    load.time_step = vs.scene.time_step;
    TR_TRY(apps::LoadedMesh loaded, apps::load_tet_mesh(vs.scene.mesh.string(), load));
    const std::string mesh_name = vs.scene.mesh.string();
    for (const Field& f : loaded.tets.point_fields()) vs.arrays.push_back(f.name);
    for (const Field& f : loaded.tets.cell_fields()) vs.arrays.push_back(f.name);
    vs.arrays.push_back(kConstant);
    vs.input = std::move(loaded.input);
    const Bounds3 bounds = loaded.tets.bounds();
    if (options.flow_volume) vs.scene.flow_volume = options.flow_volume;
    if (std::vector<std::string> vectors = vector_arrays(loaded.tets); !vectors.empty()) {
        // The sort's mesh may be convexified: flow volumes grow through a copy as loaded.
        auto flow = std::make_unique<FlowDomain>();
        flow->path = mesh_name;
        flow->loaded.tets = loaded.tets;
        flow->loaded.input.time_values = vs.input.time_values;
        flow->loaded.input.time_step = vs.input.time_step;
        flow->vector_arrays = std::move(vectors);
        auto adjacency = build_face_adjacency(flow->loaded.tets);
        if (!adjacency.ok()) return apps::with_where(adjacency.error(), mesh_name);
        flow->adjacency = std::move(adjacency).value();
        vs.flow = std::move(flow);
    }
    if (vs.scene.flow_volume) {
        if (!vs.flow) {
            return make_error(ErrorCode::kNotFound,
                              "no 3-component point array '" + vs.scene.flow_volume->vectors +
                                  "' (vector arrays: none)",
                              mesh_name);
        }
        TR_TRY_STATUS(check_flow_spec(*vs.flow, *vs.scene.flow_volume));
    }
    {
        auto setup = apps::prepare_sort(std::move(loaded.tets), options.sort);
        if (!setup.ok()) return apps::with_where(setup.error(), mesh_name);
        vs.setup = std::move(setup).value();
    }
    vs.longest_edge = longest_edge(vs.setup.mesh);
    if (options.size_given || !scene_mode) {
        vs.scene.width = options.width;
        vs.scene.height = options.height;
    }
    int component = -1;
    if (scene_mode) {
        vs.scalar_name = vs.scene.scalar;
        component = vs.scene.component;
    } else {
        vs.scalar_name = options.scalar.empty() ? vs.arrays.front() : options.scalar;
        vs.scene.camera = framing_camera(bounds, Vec3(1.0, -1.2, 0.8));
    }
    double lo = 0, hi = 1;
    auto values = scalar_values(vs, vs.scalar_name, component, lo, hi);
    if (!values.ok()) return apps::with_where(values.error(), mesh_name);
    vs.scalar = std::move(values).value();
    TransferEdit& edit = vs.edit;
    edit.lo = lo, edit.hi = hi;
    if (scene_mode && options.colormap.empty()) {
        const TransferFunction& tf = vs.scene.transfer_function;
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
        edit.colormap = options.colormap.empty() ? "viridis" : options.colormap;
        edit.opacity = ramp_opacity(lo, hi, options.max_opacity > 0 ? options.max_opacity : 0.3);
        edit.unit_distance =
            scene_mode ? vs.scene.transfer_function.unit_distance() : bounds.diagonal() / 20.0;
    }
    if (options.unit_distance > 0) edit.unit_distance = options.unit_distance;
    if (!(edit.unit_distance > 0)) edit.unit_distance = 1;
    TR_TRY(vs.scene.transfer_function, make_transfer_function(edit));

    // Opaque surfaces, as `tetrender render` takes them.
    for (const OpaqueSpec& spec : vs.scene.opaque) {
        if (spec.boundary) {
            vs.opaque.push_back(boundary_surface(vs.setup.mesh, vs.setup.adjacency));
            vs.opaque_colors.push_back(spec.color);
            continue;
        }
        if (!spec.file.empty()) {
            TR_TRY(SurfaceMesh surface, read_surface(spec.file));
            vs.opaque.push_back(std::move(surface));
            vs.opaque_colors.push_back(spec.color);
            continue;
        }
        bool found = false;
        for (const SurfaceMesh& s : vs.input.surfaces) {
            if (spec.side_set == "*" || s.name == spec.side_set) {
                vs.opaque.push_back(s);
                vs.opaque_colors.push_back(spec.color);
                found = true;
            }
        }
        if (!found) {
            return make_error(ErrorCode::kNotFound,
                              "no side set '" + spec.side_set + "' in the mesh", mesh_name);
        }
    }
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

}  // namespace tr::viewer
