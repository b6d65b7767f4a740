#pragma once
// Private: IceT's sort-last compositing of the ranks' pictures (docs/distributed.md). Each rank
// hands its part's picture as premultiplied RGBA over transparent black; IceT blends them in
// the given front-to-back order of ranks (ICET_COMPOSITE_MODE_BLEND, ordered compositing, its
// single-image strategy: radix-k or binary swap as IceT chooses) and rank 0 receives the
// blend. Needs MPI started (distributed/mpi_world.h).

#include <core/result.h>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace tr::distributed_detail {

// A rectangle of valid pixels, in the picture's own rows (IceT's viewport <x, y, w, h>).
struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
};

struct CompositeStats {
    double composite_ms = 0;       // IceT's own compositing time on this rank
    std::uint64_t bytes_sent = 0;  // what IceT sent from this rank
};

class IcetCompositor {
  public:
    IcetCompositor();  // an IceT context on MPI_COMM_WORLD
    ~IcetCompositor();
    IcetCompositor(const IcetCompositor&) = delete;
    IcetCompositor& operator=(const IcetCompositor&) = delete;

    // Collective. `rgba`: width x height x 4 floats in [0, 1], premultiplied, rows in any order
    // as long as every rank uses the same; `valid`: where this rank's picture is not
    // transparent (IceT sends only that); `front_to_back`: every rank once. Returns the blend on
    // rank 0 (an empty vector elsewhere). Errors: kInternal when IceT reports one.
    Result<std::vector<float>> composite(std::span<const float> rgba, int width, int height,
                                         const PixelRect& valid, std::span<const int> front_to_back,
                                         CompositeStats* stats = nullptr);

  private:
    struct State;
    std::unique_ptr<State> state_;
};

// The smallest rectangle holding every pixel with a channel that is not 0 (empty: none).
PixelRect nonzero_rect(std::span<const float> rgba, int width, int height);

}  // namespace tr::distributed_detail
