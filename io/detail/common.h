#pragma once
// Private helpers shared by io/'s readers and writers (std only, no VTK): the internal error
// exception, file sniffing, mesh validation and concatenation, progress ranges.

#include <core/progress.h>
#include <core/result.h>
#include <mesh/unstructured_mesh.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace tr::io_detail {

// Thrown inside io/ by parsers and converted to an Error at the public function's catch site.
class IoError : public std::runtime_error {
  public:
    explicit IoError(Error error) : std::runtime_error(error.message), error_(std::move(error)) {}
    const Error& error() const { return error_; }

  private:
    Error error_;
};

[[noreturn]] void fail(ErrorCode code, std::string message, std::string where);

// Turns a multi-line message (VTK's) into one line: newlines become spaces, runs of spaces
// collapse, leading and trailing blanks go.
std::string one_line(const std::string& text);

// The extension with its dot, lower-case (".vtu"); "" when there is none.
std::string lower_extension(const std::filesystem::path& path);

// Throws kNotFound when the path does not exist, kIo when it is not a regular file or cannot
// be read, kParse when it is empty. Returns the size in bytes.
std::uintmax_t check_readable_file(const std::filesystem::path& path);

// The first (or last) up to `n` bytes of a file.
std::string read_head(const std::filesystem::path& path, std::size_t n);
std::string read_tail(const std::filesystem::path& path, std::size_t n);
// The whole file (text formats).
std::string read_all(const std::filesystem::path& path);

// A sub-range of the caller's progress: fraction f of this step is reported as
// lo + f * (hi - lo) under stage "reading".
struct ProgressRange {
    const ProgressFn* fn = nullptr;
    double lo = 0.0;
    double hi = 1.0;
    void report(double fraction) const;
    ProgressRange sub(double a, double b) const;  // [a, b] of this range
};

// Checks what io/ promises about a mesh it returns: offsets monotone and consistent,
// connectivity in range, finite coordinates, fields of the right size, not empty.
void validate_mesh(const UnstructuredMesh& mesh, const std::string& where);

// Appends `src` to `dst` (points, cells, surfaces). Fields are kept when both have a field of
// that name and component count (so a field missing from one part is dropped, as
// vtkAppendFilter does); float32 is kept only when both are float32. `dst` may be empty
// (then it becomes src).
void append_mesh(UnstructuredMesh& dst, UnstructuredMesh src);

// Fan-triangulates a polygon (corner ids) into `out`.
void fan_triangulate(const std::vector<std::int64_t>& corners,
                     std::vector<std::array<std::uint32_t, 3>>& out, std::size_t num_points,
                     const std::string& where);

// Checks a surface: indices in range, finite points, at least one triangle.
void validate_surface(const SurfaceMesh& surface, const std::string& where);

}  // namespace tr::io_detail
