// Comm over MPI: see parallel/mpi/mpi_comm.hpp.
#include "parallel/mpi/mpi_comm.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace fdem {

MpiSession::MpiSession(int* argc, char*** argv) {
    int provided = 0;
    MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
    if (provided < MPI_THREAD_FUNNELED) {
        MPI_Finalize();
        throw std::runtime_error("the MPI library does not provide MPI_THREAD_FUNNELED");
    }
}

MpiSession::~MpiSession() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Finalize();
}

MpiComm::MpiComm(MPI_Comm parent) {
    MPI_Comm_dup(parent, &comm_);
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &size_);
}

MpiComm::~MpiComm() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized && comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

void MpiComm::sum(ExactSum* sums, int n) const {
    // per sum: the normalised words (digits < 2^32, so any realistic process count cannot
    // overflow an int64) and the counts of +inf, -inf and NaN terms: integer sums, associative
    // and exact; all n in one MPI_Allreduce
    constexpr int kW = ExactSum::kWords;
    constexpr int kStride = kW + 3;
    std::vector<int64_t>& buf = sum_buf_;
    buf.assign(static_cast<size_t>(kStride) * static_cast<size_t>(n), 0);  // keeps its capacity
    for (int j = 0; j < n; ++j) {
        ExactSum& s = sums[j];
        int64_t* b = buf.data() + static_cast<size_t>(kStride) * static_cast<size_t>(j);
        s.normalise();
        for (int k = 0; k < kW; ++k)
            b[k] = s.words()[k];
        if (s.has_special()) {
            const double v = s.special();
            if (std::isnan(v)) {
                b[kW + 2] = 1;
            } else {
                b[kW + (v > 0 ? 0 : 1)] = 1;
            }
        }
    }
    MPI_Allreduce(MPI_IN_PLACE, buf.data(), kStride * n, MPI_INT64_T, MPI_SUM, comm_);
    for (int j = 0; j < n; ++j) {
        const int64_t* b = buf.data() + static_cast<size_t>(kStride) * static_cast<size_t>(j);
        const int64_t pos = b[kW], neg = b[kW + 1], nan = b[kW + 2];
        const bool special = pos + neg + nan > 0;
        double value = 0;
        if (nan > 0 || (pos > 0 && neg > 0)) {
            value = std::numeric_limits<double>::quiet_NaN();
        } else if (pos > 0) {
            value = std::numeric_limits<double>::infinity();
        } else if (neg > 0) {
            value = -std::numeric_limits<double>::infinity();
        }
        sums[j].assign(b, special, value);
    }
}

void MpiComm::allgatherv(double* data, const std::vector<int>& counts,
                         const std::vector<int>& displs) const {
    MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, data, counts.data(), displs.data(),
                   MPI_DOUBLE, comm_);
}

void MpiComm::allgather_bytes(const std::vector<char>& mine, std::vector<char>& all) const {
    counts_.resize(static_cast<size_t>(size_));
    displs_.resize(static_cast<size_t>(size_));
    const int n = static_cast<int>(mine.size());
    MPI_Allgather(&n, 1, MPI_INT, counts_.data(), 1, MPI_INT, comm_);
    int64_t total = 0;
    for (int r = 0; r < size_; ++r) {
        displs_[static_cast<size_t>(r)] = static_cast<int>(total);
        total += counts_[static_cast<size_t>(r)];
    }
    if (total > std::numeric_limits<int>::max())
        throw std::runtime_error("allgather_bytes: more than 2 GiB in one exchange");
    resize_grow(all, static_cast<size_t>(total));
    MPI_Allgatherv(mine.data(), n, MPI_BYTE, all.data(), counts_.data(), displs_.data(), MPI_BYTE,
                   comm_);
}

void MpiComm::exchange(const double* send, const std::vector<int>& send_counts,
                       const std::vector<int>& send_displs, double* recv,
                       const std::vector<int>& recv_counts,
                       const std::vector<int>& recv_displs) const {
    constexpr int kTag = 15;
    requests_.resize(2 * static_cast<size_t>(size_));
    int n = 0;
    for (int p = 0; p < size_; ++p) {
        const size_t q = static_cast<size_t>(p);
        if (p != rank_ && recv_counts[q] > 0) {
            MPI_Irecv(recv + recv_displs[q], recv_counts[q], MPI_DOUBLE, p, kTag, comm_,
                      &requests_[static_cast<size_t>(n++)]);
        }
    }
    for (int p = 0; p < size_; ++p) {
        const size_t q = static_cast<size_t>(p);
        if (p != rank_ && send_counts[q] > 0) {
            MPI_Isend(send + send_displs[q], send_counts[q], MPI_DOUBLE, p, kTag, comm_,
                      &requests_[static_cast<size_t>(n++)]);
        }
    }
    MPI_Waitall(n, requests_.data(), MPI_STATUSES_IGNORE);
}

void MpiComm::exchange_sized(const std::vector<int32_t>& neighbours, const double* send,
                             const std::vector<int>& send_counts,
                             const std::vector<int>& send_displs, std::vector<double>& recv,
                             std::vector<int>& recv_counts, std::vector<int>& recv_displs) const {
    constexpr int kTag = 16;
    const size_t n = neighbours.size();
    if (requests_.size() < n) requests_.resize(n);
    if (messages_.size() < n) messages_.resize(n);
    for (size_t k = 0; k < n; ++k) {
        const int q = neighbours[k];
        MPI_Isend(send + send_displs[static_cast<size_t>(q)], send_counts[static_cast<size_t>(q)],
                  MPI_DOUBLE, q, kTag, comm_, &requests_[k]);
    }
    // the lengths from the probed messages, then the receives into place
    recv_counts.assign(static_cast<size_t>(size_), 0);
    recv_displs.assign(static_cast<size_t>(size_), 0);
    int total = 0;
    for (size_t k = 0; k < n; ++k) {
        const int q = neighbours[k];
        MPI_Status st;
        MPI_Mprobe(q, kTag, comm_, &messages_[k], &st);
        int count = 0;
        MPI_Get_count(&st, MPI_DOUBLE, &count);
        recv_counts[static_cast<size_t>(q)] = count;
        recv_displs[static_cast<size_t>(q)] = total;
        total += count;
    }
    if (recv.size() < static_cast<size_t>(total))
        recv.resize(std::max(static_cast<size_t>(total), 2 * recv.size()));
    for (size_t k = 0; k < n; ++k) {
        const int q = neighbours[k];
        MPI_Mrecv(recv.data() + recv_displs[static_cast<size_t>(q)],
                  recv_counts[static_cast<size_t>(q)], MPI_DOUBLE, &messages_[k],
                  MPI_STATUS_IGNORE);
    }
    MPI_Waitall(static_cast<int>(n), requests_.data(), MPI_STATUSES_IGNORE);
}

double MpiComm::max(double x) const {
    MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MAX, comm_);
    return x;
}

double MpiComm::min(double x) const {
    MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MIN, comm_);
    return x;
}

void MpiComm::min(double* x, int n) const {
    MPI_Allreduce(MPI_IN_PLACE, x, n, MPI_DOUBLE, MPI_MIN, comm_);
}

int64_t MpiComm::sum(int64_t n) const {
    MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_INT64_T, MPI_SUM, comm_);
    return n;
}

void MpiComm::broadcast(std::string& text, int root) const {
    uint64_t n = text.size();
    MPI_Bcast(&n, 1, MPI_UINT64_T, root, comm_);
    text.resize(n);
    // in pieces of at most 1 GiB: MPI counts are int (a mesh of 10^8 triangles is ~2 GB)
    constexpr uint64_t kPiece = uint64_t{1} << 30;
    for (uint64_t at = 0; at < n; at += kPiece) {
        MPI_Bcast(text.data() + at, static_cast<int>(std::min(kPiece, n - at)), MPI_CHAR, root,
                  comm_);
    }
}

void MpiComm::barrier() const {
    MPI_Barrier(comm_);
}

}  // namespace fdem
