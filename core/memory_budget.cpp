#include <core/memory_budget.h>

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <unistd.h>

namespace tr {
namespace {

std::atomic<std::uint64_t> g_budget{0};

}  // namespace

std::uint64_t physical_memory() {
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long page_size = ::sysconf(_SC_PAGESIZE);
    if (pages <= 0 || page_size <= 0) return 0;
    return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
}

std::uint64_t memory_budget() {
    const std::uint64_t set = g_budget.load();
    if (set > 0) return set;
    const std::uint64_t physical = physical_memory();
    return physical > 0 ? physical / 10 * 8 : (std::uint64_t{8} << 30);
}

void set_memory_budget(std::uint64_t bytes) { g_budget.store(bytes); }

Result<std::uint64_t> parse_byte_size(std::string_view text) {
    const auto bad = [&] {
        return make_error(ErrorCode::kInvalidArgument,
                          "a memory size is a number with an optional k, M, G or T (powers of "
                          "1024), like 8G or 512M, not '" +
                              std::string(text) + "'");
    };
    std::string number(text);
    double scale = 1.0;
    // Optional "B" or "iB" after the unit.
    if (!number.empty() && (number.back() == 'B' || number.back() == 'b')) number.pop_back();
    if (!number.empty() && number.back() == 'i') number.pop_back();
    if (!number.empty()) {
        switch (std::toupper(static_cast<unsigned char>(number.back()))) {
            case 'K':
                scale = 1024.0;
                break;
            case 'M':
                scale = 1024.0 * 1024.0;
                break;
            case 'G':
                scale = 1024.0 * 1024.0 * 1024.0;
                break;
            case 'T':
                scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
                break;
            default:
                break;
        }
        if (scale > 1.0) number.pop_back();
    }
    if (number.empty() ||
        !(std::isdigit(static_cast<unsigned char>(number.front())) || number.front() == '.')) {
        return bad();
    }
    double value = 0;
    std::size_t used = 0;
    try {
        value = std::stod(number, &used);
    } catch (...) {
        return bad();
    }
    const double bytes = value * scale;
    if (used != number.size() || !(bytes >= 1.0) || bytes > std::ldexp(1.0, 60)) return bad();
    return static_cast<std::uint64_t>(bytes);
}

std::string byte_size_text(double bytes) {
    const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
    int u = 0;
    while (bytes >= 1024.0 && u < 6) bytes /= 1024.0, ++u;
    char text[32];
    std::snprintf(text, sizeof text, bytes < 10.0 && u > 0 ? "%.1f %s" : "%.0f %s", bytes,
                  units[u]);
    return text;
}

Status check_memory(double bytes, const std::string& what) {
    const double budget = static_cast<double>(memory_budget());
    if (!(bytes > budget)) return {};
    return make_error(ErrorCode::kInvalidArgument, what + " would take about " +
                                                       byte_size_text(bytes) +
                                                       ", more than the memory budget of " +
                                                       byte_size_text(budget) + " (--max-memory)");
}

}  // namespace tr
