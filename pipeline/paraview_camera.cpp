#include <pipeline/paraview_camera.h>

#include <cctype>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <unistd.h>
#include <vector>

namespace tr {
namespace {

// The value of attribute `name` in the tag text `tag` (`name="value"` after a blank), or none.
std::optional<std::string> attribute(std::string_view tag, std::string_view name) {
    for (std::size_t at = tag.find(name); at != std::string_view::npos;
         at = tag.find(name, at + 1)) {
        const bool starts = at > 0 && std::isspace(static_cast<unsigned char>(tag[at - 1]));
        std::size_t p = at + name.size();
        while (p < tag.size() && std::isspace(static_cast<unsigned char>(tag[p]))) ++p;
        if (!starts || p >= tag.size() || tag[p] != '=') continue;
        ++p;
        while (p < tag.size() && std::isspace(static_cast<unsigned char>(tag[p]))) ++p;
        if (p >= tag.size() || tag[p] != '"') continue;
        const std::size_t end = tag.find('"', p + 1);
        if (end == std::string_view::npos) return std::nullopt;
        return std::string(tag.substr(p + 1, end - p - 1));
    }
    return std::nullopt;
}

// Each <Property name="N" ...> ... </Property> as N -> its elements' values by index (as
// text). A plain scan (std::regex trips GCC 12's uninitialized-use warnings under the
// sanitizers).
std::map<std::string, std::map<int, std::string>> properties(std::string_view text) {
    std::map<std::string, std::map<int, std::string>> found;
    for (std::size_t at = text.find("<Property"); at != std::string_view::npos;
         at = text.find("<Property", at + 1)) {
        const std::size_t tag_end = text.find('>', at);
        if (tag_end == std::string_view::npos) break;
        const auto name = attribute(text.substr(at, tag_end - at), "name");
        const std::size_t close = text.find("</Property", tag_end);
        if (!name || close == std::string_view::npos) continue;
        auto& values = found[*name];
        const std::string_view body = text.substr(tag_end, close - tag_end);
        for (std::size_t e = body.find("<Element"); e != std::string_view::npos;
             e = body.find("<Element", e + 1)) {
            const std::size_t e_end = body.find('>', e);
            if (e_end == std::string_view::npos) break;
            const std::string_view tag = body.substr(e, e_end - e);
            const auto index = attribute(tag, "index");
            const auto value = attribute(tag, "value");
            if (!index || !value || index->empty() || index->size() > 6 ||
                index->find_first_not_of("0123456789") != std::string::npos) {
                continue;
            }
            values[std::stoi(*index)] = *value;
        }
    }
    return found;
}

Result<double> number(const std::string& text, const std::string& what, const std::string& source) {
    try {
        std::size_t used = 0;
        const double value = std::stod(text, &used);
        if (used == text.size()) return value;
    } catch (const std::exception&) {
    }
    return make_error(ErrorCode::kParse, what + ": '" + text + "' is not a number", source);
}

}  // namespace

Result<Camera> parse_paraview_camera(const std::string& text, const std::string& source) {
    if (text.find("<PVCameraConfiguration") == std::string::npos) {
        return make_error(ErrorCode::kParse,
                          "not a ParaView camera file (no <PVCameraConfiguration>)", source);
    }
    const auto found = properties(text);
    const auto vector = [&](const char* name, bool required, Vec3 fallback) -> Result<Vec3> {
        const auto it = found.find(name);
        if (it == found.end()) {
            if (required) return make_error(ErrorCode::kParse, std::string("no ") + name, source);
            return fallback;
        }
        Vec3 v(0.0);
        for (int i = 0; i < 3; ++i) {
            const auto e = it->second.find(i);
            if (e == it->second.end()) {
                return make_error(ErrorCode::kParse,
                                  std::string(name) + ": no element " + std::to_string(i), source);
            }
            TR_TRY(v[i],
                   number(e->second, std::string(name) + " element " + std::to_string(i), source));
        }
        return v;
    };
    const auto scalar = [&](const char* name, double fallback) -> Result<double> {
        const auto it = found.find(name);
        if (it == found.end() || !it->second.count(0)) return fallback;
        return number(it->second.at(0), name, source);
    };
    Camera camera;
    TR_TRY(camera.position, vector("CameraPosition", true, Vec3(0.0)));
    TR_TRY(camera.focal_point, vector("CameraFocalPoint", true, Vec3(0.0)));
    TR_TRY(camera.view_up, vector("CameraViewUp", false, Vec3(0, 1, 0)));
    TR_TRY(camera.view_angle, scalar("CameraViewAngle", 30.0));
    TR_TRY(camera.parallel_scale, scalar("CameraParallelScale", 1.0));
    TR_TRY(const double parallel, scalar("CameraParallelProjection", 0.0));
    camera.parallel = parallel != 0.0;
    if (const Status ok = check_camera(camera); !ok.ok()) {
        return make_error(ErrorCode::kInvalidArgument, ok.error().message, source);
    }
    return camera;
}

Result<Camera> read_paraview_camera(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error(ErrorCode::kNotFound, "cannot open the camera file", path.string());
    std::stringstream text;
    text << in.rdbuf();
    return parse_paraview_camera(text.str(), path.string());
}

std::string paraview_camera_xml(const Camera& camera) {
    std::string xml =
        "<?xml version=\"1.0\"?>\n<PVCameraConfiguration description=\"ParaView camera "
        "configuration\" version=\"1.0\">\n  <Proxy group=\"views\" type=\"RenderView\" "
        "id=\"1\" servers=\"21\">\n";
    const auto property = [&](const char* name, const std::vector<double>& values) {
        xml += std::string("    <Property name=\"") + name + "\" id=\"1." + name +
               "\" number_of_elements=\"" + std::to_string(values.size()) + "\">\n";
        for (std::size_t i = 0; i < values.size(); ++i) {
            char value[40];
            std::snprintf(value, sizeof value, "%.17g", values[i]);
            xml += "      <Element index=\"" + std::to_string(i) + "\" value=\"" + value + "\"/>\n";
        }
        xml += "    </Property>\n";
    };
    const auto v3 = [](const Vec3& v) { return std::vector<double>{v.x, v.y, v.z}; };
    property("CameraPosition", v3(camera.position));
    property("CameraFocalPoint", v3(camera.focal_point));
    property("CameraViewUp", v3(camera.view_up));
    property("CenterOfRotation", v3(camera.focal_point));
    property("CameraViewAngle", {camera.view_angle});
    property("CameraParallelScale", {camera.parallel_scale});
    property("CameraParallelProjection", {camera.parallel ? 1.0 : 0.0});
    xml += "  </Proxy>\n</PVCameraConfiguration>\n";
    return xml;
}

Status write_paraview_camera(const Camera& camera, const std::filesystem::path& path) {
    const std::filesystem::path temp = path.parent_path() / (".tmp." + std::to_string(::getpid()) +
                                                             "." + path.filename().string());
    {
        std::ofstream out(temp, std::ios::binary);
        out << paraview_camera_xml(camera);
        if (!out) {
            std::error_code ignored;
            std::filesystem::remove(temp, ignored);
            return make_error(ErrorCode::kIo, "cannot write the camera file", path.string());
        }
    }
    std::error_code renamed;
    std::filesystem::rename(temp, path, renamed);
    if (renamed) {
        std::error_code ignored;
        std::filesystem::remove(temp, ignored);
        return make_error(ErrorCode::kIo, "cannot write: " + renamed.message(), path.string());
    }
    return Status{};
}

}  // namespace tr
