#include <distributed/detail/collectives.h>

#include <mpi.h>

#include <limits>
#include <stdexcept>

namespace tr::distributed_detail {
namespace {

int world_size() {
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    return size;
}

int world_rank() {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    return rank;
}

constexpr std::size_t kMaxCount = static_cast<std::size_t>(std::numeric_limits<int>::max());

// Every rank learns whether every rank's counts fit an int, and all throw together if not
// (one rank throwing alone would leave the others waiting in the next collective).
void check_counts_fit(bool fits) {
    if (!all_ranks(fits)) throw std::length_error("more than 2^31 items in one MPI message");
}

// MPI counts are ints (checked beforehand with check_counts_fit).
int as_count(std::size_t n) {
    if (n > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
        throw std::length_error("more than 2^31 items in one MPI message");
    }
    return static_cast<int>(n);
}

}  // namespace

std::int64_t sum_over_ranks(std::int64_t value) {
    std::int64_t sum = 0;
    MPI_Allreduce(&value, &sum, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
    return sum;
}

double max_over_ranks(double value) {
    double out = 0;
    MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return out;
}

bool all_ranks(bool value) {
    int mine = value ? 1 : 0, out = 0;
    MPI_Allreduce(&mine, &out, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return out == 1;
}

Bounds3 bounds_over_ranks(const Bounds3& bounds) {
    // Empty bounds are +inf / -inf: the min of lo and max of hi ignore them.
    double lo[3] = {bounds.lo.x, bounds.lo.y, bounds.lo.z};
    double hi[3] = {bounds.hi.x, bounds.hi.y, bounds.hi.z};
    double out_lo[3], out_hi[3];
    MPI_Allreduce(lo, out_lo, 3, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(hi, out_hi, 3, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    Bounds3 out;
    out.lo = Vec3(out_lo[0], out_lo[1], out_lo[2]);
    out.hi = Vec3(out_hi[0], out_hi[1], out_hi[2]);
    return out;
}

std::vector<Vec3> gather_to_all(std::span<const Vec3> mine) {
    check_counts_fit(mine.size() * 3 <= kMaxCount / 64);
    const int size = world_size();
    const int count = as_count(mine.size() * 3);
    std::vector<int> counts(static_cast<std::size_t>(size));
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::vector<int> offsets(counts.size(), 0);
    std::size_t total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
        offsets[r] = as_count(total);
        total += static_cast<std::size_t>(counts[r]);
    }
    std::vector<Vec3> all(total / 3);
    MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                   MPI_DOUBLE, MPI_COMM_WORLD);
    return all;
}

std::vector<TetPiece> exchange_pieces(const PiecesByRank& out, std::uint64_t* bytes_sent) {
    static_assert(sizeof(TetPiece) == 16 * sizeof(double));
    const int size = world_size();
    const int rank = world_rank();
    check_counts_fit(out.pieces.size() <= kMaxCount);
    MPI_Datatype piece_type;
    MPI_Type_contiguous(16, MPI_DOUBLE, &piece_type);
    MPI_Type_commit(&piece_type);
    std::vector<int> send_counts(static_cast<std::size_t>(size)), send_offsets(send_counts.size());
    std::uint64_t sent = 0;
    for (int r = 0; r < size; ++r) {
        send_counts[r] = as_count(out.first[r + 1] - out.first[r]);
        send_offsets[r] = as_count(out.first[r]);
        if (r != rank) sent += static_cast<std::uint64_t>(send_counts[r]) * sizeof(TetPiece);
    }
    std::vector<int> receive_counts(send_counts.size()), receive_offsets(send_counts.size());
    MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::size_t received = 0;
    for (int r = 0; r < size; ++r) received += static_cast<std::size_t>(receive_counts[r]);
    check_counts_fit(received <= kMaxCount);
    received = 0;
    for (int r = 0; r < size; ++r) {
        receive_offsets[r] = as_count(received);
        received += static_cast<std::size_t>(receive_counts[r]);
    }
    std::vector<TetPiece> in(received);
    MPI_Alltoallv(out.pieces.data(), send_counts.data(), send_offsets.data(), piece_type, in.data(),
                  receive_counts.data(), receive_offsets.data(), piece_type, MPI_COMM_WORLD);
    MPI_Type_free(&piece_type);
    if (bytes_sent) *bytes_sent = sent;
    return in;
}

std::vector<double> gather_to_root(double value) {
    std::vector<double> all(world_rank() == 0 ? static_cast<std::size_t>(world_size()) : 0);
    MPI_Gather(&value, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    return all;
}

std::vector<std::string> gather_to_root(const std::vector<std::string>& mine) {
    // Strings as one buffer of NUL-terminated texts per rank.
    std::string packed;
    for (const std::string& s : mine) packed += s + '\0';
    check_counts_fit(packed.size() <= kMaxCount / 1024);
    const int count = as_count(packed.size());
    const int size = world_size();
    const bool root = world_rank() == 0;
    std::vector<int> counts(root ? static_cast<std::size_t>(size) : 0);
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::vector<int> offsets(counts.size(), 0);
    std::size_t total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
        offsets[r] = as_count(total);
        total += static_cast<std::size_t>(counts[r]);
    }
    std::string all(total, '\0');
    MPI_Gatherv(packed.data(), count, MPI_CHAR, all.data(), counts.data(), offsets.data(), MPI_CHAR,
                0, MPI_COMM_WORLD);
    std::vector<std::string> out;
    for (std::size_t start = 0; start < all.size();) {
        const std::size_t end = all.find('\0', start);
        out.push_back(all.substr(start, end - start));
        start = end + 1;
    }
    return out;
}

}  // namespace tr::distributed_detail
