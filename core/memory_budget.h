#pragma once
// How much memory tetrender may take, and the check made before a large allocation, so that
// an absurd size is refused up front with what it would take, never by std::bad_alloc (or by
// the kernel's OOM killer) minutes into the work.
//
// The budget is process-wide, like the thread count (core/parallel.h): set_memory_budget (the
// programs' --max-memory), else 80% of the machine's physical memory.

#include <core/result.h>

#include <cstdint>
#include <string>
#include <string_view>

namespace tr {

// The machine's physical memory in bytes (0 when the system does not say).
std::uint64_t physical_memory();

// The budget in bytes: the one set, else 80% of physical_memory() (8 GiB when that is unknown).
std::uint64_t memory_budget();

// Sets the budget; 0 restores the default.
void set_memory_budget(std::uint64_t bytes);

// "8G", "512M", "1.5GB", "64k", "100000000" (bytes; k, M, G, T are powers of 1024, an optional
// trailing B or iB). Error kInvalidArgument, naming the text, for anything else, zero or over
// 2^60.
Result<std::uint64_t> parse_byte_size(std::string_view text);

// "4.9 GB", "512 MB", "20 kB", "100 B" (powers of 1024, 2 significant digits at least).
std::string byte_size_text(double bytes);

// OK when `bytes` fits the budget; else kInvalidArgument: "<what> would take about 4.9 GB,
// more than the memory budget of 2 GB (--max-memory)".
Status check_memory(double bytes, const std::string& what);

}  // namespace tr
