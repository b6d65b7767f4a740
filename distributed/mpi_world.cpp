#include <distributed/mpi_world.h>

#include <mpi.h>

#include <string>
#include <vector>

namespace tr {
namespace {

void broadcast_string(std::string& text, int root) {
    int length = static_cast<int>(text.size());
    MPI_Bcast(&length, 1, MPI_INT, root, MPI_COMM_WORLD);
    text.resize(static_cast<std::size_t>(length));
    MPI_Bcast(text.data(), length, MPI_CHAR, root, MPI_COMM_WORLD);
}

}  // namespace

Result<std::unique_ptr<MpiWorld>> MpiWorld::start(int* argc, char*** argv) {
    int initialized = 0;
    MPI_Initialized(&initialized);
    bool finalize = false;
    if (!initialized) {
        int provided = 0;
        if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
            return make_error(ErrorCode::kInternal, "MPI could not start (MPI_Init_thread)");
        }
        finalize = true;
    }
    // Errors come back as codes (and become this library's errors), never abort the job.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    return std::unique_ptr<MpiWorld>(new MpiWorld(rank, size, finalize));
}

MpiWorld::MpiWorld(int rank, int size, bool finalize)
    : rank_(rank), size_(size), finalize_(finalize) {}

MpiWorld::~MpiWorld() {
    if (finalize_) MPI_Finalize();
}

Status MpiWorld::agree(const Status& mine) const {
    int first_failed = mine.ok() ? size_ : rank_;
    int lowest = size_;
    MPI_Allreduce(&first_failed, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (lowest == size_) return {};
    int code = mine.ok() ? 0 : static_cast<int>(mine.error().code);
    std::string message = mine.ok() ? std::string() : mine.error().message;
    std::string where = mine.ok() ? std::string() : mine.error().where;
    MPI_Bcast(&code, 1, MPI_INT, lowest, MPI_COMM_WORLD);
    broadcast_string(message, lowest);
    broadcast_string(where, lowest);
    if (size_ > 1) message += " (rank " + std::to_string(lowest) + ")";
    return make_error(static_cast<ErrorCode>(code), message, where);
}

}  // namespace tr
