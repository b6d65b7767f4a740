#pragma once
// TR_CHECK / TR_CHECK_EQ: assertions for bugs (never for bad input), active in every build.

#include <sstream>
#include <string>

namespace tr::detail {
[[noreturn]] void check_failed(const char* file, int line, const std::string& what);
}  // namespace tr::detail

#define TR_CHECK(cond)                                                                      \
    do {                                                                                    \
        if (!(cond)) ::tr::detail::check_failed(__FILE__, __LINE__, "TR_CHECK(" #cond ")"); \
    } while (false)

#define TR_CHECK_EQ(a, b)                                                              \
    do {                                                                               \
        const auto& tr_a_ = (a);                                                       \
        const auto& tr_b_ = (b);                                                       \
        if (!(tr_a_ == tr_b_)) {                                                       \
            std::ostringstream tr_os_;                                                 \
            tr_os_ << "TR_CHECK_EQ(" #a ", " #b ") with " << tr_a_ << " != " << tr_b_; \
            ::tr::detail::check_failed(__FILE__, __LINE__, tr_os_.str());              \
        }                                                                              \
    } while (false)
