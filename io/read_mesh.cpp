#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/read_mesh.h>

#include <algorithm>
#include <map>
#include <new>

namespace tr {

namespace {

using namespace io_detail;

enum class Format { kVtkXml, kVtkLegacy, kExodus, kPvd, kTetgen, kCsv, kPlot3d, kMfem, kUnknown };

bool ends_with(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool is_exodus_extension(const std::string& ext) {
    return ext == ".exo" || ext == ".e" || ext == ".ex2" || ext == ".g" || ext == ".exii";
}

bool all_digits(const std::string& s) {
    return !s.empty() &&
           std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

// The files of a decomposed Exodus set when `path` names one of them: BASE.N.r, BASE with an
// Exodus extension, r in [0, N) written with as many digits as the member named (SEACAS's
// naming: mesh.e.4.0 .. mesh.e.4.3, mesh.e.16.00 .. mesh.e.16.15). Empty for any other name.
std::vector<fs::path> exodus_set(const fs::path& path) {
    const std::string name = path.filename().string();
    const std::size_t last = name.rfind('.');
    if (last == std::string::npos || last == 0) return {};
    const std::size_t middle = name.rfind('.', last - 1);
    if (middle == std::string::npos || middle == 0) return {};
    const std::string count = name.substr(middle + 1, last - middle - 1);
    const std::string rank = name.substr(last + 1);
    const std::string base = name.substr(0, middle);
    std::string ext = fs::path(base).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (!all_digits(count) || !all_digits(rank) || !is_exodus_extension(ext)) return {};
    if (count.size() > 6 || rank.size() > 6) return {};
    const int n = std::stoi(count);
    if (n < 1 || std::stoi(rank) >= n) return {};
    std::vector<fs::path> files;
    for (int r = 0; r < n; ++r) {
        std::string digits = std::to_string(r);
        if (digits.size() < rank.size()) digits.insert(0, rank.size() - digits.size(), '0');
        files.push_back(path.parent_path() / (base + "." + count + "." + digits));
    }
    return files;
}

// Every file of an Exodus set, appended (their shared points merged later, by coordinates).
UnstructuredMesh read_exodus_set(const fs::path& path, const std::vector<fs::path>& files,
                                 int time_step, const ProgressRange& progress) {
    UnstructuredMesh mesh;
    for (std::size_t k = 0; k < files.size(); ++k) {
        std::error_code ec;
        if (!fs::exists(files[k], ec)) {
            fail(ErrorCode::kNotFound,
                 "file '" + files[k].filename().string() + "' of the Exodus set is missing",
                 path.string());
        }
        const double lo = static_cast<double>(k) / static_cast<double>(files.size());
        const double hi = static_cast<double>(k + 1) / static_cast<double>(files.size());
        check_readable_file(files[k]);
        append_mesh(mesh, read_exodus(files[k], time_step, progress.sub(lo, hi)));
    }
    mesh.format = "Exodus II file set of " + std::to_string(files.size()) + " files";
    return mesh;
}

Format format_of(const fs::path& path, const std::string& ext) {
    std::string name = path.filename().string();
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (ends_with(name, "xyz.bin") || ext == ".xyz") return Format::kPlot3d;
    if (ext == ".vtu" || ext == ".pvtu" || ext == ".vts" || ext == ".vtr" || ext == ".vti" ||
        ext == ".vtp") {
        return Format::kVtkXml;
    }
    if (ext == ".vtk") return Format::kVtkLegacy;
    if (is_exodus_extension(ext) || !exodus_set(path).empty()) return Format::kExodus;
    if (ext == ".pvd") return Format::kPvd;
    if (ext == ".node" || ext == ".ele") return Format::kTetgen;
    if (ext == ".csv") return Format::kCsv;
    if (ext == ".mesh") return Format::kMfem;
    return Format::kUnknown;
}

std::string extension_list() {
    std::string list;
    for (const std::string& e : supported_mesh_extensions()) list += (list.empty() ? "" : " ") + e;
    return list;
}

void check_single_step(int time_step, const fs::path& path) {
    if (time_step != 0) {
        fail(ErrorCode::kInvalidArgument,
             "time step " + std::to_string(time_step) +
                 " out of range: the file is not a time series (it has one step, 0)",
             path.string());
    }
}

UnstructuredMesh read_any(const fs::path& path, int time_step, const ProgressRange& progress,
                          bool allow_pvd, bool whole_exodus_set = true);

UnstructuredMesh read_pvd_series(const fs::path& path, int time_step,
                                 const ProgressRange& progress) {
    const std::vector<PvdEntry> entries = parse_pvd(path);
    std::vector<double> times;
    for (const PvdEntry& e : entries) times.push_back(e.time);
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    if (time_step < 0 || static_cast<std::size_t>(time_step) >= times.size()) {
        fail(ErrorCode::kInvalidArgument,
             "time step " + std::to_string(time_step) + " out of range: the collection has " +
                 std::to_string(times.size()) + " time steps",
             path.string());
    }
    const double t = times[static_cast<std::size_t>(time_step)];
    std::vector<PvdEntry> parts;
    for (const PvdEntry& e : entries) {
        if (e.time == t) parts.push_back(e);
    }
    std::stable_sort(parts.begin(), parts.end(),
                     [](const PvdEntry& a, const PvdEntry& b) { return a.part < b.part; });
    UnstructuredMesh mesh;
    std::string inner_format;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        std::error_code ec;
        if (!fs::exists(parts[k].file, ec)) {
            fail(ErrorCode::kNotFound,
                 "data set file '" + parts[k].file.string() + "' listed in the .pvd does not exist",
                 path.string());
        }
        const double lo = static_cast<double>(k) / static_cast<double>(parts.size());
        const double hi = static_cast<double>(k + 1) / static_cast<double>(parts.size());
        UnstructuredMesh part = read_any(parts[k].file, 0, progress.sub(lo, hi), false);
        inner_format = part.format;
        append_mesh(mesh, std::move(part));
    }
    mesh.format = "ParaView collection (.pvd) of " + inner_format;
    mesh.time_values = times;
    mesh.time_step = time_step;
    return mesh;
}

UnstructuredMesh read_any(const fs::path& path, int time_step, const ProgressRange& progress,
                          bool allow_pvd, bool whole_exodus_set) {
    check_readable_file(path);
    const std::string ext = lower_extension(path);
    switch (format_of(path, ext)) {
        case Format::kVtkXml:
            check_single_step(time_step, path);
            return read_vtk_xml(path, ext, progress);
        case Format::kVtkLegacy:
            check_single_step(time_step, path);
            return read_vtk_legacy(path, progress);
        case Format::kExodus:
            if (const auto set = exodus_set(path); whole_exodus_set && !set.empty()) {
                return read_exodus_set(path, set, time_step, progress);
            }
            return read_exodus(path, time_step, progress);
        case Format::kPvd:
            if (!allow_pvd) fail(ErrorCode::kUnsupported, "a .pvd inside a .pvd", path.string());
            return read_pvd_series(path, time_step, progress);
        case Format::kTetgen:
            check_single_step(time_step, path);
            return read_tetgen(path, progress);
        case Format::kCsv:
            check_single_step(time_step, path);
            return read_csv_points(path, progress);
        case Format::kPlot3d:
            check_single_step(time_step, path);
            return read_plot3d(path, progress);
        case Format::kMfem:
            check_single_step(time_step, path);
            return read_mfem(path, progress);
        case Format::kUnknown:
            break;
    }
    fail(ErrorCode::kUnsupported,
         "unknown mesh file extension '" + ext + "'; supported: " + extension_list(),
         path.string());
}

}  // namespace

std::vector<std::string> supported_mesh_extensions() {
    return {".vtu", ".pvtu", ".vts", ".vtr",  ".vti", ".vtp", ".vtk", ".exo",    ".e",   ".ex2",
            ".g",   ".exii", ".pvd", ".node", ".ele", ".csv", ".xyz", "xyz.bin", ".mesh"};
}

Result<std::vector<std::filesystem::path>> mesh_pieces(const std::filesystem::path& path) {
    try {
        check_readable_file(path);
        if (lower_extension(path) == ".pvtu") return pvtu_pieces(path, false);
        if (auto set = exodus_set(path); !set.empty()) return set;
        return std::vector<std::filesystem::path>{path};
    } catch (const IoError& e) {
        return e.error();
    } catch (const std::exception& e) {
        return make_error(ErrorCode::kInternal,
                          one_line(std::string("unexpected failure: ") + e.what()), path.string());
    }
}

Result<UnstructuredMesh> read_mesh(const std::filesystem::path& path, const ReadOptions& options) {
    const std::string where = path.string();
    try {
        const ProgressRange progress{&options.progress, 0.0, 1.0};
        progress.report(0.0);
        UnstructuredMesh mesh =
            read_any(path, options.time_step, progress, true, options.whole_exodus_set);
        validate_mesh(mesh, where);
        progress.report(1.0);
        return mesh;
    } catch (const IoError& e) {
        return e.error();
    } catch (const std::bad_alloc&) {
        return make_error(ErrorCode::kIo, "out of memory while reading", where);
    } catch (const std::exception& e) {
        return make_error(ErrorCode::kInternal,
                          one_line(std::string("unexpected failure: ") + e.what()), where);
    } catch (...) {
        return make_error(ErrorCode::kInternal, "unexpected failure (unknown exception)", where);
    }
}

}  // namespace tr
