#pragma once
// Result<T>: a value or an Error (code, message, where). The return type of every fallible API.

#include <string>
#include <utility>
#include <variant>

namespace tr {

enum class ErrorCode {
    kInvalidArgument,  // a caller passed something that makes no sense (sizes, options)
    kNotFound,         // a file, an array, a key that does not exist
    kParse,            // a file or document that is malformed or truncated
    kUnsupported,      // valid input this build cannot handle (a cell type, a disabled option)
    kInvalidMesh,      // geometry or topology that cannot be used (NaN, bad indices, non-manifold)
    kIo,               // the operating system refused (permissions, disk full)
    kInternal,         // a failure inside a third-party library that we caught
};

// Human-readable name of an error code ("parse error", ...).
const char* error_code_name(ErrorCode code);

struct Error {
    ErrorCode code = ErrorCode::kInternal;
    std::string message;  // what is wrong, one line
    std::string where;    // file path, "path:line", JSON path or cell index; may be empty
    std::string about;    // the caller's input it is about, by the library's name for it ("iso",
                          // "slices[1]"), so a caller maps it to its own words; may be empty

    // "where: error: message" (or "error: message" when where is empty), one line.
    std::string to_string() const;
};

template <class T>
class [[nodiscard]] Result {
  public:
    Result(T value) : state_(std::move(value)) {}      // NOLINT: implicit by design
    Result(Error error) : state_(std::move(error)) {}  // NOLINT: implicit by design

    bool ok() const { return state_.index() == 0; }
    explicit operator bool() const { return ok(); }

    // Precondition: ok().
    T& value() & { return std::get<0>(state_); }
    const T& value() const& { return std::get<0>(state_); }
    T&& value() && { return std::get<0>(std::move(state_)); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }

    // Precondition: !ok().
    const Error& error() const { return std::get<1>(state_); }

  private:
    std::variant<T, Error> state_;
};

// Result<void>: success or an Error.
template <>
class [[nodiscard]] Result<void> {
  public:
    Result() = default;
    Result(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT: implicit by design

    bool ok() const { return ok_; }
    explicit operator bool() const { return ok_; }
    const Error& error() const { return error_; }

  private:
    Error error_;
    bool ok_ = true;
};

using Status = Result<void>;

inline Error make_error(ErrorCode code, std::string message, std::string where = {}) {
    Error error;
    error.code = code;
    error.message = std::move(message);
    error.where = std::move(where);
    return error;
}

// `error` with Error::about set.
inline Error with_about(Error error, std::string about) {
    error.about = std::move(about);
    return error;
}

}  // namespace tr

// Propagates an error: `TR_TRY(auto mesh, read_mesh(path));` or `TR_TRY_STATUS(write(...));`
#define TR_CONCAT_INNER(a, b) a##b
#define TR_CONCAT(a, b) TR_CONCAT_INNER(a, b)
#define TR_TRY_IMPL(tmp, decl, expr)   \
    auto tmp = (expr);                 \
    if (!tmp.ok()) return tmp.error(); \
    decl = std::move(tmp).value()
#define TR_TRY(decl, expr) TR_TRY_IMPL(TR_CONCAT(tr_try_, __LINE__), decl, expr)
#define TR_TRY_STATUS(expr)                              \
    do {                                                 \
        auto tr_status_ = (expr);                        \
        if (!tr_status_.ok()) return tr_status_.error(); \
    } while (false)
