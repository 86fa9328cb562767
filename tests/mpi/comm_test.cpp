// MpiComm (parallel/mpi/mpi_comm.hpp) and run_collectively (parallel/comm.hpp) under mpirun with
// 1-4 processes (spec parallel-and-python.md T10, D8, D9).
#include "parallel/mpi/mpi_comm.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "fdem/error.hpp"

namespace fdem {
namespace {

// the same terms on every process: heavy cancellation over a wide exponent range
std::vector<double> terms(size_t n) {
    std::mt19937_64 rng(2026);
    std::uniform_real_distribution<double> mant(-1.0, 1.0);
    std::uniform_int_distribution<int> ex(-60, 60);
    std::vector<double> xs(n);
    for (double& x : xs)
        x = std::ldexp(mant(rng), ex(rng));
    return xs;
}

// T10 across real processes: each process sums its share (dealt in two different ways) and the
// global exact sum equals the one-process exact sum bit for bit, on every process.
TEST(MpiComm, ExactSumIsTheSameForAnyProcessCount) {
    const MpiComm comm;
    const std::vector<double> xs = terms(200000);
    ExactSum all;
    for (double x : xs)
        all.add(x);
    const double serial = all.value();

    ExactSum dealt, blocks;
    const size_t p = static_cast<size_t>(comm.size()), r = static_cast<size_t>(comm.rank());
    for (size_t i = r; i < xs.size(); i += p)
        dealt.add(xs[i]);
    const size_t b = (xs.size() + p - 1) / p;
    for (size_t i = r * b; i < std::min(xs.size(), (r + 1) * b); ++i)
        blocks.add(xs[i]);
    comm.sum(dealt);
    comm.sum(blocks);
    EXPECT_EQ(std::bit_cast<uint64_t>(dealt.value()), std::bit_cast<uint64_t>(serial));
    EXPECT_EQ(std::bit_cast<uint64_t>(blocks.value()), std::bit_cast<uint64_t>(serial));
    EXPECT_TRUE(dealt == all);

    // a naive MPI_SUM of the per-process doubles is what D7.5 forbids: it need not agree
    double naive = 0;
    for (size_t i = r; i < xs.size(); i += p)
        naive += xs[i];
    MPI_Allreduce(MPI_IN_PLACE, &naive, 1, MPI_DOUBLE, MPI_SUM, comm.handle());
    if (comm.size() > 1) {
        RecordProperty("naive_mpi_sum_differs",
                       std::bit_cast<uint64_t>(naive) != std::bit_cast<uint64_t>(serial));
    }
}

TEST(MpiComm, NonFiniteTermsOnOneProcess) {
    const MpiComm comm;
    ExactSum s;
    s.add(1.0);
    if (comm.rank() == comm.size() - 1) s.add(INFINITY);
    comm.sum(s);
    EXPECT_EQ(s.value(), INFINITY);
    ExactSum t;
    if (comm.rank() == 0) t.add(INFINITY);
    if (comm.rank() == comm.size() - 1) t.add(-INFINITY);
    comm.sum(t);
    EXPECT_TRUE(std::isnan(t.value()));
}

TEST(MpiComm, ReductionsAndBroadcast) {
    const MpiComm comm;
    EXPECT_EQ(comm.max(static_cast<double>(comm.rank())), comm.size() - 1.0);
    EXPECT_EQ(comm.min(static_cast<double>(comm.rank())), 0.0);
    EXPECT_EQ(comm.sum(int64_t{comm.rank()} + 1), int64_t{comm.size()} * (comm.size() + 1) / 2);
    std::string text = comm.rank() == comm.size() - 1 ? std::string("line 1\nline: 2\0x", 16) : "";
    comm.broadcast(text, comm.size() - 1);
    EXPECT_EQ(text, std::string("line 1\nline: 2\0x", 16));
}

TEST(MpiComm, MinOfSeveralAllGatherBytesAndExchange) {
    const MpiComm comm;
    const int P = comm.size(), r = comm.rank();
    double m[2] = {static_cast<double>(r), -static_cast<double>(r)};
    comm.min(m, 2);
    EXPECT_EQ(m[0], 0.0);
    EXPECT_EQ(m[1], -(P - 1.0));
    // every process's bytes in rank order, process r contributing r + 1 bytes of value r
    const std::vector<char> mine(static_cast<size_t>(r) + 1, static_cast<char>(r));
    std::vector<char> all;
    comm.allgather_bytes(mine, all);
    std::vector<char> want;
    for (int q = 0; q < P; ++q)
        want.insert(want.end(), static_cast<size_t>(q) + 1, static_cast<char>(q));
    EXPECT_EQ(all, want);
    // exchange: process r sends q + 1 values 100 r + k to every q != r (none to itself)
    std::vector<int> sc(static_cast<size_t>(P)), sd(static_cast<size_t>(P)),
        rc(static_cast<size_t>(P)), rd(static_cast<size_t>(P));
    std::vector<double> send, recv;
    for (int q = 0; q < P; ++q) {
        sd[static_cast<size_t>(q)] = static_cast<int>(send.size());
        sc[static_cast<size_t>(q)] = q == r ? 0 : q + 1;
        for (int k = 0; k < sc[static_cast<size_t>(q)]; ++k)
            send.push_back(100.0 * r + k);
        rd[static_cast<size_t>(q)] = static_cast<int>(recv.size());
        rc[static_cast<size_t>(q)] = q == r ? 0 : r + 1;
        recv.resize(recv.size() + static_cast<size_t>(rc[static_cast<size_t>(q)]), -1.0);
    }
    comm.exchange(send.data(), sc, sd, recv.data(), rc, rd);
    for (int q = 0; q < P; ++q) {
        for (int k = 0; k < rc[static_cast<size_t>(q)]; ++k)
            EXPECT_EQ(recv[static_cast<size_t>(rd[static_cast<size_t>(q)] + k)], 100.0 * q + k)
                << "from process " << q;
    }
}

// D9: an error on one process stops every process with the same type and message (no hang:
// ctest's timeout would catch one).
TEST(RunCollectively, InputErrorOnTheLastProcessReachesAll) {
    const MpiComm comm;
    const int bad = comm.size() - 1;
    try {
        run_collectively(comm, [&] {
            if (comm.rank() == bad) {
                throw InputError({"scenario.toml", 12, 18}, "youngs_modulus",
                                 "must be > 0 Pa, got -5e+10", "youngs_modulus = -50e9");
            }
        });
        FAIL() << "no error on rank " << comm.rank();
    } catch (const InputError& e) {
        const InputError expected({"scenario.toml", 12, 18}, "youngs_modulus",
                                  "must be > 0 Pa, got -5e+10", "youngs_modulus = -50e9");
        EXPECT_STREQ(e.what(), expected.what());
        EXPECT_EQ(e.key(), "youngs_modulus");
        EXPECT_EQ(e.location().line, 12);
    }
}

TEST(RunCollectively, TheLowestFailingRankSpeaks) {
    const MpiComm comm;
    try {
        run_collectively(comm, [&] {
            // every rank fails, each with its own step: rank 0's error must win everywhere
            throw SimulationError(100 + comm.rank(), 0.1 / 3.0, "node 7 (body 0)",
                                  "position or velocity is not finite");
        });
        FAIL() << "no error";
    } catch (const SimulationError& e) {
        EXPECT_EQ(e.step(), 100);
        EXPECT_EQ(std::bit_cast<uint64_t>(e.time()), std::bit_cast<uint64_t>(0.1 / 3.0));
        const SimulationError expected(100, 0.1 / 3.0, "node 7 (body 0)",
                                       "position or velocity is not finite");
        EXPECT_STREQ(e.what(), expected.what());
    }
}

TEST(RunCollectively, NoErrorNoThrowAndOtherExceptions) {
    const MpiComm comm;
    EXPECT_NO_THROW(run_collectively(comm, [] {}));
    try {
        run_collectively(comm, [&] {
            if (comm.rank() == 0) throw std::logic_error("boom");
        });
        FAIL() << "no error";
    } catch (const InputError&) {
        FAIL() << "wrong type";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "boom");
    } catch (const std::logic_error& e) {
        EXPECT_EQ(comm.size(), 1);  // one process rethrows the original exception
        EXPECT_STREQ(e.what(), "boom");
    }
}

}  // namespace
}  // namespace fdem
