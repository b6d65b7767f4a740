#pragma once
// Tick values for a colour bar: "nice" numbers (1, 2 or 5 times a power of ten) covering a
// range, on a linear or a logarithmic scale, and their labels.

#include <string>
#include <vector>

namespace tr {

struct Ticks {
    std::vector<double> values;  // increasing, each within [lo, hi]
    double step = 0;             // linear: the spacing (1, 2 or 5 x 10^k); log: 0
};

// Linear ticks: multiples of a nice step (1, 2 or 5 x 10^k) inside [lo, hi], the step the
// smallest nice one that gives at most `max_count` ticks (at least 2 for a range wider than
// zero), so the first tick lies less than a step above lo and the last less than a step below
// hi. lo == hi gives that one value; non-finite input gives none.
Ticks linear_ticks(double lo, double hi, int max_count = 6);

// Log ticks for 0 < lo < hi: the powers of ten inside [lo, hi]; when fewer than 2 fall inside,
// 1, 2 and 5 times each power of ten (and, if still fewer than 2, the linear ticks). At most
// `max_count`: every k-th decade when there are more. Empty for lo <= 0.
Ticks log_ticks(double lo, double hi, int max_count = 6);

// A short label: the value rounded to the step's decimals ("0.25", "1500", "-2"), or %.3g for
// large or tiny magnitudes and log scales ("1e+06", "2e-05"); "-0" printed as "0".
std::string tick_label(double value, double step);

// A range end: 4 significant digits (%.4g).
std::string range_label(double value);

}  // namespace tr
