// Comm over MPI (issue #15, spec parallel-and-python.md D1): the only headers that include
// <mpi.h>, built into the fdem_mpi library with -DFDEM_MPI=ON.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <vector>

#include "parallel/comm.hpp"

namespace fdem {

/// MPI_Init_thread(MPI_THREAD_FUNNELED) for the lifetime of the object (only the thread that
/// created it calls MPI; OpenMP threads inside a process never do), then MPI_Finalize.
class MpiSession {
public:
    MpiSession(int* argc, char*** argv);
    ~MpiSession();
    MpiSession(const MpiSession&) = delete;
    MpiSession& operator=(const MpiSession&) = delete;
};

/// A duplicate of a communicator (MPI_COMM_WORLD by default), so fdem's messages never mix with
/// a caller's.
class MpiComm final : public Comm {
public:
    explicit MpiComm(MPI_Comm parent = MPI_COMM_WORLD);
    ~MpiComm() override;
    MpiComm(const MpiComm&) = delete;
    MpiComm& operator=(const MpiComm&) = delete;

    int rank() const override { return rank_; }
    int size() const override { return size_; }
    using Comm::sum;
    void sum(ExactSum* s, int n) const override;
    void allgatherv(double* data, const std::vector<int>& counts,
                    const std::vector<int>& displs) const override;
    void allgather_bytes(const std::vector<char>& mine, std::vector<char>& all) const override;
    void exchange(const double* send, const std::vector<int>& send_counts,
                  const std::vector<int>& send_displs, double* recv,
                  const std::vector<int>& recv_counts,
                  const std::vector<int>& recv_displs) const override;
    void exchange_sized(const std::vector<int32_t>& neighbours, const double* send,
                        const std::vector<int>& send_counts, const std::vector<int>& send_displs,
                        std::vector<double>& recv, std::vector<int>& recv_counts,
                        std::vector<int>& recv_displs) const override;
    double max(double x) const override;
    double min(double x) const override;
    void min(double* x, int n) const override;
    int64_t sum(int64_t n) const override;
    void broadcast(std::string& text, int root) const override;
    void barrier() const override;
    MPI_Comm handle() const { return comm_; }

private:
    MPI_Comm comm_ = MPI_COMM_NULL;
    mutable std::vector<int64_t>
        sum_buf_;  ///< sum()'s words, sized on first use (no allocation per step)
    mutable std::vector<int> counts_, displs_;   ///< allgather_bytes()'s, sized on first use
    mutable std::vector<MPI_Request> requests_;  ///< exchange()'s, sized on first use
    mutable std::vector<MPI_Message> messages_;  ///< exchange_sized()'s probed messages
    int rank_ = 0;
    int size_ = 1;
};

}  // namespace fdem
