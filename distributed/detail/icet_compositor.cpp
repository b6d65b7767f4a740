#include <distributed/detail/icet_compositor.h>

#include <IceT.h>
#include <IceTMPI.h>
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace tr::distributed_detail {

struct IcetCompositor::State {
    IceTCommunicator communicator = nullptr;
    IceTContext context = nullptr;
    int width = 0, height = 0;  // the tile as last set
};

IcetCompositor::IcetCompositor() : state_(std::make_unique<State>()) {
    state_->communicator = icetCreateMPICommunicator(MPI_COMM_WORLD);
    state_->context = icetCreateContext(state_->communicator);
    icetDiagnostics(ICET_DIAG_ERRORS | ICET_DIAG_ALL_NODES);
    icetSetColorFormat(ICET_IMAGE_COLOR_RGBA_FLOAT);
    icetSetDepthFormat(ICET_IMAGE_DEPTH_NONE);
    icetCompositeMode(ICET_COMPOSITE_MODE_BLEND);
    icetEnable(ICET_ORDERED_COMPOSITE);
    icetDisable(ICET_CORRECT_COLORED_BACKGROUND);
    // One tile: SEQUENTIAL hands the whole picture to the single-image strategy, which keeps
    // the order (radix-k, binary swap: IceT picks by the number of ranks).
    icetStrategy(ICET_STRATEGY_SEQUENTIAL);
    icetSingleImageStrategy(ICET_SINGLE_IMAGE_STRATEGY_AUTOMATIC);
}

IcetCompositor::~IcetCompositor() {
    if (state_->context) icetDestroyContext(state_->context);
    if (state_->communicator) icetDestroyMPICommunicator(state_->communicator);
}

Result<std::vector<float>> IcetCompositor::composite(std::span<const float> rgba, int width,
                                                     int height, const PixelRect& valid,
                                                     std::span<const int> front_to_back,
                                                     CompositeStats* stats) {
    icetSetContext(state_->context);
    if (width != state_->width || height != state_->height) {
        icetResetTiles();
        icetAddTile(0, 0, width, height, 0);
        state_->width = width;
        state_->height = height;
    }
    std::vector<IceTInt> order(front_to_back.begin(), front_to_back.end());
    icetCompositeOrder(order.data());
    const IceTInt viewport[4] = {valid.x, valid.y, valid.width, valid.height};
    const IceTFloat transparent[4] = {0, 0, 0, 0};
    const IceTImage image =
        icetCompositeImage(rgba.data(), nullptr, viewport, nullptr, nullptr, transparent);
    if (const IceTEnum error = icetGetError(); error != ICET_NO_ERROR) {
        char code[16];
        std::snprintf(code, sizeof(code), "0x%x", static_cast<unsigned>(error));
        return make_error(ErrorCode::kInternal,
                          std::string("IceT failed to composite (error ") + code + ")");
    }
    if (stats) {
        IceTDouble seconds = 0;
        icetGetDoublev(ICET_COMPOSITE_TIME, &seconds);
        IceTInt bytes = 0;
        icetGetIntegerv(ICET_BYTES_SENT, &bytes);
        stats->composite_ms = 1000.0 * seconds;
        stats->bytes_sent = static_cast<std::uint64_t>(bytes);
    }
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0 || icetImageIsNull(image)) return std::vector<float>();
    const IceTFloat* color = icetImageGetColorcf(image);
    return std::vector<float>(color, color + static_cast<std::size_t>(width) * height * 4);
}

PixelRect nonzero_rect(std::span<const float> rgba, int width, int height) {
    int x0 = width, y0 = height, x1 = -1, y1 = -1;
    for (int y = 0; y < height; ++y) {
        const float* row = rgba.data() + static_cast<std::size_t>(y) * width * 4;
        for (int x = 0; x < width; ++x) {
            const float* p = row + 4 * x;
            if (p[0] != 0 || p[1] != 0 || p[2] != 0 || p[3] != 0) {
                x0 = std::min(x0, x);
                x1 = std::max(x1, x);
                y0 = std::min(y0, y);
                y1 = std::max(y1, y);
            }
        }
    }
    if (x1 < 0) return {};
    return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

}  // namespace tr::distributed_detail
