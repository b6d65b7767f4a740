#include <cstdio>
#include <fstream>
#include <map>
#include <pipeline/paraview_camera.h>
#include <regex>
#include <sstream>
#include <unistd.h>
#include <vector>

namespace tr {
namespace {

// Each <Property name="N" ...> ... </Property> as N -> its elements' values by index (as text).
std::map<std::string, std::map<int, std::string>> properties(const std::string& text) {
    std::map<std::string, std::map<int, std::string>> found;
    static const std::regex property(
        R"re(<Property\s[^>]*name\s*=\s*"([^"]*)"[^>]*>([\s\S]*?)</Property\s*>)re");
    static const std::regex element(
        R"re(<Element\s[^>]*index\s*=\s*"([0-9]+)"[^>]*value\s*=\s*"([^"]*)"[^>]*/?>)re");
    for (auto p = std::sregex_iterator(text.begin(), text.end(), property);
         p != std::sregex_iterator(); ++p) {
        auto& values = found[(*p)[1].str()];
        const std::string body = (*p)[2].str();
        for (auto e = std::sregex_iterator(body.begin(), body.end(), element);
             e != std::sregex_iterator(); ++e) {
            values[std::stoi((*e)[1].str())] = (*e)[2].str();
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
