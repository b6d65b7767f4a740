#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/read_surface.h>

#include <new>

namespace tr {

using namespace io_detail;

std::vector<std::string> supported_surface_extensions() {
    return {".stl", ".ply", ".obj", ".vtp", ".vtk", ".off", ".poly"};
}

Result<SurfaceMesh> read_surface(const std::filesystem::path& path) {
    const std::string where = path.string();
    try {
        check_readable_file(path);
        const std::string ext = lower_extension(path);
        SurfaceMesh surface;
        if (ext == ".off") {
            surface = read_off(path);
        } else if (ext == ".poly") {
            surface = read_poly(path);
        } else if (ext == ".ply") {
            surface = read_ply(path);
        } else if (ext == ".obj") {
            surface = read_obj(path);
        } else if (ext == ".stl") {
            surface = read_stl(path);
        } else if (ext == ".vtp" || ext == ".vtk") {
            surface = read_vtk_surface(path, ext);
        } else {
            std::string list;
            for (const std::string& e : supported_surface_extensions())
                list += (list.empty() ? "" : " ") + e;
            fail(ErrorCode::kUnsupported,
                 "unknown surface file extension '" + ext + "'; supported: " + list, where);
        }
        surface.name = path.stem().string();
        validate_surface(surface, where);
        if (surface.triangles.empty())
            fail(ErrorCode::kInvalidMesh, "the surface has no triangles", where);
        return surface;
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
