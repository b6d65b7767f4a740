// The memory budget: sizes as users write them, the message of a refusal, the default from the
// machine's memory.
#include <core/memory_budget.h>

#include <gtest/gtest.h>

namespace tr {
namespace {

TEST(MemoryBudget, SizesAsUsersWriteThem) {
    EXPECT_EQ(parse_byte_size("8G").value(), std::uint64_t{8} << 30);
    EXPECT_EQ(parse_byte_size("512M").value(), std::uint64_t{512} << 20);
    EXPECT_EQ(parse_byte_size("1.5GB").value(), std::uint64_t{3} << 29);
    EXPECT_EQ(parse_byte_size("64k").value(), std::uint64_t{64} << 10);
    EXPECT_EQ(parse_byte_size("2GiB").value(), std::uint64_t{2} << 30);
    EXPECT_EQ(parse_byte_size("100000000").value(), std::uint64_t{100000000});
    for (const char* bad : {"", "G", "12Q", "-1G", "0", "1e30", "8 G", "nan", "inf", "8GG"}) {
        const auto parsed = parse_byte_size(bad);
        ASSERT_FALSE(parsed.ok()) << bad;
        EXPECT_NE(parsed.error().message.find("like 8G or 512M"), std::string::npos);
    }
    EXPECT_EQ(byte_size_text(100), "100 B");
    EXPECT_EQ(byte_size_text(4.9 * (1 << 30)), "4.9 GB");
    EXPECT_EQ(byte_size_text(512.0 * (1 << 20)), "512 MB");
}

TEST(MemoryBudget, ARefusalSaysWhatItWouldTakeAndTheBudget) {
    set_memory_budget(std::uint64_t{2} << 30);
    EXPECT_EQ(memory_budget(), std::uint64_t{2} << 30);
    EXPECT_TRUE(check_memory(1.9 * (1 << 30), "x").ok());
    const Status refused = check_memory(4.9 * (1 << 30), "tetrahedralizing 8 cells");
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().message,
              "tetrahedralizing 8 cells would take about 4.9 GB, more than the memory budget of "
              "2.0 GB (--max-memory)");
    // The default: 80% of the machine's memory.
    set_memory_budget(0);
    const std::uint64_t physical = physical_memory();
    ASSERT_GT(physical, 0u);
    EXPECT_EQ(memory_budget(), physical / 10 * 8);
}

}  // namespace
}  // namespace tr
