#include <io/detail/common.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

namespace tr::io_detail {

namespace fs = std::filesystem;

void fail(ErrorCode code, std::string message, std::string where) {
    throw IoError(make_error(code, one_line(message), std::move(where)));
}

std::string one_line(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    bool space = false;
    for (char ch : text) {
        const bool blank = ch == '\n' || ch == '\r' || ch == '\t' || ch == ' ';
        if (blank) {
            space = !out.empty();
            continue;
        }
        if (space) out.push_back(' ');
        space = false;
        // Keep the message printable.
        out.push_back(std::isprint(static_cast<unsigned char>(ch)) ? ch : '?');
    }
    return out;
}

std::string lower_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    return ext;
}

std::uintmax_t check_readable_file(const fs::path& path) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (ec || !fs::exists(status)) {
        fail(ErrorCode::kNotFound, "no such file", path.string());
    }
    if (!fs::is_regular_file(status)) fail(ErrorCode::kIo, "not a regular file", path.string());
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) fail(ErrorCode::kIo, "cannot read the file size: " + ec.message(), path.string());
    if (size == 0) fail(ErrorCode::kParse, "empty file", path.string());
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(ErrorCode::kIo, "cannot open the file for reading", path.string());
    return size;
}

std::string read_head(const fs::path& path, std::size_t n) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(ErrorCode::kIo, "cannot open the file for reading", path.string());
    std::string buffer(n, '\0');
    in.read(buffer.data(), static_cast<std::streamsize>(n));
    buffer.resize(static_cast<std::size_t>(in.gcount()));
    return buffer;
}

std::string read_tail(const fs::path& path, std::size_t n) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) fail(ErrorCode::kIo, "cannot open the file for reading", path.string());
    const std::streamoff size = in.tellg();
    const std::streamoff start = size > static_cast<std::streamoff>(n)
                                     ? size - static_cast<std::streamoff>(n)
                                     : std::streamoff(0);
    in.seekg(start);
    std::string buffer(static_cast<std::size_t>(size - start), '\0');
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    buffer.resize(static_cast<std::size_t>(in.gcount()));
    return buffer;
}

std::string read_all(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(ErrorCode::kIo, "cannot open the file for reading", path.string());
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) fail(ErrorCode::kIo, "read error", path.string());
    return std::move(buffer).str();
}

void ProgressRange::report(double fraction) const {
    if (fn == nullptr || !*fn) return;
    const double f = std::clamp(fraction, 0.0, 1.0);
    report_progress(*fn, "reading", lo + f * (hi - lo));
}

ProgressRange ProgressRange::sub(double a, double b) const {
    return ProgressRange{fn, lo + a * (hi - lo), lo + b * (hi - lo)};
}

namespace {

void validate_fields(const std::vector<Field>& fields, std::size_t num_tuples, const char* kind,
                     const std::string& where) {
    for (const Field& f : fields) {
        const std::size_t n = std::visit([](const auto& v) { return v.size(); }, f.values);
        if (f.num_components < 1 || n != num_tuples * static_cast<std::size_t>(f.num_components)) {
            fail(ErrorCode::kParse,
                 std::string(kind) + " array '" + f.name + "' has " + std::to_string(n) +
                     " values, expected " + std::to_string(num_tuples) + " tuples of " +
                     std::to_string(f.num_components),
                 where);
        }
    }
}

}  // namespace

void validate_mesh(const UnstructuredMesh& mesh, const std::string& where) {
    if (mesh.points.empty() && mesh.types.empty())
        fail(ErrorCode::kInvalidMesh, "empty mesh", where);
    if (mesh.points.empty()) {
        fail(ErrorCode::kInvalidMesh,
             "mesh has " + std::to_string(mesh.types.size()) + " cells but no points", where);
    }
    for (std::size_t i = 0; i < mesh.points.size(); ++i) {
        const Vec3& p = mesh.points[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            std::ostringstream msg;
            msg << "point " << i << " has a non-finite coordinate (" << p.x << ", " << p.y << ", "
                << p.z << ")";
            fail(ErrorCode::kInvalidMesh, msg.str(), where);
        }
    }
    const std::size_t num_cells = mesh.types.size();
    if (num_cells > 0) {
        if (mesh.offsets.size() != num_cells + 1) {
            fail(ErrorCode::kParse,
                 "offsets has " + std::to_string(mesh.offsets.size()) + " entries for " +
                     std::to_string(num_cells) + " cells",
                 where);
        }
        if (mesh.offsets.front() != 0) fail(ErrorCode::kParse, "offsets do not start at 0", where);
        for (std::size_t c = 0; c < num_cells; ++c) {
            if (mesh.offsets[c + 1] < mesh.offsets[c]) {
                fail(ErrorCode::kParse,
                     "offsets are not monotone at cell " + std::to_string(c) + " (" +
                         std::to_string(mesh.offsets[c]) + " then " +
                         std::to_string(mesh.offsets[c + 1]) + ")",
                     where);
            }
        }
        if (mesh.offsets.back() != static_cast<std::int64_t>(mesh.connectivity.size())) {
            fail(ErrorCode::kParse,
                 "offsets end at " + std::to_string(mesh.offsets.back()) +
                     " but connectivity has " + std::to_string(mesh.connectivity.size()) +
                     " entries",
                 where);
        }
        const auto num_points = static_cast<std::int64_t>(mesh.points.size());
        for (std::size_t c = 0; c < num_cells; ++c) {
            for (std::int64_t k = mesh.offsets[c]; k < mesh.offsets[c + 1]; ++k) {
                const std::int64_t id = mesh.connectivity[static_cast<std::size_t>(k)];
                if (id < 0 || id >= num_points) {
                    fail(ErrorCode::kInvalidMesh,
                         "cell " + std::to_string(c) + " uses point " + std::to_string(id) +
                             ", out of range [0, " + std::to_string(num_points) + ")",
                         where);
                }
            }
        }
    } else if (!mesh.offsets.empty() && !(mesh.offsets.size() == 1 && mesh.offsets[0] == 0)) {
        fail(ErrorCode::kParse, "offsets given for a mesh without cells", where);
    }
    validate_fields(mesh.point_fields, mesh.points.size(), "point", where);
    validate_fields(mesh.cell_fields, num_cells, "cell", where);
    for (const SurfaceMesh& s : mesh.surfaces) validate_surface(s, where);
}

namespace {

// Appends b's values to a's; the result is float32 only when both are.
Field append_field(const Field& a, const Field& b) {
    Field out;
    out.name = a.name;
    out.num_components = a.num_components;
    if (!a.is_double() && !b.is_double()) {
        std::vector<float> v = std::get<0>(a.values);
        const auto& w = std::get<0>(b.values);
        v.insert(v.end(), w.begin(), w.end());
        out.values = std::move(v);
    } else {
        std::vector<double> v;
        const auto push = [&v](const Field& f) {
            std::visit([&v](const auto& x) { v.insert(v.end(), x.begin(), x.end()); }, f.values);
        };
        push(a);
        push(b);
        out.values = std::move(v);
    }
    return out;
}

std::vector<Field> append_fields(const std::vector<Field>& a, const std::vector<Field>& b) {
    std::vector<Field> out;
    for (const Field& f : a) {
        const Field* g = find_field(b, f.name);
        if (g != nullptr && g->num_components == f.num_components) {
            out.push_back(append_field(f, *g));
        }
    }
    return out;
}

}  // namespace

void append_mesh(UnstructuredMesh& dst, UnstructuredMesh src) {
    const bool dst_empty = dst.points.empty() && dst.types.empty();
    if (dst_empty) {
        std::vector<SurfaceMesh> surfaces = std::move(dst.surfaces);
        std::string format = std::move(dst.format);
        std::vector<double> times = std::move(dst.time_values);
        const int step = dst.time_step;
        dst = std::move(src);
        dst.surfaces.insert(dst.surfaces.begin(), std::make_move_iterator(surfaces.begin()),
                            std::make_move_iterator(surfaces.end()));
        if (!format.empty()) dst.format = std::move(format);
        if (!times.empty()) {
            dst.time_values = std::move(times);
            dst.time_step = step;
        }
        return;
    }
    const auto base = static_cast<std::int64_t>(dst.points.size());
    const bool dst_had_cells = !dst.types.empty();
    dst.points.insert(dst.points.end(), src.points.begin(), src.points.end());
    if (!src.types.empty()) {
        if (!dst_had_cells) dst.offsets = {0};
        const std::int64_t conn_base = static_cast<std::int64_t>(dst.connectivity.size());
        for (std::size_t c = 1; c < src.offsets.size(); ++c) {
            dst.offsets.push_back(conn_base + src.offsets[c]);
        }
        for (std::int64_t id : src.connectivity) dst.connectivity.push_back(base + id);
        dst.types.insert(dst.types.end(), src.types.begin(), src.types.end());
    }
    dst.point_fields = append_fields(dst.point_fields, src.point_fields);
    // Cell fields line up only when both parts have cells (or neither).
    if (dst_had_cells && !src.types.empty()) {
        dst.cell_fields = append_fields(dst.cell_fields, src.cell_fields);
    } else if (!src.types.empty()) {
        dst.cell_fields = std::move(src.cell_fields);
    }
    for (SurfaceMesh& s : src.surfaces) dst.surfaces.push_back(std::move(s));
}

void fan_triangulate(const std::vector<std::int64_t>& corners,
                     std::vector<std::array<std::uint32_t, 3>>& out, std::size_t num_points,
                     const std::string& where) {
    for (std::int64_t id : corners) {
        if (id < 0 || static_cast<std::uint64_t>(id) >= num_points) {
            fail(ErrorCode::kInvalidMesh,
                 "polygon uses point " + std::to_string(id) + ", out of range [0, " +
                     std::to_string(num_points) + ")",
                 where);
        }
    }
    for (std::size_t k = 2; k < corners.size(); ++k) {
        out.push_back({static_cast<std::uint32_t>(corners[0]),
                       static_cast<std::uint32_t>(corners[k - 1]),
                       static_cast<std::uint32_t>(corners[k])});
    }
}

void validate_surface(const SurfaceMesh& surface, const std::string& where) {
    if (surface.points.empty() && surface.triangles.empty()) {
        fail(ErrorCode::kInvalidMesh, "empty surface", where);
    }
    for (std::size_t i = 0; i < surface.points.size(); ++i) {
        const Vec3& p = surface.points[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            fail(ErrorCode::kInvalidMesh,
                 "surface point " + std::to_string(i) + " has a non-finite coordinate", where);
        }
    }
    for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
        for (std::uint32_t id : surface.triangles[t]) {
            if (id >= surface.points.size()) {
                fail(ErrorCode::kInvalidMesh,
                     "triangle " + std::to_string(t) + " uses point " + std::to_string(id) +
                         ", out of range [0, " + std::to_string(surface.points.size()) + ")",
                     where);
            }
        }
    }
}

}  // namespace tr::io_detail
