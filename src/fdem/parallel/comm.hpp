// Communication between the processes of a run (issue #15; spec parallel-and-python.md D1, D8,
// D9). An interface, so that the library never includes <mpi.h>: SerialComm (one process) is
// part of the library; MpiComm (parallel/mpi/mpi_comm.hpp) is in the fdem_mpi library, built only
// with -DFDEM_MPI=ON. Every call is collective: all processes of the run make it, in the same
// order.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "fdem/exact_sum.hpp"

namespace fdem {

class Comm {
public:
    virtual ~Comm() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;
    /// The global exact sum (theory §4.4) of every process's s, on every process: integer sums
    /// of the words, then one rounding by the caller, so the bits do not depend on the process
    /// count (spec D8.2). Never MPI_SUM on doubles (D7.5).
    virtual void sum(ExactSum& s) const { sum(&s, 1); }
    /// n exact sums in one exchange
    virtual void sum(ExactSum* s, int n) const = 0;
    /// In place: process p's part data[displs[p] .. displs[p] + counts[p]) (doubles) on every
    /// process (an all-gather of contiguous parts).
    virtual void allgatherv(double* data, const std::vector<int>& counts,
                            const std::vector<int>& displs) const = 0;
    /// Every process's bytes, concatenated in rank order, into all (resized; its capacity is
    /// kept, so a caller reusing it does not allocate once it is large enough).
    virtual void allgather_bytes(const std::vector<char>& mine, std::vector<char>& all) const = 0;
    /// Point-to-point exchange with the processes that have something to send or receive:
    /// send[send_displs[p] .. + send_counts[p]) goes to process p, which receives it into its
    /// recv[recv_displs[me] .. + recv_counts[me]) (counts in doubles; the two sides' counts
    /// must agree). Collective over the processes that exchange (every process calls it).
    virtual void exchange(const double* send, const std::vector<int>& send_counts,
                          const std::vector<int>& send_displs, double* recv,
                          const std::vector<int>& recv_counts,
                          const std::vector<int>& recv_displs) const = 0;
    /// Point-to-point exchange of messages whose lengths only the senders know, with a fixed set
    /// of neighbours (ascending; q lists this process iff it lists q): send[send_displs[q] ..
    /// + send_counts[q]) (doubles; 0 is a message too) goes to each neighbour q, and each
    /// neighbour's message is received into recv (grown when needed, never shrunk) at
    /// recv_displs[q], its length in recv_counts[q] (both sized to size(); 0 for the others,
    /// received in the order of neighbours). One message each way per neighbour; collective
    /// over the neighbours.
    virtual void exchange_sized(const std::vector<int32_t>& neighbours, const double* send,
                                const std::vector<int>& send_counts,
                                const std::vector<int>& send_displs, std::vector<double>& recv,
                                std::vector<int>& recv_counts,
                                std::vector<int>& recv_displs) const = 0;
    /// Order-free reductions (D8.1): the same result for any process count.
    virtual double max(double x) const = 0;
    virtual double min(double x) const = 0;
    /// n minima in one exchange, in place
    virtual void min(double* x, int n) const = 0;
    virtual int64_t sum(int64_t n) const = 0;
    /// root's text on every process
    virtual void broadcast(std::string& text, int root) const = 0;
    virtual void barrier() const = 0;
};

/// v.resize(n), growing the capacity at least twofold when it grows: buffers whose size follows
/// a count that rises slowly over a run (the pairs in contact of a distributed step) allocate
/// O(log n) times, not at every new maximum (resize() of a vector that shrank in between grows
/// the capacity only to about n). Spec T9: no allocation in a step after warm-up.
template <class T>
void resize_grow(std::vector<T>& v, size_t n) {
    if (n > v.capacity()) v.reserve(std::max(n, 2 * v.capacity()));
    v.resize(n);
}

/// One process: every reduction is the identity.
class SerialComm final : public Comm {
public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    void sum(ExactSum*, int) const override {}
    void allgatherv(double*, const std::vector<int>&, const std::vector<int>&) const override {}
    void allgather_bytes(const std::vector<char>& mine, std::vector<char>& all) const override {
        all.assign(mine.begin(), mine.end());
    }
    void exchange(const double*, const std::vector<int>&, const std::vector<int>&, double*,
                  const std::vector<int>&, const std::vector<int>&) const override {}
    void exchange_sized(const std::vector<int32_t>&, const double*, const std::vector<int>&,
                        const std::vector<int>&, std::vector<double>&,
                        std::vector<int>& recv_counts,
                        std::vector<int>& recv_displs) const override {
        recv_counts.assign(1, 0);
        recv_displs.assign(1, 0);
    }
    double max(double x) const override { return x; }
    double min(double x) const override { return x; }
    void min(double*, int) const override {}
    int64_t sum(int64_t n) const override { return n; }
    void broadcast(std::string&, int) const override {}
    void barrier() const override {}
};

/// Run fn on every process. If it throws on any process, every process throws the same error
/// (spec D9): that of the lowest failing rank, with its type (InputError, SimulationError, or
/// std::runtime_error for anything else) and the same what(), so the exit code and the message
/// are those of a one-process run. fn itself must not make collective calls that a failing
/// process would skip (that would hang): it is for the work each process does on its own
/// (reading input, checking its part), between collectives.
void run_collectively(const Comm& comm, const std::function<void()>& fn);

/// The wire form of an error (used by run_collectively; exposed for its tests): an exception
/// to text, and the text back to the same exception type with the same what().
std::string encode_error(const std::exception& e);
[[noreturn]] void throw_decoded_error(const std::string& text);

}  // namespace fdem
