#include <overlay/ticks.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

namespace tr {
namespace {

// The nice steps in increasing order starting below `raw`.
double nice_step_at_least(double raw) {
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0, 10.0}) {
        if (m * power >= raw * (1 - 1e-12)) return m * power;
    }
    return 10.0 * power;
}

double next_nice(double step) {
    const double power = std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    const double m = std::round(step / power);
    return m < 1.5 ? 2 * power : m < 3 ? 5 * power : 10 * power;
}

std::vector<double> multiples_inside(double lo, double hi, double step) {
    std::vector<double> out;
    const double first = std::ceil(lo / step - 1e-9);
    const double last = std::floor(hi / step + 1e-9);
    for (double k = first; k <= last && out.size() < 1000; k += 1) {
        double v = k * step;
        if (std::abs(v) < step * 1e-9) v = 0;
        out.push_back(std::clamp(v, lo, hi));
    }
    return out;
}

}  // namespace

Ticks linear_ticks(double lo, double hi, int max_count) {
    Ticks t;
    if (!std::isfinite(lo) || !std::isfinite(hi)) return t;
    if (lo > hi) std::swap(lo, hi);
    if (!(hi > lo)) {
        t.values = {lo};
        return t;
    }
    max_count = std::max(max_count, 2);
    double step = nice_step_at_least((hi - lo) / max_count);
    std::vector<double> values = multiples_inside(lo, hi, step);
    while (static_cast<int>(values.size()) > max_count) {
        step = next_nice(step);
        values = multiples_inside(lo, hi, step);
    }
    // Fewer than two ticks: a smaller step (the range holds at most one multiple).
    while (values.size() < 2 && step > (hi - lo) * 1e-12) {
        const double power = std::pow(10.0, std::floor(std::log10(step) + 1e-9));
        const double m = std::round(step / power);
        step = m > 7 ? 5 * power : m > 3 ? 2 * power : m > 1.5 ? power : 0.5 * power;
        values = multiples_inside(lo, hi, step);
    }
    t.values = std::move(values);
    t.step = step;
    return t;
}

Ticks log_ticks(double lo, double hi, int max_count) {
    Ticks t;
    if (!(lo > 0) || !std::isfinite(lo) || !std::isfinite(hi)) return t;
    if (lo > hi) std::swap(lo, hi);
    max_count = std::max(max_count, 2);
    const int e0 = static_cast<int>(std::ceil(std::log10(lo) - 1e-9));
    const int e1 = static_cast<int>(std::floor(std::log10(hi) + 1e-9));
    const int decades = e1 - e0 + 1;
    if (decades >= 2) {
        const int every = (decades + max_count - 1) / max_count;
        for (int e = e0; e <= e1; e += every) {
            t.values.push_back(std::clamp(std::pow(10.0, e), lo, hi));
        }
        return t;
    }
    for (int e = e0 - 1; e <= e1; ++e) {
        for (double m : {1.0, 2.0, 5.0}) {
            const double v = m * std::pow(10.0, e);
            if (v >= lo * (1 - 1e-12) && v <= hi * (1 + 1e-12)) {
                t.values.push_back(std::clamp(v, lo, hi));
            }
        }
    }
    if (t.values.size() < 2 || static_cast<int>(t.values.size()) > max_count) {
        return linear_ticks(lo, hi, max_count);
    }
    return t;
}

std::string tick_label(double value, double step) {
    char buffer[64];
    const double magnitude = std::max(std::abs(value), step);
    if (step > 0 && magnitude < 1e5 && step >= 1e-4) {
        const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
        std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    } else {
        std::snprintf(buffer, sizeof buffer, "%.3g", value);
    }
    // "-0.00" reads as 0 (the text after the sign; not erase(0, 1), which GCC 12 at -O2 with
    // the sanitizers flags as an overlapping copy, -Werror=restrict).
    const char* text = buffer;
    if (buffer[0] == '-' &&
        std::string_view(buffer).find_first_not_of("-0.") == std::string::npos) {
        ++text;
    }
    return std::string(text);
}

std::string range_label(double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.4g", value);
    return std::string_view(buffer) == "-0" ? std::string("0") : std::string(buffer);
}

}  // namespace tr
