// tetrender._core: the library's entry points for Python (pybind11 + numpy). Thin: every call
// goes to the library (io/read_mesh, mesh/tetrahedralize, project/scene, pipeline/, sort/);
// only array shapes are checked here. The Pythonic API (Mesh, Scene, render...) is
// python/tetrender/__init__.py. Errors become tetrender.Error with the library's one line;
// the GIL is released while reading, tetrahedralizing, rendering, sorting and verifying.
#include <core/image.h>
#include <core/memory_budget.h>
#include <flowtex/advect_frames.h>
#include <flowtex/spot_noise_frames.h>
#include <io/read_mesh.h>
#include <io/write_image.h>
#include <mesh/tetrahedralize.h>
#include <pipeline/annotations.h>
#include <pipeline/flow_volume_scene.h>
#include <pipeline/pipeline.h>
#include <pipeline/quick_scene.h>
#include <sort/order_verifier.h>

#include <cstring>
#include <memory>
#include <mutex>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <stdexcept>
#include <string>

namespace py = pybind11;

namespace {

// What tetrender.Error carries: the library's one-line message.
struct LibraryError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

template <class T>
T unwrap(tr::Result<T> result) {
    if (!result.ok()) throw LibraryError(result.error().to_string());
    return std::move(result).value();
}

void unwrap(const tr::Status& status) {
    if (!status.ok()) throw LibraryError(status.error().to_string());
}

[[noreturn]] void bad_argument(const std::string& message) {
    throw LibraryError("error: " + message);
}

// A read-only numpy view of `count` values of T at `data`, kept alive by `owner`.
template <class T>
py::array view(const T* data, std::vector<py::ssize_t> shape, const py::object& owner) {
    py::array array(py::dtype::of<T>(), std::move(shape), data, owner);
    py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return array;
}

// A field as a numpy view: (n,) for one component, (n, k) otherwise.
py::array field_view(const tr::Field& field, const py::object& owner) {
    const auto n = static_cast<py::ssize_t>(field.num_tuples());
    std::vector<py::ssize_t> shape = {n};
    if (field.num_components != 1) shape.push_back(field.num_components);
    return std::visit([&](const auto& values) { return view(values.data(), shape, owner); },
                      field.values);
}

py::dict fields_dict(const std::vector<tr::Field>& fields, const py::object& owner) {
    py::dict out;
    for (const tr::Field& field : fields) out[py::str(field.name)] = field_view(field, owner);
    return out;
}

// A field from a numpy array of `expected` tuples: float32 stays float32, anything else becomes
// float64 (copied into the library's storage).
tr::Field field_from(const std::string& where, const std::string& name, const py::array& array,
                     std::size_t expected) {
    if (array.ndim() < 1 || array.ndim() > 2) {
        bad_argument(where + "['" + name + "']: expected an (n,) or (n, k) array, got " +
                     std::to_string(array.ndim()) + " dimensions");
    }
    const auto tuples = static_cast<std::size_t>(array.shape(0));
    const int components = array.ndim() == 2 ? static_cast<int>(array.shape(1)) : 1;
    if (tuples != expected) {
        bad_argument(where + "['" + name + "']: " + std::to_string(tuples) + " tuples for " +
                     std::to_string(expected) + (where == "point_data" ? " points" : " cells"));
    }
    if (components < 1) bad_argument(where + "['" + name + "']: no components");
    if (array.dtype().is(py::dtype::of<float>())) {
        auto values = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
        return tr::make_float_field(
            name, components, std::vector<float>(values.data(), values.data() + values.size()));
    }
    auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
    if (!values) bad_argument(where + "['" + name + "']: not a numeric array");
    return tr::make_double_field(name, components,
                                 std::vector<double>(values.data(), values.data() + values.size()));
}

// A mesh as a simulation or a file gives it (mesh/unstructured_mesh.h), shared with numpy views.
struct MeshHandle {
    std::shared_ptr<const tr::UnstructuredMesh> mesh;
};

// A tetrahedral mesh (mesh/tet_mesh.h), shared with numpy views.
struct TetHandle {
    std::shared_ptr<const tr::TetMesh> mesh;
    tr::TetrahedralizeReport report;
};

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Int64Array = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;
using UInt8Array = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>;

MeshHandle mesh_from_arrays(const DoubleArray& points, const Int64Array& connectivity,
                            const Int64Array& offsets, const UInt8Array& types,
                            const py::dict& point_data, const py::dict& cell_data) {
    if (points.ndim() != 2 || points.shape(1) != 3) {
        std::string shape;
        for (py::ssize_t i = 0; i < points.ndim(); ++i)
            shape += (i ? ", " : "") + std::to_string(points.shape(i));
        bad_argument("points: expected an (n, 3) array, got shape (" + shape + ")");
    }
    if (connectivity.ndim() != 1 || offsets.ndim() != 1 || types.ndim() != 1) {
        bad_argument("connectivity, offsets and types must be 1-dimensional arrays");
    }
    std::vector<double> xyz(points.data(), points.data() + points.size());
    std::vector<std::int64_t> conn(connectivity.data(), connectivity.data() + connectivity.size());
    std::vector<std::int64_t> offs(offsets.data(), offsets.data() + offsets.size());
    std::vector<std::uint8_t> cell_types(types.data(), types.data() + types.size());
    auto mesh = unwrap(tr::make_unstructured_mesh(xyz, conn, offs, cell_types));
    for (auto [name, array] : point_data) {
        mesh.point_fields.push_back(
            field_from("point_data", py::str(name), py::array::ensure(array), mesh.num_points()));
    }
    for (auto [name, array] : cell_data) {
        mesh.cell_fields.push_back(
            field_from("cell_data", py::str(name), py::array::ensure(array), mesh.num_cells()));
    }
    mesh.format = "numpy arrays";
    return {std::make_shared<const tr::UnstructuredMesh>(std::move(mesh))};
}

// A scene (pipeline/scene.h) with the pipeline that renders it, keeping what it loaded between
// renders. One render at a time (the mutex), the GIL released meanwhile.
struct SceneHandle {
    tr::Scene scene;
    std::unique_ptr<tr::Pipeline> pipeline = std::make_unique<tr::Pipeline>();
    std::unique_ptr<std::mutex> mutex = std::make_unique<std::mutex>();

    tr::SceneVolume& volume(std::size_t index) {
        if (index >= scene.volumes.size()) {
            bad_argument("volume " + std::to_string(index) + " out of range (the scene has " +
                         std::to_string(scene.volumes.size()) + ")");
        }
        return scene.volumes[index];
    }
};

py::array image_array(const tr::Image& image, bool as_float) {
    const auto h = static_cast<py::ssize_t>(image.height);
    const auto w = static_cast<py::ssize_t>(image.width);
    if (as_float) {
        py::array_t<float> out({h, w, py::ssize_t{3}});
        std::memcpy(out.mutable_data(), image.pixels.data(),
                    image.pixels.size() * sizeof(tr::Vec3f));
        return out;
    }
    const std::vector<std::uint8_t> rgb = tr::to_rgb8(image);
    py::array_t<std::uint8_t> out({h, w, py::ssize_t{3}});
    std::memcpy(out.mutable_data(), rgb.data(), rgb.size());
    return out;
}

py::dict stats_dict(const tr::NamedStats& stats) {
    py::dict out;
    for (const auto& [name, value] : stats.entries()) {
        std::visit([&](const auto& v) { out[py::str(name)] = v; }, value);
    }
    return out;
}

// The library's errors, raised as tetrender.Error.
void bind_errors(py::module_& m) {
    static py::exception<LibraryError> error(m, "Error", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const LibraryError& e) {
            error(e.what());
        }
    });
}

// Meshes held by the library, shared with numpy views.
void bind_mesh_handles(py::module_& m) {
    py::class_<MeshHandle>(m, "MeshHandle", "A mesh held by the library (shared with numpy views).")
        .def_property_readonly(
            "points",
            [](py::object self) {
                const auto& mesh = *self.cast<MeshHandle&>().mesh;
                return view(&mesh.points.data()->x,
                            {static_cast<py::ssize_t>(mesh.num_points()), py::ssize_t{3}}, self);
            },
            "(n, 3) float64, read-only view")
        .def_property_readonly(
            "connectivity",
            [](py::object self) {
                const auto& mesh = *self.cast<MeshHandle&>().mesh;
                return view(mesh.connectivity.data(),
                            {static_cast<py::ssize_t>(mesh.connectivity.size())}, self);
            },
            "int64, read-only view")
        .def_property_readonly(
            "offsets",
            [](py::object self) {
                const auto& mesh = *self.cast<MeshHandle&>().mesh;
                return view(mesh.offsets.data(), {static_cast<py::ssize_t>(mesh.offsets.size())},
                            self);
            },
            "int64 (cells + 1), read-only view")
        .def_property_readonly(
            "types",
            [](py::object self) {
                const auto& mesh = *self.cast<MeshHandle&>().mesh;
                static_assert(sizeof(tr::CellType) == 1);
                return view(reinterpret_cast<const std::uint8_t*>(mesh.types.data()),
                            {static_cast<py::ssize_t>(mesh.types.size())}, self);
            },
            "uint8 VTK cell types, read-only view")
        .def_property_readonly(
            "point_data",
            [](py::object self) {
                return fields_dict(self.cast<MeshHandle&>().mesh->point_fields, self);
            },
            "dict of read-only views")
        .def_property_readonly(
            "cell_data",
            [](py::object self) {
                return fields_dict(self.cast<MeshHandle&>().mesh->cell_fields, self);
            },
            "dict of read-only views")
        .def_property_readonly(
            "time_values", [](const MeshHandle& h) { return h.mesh->time_values; },
            "time values of every step of the source (empty: not a series)")
        .def_property_readonly(
            "time_step", [](const MeshHandle& h) { return h.mesh->time_step; }, "the step read")
        .def_property_readonly(
            "format", [](const MeshHandle& h) { return h.mesh->format; }, "where it came from");

    py::class_<TetHandle>(m, "TetHandle", "A tetrahedral mesh held by the library.")
        .def_property_readonly(
            "points",
            [](py::object self) {
                const auto& mesh = *self.cast<TetHandle&>().mesh;
                return view(&mesh.points().data()->x,
                            {static_cast<py::ssize_t>(mesh.num_points()), py::ssize_t{3}}, self);
            },
            "(n, 3) float64, read-only view")
        .def_property_readonly(
            "tets",
            [](py::object self) {
                const auto& mesh = *self.cast<TetHandle&>().mesh;
                static_assert(sizeof(tr::Tet) == 4 * sizeof(tr::PointId));
                return view(mesh.tets().data()->data(),
                            {static_cast<py::ssize_t>(mesh.num_tets()), py::ssize_t{4}}, self);
            },
            "(m, 4) uint32 point ids, read-only view, positively oriented")
        .def_property_readonly(
            "source_cells",
            [](py::object self) {
                const auto& mesh = *self.cast<TetHandle&>().mesh;
                return view(mesh.source_cells().data(),
                            {static_cast<py::ssize_t>(mesh.source_cells().size())}, self);
            },
            "uint32: the input cell each tet came from")
        .def_property_readonly(
            "point_data",
            [](py::object self) {
                return fields_dict(self.cast<TetHandle&>().mesh->point_fields(), self);
            },
            "dict of read-only views")
        .def_property_readonly(
            "cell_data",
            [](py::object self) {
                return fields_dict(self.cast<TetHandle&>().mesh->cell_fields(), self);
            },
            "dict of read-only views (one tuple per tet)")
        .def_property_readonly(
            "report",
            [](const TetHandle& h) {
                py::dict r;
                r["merged_points"] = h.report.num_merged_points;
                r["inverted_cells"] = h.report.num_inverted_cells;
                r["degenerate_cells"] = h.report.num_degenerate_cells;
                r["degenerate_tets"] = h.report.num_degenerate_tets;
                r["tangled_cells"] = h.report.num_tangled_cells;
                r["skipped_cells"] = h.report.num_skipped_cells;
                r["tets"] = h.report.num_tets;
                return r;
            },
            "what the split did (mesh/tetrahedralize.h TetrahedralizeReport)");
}

// Spot noise and texture advection (flowtex/).
void bind_flow_textures(py::module_& m) {
    // Spot noise and texture advection (flowtex/): the frames of an in-memory tet mesh's
    // steady flow, as `tetrender spotnoise` and `tetrender advect` write them.
    // `mesh`: a TetHandle, or a MeshHandle of a planar 2D mesh (the flow on its plane).
    const auto flow_frames = [](const py::object& mesh, const std::string& name,
                                const std::string& vectors, bool as_float, const auto& run) {
        tr::SceneVolume volume;
        volume.mesh = name;
        if (py::isinstance<MeshHandle>(mesh)) {
            volume.data = mesh.cast<const MeshHandle&>().mesh;
        } else {
            volume.tets = mesh.cast<const TetHandle&>().mesh;
        }
        std::vector<tr::Image> frames;
        const auto collect = [&](int, const tr::Image& picture) -> tr::Status {
            frames.push_back(picture);
            return {};
        };
        auto report = [&]() -> decltype(run(std::declval<const tr::FlowDomain&>(),
                                            std::declval<const tr::VelocityField&>(), collect)) {
            py::gil_scoped_release release;
            tr::Pipeline pipeline;
            TR_TRY(const tr::FlowDomain domain, pipeline.flow_domain(volume));
            TR_TRY(const tr::VelocityField velocity, tr::load_velocity(domain, vectors, false));
            return run(domain, velocity, collect);
        }();
        auto made = unwrap(std::move(report));
        py::list pictures;
        for (const tr::Image& f : frames) pictures.append(image_array(f, as_float));
        return std::make_pair(pictures, made);
    };
    m.def(
        "spot_noise",
        [flow_frames](const py::object& mesh, const std::string& name, const std::string& scalar,
                      double iso, const std::string& vectors, int steps, std::size_t count,
                      double dt, double band, int lifetime, int width, int height,
                      std::uint64_t seed, bool as_float) {
            tr::SpotNoiseFramesOptions options;
            options.scalar = scalar;
            options.spots.iso = iso;
            options.spots.count = count;
            options.spots.dt = dt;
            options.spots.band = band;
            options.spots.lifetime_frames = lifetime;
            options.spots.seed = seed;
            options.steps = steps;
            options.width = width;
            options.height = height;
            auto [pictures, report] =
                flow_frames(mesh, name, vectors, as_float,
                            [&](const tr::FlowDomain& domain, const tr::VelocityField& velocity,
                                const auto& collect) {
                                options.planar = domain.planar;
                                return tr::spot_noise_frames(domain.mesh(), *domain.adjacency,
                                                             velocity, options, collect);
                            });
            py::dict info;
            info["band_tets"] = report.band_tets;
            info["spots"] = report.spots;
            info["band"] = report.band;
            info["dt"] = report.dt;
            info["mean_speed"] = report.mean_speed;
            info["reseeded"] = report.reseeded;
            return py::make_tuple(pictures, info);
        },
        py::arg("mesh"), py::arg("name"), py::arg("scalar"), py::arg("iso"), py::arg("vectors"),
        py::arg("steps"), py::arg("count"), py::arg("dt"), py::arg("band"), py::arg("lifetime"),
        py::arg("width"), py::arg("height"), py::arg("seed"), py::arg("as_float"),
        "flowtex/spot_noise_frames.h spot_noise_frames");
    m.def(
        "advect",
        [flow_frames](const py::object& mesh, const std::string& name, const std::string& vectors,
                      std::optional<std::array<double, 3>> point,
                      std::optional<std::array<double, 3>> normal, int steps, double dt,
                      int resolution, const std::string& method, int width, int height,
                      bool as_float) {
            tr::AdvectFramesOptions options;
            if (point) options.slice_point = tr::Vec3((*point)[0], (*point)[1], (*point)[2]);
            if (normal) options.slice_normal = tr::Vec3((*normal)[0], (*normal)[1], (*normal)[2]);
            options.steps = steps;
            options.dt = dt;
            options.sheet_resolution = resolution;
            if (method == "forward") {
                options.method = tr::AdvectionMethod::kForward;
            } else if (method != "backward") {
                bad_argument("method must be 'backward' or 'forward', not '" + method + "'");
            }
            options.width = width;
            options.height = height;
            auto [pictures, report] =
                flow_frames(mesh, name, vectors, as_float,
                            [&](const tr::FlowDomain& domain, const tr::VelocityField& velocity,
                                const auto& collect) {
                                options.planar = domain.planar;
                                return tr::advect_frames(domain.mesh(), *domain.adjacency, velocity,
                                                         options, collect);
                            });
            py::dict info;
            info["sheet_points"] = report.sheet_points;
            info["sheet_triangles"] = report.sheet_triangles;
            info["dt"] = report.dt;
            info["mean_speed"] = report.mean_speed;
            return py::make_tuple(pictures, info);
        },
        py::arg("mesh"), py::arg("name"), py::arg("vectors"), py::arg("point"), py::arg("normal"),
        py::arg("steps"), py::arg("dt"), py::arg("resolution"), py::arg("method"), py::arg("width"),
        py::arg("height"), py::arg("as_float"), "flowtex/advect_frames.h advect_frames");
}

// The memory budget, meshes from arrays and files, the split into tets.
void bind_memory_and_meshes(py::module_& m) {
    m.def(
        "set_max_memory", [](std::uint64_t bytes) { tr::set_memory_budget(bytes); },
        py::arg("bytes"), "core/memory_budget.h set_memory_budget (0: the default)");
    m.def(
        "parse_byte_size",
        [](const std::string& text) { return unwrap(tr::parse_byte_size(text)); }, py::arg("text"),
        "core/memory_budget.h parse_byte_size");
    m.def("max_memory", &tr::memory_budget, "core/memory_budget.h memory_budget");
    m.def("mesh_from_arrays", &mesh_from_arrays, py::arg("points"), py::arg("connectivity"),
          py::arg("offsets"), py::arg("types"), py::arg("point_data"), py::arg("cell_data"),
          "Copies numpy arrays into a library mesh (sizes checked; the rest by tetrahedralize).");

    m.def(
        "read",
        [](const std::string& path, int time_step) {
            tr::ReadOptions options;
            options.time_step = time_step;
            tr::Result<tr::UnstructuredMesh> mesh = [&] {
                py::gil_scoped_release release;
                return tr::read_mesh(path, options);
            }();
            return MeshHandle{
                std::make_shared<const tr::UnstructuredMesh>(unwrap(std::move(mesh)))};
        },
        py::arg("path"), py::arg("time_step") = 0, "io/read_mesh.h read_mesh");

    m.def(
        "tetrahedralize",
        [](const MeshHandle& mesh, double merge_tolerance, bool merge_points) {
            tr::TetrahedralizeOptions options;
            options.merge_tolerance = merge_tolerance;
            options.merge_points = merge_points;
            TetHandle out;
            tr::Result<tr::TetMesh> tets = [&] {
                py::gil_scoped_release release;
                return tr::tetrahedralize(*mesh.mesh, options, &out.report);
            }();
            out.mesh = std::make_shared<const tr::TetMesh>(unwrap(std::move(tets)));
            return out;
        },
        py::arg("mesh"), py::arg("merge_tolerance") = 0.0, py::arg("merge_points") = true,
        "mesh/tetrahedralize.h tetrahedralize");
}

// A scene's contents: its volumes' meshes, the view, the scene file.
void bind_scene_contents(py::class_<SceneHandle>& scene) {
    scene
        .def_property_readonly("num_volumes",
                               [](const SceneHandle& s) { return s.scene.volumes.size(); })
        .def_property_readonly("width", [](const SceneHandle& s) { return s.scene.width; })
        .def_property_readonly("height", [](const SceneHandle& s) { return s.scene.height; })
        .def_property_readonly("method", [](const SceneHandle& s) { return s.scene.method_name(); })
        .def(
            "volume_mesh_path",
            [](SceneHandle& s, std::size_t i) { return s.volume(i).mesh.string(); },
            py::arg("volume"))
        .def(
            "set_volume_mesh",
            [](SceneHandle& s, std::size_t i, const MeshHandle& mesh, const std::string& name) {
                tr::SceneVolume& volume = s.volume(i);
                volume.data = mesh.mesh;
                volume.tets.reset();
                volume.mesh = name;
            },
            py::arg("volume"), py::arg("mesh"), py::arg("name"))
        .def(
            "set_volume_tets",
            [](SceneHandle& s, std::size_t i, const TetHandle& mesh, const std::string& name) {
                tr::SceneVolume& volume = s.volume(i);
                volume.tets = mesh.mesh;
                volume.data.reset();
                volume.mesh = name;
            },
            py::arg("volume"), py::arg("mesh"), py::arg("name"))
        .def(
            "set_view",
            [](SceneHandle& s, const SceneHandle& from, bool image) {
                std::lock_guard lock(*s.mutex);
                s.scene.camera = from.scene.camera;
                if (image) {
                    s.scene.width = from.scene.width;
                    s.scene.height = from.scene.height;
                    s.scene.background = from.scene.background;
                }
            },
            py::arg("from"), py::arg("image"),
            "Takes the camera (and the image settings) of another scene; meshes stay loaded.")
        .def(
            "write",
            [](const SceneHandle& s, const std::string& path) {
                unwrap(tr::write_scene(s.scene, path));
            },
            py::arg("path"), "pipeline/scene.h write_scene");
}

// Rendering a scene: the picture, the visibility order and its check, the loaded tets.
void bind_scene_rendering(py::class_<SceneHandle>& scene) {
    scene
        .def(
            "render",
            [](SceneHandle& s, const std::string& method, const std::string& sort,
               const std::string& integrator, bool as_float, bool legend, bool bounding_box,
               bool axes, const std::string& method_json, bool annotations_optional) {
                tr::RenderOptions options;
                options.sort = unwrap(tr::sort_method_named(sort));
                unwrap(tr::set_integrator_option(options, integrator));
                tr::Scene scene = s.scene;
                if (!method_json.empty()) {
                    // A whole method object: checked by the scene parser inside a scene that
                    // has nothing else of its own.
                    const std::string text =
                        R"({"mesh": "-", "scalar": "-", "transfer_function": {"color": )"
                        R"([[0, 0, 0, 0]], "opacity": [[0, 0]], "unit_distance": 1}, )"
                        R"("camera": {"position": [0, 0, 1], "focal_point": [0, 0, 0], )"
                        R"("view_up": [0, 1, 0]}, "image": {"width": 1, "height": 1}, )"
                        R"("method": )" +
                        method_json + "}";
                    scene.method = unwrap(tr::parse_scene(text, ".", "<method>")).method;
                } else if (!method.empty()) {
                    tr::MethodSpec spec = scene.method.value_or(tr::MethodSpec{});
                    spec.name = method;
                    scene.method = spec;
                }
                tr::Result<tr::RenderResult> result = [&]() -> tr::Result<tr::RenderResult> {
                    py::gil_scoped_release release;
                    std::lock_guard lock(*s.mutex);
                    TR_TRY(tr::RenderResult rendered, s.pipeline->render(scene, options));
                    if (legend || bounding_box || axes) {
                        tr::AnnotationOptions annotations;
                        annotations.legend = legend;
                        annotations.bounding_box = bounding_box;
                        annotations.axes = axes;
                        const tr::Status drawn =
                            tr::annotate(rendered.image, scene, *s.pipeline, annotations);
                        // Optional (a quick look's legend, as the CLI's): a picture too small
                        // for it is still a picture, with a note.
                        if (!drawn.ok() && !annotations_optional) return drawn.error();
                        if (!drawn.ok()) {
                            rendered.notes.push_back("no annotations: " + drawn.error().message);
                        }
                    }
                    return rendered;
                }();
                tr::RenderResult rendered = unwrap(std::move(result));
                py::object flow = py::none();
                if (rendered.flow_volume) {
                    // The dye's tets, sharing the flow volume (aliasing: it stays alive).
                    flow =
                        py::cast(TetHandle{std::shared_ptr<const tr::TetMesh>(
                                               rendered.flow_volume, &rendered.flow_volume->mesh),
                                           {}});
                }
                return py::make_tuple(image_array(rendered.image, as_float),
                                      stats_dict(rendered.stats), rendered.notes, flow);
            },
            py::arg("method"), py::arg("sort"), py::arg("integrator"), py::arg("as_float"),
            py::arg("legend") = false, py::arg("bounding_box") = false, py::arg("axes") = false,
            py::arg("method_json") = "", py::arg("annotations_optional") = false)
        .def(
            "sort",
            [](py::object self, std::size_t index, const std::string& method) {
                SceneHandle& s = self.cast<SceneHandle&>();
                const tr::SortMethod sort = unwrap(tr::sort_method_named(method));
                const tr::SceneVolume volume = s.volume(index);
                tr::Result<tr::ViewOrder> order = [&] {
                    py::gil_scoped_release release;
                    std::lock_guard lock(*s.mutex);
                    const tr::CameraFrame frame(s.scene.camera, s.scene.width, s.scene.height);
                    return s.pipeline->visibility_order(volume, frame, sort);
                }();
                tr::ViewOrder view = unwrap(std::move(order));
                py::array_t<tr::CellId> ids(static_cast<py::ssize_t>(view.order.size()));
                std::memcpy(ids.mutable_data(), view.order.data(),
                            view.order.size() * sizeof(tr::CellId));
                py::dict stats;
                stats["cells"] = view.stats.cells;
                stats["by_mpvo"] = view.stats.by_mpvo;
                stats["by_fallback"] = view.stats.by_fallback;
                stats["cells_in_cycles"] = view.stats.cells_in_cycles;
                stats["cycles_broken"] = view.stats.cycles_broken;
                stats["behind_eye"] = view.stats.behind_eye;
                stats["milliseconds"] = view.stats.milliseconds;
                return py::make_tuple(ids, view.exact, view.prepared.note, stats);
            },
            py::arg("volume"), py::arg("method"))
        .def(
            "check_order",
            [](SceneHandle& s, std::size_t index,
               const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& order,
               double min_segment) {
                const tr::SceneVolume volume = s.volume(index);
                if (order.ndim() != 1) bad_argument("order: expected a 1-dimensional array");
                tr::Result<std::shared_ptr<const tr::LoadedMesh>> mesh = [&] {
                    py::gil_scoped_release release;
                    std::lock_guard lock(*s.mutex);
                    return s.pipeline->mesh(volume);
                }();
                const std::shared_ptr<const tr::LoadedMesh> loaded = unwrap(std::move(mesh));
                const tr::TetMesh& tets = loaded->tets;
                std::vector<tr::CellId> ids(static_cast<std::size_t>(order.size()));
                for (py::ssize_t i = 0; i < order.size(); ++i) {
                    const std::int64_t id = order.data()[i];
                    if (id < 0 || static_cast<std::size_t>(id) >= tets.num_real_tets()) {
                        bad_argument("order[" + std::to_string(i) + "] = " + std::to_string(id) +
                                     " is not a cell of the volume's mesh (it has " +
                                     std::to_string(tets.num_real_tets()) + " tets)");
                    }
                    ids[static_cast<std::size_t>(i)] = static_cast<tr::CellId>(id);
                }
                tr::OrderCheck check;
                {
                    py::gil_scoped_release release;
                    const tr::CameraFrame frame(s.scene.camera, s.scene.width, s.scene.height);
                    check = tr::check_order(tets, ids, frame, min_segment);
                }
                py::dict out;
                out["rays"] = check.rays;
                out["pairs"] = check.pairs;
                out["violations"] = check.violations;
                out["missing_cells"] = check.missing_cells;
                out["milliseconds"] = check.milliseconds;
                return out;
            },
            py::arg("volume"), py::arg("order"), py::arg("min_segment") = 1e-9)
        .def(
            "volume_tets",
            [](SceneHandle& s, std::size_t index) {
                const tr::SceneVolume volume = s.volume(index);
                tr::Result<std::shared_ptr<const tr::LoadedMesh>> mesh = [&] {
                    py::gil_scoped_release release;
                    std::lock_guard lock(*s.mutex);
                    return s.pipeline->mesh(volume);
                }();
                std::shared_ptr<const tr::LoadedMesh> loaded = unwrap(std::move(mesh));
                // Shares the loaded mesh's tets (aliasing: the LoadedMesh stays alive).
                return TetHandle{std::shared_ptr<const tr::TetMesh>(loaded, &loaded->tets),
                                 loaded->report};
            },
            py::arg("volume"), "The volume's mesh as the pipeline loaded it (tetrahedral).");
}

// Pictures and scene files, and the quick-look scene of a mesh.
void bind_images_and_scene_files(py::module_& m) {
    m.def(
        "write_image",
        [](const py::array& array, const std::string& path) {
            if (array.ndim() != 3 || array.shape(2) != 3) {
                bad_argument(path + ": expected an (H, W, 3) image array");
            }
            tr::Image image(static_cast<int>(array.shape(1)), static_cast<int>(array.shape(0)));
            if (array.dtype().is(py::dtype::of<std::uint8_t>())) {
                auto bytes = py::array_t<std::uint8_t, py::array::c_style>::ensure(array);
                for (std::size_t i = 0; i < image.pixels.size(); ++i) {
                    for (int c = 0; c < 3; ++c)
                        image.pixels[i][c] = bytes.data()[3 * i + c] / 255.0f;
                }
            } else {
                auto floats =
                    py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
                if (!floats) bad_argument(path + ": not a numeric image array");
                std::memcpy(image.pixels.data(), floats.data(),
                            image.pixels.size() * sizeof(tr::Vec3f));
            }
            py::gil_scoped_release release;
            tr::Status written = tr::write_image(image, path);
            py::gil_scoped_acquire acquire;
            unwrap(written);
        },
        py::arg("image"), py::arg("path"), "io/write_image.h write_image (.png or .pfm)");

    m.def(
        "read_image",
        [](const std::string& path) { return image_array(unwrap(tr::read_image(path)), true); },
        py::arg("path"), "io/write_image.h read_image: (H, W, 3) float32");

    m.def(
        "read_scene",
        [](const std::string& path) {
            SceneHandle s;
            s.scene = unwrap(tr::read_scene(path));
            return s;
        },
        py::arg("path"), "pipeline/scene.h read_scene");

    m.def(
        "parse_scene",
        [](const std::string& text, const std::string& base_dir, const std::string& name) {
            SceneHandle s;
            s.scene = unwrap(tr::parse_scene(text, base_dir, name));
            return s;
        },
        py::arg("text"), py::arg("base_dir"), py::arg("name"), "pipeline/scene.h parse_scene");

    m.def(
        "quick_scene",
        [](const TetHandle& mesh, const std::string& name, const std::string& scalar, int component,
           int width, int height, const std::string& view, const std::string& colormap,
           const std::string& look, const std::optional<std::array<double, 2>>& range,
           std::optional<double> opacity, std::optional<double> unit_distance, double azimuth,
           double elevation, double zoom, const std::optional<std::array<double, 3>>& background,
           bool log) {
            if (look != "fitted" && look != "classic") {
                bad_argument("look must be 'fitted' or 'classic', not '" + look + "'");
            }
            tr::QuickSceneOptions options =
                look == "classic" ? tr::classic_quick_look() : tr::QuickSceneOptions{};
            // None: the CLI's default, the first point array, else the first cell array.
            options.scalar = scalar.empty() ? tr::default_quick_scalar(*mesh.mesh) : scalar;
            if (options.scalar.empty()) {
                bad_argument("the mesh has no point or cell array to show; hand one over");
            }
            options.component = component;
            options.width = width;
            options.height = height;
            options.view = view;
            options.colormap = colormap;
            options.range = range;
            options.log_scale = log;
            if (opacity) {
                options.max_opacity = *opacity;
                if (!options.opacity_curve.empty())
                    options.opacity_curve = {{0.0, 0.0}, {1.0, *opacity}};
            }
            if (unit_distance) options.unit_distance = *unit_distance;
            options.azimuth = azimuth, options.elevation = elevation, options.zoom = zoom;
            if (background)
                options.background = tr::Vec3((*background)[0], (*background)[1], (*background)[2]);
            SceneHandle s;
            s.scene = unwrap(tr::make_quick_scene(name, *mesh.mesh, options));
            s.scene.volumes.at(0).tets = mesh.mesh;
            return s;
        },
        py::arg("mesh"), py::arg("name"), py::arg("scalar"), py::arg("component"), py::arg("width"),
        py::arg("height"), py::arg("view"), py::arg("colormap"), py::arg("look") = "fitted",
        py::arg("range") = std::nullopt, py::arg("opacity") = std::nullopt,
        py::arg("unit_distance") = std::nullopt, py::arg("azimuth") = 0.0,
        py::arg("elevation") = 0.0, py::arg("zoom") = 1.0, py::arg("background") = std::nullopt,
        py::arg("log") = false,
        "pipeline/quick_scene.h make_quick_scene: the CLI's quick-look scene of a mesh");
}

}  // namespace

PYBIND11_MODULE(_core, m) {
    m.doc() = "tetrender's C++ core; use the tetrender package, not this module.";
    bind_errors(m);
    bind_mesh_handles(m);
    bind_flow_textures(m);
    bind_memory_and_meshes(m);
    py::class_<SceneHandle> scene(m, "SceneHandle", "A scene and the pipeline that renders it.");
    bind_scene_contents(scene);
    bind_scene_rendering(scene);
    bind_images_and_scene_files(m);
}
