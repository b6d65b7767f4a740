#include <pipeline/scene.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace tr {
namespace {

using json = nlohmann::json;

// Thrown inside the parser only; parse_scene is the one catch site.
struct SceneError {
    std::string path;
    std::string message;
};

[[noreturn]] void fail(const std::string& path, const std::string& message) {
    throw SceneError{path, message};
}

void check_keys(const json& j, const std::string& path, const std::set<std::string>& allowed) {
    if (!j.is_object()) fail(path, "expected an object");
    for (const auto& [key, value] : j.items()) {
        if (!allowed.count(key)) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
            fail(path + "." + key, "unknown key (allowed here: " + list + ")");
        }
    }
}

const json& require(const json& j, const std::string& path, const char* key) {
    if (!j.contains(key)) fail(path + "." + key, "missing");
    return j.at(key);
}

double number(const json& j, const std::string& path) {
    if (!j.is_number()) fail(path, "expected a number");
    const double x = j.get<double>();
    if (!std::isfinite(x)) fail(path, "expected a finite number");
    return x;
}

int integer(const json& j, const std::string& path) {
    if (!j.is_number_integer()) fail(path, "expected an integer");
    const auto x = j.get<std::int64_t>();
    if (x < std::numeric_limits<int>::min() || x > std::numeric_limits<int>::max()) {
        fail(path, "integer out of range");
    }
    return static_cast<int>(x);
}

std::vector<double> numbers(const json& j, const std::string& path, std::size_t n) {
    if (!j.is_array() || j.size() != n) {
        fail(path, "expected an array of " + std::to_string(n) + " numbers");
    }
    std::vector<double> out;
    for (std::size_t i = 0; i < n; ++i)
        out.push_back(number(j[i], path + "[" + std::to_string(i) + "]"));
    return out;
}

Vec3 vec3(const json& j, const std::string& path) {
    const auto v = numbers(j, path, 3);
    return {v[0], v[1], v[2]};
}

TransferFunction transfer_function(const json& j, const std::string& path) {
    check_keys(j, path, {"color", "opacity", "unit_distance"});
    const json& color = require(j, path, "color");
    const json& opacity = require(j, path, "opacity");
    if (!color.is_array() || color.empty())
        fail(path + ".color", "expected a non-empty array of [s, r, g, b]");
    if (!opacity.is_array() || opacity.empty())
        fail(path + ".opacity", "expected a non-empty array of [s, a]");
    std::vector<ColorPoint> c;
    for (std::size_t i = 0; i < color.size(); ++i) {
        const auto v = numbers(color[i], path + ".color[" + std::to_string(i) + "]", 4);
        c.push_back({v[0], {v[1], v[2], v[3]}});
    }
    std::vector<OpacityPoint> o;
    for (std::size_t i = 0; i < opacity.size(); ++i) {
        const auto v = numbers(opacity[i], path + ".opacity[" + std::to_string(i) + "]", 2);
        o.push_back({v[0], v[1]});
    }
    const double unit = number(require(j, path, "unit_distance"), path + ".unit_distance");
    auto tf = TransferFunction::create(std::move(c), std::move(o), unit);
    if (!tf.ok()) fail(path, tf.error().message);
    return std::move(tf).value();
}

Camera camera(const json& j, const std::string& path) {
    check_keys(j, path,
               {"position", "focal_point", "view_up", "view_angle", "parallel", "parallel_scale"});
    Camera c;
    c.position = vec3(require(j, path, "position"), path + ".position");
    c.focal_point = vec3(require(j, path, "focal_point"), path + ".focal_point");
    c.view_up = vec3(require(j, path, "view_up"), path + ".view_up");
    if (j.contains("view_angle")) c.view_angle = number(j["view_angle"], path + ".view_angle");
    if (j.contains("parallel")) {
        if (!j["parallel"].is_boolean()) fail(path + ".parallel", "expected true or false");
        c.parallel = j["parallel"].get<bool>();
    }
    if (j.contains("parallel_scale")) {
        c.parallel_scale = number(j["parallel_scale"], path + ".parallel_scale");
    }
    if (const Status ok = check_camera(c); !ok.ok()) {
        // check_camera's messages start with the key at fault, when there is one.
        const std::string& message = ok.error().message;
        std::string where = path;
        for (const char* key : {"view_up", "view_angle", "parallel_scale"}) {
            if (message.rfind(key, 0) == 0) where = path + "." + key;
        }
        fail(where, message);
    }
    return c;
}

FlowVolumeSpec flow_volume(const json& j, const std::string& path) {
    check_keys(j, path,
               {"vectors", "seed_center", "seed_size", "seed_resolution", "seed_normal", "steps",
                "dt", "compressible", "split_threshold", "unsteady", "start_time", "color",
                "opacity", "unit_distance", "context"});
    const auto flag = [&](const char* key, bool& out) {
        if (!j.contains(key)) return;
        if (!j[key].is_boolean()) fail(path + "." + key, "expected true or false");
        out = j[key].get<bool>();
    };
    FlowVolumeSpec f;
    const json& vectors = require(j, path, "vectors");
    if (!vectors.is_string() || vectors.get<std::string>().empty()) {
        fail(path + ".vectors", "expected a vector array's name");
    }
    f.vectors = vectors.get<std::string>();
    // seed_center, seed_size and dt may be left to the data (resolve_flow_spec).
    f.choose.seed_center = !j.contains("seed_center");
    if (!f.choose.seed_center) f.seed_center = vec3(j["seed_center"], path + ".seed_center");
    f.choose.seed_size = !j.contains("seed_size");
    if (!f.choose.seed_size) {
        const auto size = numbers(j["seed_size"], path + ".seed_size", 2);
        if (!(size[0] > 0 && size[1] > 0)) fail(path + ".seed_size", "must be positive");
        f.seed_width = size[0];
        f.seed_height = size[1];
    }
    f.choose.dt = !j.contains("dt");
    if (j.contains("seed_resolution")) {
        f.seed_resolution = integer(j["seed_resolution"], path + ".seed_resolution");
        if (f.seed_resolution < 1 || f.seed_resolution > 4096) {
            fail(path + ".seed_resolution", "must be between 1 and 4096");
        }
    }
    if (j.contains("seed_normal")) {
        f.seed_normal = vec3(j["seed_normal"], path + ".seed_normal");
        if (glm::length(*f.seed_normal) == 0) fail(path + ".seed_normal", "must not be zero");
    }
    if (j.contains("steps")) {
        f.steps = integer(j["steps"], path + ".steps");
        if (f.steps < 1 || f.steps > 100000) fail(path + ".steps", "must be between 1 and 100000");
    }
    if (j.contains("dt")) {
        f.dt = number(j["dt"], path + ".dt");
        if (!(f.dt > 0)) fail(path + ".dt", "must be positive");
    }
    flag("compressible", f.compressible);
    if (j.contains("split_threshold")) {
        f.split_threshold = number(j["split_threshold"], path + ".split_threshold");
        if (!(f.split_threshold == 0 || f.split_threshold >= 1.5)) {
            fail(path + ".split_threshold", "must be 0 (off) or at least 1.5");
        }
    }
    flag("unsteady", f.unsteady);
    if (j.contains("start_time")) f.start_time = number(j["start_time"], path + ".start_time");
    if (j.contains("color")) {
        f.color = vec3(j["color"], path + ".color");
        for (int c = 0; c < 3; ++c) {
            if (f.color[c] < 0 || f.color[c] > 1)
                fail(path + ".color", "components must be in [0, 1]");
        }
    }
    if (j.contains("opacity")) {
        f.opacity = number(j["opacity"], path + ".opacity");
        if (!(f.opacity > 0 && f.opacity < 1)) fail(path + ".opacity", "must be in (0, 1)");
    }
    if (j.contains("unit_distance")) {
        f.unit_distance = number(j["unit_distance"], path + ".unit_distance");
        if (!(*f.unit_distance > 0)) fail(path + ".unit_distance", "must be positive");
    }
    flag("context", f.context);
    return f;
}

json flow_volume_json(const FlowVolumeSpec& f) {
    const auto array = [](const Vec3& v) { return json::array({v.x, v.y, v.z}); };
    json j = {{"vectors", f.vectors},
              {"seed_resolution", f.seed_resolution},
              {"steps", f.steps},
              {"compressible", f.compressible},
              {"split_threshold", f.split_threshold},
              {"unsteady", f.unsteady},
              {"color", array(f.color)},
              {"opacity", f.opacity},
              {"context", f.context}};
    // What the data is left to choose stays unsaid.
    if (!f.choose.seed_center) j["seed_center"] = array(f.seed_center);
    if (!f.choose.seed_size) j["seed_size"] = {f.seed_width, f.seed_height};
    if (!f.choose.dt) j["dt"] = f.dt;
    if (f.seed_normal) j["seed_normal"] = array(*f.seed_normal);
    if (f.start_time) j["start_time"] = *f.start_time;
    if (f.unit_distance) j["unit_distance"] = *f.unit_distance;
    return j;
}

// The keys of one volume, at `path` ("$" for the top-level keys, "$.volumes[i]" otherwise).
SceneVolume volume(const json& j, const std::string& path, const std::filesystem::path& base_dir) {
    SceneVolume v;
    const json& mesh = require(j, path, "mesh");
    if (!mesh.is_string() || mesh.get<std::string>().empty())
        fail(path + ".mesh", "expected a file path");
    v.mesh = base_dir / mesh.get<std::string>();
    const json& scalar = require(j, path, "scalar");
    if (!scalar.is_string() || scalar.get<std::string>().empty())
        fail(path + ".scalar", "expected an array name");
    v.scalar = scalar.get<std::string>();
    if (j.contains("component")) {
        const json& c = j["component"];
        if (c.is_string()) {
            if (c.get<std::string>() != "magnitude") {
                fail(path + ".component", "expected \"magnitude\" or a component index");
            }
        } else {
            v.component = integer(c, path + ".component");
            if (v.component < 0) fail(path + ".component", "must be >= 0");
        }
    }
    v.transfer_function =
        transfer_function(require(j, path, "transfer_function"), path + ".transfer_function");
    if (j.contains("time_step")) {
        v.time_step = integer(j["time_step"], path + ".time_step");
        if (v.time_step < 0) fail(path + ".time_step", "must be >= 0");
    }
    return v;
}

const std::set<std::string> kVolumeKeys = {"mesh", "scalar", "component", "transfer_function",
                                           "time_step"};

MethodSpec method(const json& j, const std::string& path) {
    if (!j.is_object()) fail(path, "expected an object");
    MethodSpec m;
    const json& name = require(j, path, "name");
    if (!name.is_string() || name.get<std::string>().empty())
        fail(path + ".name", "expected a method name");
    m.name = name.get<std::string>();
    for (const auto& [key, value] : j.items()) {
        const std::string at = path + "." + key;
        if (key == "name") continue;
        if (key == "repetitions") {
            m.repetitions = integer(value, at);
            if (*m.repetitions < 1) fail(at, "must be >= 1");
        } else if (key == "seed") {
            if (!value.is_number_integer()) fail(at, "expected an integer");
            m.seed = value.get<std::int64_t>();
        } else if (value.is_boolean()) {
            m.options[key] = value.get<bool>();
        } else if (value.is_number_integer()) {
            m.options[key] = value.get<std::int64_t>();
        } else if (value.is_number()) {
            m.options[key] = number(value, at);
        } else if (value.is_string()) {
            m.options[key] = value.get<std::string>();
        } else if (value.is_array() && !value.empty() &&
                   std::all_of(value.begin(), value.end(),
                               [](const json& row) { return row.is_array(); })) {
            NumberLists lists;
            for (std::size_t i = 0; i < value.size(); ++i) {
                std::vector<double> row;
                for (std::size_t k = 0; k < value[i].size(); ++k) {
                    row.push_back(number(value[i][k], at + "[" + std::to_string(i) + "][" +
                                                          std::to_string(k) + "]"));
                }
                lists.push_back(std::move(row));
            }
            m.options[key] = std::move(lists);
        } else {
            fail(at, "expected a number, a string, true/false or a list of lists of numbers");
        }
    }
    return m;
}

json method_json(const MethodSpec& m) {
    json j = {{"name", m.name}};
    if (m.repetitions) j["repetitions"] = *m.repetitions;
    if (m.seed) j["seed"] = *m.seed;
    for (const auto& [key, value] : m.options) {
        std::visit([&, k = key](const auto& v) { j[k] = v; }, value);
    }
    return j;
}

json volume_json(const SceneVolume& v, const std::filesystem::path& folder) {
    std::error_code ec;
    auto mesh = std::filesystem::relative(v.mesh, folder, ec);
    json j;
    j["mesh"] = (ec || mesh.empty() ? v.mesh : mesh).generic_string();
    j["scalar"] = v.scalar;
    if (v.component >= 0) {
        j["component"] = v.component;
    } else {
        j["component"] = "magnitude";
    }
    json color = json::array(), opacity = json::array();
    for (const auto& p : v.transfer_function.color_points()) {
        color.push_back({p.s, p.rgb.r, p.rgb.g, p.rgb.b});
    }
    for (const auto& p : v.transfer_function.opacity_points()) opacity.push_back({p.s, p.a});
    j["transfer_function"] = {{"color", color},
                              {"opacity", opacity},
                              {"unit_distance", v.transfer_function.unit_distance()}};
    if (v.time_step) j["time_step"] = v.time_step;
    return j;
}

}  // namespace

const std::string& Scene::method_name() const {
    static const std::string kDefault = kDefaultMethod;
    return method ? method->name : kDefault;
}

Result<Scene> parse_scene(const std::string& text, const std::filesystem::path& base_dir,
                          const std::string& name) {
    json j;
    try {
        j = json::parse(text);
    } catch (const json::parse_error& e) {
        std::string what = e.what();
        // "[json.exception.parse_error.101] parse error at line 3, column 5: ..." -> keep the
        // part after the id.
        const auto pos = what.find("] ");
        if (pos != std::string::npos) what = what.substr(pos + 2);
        return make_error(ErrorCode::kParse, what, name);
    } catch (const json::out_of_range& e) {
        // A number beyond a double (1e400): "[json.exception.out_of_range.406] number overflow
        // parsing '1e400'" -> the part after the id.
        std::string what = e.what();
        const auto pos = what.find("] ");
        if (pos != std::string::npos) what = what.substr(pos + 2);
        return make_error(ErrorCode::kParse, what + " (beyond a double)", name);
    }
    try {
        Scene scene;
        scene.source = name;
        std::set<std::string> top = {"camera",      "image",  "opaque",
                                     "flow_volume", "method", "volumes"};
        top.insert(kVolumeKeys.begin(), kVolumeKeys.end());
        check_keys(j, "$", top);
        bool has_top_level = false;
        for (const std::string& key : kVolumeKeys) has_top_level = has_top_level || j.contains(key);
        if (j.contains("volumes")) {
            if (has_top_level) {
                fail("$.volumes",
                     "a scene has either the top-level mesh, scalar, component, time_step and "
                     "transfer_function or `volumes`, never both");
            }
            const json& list = j["volumes"];
            if (!list.is_array() || list.empty() || list.size() > kMaxVolumes) {
                fail("$.volumes",
                     "expected an array of 1 to " + std::to_string(kMaxVolumes) + " volumes");
            }
            for (std::size_t i = 0; i < list.size(); ++i) {
                const std::string path = "$.volumes[" + std::to_string(i) + "]";
                check_keys(list[i], path, kVolumeKeys);
                scene.volumes.push_back(volume(list[i], path, base_dir));
            }
            scene.volumes_key = true;
        } else {
            scene.volumes.push_back(volume(j, "$", base_dir));
        }
        if (j.contains("method")) scene.method = method(j["method"], "$.method");
        scene.camera = camera(require(j, "$", "camera"), "$.camera");
        const json& image = require(j, "$", "image");
        check_keys(image, "$.image", {"width", "height", "background"});
        scene.width = integer(require(image, "$.image", "width"), "$.image.width");
        scene.height = integer(require(image, "$.image", "height"), "$.image.height");
        for (const auto& [value, key] :
             {std::pair{scene.width, "width"}, {scene.height, "height"}}) {
            if (value < 1 || value > kMaxImageSide) {
                fail(std::string("$.image.") + key,
                     "must be between 1 and " + std::to_string(kMaxImageSide));
            }
        }
        if (image.contains("background")) {
            scene.background = vec3(image["background"], "$.image.background");
            for (int c = 0; c < 3; ++c) {
                if (scene.background[c] < 0 || scene.background[c] > 1) {
                    fail("$.image.background", "components must be in [0, 1]");
                }
            }
        }
        if (j.contains("opaque")) {
            const json& list = j["opaque"];
            if (!list.is_array()) fail("$.opaque", "expected an array of surfaces");
            for (std::size_t i = 0; i < list.size(); ++i) {
                const std::string path = "$.opaque[" + std::to_string(i) + "]";
                check_keys(list[i], path, {"file", "side_set", "boundary", "volume", "color"});
                OpaqueSpec spec;
                const bool has_file = list[i].contains("file");
                const bool has_side_set = list[i].contains("side_set");
                const bool has_boundary = list[i].contains("boundary");
                if (int(has_file) + int(has_side_set) + int(has_boundary) != 1) {
                    fail(path, "give exactly one of file, side_set and boundary");
                }
                if (has_boundary) {
                    if (!list[i]["boundary"].is_boolean() || !list[i]["boundary"].get<bool>()) {
                        fail(path + ".boundary", "expected true");
                    }
                    spec.boundary = true;
                }
                if (has_boundary) {
                    // nothing more to read
                } else if (has_file) {
                    if (!list[i]["file"].is_string()) fail(path + ".file", "expected a file path");
                    spec.file = base_dir / list[i]["file"].get<std::string>();
                } else {
                    if (!list[i]["side_set"].is_string()) {
                        fail(path + ".side_set", "expected a side-set name or \"*\"");
                    }
                    spec.side_set = list[i]["side_set"].get<std::string>();
                }
                if (list[i].contains("volume")) {
                    const int v = integer(list[i]["volume"], path + ".volume");
                    if (v < 0 || static_cast<std::size_t>(v) >= scene.volumes.size()) {
                        fail(path + ".volume", "no volume " + std::to_string(v) + " in the scene");
                    }
                    spec.volume = static_cast<std::size_t>(v);
                }
                if (list[i].contains("color")) {
                    spec.color = vec3(list[i]["color"], path + ".color");
                    for (int c = 0; c < 3; ++c) {
                        if (spec.color[c] < 0 || spec.color[c] > 1) {
                            fail(path + ".color", "components must be in [0, 1]");
                        }
                    }
                }
                scene.opaque.push_back(spec);
            }
        }
        if (j.contains("flow_volume"))
            scene.flow_volume = flow_volume(j["flow_volume"], "$.flow_volume");
        return scene;
    } catch (const SceneError& e) {
        return make_error(ErrorCode::kParse, e.path + ": " + e.message, name);
    } catch (const json::exception& e) {
        return make_error(ErrorCode::kParse, e.what(), name);
    }
}

Result<Scene> read_scene(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        return make_error(ErrorCode::kNotFound, "no such scene file", path.string());
    }
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    if (!in.good() && !in.eof()) {
        return make_error(ErrorCode::kIo, "cannot read the file", path.string());
    }
    return parse_scene(text.str(), path.parent_path(), path.string());
}

Status write_scene(const Scene& scene, const std::filesystem::path& path) {
    if (scene.volumes.empty()) {
        return make_error(ErrorCode::kInvalidArgument, "a scene without a volume", path.string());
    }
    json j;
    std::error_code ec;
    const std::filesystem::path folder =
        path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
    if (scene.volumes_key || scene.volumes.size() > 1) {
        j["volumes"] = json::array();
        for (const SceneVolume& v : scene.volumes) j["volumes"].push_back(volume_json(v, folder));
    } else {
        j = volume_json(scene.volumes[0], folder);
    }
    const Camera& c = scene.camera;
    j["camera"] = {{"position", {c.position.x, c.position.y, c.position.z}},
                   {"focal_point", {c.focal_point.x, c.focal_point.y, c.focal_point.z}},
                   {"view_up", {c.view_up.x, c.view_up.y, c.view_up.z}},
                   {"view_angle", c.view_angle},
                   {"parallel", c.parallel},
                   {"parallel_scale", c.parallel_scale}};
    j["image"] = {{"width", scene.width},
                  {"height", scene.height},
                  {"background", {scene.background.x, scene.background.y, scene.background.z}}};
    if (!scene.opaque.empty()) {
        json list = json::array();
        for (const OpaqueSpec& o : scene.opaque) {
            if (o.surface) continue;  // handed over in memory: no file to name
            json item;
            if (o.boundary) {
                item["boundary"] = true;
            } else if (o.side_set.empty()) {
                auto rel = std::filesystem::relative(o.file, folder, ec);
                item["file"] = (ec || rel.empty() ? o.file : rel).generic_string();
            } else {
                item["side_set"] = o.side_set;
            }
            if (o.volume != 0) item["volume"] = o.volume;
            item["color"] = {o.color.x, o.color.y, o.color.z};
            list.push_back(item);
        }
        j["opaque"] = list;
    }
    if (scene.flow_volume) j["flow_volume"] = flow_volume_json(*scene.flow_volume);
    if (scene.method) j["method"] = method_json(*scene.method);
    const auto tmp = path.string() + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << j.dump(2) << "\n";
        if (!out) {
            std::filesystem::remove(tmp, ec);
            return make_error(ErrorCode::kIo, "cannot write the scene file", path.string());
        }
    }
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        return make_error(ErrorCode::kIo, "cannot write the scene file", path.string());
    }
    return {};
}

}  // namespace tr
