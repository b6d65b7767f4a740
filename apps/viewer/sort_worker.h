#pragma once
// The viewer's visibility sort in a worker thread: the frame asks for the order of its view and
// draws with the latest finished one, never waiting for a sort it can reuse.

#include <mesh/face_adjacency.h>
#include <mesh/tet_mesh.h>
#include <sort/visibility_sort.h>

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace tr::viewer {

struct SortedOrder {
    std::shared_ptr<const std::vector<CellId>> order;  // back to front, real cells
    std::uint64_t view_id = 0;                         // the request it answers
    SortStats stats;
};

class SortWorker {
  public:
    // `mesh` and `adjacency` must outlive the worker.
    SortWorker(const TetMesh& mesh, const FaceAdjacency& adjacency);
    ~SortWorker();
    SortWorker(const SortWorker&) = delete;
    SortWorker& operator=(const SortWorker&) = delete;

    // Asks for the order of `view`; replaces a request not yet started. `view_id` names it
    // (increasing: a new id whenever the view or the method changes).
    void request(const SortView& view, SortMethod method, std::uint64_t view_id);

    // The latest finished order, if any.
    std::optional<SortedOrder> latest() const;

    // Blocks until the order for `view_id` (or a later request) is finished, and returns it.
    SortedOrder wait_for(std::uint64_t view_id);

  private:
    void run();

    const TetMesh& mesh_;
    const FaceAdjacency& adjacency_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable done_;
    struct Request {
        SortView view;
        SortMethod method;
        std::uint64_t view_id;
    };
    std::optional<Request> pending_;
    std::optional<SortedOrder> latest_;
    bool stop_ = false;
    std::thread thread_;
};

}  // namespace tr::viewer
