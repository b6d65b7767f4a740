#pragma once
// A temporary folder for a test: created empty under the system temp dir, removed with all it
// holds when the object goes, also when an assertion returns early or an exception unwinds.
// Header-only (std only): any test target that has the repo root as include root can use it.

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

namespace tr::testing {

class TempDir {
  public:
    // A fresh folder named `prefix` + six random characters (mkdtemp: never one that exists).
    // Throws std::runtime_error when the temp dir takes no folder.
    explicit TempDir(const std::string& prefix = "tetrender_test_") {
        std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "XXXXXX"));
        if (!::mkdtemp(pattern.data())) {
            throw std::runtime_error("cannot create a temporary folder " + pattern);
        }
        path_ = pattern;
    }
    ~TempDir() {
        if (path_.empty()) return;  // moved from
        std::error_code ec;         // best effort: a destructor does not throw
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    // Moving hands the folder over: only the new owner removes it.
    TempDir(TempDir&& other) noexcept : path_(std::move(other.path_)) { other.path_.clear(); }
    TempDir& operator=(TempDir&&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::string string() const { return path_.string(); }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

  private:
    std::filesystem::path path_;
};

}  // namespace tr::testing
