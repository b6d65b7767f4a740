#include <project/colormap_preset.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

namespace tr {
namespace {

using nlohmann::json;

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// --- Colour spaces (sRGB with its transfer curve, D65; as VTK's vtkMath) ---

double to_linear(double c) { return c > 0.04045 ? std::pow((c + 0.055) / 1.055, 2.4) : c / 12.92; }
double from_linear(double c) {
    return c > 0.0031308 ? 1.055 * std::pow(c, 1.0 / 2.4) - 0.055 : 12.92 * c;
}
constexpr Vec3 kWhite{0.9505, 1.0, 1.089};

Vec3 rgb_to_lab(const Vec3& rgb) {
    const double r = to_linear(rgb.r), g = to_linear(rgb.g), b = to_linear(rgb.b);
    const Vec3 xyz(0.4124 * r + 0.3576 * g + 0.1805 * b, 0.2126 * r + 0.7152 * g + 0.0722 * b,
                   0.0193 * r + 0.1192 * g + 0.9505 * b);
    auto f = [](double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; };
    const double fx = f(xyz.x / kWhite.x), fy = f(xyz.y / kWhite.y), fz = f(xyz.z / kWhite.z);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Vec3 lab_to_rgb(const Vec3& lab) {
    const double fy = (lab.x + 16.0) / 116.0, fx = fy + lab.y / 500.0, fz = fy - lab.z / 200.0;
    auto finv = [](double t) {
        return t * t * t > 0.008856 ? t * t * t : (t - 16.0 / 116.0) / 7.787;
    };
    const double x = finv(fx) * kWhite.x, y = finv(fy) * kWhite.y, z = finv(fz) * kWhite.z;
    const double r = 3.2406 * x - 1.5372 * y - 0.4986 * z;
    const double g = -0.9689 * x + 1.8758 * y + 0.0415 * z;
    const double b = 0.0557 * x - 0.2040 * y + 1.0570 * z;
    return glm::clamp(Vec3(from_linear(r), from_linear(g), from_linear(b)), 0.0, 1.0);
}

Vec3 lab_to_msh(const Vec3& lab) {
    const double m = glm::length(lab);
    const double s = m > 0.001 ? std::acos(std::clamp(lab.x / m, -1.0, 1.0)) : 0.0;
    const double h = s > 0.001 ? std::atan2(lab.z, lab.y) : 0.0;
    return {m, s, h};
}

Vec3 msh_to_lab(const Vec3& msh) {
    return {msh.x * std::cos(msh.y), msh.x * std::sin(msh.y) * std::cos(msh.z),
            msh.x * std::sin(msh.y) * std::sin(msh.z)};
}

// Moreland's hue adjustment for interpolating to an unsaturated colour.
double adjust_hue(const Vec3& msh, double unsaturated_m) {
    if (msh.x >= unsaturated_m - 0.1) return msh.z;
    const double spin = msh.y * std::sqrt(unsaturated_m * unsaturated_m - msh.x * msh.x) /
                        (msh.x * std::sin(msh.y));
    return msh.z > -std::numbers::pi / 3 ? msh.z + spin : msh.z - spin;
}

// Moreland, "Diverging Color Maps for Scientific Visualization" (2009), as VTK does it.
Vec3 diverging(const Vec3& rgb1, const Vec3& rgb2, double t) {
    Vec3 a = lab_to_msh(rgb_to_lab(rgb1)), b = lab_to_msh(rgb_to_lab(rgb2));
    double hue_gap = std::abs(a.z - b.z);
    if (hue_gap > std::numbers::pi) hue_gap = 2 * std::numbers::pi - hue_gap;
    if (a.y > 0.05 && b.y > 0.05 && hue_gap > std::numbers::pi / 3) {
        const double mid = std::max({a.x, b.x, 88.0});
        if (t < 0.5) {
            b = {mid, 0.0, 0.0};
            t = 2 * t;
        } else {
            a = {mid, 0.0, 0.0};
            t = 2 * t - 1;
        }
    }
    if (a.y < 0.05 && b.y > 0.05) {
        a.z = adjust_hue(b, a.x);
    } else if (b.y < 0.05 && a.y > 0.05) {
        b.z = adjust_hue(a, b.x);
    }
    return lab_to_rgb(msh_to_lab(a + (b - a) * t));
}

Vec3 rgb_to_hsv(const Vec3& c) {
    const double mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b}), d = mx - mn;
    double h = 0;
    if (d > 0) {
        if (mx == c.r)
            h = std::fmod((c.g - c.b) / d + 6.0, 6.0);
        else if (mx == c.g)
            h = (c.b - c.r) / d + 2.0;
        else
            h = (c.r - c.g) / d + 4.0;
    }
    return {h / 6.0, mx > 0 ? d / mx : 0.0, mx};
}

Vec3 hsv_to_rgb(const Vec3& c) {
    const double h = std::fmod(c.x, 1.0) * 6.0, s = c.y, v = c.z;
    const int i = static_cast<int>(std::floor(h)) % 6;
    const double f = h - std::floor(h), p = v * (1 - s), q = v * (1 - s * f),
                 t = v * (1 - s * (1 - f));
    switch (i) {
        case 0:
            return {v, t, p};
        case 1:
            return {q, v, p};
        case 2:
            return {p, v, t};
        case 3:
            return {p, q, v};
        case 4:
            return {t, p, v};
        default:
            return {v, p, q};
    }
}

Vec3 interpolate(const std::string& space, const Vec3& a, const Vec3& b, double t) {
    if (space == "Lab" || space == "CIELAB") {
        return lab_to_rgb(rgb_to_lab(a) + (rgb_to_lab(b) - rgb_to_lab(a)) * t);
    }
    if (space == "Diverging") return diverging(a, b, t);
    if (space == "HSV")
        return glm::clamp(hsv_to_rgb(rgb_to_hsv(a) + (rgb_to_hsv(b) - rgb_to_hsv(a)) * t), 0.0,
                          1.0);
    return a + (b - a) * t;
}

bool known_space(const std::string& space) {
    return space == "RGB" || space == "Lab" || space == "CIELAB" || space == "Diverging" ||
           space == "HSV";
}

// --- JSON ---

std::string line_column(const std::string& text, std::size_t byte) {
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < std::min(byte, text.size()); ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return std::to_string(line) + ":" + std::to_string(column > 1 ? column - 1 : 1);
}

Error bad(const std::string& source, const std::string& path, const std::string& what) {
    return make_error(ErrorCode::kParse, path + ": " + what, source);
}

Result<std::vector<double>> numbers(const json& value, const std::string& source,
                                    const std::string& path) {
    if (!value.is_array()) return bad(source, path, "expected a list of numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < value.size(); ++i) {
        if (!value[i].is_number()) {
            return bad(source, path + "[" + std::to_string(i) + "]", "expected a number");
        }
        const double v = value[i].get<double>();
        if (!std::isfinite(v))
            return bad(source, path + "[" + std::to_string(i) + "]", "not finite");
        out.push_back(v);
    }
    return out;
}

Result<ColormapPreset> parse_one(const json& object, const std::string& source,
                                 const std::string& path) {
    if (!object.is_object()) return bad(source, path, "expected a preset object");
    ColormapPreset preset;
    if (!object.contains("Name") || !object["Name"].is_string()) {
        return bad(source, path + ".Name", "missing, or not a string");
    }
    preset.name = object["Name"].get<std::string>();
    if (object.contains("ColorSpace")) {
        if (!object["ColorSpace"].is_string())
            return bad(source, path + ".ColorSpace", "expected a string");
        preset.color_space = object["ColorSpace"].get<std::string>();
        if (!known_space(preset.color_space)) {
            return bad(source, path + ".ColorSpace",
                       "unknown colour space '" + preset.color_space +
                           "' (known: RGB, Lab, CIELAB, Diverging, HSV)");
        }
    }
    if (!object.contains("RGBPoints")) {
        return bad(source, path + ".RGBPoints",
                   "missing (presets of indexed colours, 'IndexedColors', are not read)");
    }
    auto rgb = numbers(object["RGBPoints"], source, path + ".RGBPoints");
    if (!rgb) return rgb.error();
    if (rgb->empty() || rgb->size() % 4 != 0) {
        return bad(source, path + ".RGBPoints",
                   "expected x r g b for each point: " + std::to_string(rgb->size()) +
                       " numbers is not a positive multiple of 4");
    }
    for (std::size_t i = 0; i < rgb->size(); i += 4) {
        const std::string where = path + ".RGBPoints[" + std::to_string(i) + "]";
        const ColorPoint p{(*rgb)[i], Vec3((*rgb)[i + 1], (*rgb)[i + 2], (*rgb)[i + 3])};
        if (!preset.rgb_points.empty() && p.s < preset.rgb_points.back().s) {
            return bad(source, where, "x decreases (point " + std::to_string(i / 4) + ")");
        }
        for (int c = 0; c < 3; ++c) {
            if (!(p.rgb[c] >= 0 && p.rgb[c] <= 1)) {
                return bad(source, path + ".RGBPoints[" + std::to_string(i + 1 + c) + "]",
                           "colour component outside [0, 1]");
            }
        }
        preset.rgb_points.push_back(p);
    }
    if (object.contains("Points")) {
        auto points = numbers(object["Points"], source, path + ".Points");
        if (!points) return points.error();
        if (points->size() % 4 != 0) {
            return bad(source, path + ".Points",
                       "expected x opacity midpoint sharpness for each point: " +
                           std::to_string(points->size()) + " numbers is not a multiple of 4");
        }
        bool shaped = false;
        for (std::size_t i = 0; i < points->size(); i += 4) {
            const OpacityPoint p{(*points)[i], (*points)[i + 1]};
            if (!preset.opacity_points.empty() && p.s < preset.opacity_points.back().s) {
                return bad(source, path + ".Points[" + std::to_string(i) + "]", "x decreases");
            }
            if (!(p.a >= 0 && p.a <= 1)) {
                return bad(source, path + ".Points[" + std::to_string(i + 1) + "]",
                           "opacity outside [0, 1]");
            }
            if ((*points)[i + 2] != 0.5 || (*points)[i + 3] != 0.0) shaped = true;
            preset.opacity_points.push_back(p);
        }
        if (shaped) {
            preset.notes.push_back("preset '" + preset.name +
                                   "': opacity midpoints and sharpness read as linear pieces");
        }
    }
    if (object.contains("NanColor")) {
        auto nan = numbers(object["NanColor"], source, path + ".NanColor");
        if (!nan) return nan.error();
        if (nan->size() < 3) return bad(source, path + ".NanColor", "expected r g b");
        preset.nan_color = Vec3((*nan)[0], (*nan)[1], (*nan)[2]);
    }
    return preset;
}

json numbers_json(const std::vector<double>& values) {
    json out = json::array();
    for (double v : values) out.push_back(v);
    return out;
}

// Published control points. Cool to Warm, Black-Body Radiation, Jet, Rainbow Uniform and
// Grayscale as ParaView defines them (Remoting/Views/ColorMaps.json); Viridis and Inferno from
// matplotlib's 256-entry tables (CC0; Smith & van der Walt), every 16th entry and the last:
// between them the maps are linear in RGB (how far that is from the full tables between the
// samples has not been measured here).
struct Builtin {
    const char* name;
    const char* space;
    std::vector<double> rgb;  // x r g b ...
    std::vector<double> nan;
};

const std::vector<Builtin>& builtins() {
    static const std::vector<Builtin> b = {
        {"Cool to Warm",
         "Diverging",
         {0, 0.23137254902, 0.298039215686, 0.752941176471, 0.5, 0.865, 0.865, 0.865, 1,
          0.705882352941, 0.0156862745098, 0.149019607843},
         {1, 1, 0}},
        {"Viridis (matplotlib)",
         "RGB",
         {0.0,      0.267004, 0.004874, 0.329415, 0.062745, 0.282327, 0.094955, 0.417331, 0.12549,
          0.278826, 0.17549,  0.483397, 0.188235, 0.258965, 0.251537, 0.524736, 0.25098,  0.229739,
          0.322361, 0.545706, 0.313725, 0.19943,  0.387607, 0.554642, 0.376471, 0.172719, 0.448791,
          0.557885, 0.439216, 0.149039, 0.508051, 0.55725,  0.501961, 0.127568, 0.566949, 0.550556,
          0.564706, 0.120638, 0.625828, 0.533488, 0.627451, 0.157851, 0.683765, 0.501686, 0.690196,
          0.24607,  0.73891,  0.452024, 0.752941, 0.369214, 0.788888, 0.382914, 0.815686, 0.515992,
          0.831158, 0.294279, 0.878431, 0.678489, 0.863742, 0.189503, 0.941176, 0.845561, 0.887322,
          0.099702, 1.0,      0.993248, 0.906157, 0.143936},
         {1, 0, 0}},
        {"Jet",
         "RGB",
         {-1,       0, 0, 0.5625, -0.777778, 0, 0, 1, -0.269841, 0,   1, 1, -0.015873, 0.5, 1, 0.5,
          0.238095, 1, 1, 0,      0.746032,  1, 0, 0, 1,         0.5, 0, 0},
         {1, 1, 0}},
        {"Rainbow Uniform",
         "RGB",
         {0.0,      0.02,     0.3813,   0.9981,   0.023810, 0.020000, 0.424268, 0.969070, 0.047619,
          0.02,     0.467234, 0.940033, 0.071429, 0.02,     0.5102,   0.911,    0.095238, 0.020000,
          0.546401, 0.872669, 0.119048, 0.02,     0.582600, 0.834333, 0.142857, 0.02,     0.6188,
          0.796,    0.166667, 0.020000, 0.652535, 0.749802, 0.190476, 0.02,     0.686267, 0.703600,
          0.214286, 0.02,     0.72,     0.6574,   0.238095, 0.020000, 0.757035, 0.603735, 0.261905,
          0.02,     0.794067, 0.550066, 0.285714, 0.02,     0.8311,   0.4964,   0.309524, 0.021354,
          0.864537, 0.428558, 0.333333, 0.023313, 0.897999, 0.360739, 0.357143, 0.015976, 0.931048,
          0.292563, 0.380952, 0.274211, 0.952563, 0.153568, 0.404762, 0.493355, 0.961904, 0.111195,
          0.428571, 0.6439,   0.9773,   0.0469,   0.452381, 0.762402, 0.984670, 0.034600, 0.476190,
          0.880901, 0.992033, 0.022300, 0.5,      0.999529, 0.999519, 0.013488, 0.523810, 0.999403,
          0.955036, 0.079067, 0.547619, 0.9994,   0.910666, 0.148134, 0.571429, 0.9994,   0.8663,
          0.2172,   0.595238, 0.999270, 0.818036, 0.217201, 0.619048, 0.999133, 0.769766, 0.2172,
          0.642857, 0.999,    0.7215,   0.2172,   0.666667, 0.999136, 0.673436, 0.217201, 0.690476,
          0.999267, 0.625366, 0.2172,   0.714286, 0.9994,   0.5773,   0.2172,   0.738095, 0.999403,
          0.521068, 0.217201, 0.761905, 0.9994,   0.464833, 0.2172,   0.785714, 0.9994,   0.4086,
          0.2172,   0.809524, 0.994760, 0.331773, 0.211231, 0.833333, 0.986713, 0.259518, 0.190122,
          0.857143, 0.991246, 0.147994, 0.210789, 0.880952, 0.949903, 0.116867, 0.252901, 0.904762,
          0.903200, 0.078433, 0.291800, 0.928571, 0.8565,   0.04,     0.3307,   0.952381, 0.798903,
          0.043333, 0.358434, 0.976190, 0.741299, 0.046667, 0.386167, 1.0,      0.6837,   0.05,
          0.4139},
         {1, 0, 0}},
        {"Black-Body Radiation",
         "RGB",
         {0, 0, 0, 0, 0.4, 0.901960784314, 0, 0, 0.8, 0.901960784314, 0.901960784314, 0, 1, 1, 1,
          1},
         {0, 0.498039215686, 1}},
        {"Inferno (matplotlib)",
         "RGB",
         {0.0,      0.001462, 0.000466, 0.013866, 0.062745, 0.042253, 0.028139, 0.141141, 0.12549,
          0.129285, 0.047293, 0.290788, 0.188235, 0.238273, 0.036621, 0.396353, 0.25098,  0.3415,
          0.062325, 0.429425, 0.313725, 0.441207, 0.099338, 0.431594, 0.376471, 0.54092,  0.134729,
          0.415123, 0.439216, 0.640135, 0.171438, 0.381065, 0.501961, 0.735683, 0.215906, 0.330245,
          0.564706, 0.822386, 0.275197, 0.266085, 0.627451, 0.894305, 0.353399, 0.193584, 0.690196,
          0.946965, 0.449191, 0.115272, 0.752941, 0.978422, 0.557937, 0.034931, 0.815686, 0.987874,
          0.675267, 0.065257, 0.878431, 0.974638, 0.797692, 0.206332, 0.941176, 0.947594, 0.917399,
          0.410665, 1.0,      0.988362, 0.998364, 0.644924},
         {0, 1, 0}},
        {"Grayscale", "RGB", {0, 0, 0, 0, 1, 1, 1, 1}, {1, 0, 0}},
    };
    return b;
}

}  // namespace

Result<std::vector<ColormapPreset>> parse_colormap_presets(const std::string& text,
                                                           const std::string& source) {
    json document;
    try {
        document = json::parse(text);
    } catch (const json::parse_error& e) {
        std::string what = e.what();
        const auto colon = what.find("parse error");
        if (colon != std::string::npos) what = what.substr(colon);
        return make_error(ErrorCode::kParse, "malformed JSON: " + what,
                          source + ":" + line_column(text, e.byte));
    } catch (const json::out_of_range& e) {
        // A number beyond a double (1e400): "[json.exception.out_of_range.406] number overflow
        // parsing '1e400'" -> the part after the id.
        std::string what = e.what();
        const auto pos = what.find("] ");
        if (pos != std::string::npos) what = what.substr(pos + 2);
        return make_error(ErrorCode::kParse, "malformed JSON: " + what + " (beyond a double)",
                          source);
    }
    std::vector<ColormapPreset> presets;
    if (document.is_object()) {
        auto one = parse_one(document, source, "$");
        if (!one) return one.error();
        presets.push_back(std::move(*one));
        return presets;
    }
    if (!document.is_array() || document.empty()) {
        return bad(source, "$", "expected a list of colour-map presets (ParaView's preset JSON)");
    }
    for (std::size_t i = 0; i < document.size(); ++i) {
        auto one = parse_one(document[i], source, "$[" + std::to_string(i) + "]");
        if (!one) return one.error();
        presets.push_back(std::move(*one));
    }
    return presets;
}

Result<ColormapPreset> read_colormap_preset(const std::filesystem::path& file,
                                            const std::string& name) {
    std::ifstream in(file, std::ios::binary);
    if (!in)
        return make_error(ErrorCode::kNotFound, "cannot open the colour-map file", file.string());
    std::stringstream buffer;
    buffer << in.rdbuf();
    auto presets = parse_colormap_presets(buffer.str(), file.string());
    if (!presets) return presets.error();
    if (name.empty()) return presets->front();
    for (const auto& p : *presets) {
        if (p.name == name) return p;
    }
    for (const auto& p : *presets) {
        if (lower(p.name) == lower(name)) return p;
    }
    std::string names;
    for (const auto& p : *presets) names += (names.empty() ? "'" : ", '") + p.name + "'";
    return make_error(ErrorCode::kNotFound,
                      "no colour map named '" + name + "' (the file has " + names + ")",
                      file.string());
}

std::string colormap_presets_json(const std::vector<ColormapPreset>& presets) {
    json out = json::array();
    for (const auto& p : presets) {
        json o;
        o["Name"] = p.name;
        o["ColorSpace"] = p.color_space;
        std::vector<double> rgb;
        for (const auto& c : p.rgb_points) rgb.insert(rgb.end(), {c.s, c.rgb.r, c.rgb.g, c.rgb.b});
        o["RGBPoints"] = numbers_json(rgb);
        if (!p.opacity_points.empty()) {
            std::vector<double> points;
            for (const auto& a : p.opacity_points)
                points.insert(points.end(), {a.s, a.a, 0.5, 0.0});
            o["Points"] = numbers_json(points);
        }
        if (p.nan_color) {
            o["NanColor"] = numbers_json({p.nan_color->r, p.nan_color->g, p.nan_color->b});
        }
        out.push_back(std::move(o));
    }
    return out.dump(2) + "\n";
}

Status write_colormap_presets(const std::vector<ColormapPreset>& presets,
                              const std::filesystem::path& file) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    if (!out) return make_error(ErrorCode::kIo, "cannot write the colour-map file", file.string());
    out << colormap_presets_json(presets);
    out.close();
    if (!out)
        return make_error(ErrorCode::kIo, "writing the colour-map file failed", file.string());
    return {};
}

ColormapPreset preset_from_transfer_function(const TransferFunction& tf, const std::string& name) {
    ColormapPreset p;
    p.name = name;
    p.color_space = "RGB";
    p.rgb_points = tf.color_points();
    p.opacity_points = tf.opacity_points();
    return p;
}

std::vector<ColorPoint> preset_colors(const ColormapPreset& preset, double lo, double hi) {
    const auto& in = preset.rgb_points;
    std::vector<ColorPoint> out;
    if (in.empty()) return out;
    const double x0 = in.front().s, x1 = in.back().s;
    auto map = [&](double x) { return x1 > x0 ? lo + (x - x0) / (x1 - x0) * (hi - lo) : lo; };
    if (in.size() == 1 || !(hi > lo)) {
        out.push_back({lo, in.front().rgb});
        return out;
    }
    const bool rgb = preset.color_space == "RGB";
    const int split = rgb ? 1 : std::max(1, static_cast<int>(std::ceil(256.0 / (in.size() - 1))));
    for (std::size_t i = 0; i + 1 < in.size(); ++i) {
        for (int k = 0; k < split; ++k) {
            const double t = static_cast<double>(k) / split;
            const double x = in[i].s + (in[i + 1].s - in[i].s) * t;
            out.push_back(
                {map(x), k == 0 ? in[i].rgb
                                : interpolate(preset.color_space, in[i].rgb, in[i + 1].rgb, t)});
        }
    }
    out.push_back({hi, in.back().rgb});
    return out;
}

std::vector<OpacityPoint> preset_opacity(const ColormapPreset& preset, double lo, double hi) {
    std::vector<OpacityPoint> out;
    const auto& in = preset.opacity_points;
    if (in.empty()) return out;
    const double x0 = in.front().s, x1 = in.back().s;
    for (const auto& p : in) {
        const double s = x1 > x0 ? lo + (p.s - x0) / (x1 - x0) * (hi - lo) : lo;
        out.push_back({s, std::min(p.a, 0.999)});
    }
    return out;
}

Result<TransferFunction> preset_transfer_function(const ColormapPreset& preset, double lo,
                                                  double hi, std::vector<OpacityPoint> opacity,
                                                  double unit_distance) {
    if (!std::isfinite(lo) || !std::isfinite(hi) || hi < lo) {
        return make_error(ErrorCode::kInvalidArgument,
                          "colour map '" + preset.name + "': the range is empty or not finite");
    }
    std::vector<OpacityPoint> own = preset_opacity(preset, lo, hi);
    return TransferFunction::create(preset_colors(preset, lo, hi),
                                    own.empty() ? std::move(opacity) : std::move(own),
                                    unit_distance);
}

std::vector<std::string> builtin_colormap_preset_names() {
    std::vector<std::string> names;
    for (const auto& b : builtins()) names.push_back(b.name);
    return names;
}

Result<ColormapPreset> builtin_colormap_preset(const std::string& name) {
    const std::string wanted = lower(name);
    for (const auto& b : builtins()) {
        const std::string n = lower(b.name);
        if (n == wanted || n == wanted + " (matplotlib)") {
            ColormapPreset p;
            p.name = b.name;
            p.color_space = b.space;
            for (std::size_t i = 0; i + 3 < b.rgb.size(); i += 4) {
                p.rgb_points.push_back({b.rgb[i], Vec3(b.rgb[i + 1], b.rgb[i + 2], b.rgb[i + 3])});
            }
            p.nan_color = Vec3(b.nan[0], b.nan[1], b.nan[2]);
            return p;
        }
    }
    std::string names;
    for (const auto& n : builtin_colormap_preset_names())
        names += (names.empty() ? "'" : ", '") + n + "'";
    return make_error(ErrorCode::kNotFound,
                      "unknown colour-map preset '" + name + "' (built in: " + names + ")");
}

}  // namespace tr
