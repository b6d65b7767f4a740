#pragma once
// Private: the few MPI collectives the distributed renderer uses, over MPI_COMM_WORLD, in the
// types it speaks. Every rank must call each of them, in the same order.

#include <core/math.h>
#include <distributed/box_cut.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tr::distributed_detail {

std::int64_t sum_over_ranks(std::int64_t value);
double max_over_ranks(double value);
bool all_ranks(bool value);
// The union of every rank's bounds (empty ones ignored).
Bounds3 bounds_over_ranks(const Bounds3& bounds);

// Every rank's points, concatenated in rank order, on every rank.
std::vector<Vec3> gather_to_all(std::span<const Vec3> mine);

// Tets to send, grouped by the rank they go to: rank r's are pieces[first[r] .. first[r + 1]).
struct PiecesByRank {
    std::vector<TetPiece> pieces;
    std::vector<std::size_t> first;  // one more than the number of ranks
};

// Sends each rank its group and returns what every rank sent here, concatenated in rank order
// (what this rank sent itself included). `bytes_sent`: what left this rank for others.
// Precondition: one group per rank; fewer than 2^31 pieces to any one rank.
std::vector<TetPiece> exchange_pieces(const PiecesByRank& out, std::uint64_t* bytes_sent);

// Every rank's value on rank 0, in rank order (empty elsewhere).
std::vector<double> gather_to_root(double value);
// Every rank's strings on rank 0, concatenated in rank order (empty elsewhere).
std::vector<std::string> gather_to_root(const std::vector<std::string>& mine);

}  // namespace tr::distributed_detail
