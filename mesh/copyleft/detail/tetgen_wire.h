#pragma once
// Private: the bytes that travel between run_tetgen (tetgen_plc.cpp) and the TetGen worker
// program (tetgen_worker_main.cpp) over a socket: the request (switches and the PLC) one way,
// the answer (the mesh, or why there is none) the other. Both ends are built from the same
// sources, so the layout is native (no byte swapping); the readers still check every count
// against the bytes received, and a short or inconsistent message is an error, never a crash.

#include <core/result.h>
#include <mesh/copyleft/detail/tetgen_plc.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tr::detail {

struct TetgenRequest {
    std::string switches;  // TetGen syntax, without the dash
    TetgenPlc plc;
};

// What the TetGen call produced.
enum class TetgenOutcome : std::int32_t {
    kOk,
    kTetgenError,  // TetGen threw an int: `code`
    kOutOfMemory,
    kException,  // another exception: `text`
    kBadSwitches,
    kBadOutput,  // a tet with an index out of range
};

struct TetgenAnswer {
    TetgenOutcome outcome = TetgenOutcome::kOk;
    std::int32_t code = 0;
    std::string text;
    TetgenResult result;
};

std::vector<char> encode_request(const TetgenRequest& request);
Result<TetgenRequest> decode_request(const std::vector<char>& bytes);

std::vector<char> encode_answer(const TetgenAnswer& answer);
Result<TetgenAnswer> decode_answer(const std::vector<char>& bytes);

}  // namespace tr::detail
