#pragma once
// Checks of numeric command-line options whose message is one short line saying what is
// wrong. CLI11's own (CLI::PositiveNumber, CLI::NonNegativeNumber, CLI::Range) print their bounds
// with std::to_string: "--dt 0" said "Value 0 not in range 0.000000 to 17976931348623157081...",
// DBL_MAX's 309 digits (issue 13). With these, CLI11 prints "tetrender: --dt: must be a finite
// number > 0, not '0'".

#include <apps/cli_common.h>

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <type_traits>

namespace tr::apps {

namespace cli_checks_detail {

inline std::string number_text(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

}  // namespace cli_checks_detail

// A finite number (not NaN, not infinite).
inline const CLI::Validator kFinite(
    [](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v)) {
            return "must be a finite number, not '" + text + "'";
        }
        return {};
    },
    "FINITE");

// A finite number > 0.
inline const CLI::Validator kPositive(
    [](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || !(v > 0) || !std::isfinite(v)) {
            return "must be a finite number > 0, not '" + text + "'";
        }
        return {};
    },
    "POSITIVE");

// A finite number >= 0.
inline const CLI::Validator kNonNegative(
    [](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || !(v >= 0) || !std::isfinite(v)) {
            return "must be a finite number >= 0, not '" + text + "'";
        }
        return {};
    },
    "NONNEGATIVE");

// An integer >= 0 that fits an int (time steps).
inline const CLI::Validator kNonNegativeInteger(
    [](std::string& text) -> std::string {
        int v = 0;
        if (!CLI::detail::lexical_cast(text, v) || v < 0) {
            return "must be an integer >= 0, not '" + text + "'";
        }
        return {};
    },
    "NONNEGATIVE");

// A number from `lo` to `hi` (both included): "must be a number from 0.1 to 1000, not '0'";
// for an integer type T, "must be an integer from 0 to 100000, not '1.5'".
template <class T>
CLI::Validator in_range(T lo, T hi) {
    using cli_checks_detail::number_text;
    const bool integer = std::is_integral_v<T>;
    const auto text_of = [](T v) {
        if constexpr (std::is_integral_v<T>) {
            return std::to_string(v);
        } else {
            return number_text(static_cast<double>(v));
        }
    };
    const std::string bounds = "from " + text_of(lo) + " to " + text_of(hi);
    return CLI::Validator(
        [lo, hi, integer, bounds](std::string& text) -> std::string {
            bool ok = false;
            if constexpr (std::is_integral_v<T>) {
                T v{};
                ok = CLI::detail::lexical_cast(text, v) && v >= lo && v <= hi;
            } else {
                double v = 0;
                ok = CLI::detail::lexical_cast(text, v) && v >= static_cast<double>(lo) &&
                     v <= static_cast<double>(hi);
            }
            if (ok) return {};
            return std::string("must be ") + (integer ? "an integer " : "a number ") + bounds +
                   ", not '" + text + "'";
        },
        (integer ? "INT in [" : "FLOAT in [") + text_of(lo) + " - " + text_of(hi) + "]");
}

// Parses the command line. --help and --version print CLI11's text; a bad command line prints
// one line "<program>: <what is wrong>" (CLI11's own exit() adds "Run with --help for more
// information."). Returns the exit code to end with, or nothing when the program goes on.
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv,
                                             const char* program) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return kExitUsage;
    }
    return std::nullopt;
}

}  // namespace tr::apps
