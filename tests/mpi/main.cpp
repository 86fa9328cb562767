// GoogleTest under mpirun (label mpi): every process runs every test (each test is collective);
// only rank 0 prints, and the exit code is non-zero on every process if any failed.
#include <gtest/gtest.h>

#include "parallel/mpi/mpi_comm.hpp"

int main(int argc, char** argv) {
    fdem::MpiSession mpi(&argc, &argv);
    ::testing::InitGoogleTest(&argc, argv);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) {
        auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
        delete listeners.Release(listeners.default_result_printer());
    }
    int rc = RUN_ALL_TESTS();
    MPI_Allreduce(MPI_IN_PLACE, &rc, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return rc;
}
