#pragma once
// The MPI processes a distributed render runs on (docs/distributed.md): started once per
// program by the app (`tetrender-mpi`, under mpirun or srun), then handed to the renderer.
// This header speaks std only; MPI itself stays in distributed/'s sources.

#include <core/result.h>

#include <memory>

namespace tr {

class MpiWorld {
  public:
    // Initialises MPI (threads: only the calling thread makes MPI calls) unless the program
    // already did; finalises it on destruction if it initialised it. Errors: kInternal when
    // MPI cannot start. Not copyable; one per program.
    static Result<std::unique_ptr<MpiWorld>> start(int* argc, char*** argv);
    ~MpiWorld();
    MpiWorld(const MpiWorld&) = delete;
    MpiWorld& operator=(const MpiWorld&) = delete;

    int rank() const { return rank_; }
    int size() const { return size_; }

    // Collective (every rank calls it): the same status on every rank — ok when every rank's
    // is ok, otherwise the error of the lowest rank that failed, with " (rank R)" after its
    // message when there are several ranks. How one rank's failure stops all without a hang.
    Status agree(const Status& mine) const;

  private:
    MpiWorld(int rank, int size, bool finalize);
    int rank_ = 0;
    int size_ = 1;
    bool finalize_ = false;
};

}  // namespace tr
