// parallel/mesh_broadcast: process 0 reads a mesh and every other process receives the same mesh
// (or the same InputError) without reading the file. One process plays both sides here through
// a loopback Comm whose broadcast records what process 0 sends and replays it on "process 1";
// the real MPI broadcast runs in every mpi.same_as_serial test of a .geo scenario.
#include <gtest/gtest.h>

#include <string>

#include "fdem/error.hpp"
#include "fdem/mesh.hpp"
#include "io/mesh_bytes.hpp"
#include "parallel/comm.hpp"
#include "parallel/mesh_broadcast.hpp"

namespace fdem {
namespace {

const std::string kData = FDEM_TEST_DATA_DIR;

// rank 0: broadcast records the text it sends in wire; rank 1: broadcast receives wire
class LoopbackComm final : public Comm {
public:
    LoopbackComm(int rank, std::string& wire) : rank_(rank), wire_(wire) {}
    int rank() const override { return rank_; }
    int size() const override { return 2; }
    void sum(ExactSum*, int) const override {}
    void allgatherv(double*, const std::vector<int>&, const std::vector<int>&) const override {}
    void allgather_bytes(const std::vector<char>&, std::vector<char>&) const override {}
    void exchange(const double*, const std::vector<int>&, const std::vector<int>&, double*,
                  const std::vector<int>&, const std::vector<int>&) const override {}
    void exchange_sized(const std::vector<int32_t>&, const double*, const std::vector<int>&,
                        const std::vector<int>&, std::vector<double>&, std::vector<int>&,
                        std::vector<int>&) const override {}
    double max(double x) const override { return x; }
    double min(double x) const override { return x; }
    void min(double*, int) const override {}
    int64_t sum(int64_t n) const override { return n; }
    void broadcast(std::string& text, int root) const override {
        EXPECT_EQ(root, 0);
        if (rank_ == 0) {
            wire_ = text;
        } else {
            text = wire_;
        }
    }
    void barrier() const override {}

private:
    int rank_;
    std::string& wire_;
};

TEST(MeshBroadcast, EveryProcessGetsProcessZerosMeshWithoutReadingTheFile) {
    std::string wire;
    const LoopbackComm p0(0, wire), p1(1, wire);
    const std::string geo = kData + "/jointed_blocks.geo";
    const MeshData read = read_mesh(geo, 0.1);
    const MeshData sent = broadcast_mesh_reader(p0)(geo, 0.1, 1, MeshLimits{});
    ASSERT_FALSE(wire.empty());
    // process 1 never opens the path: a file that does not exist gives it the mesh all the same
    const MeshData got = broadcast_mesh_reader(p1)("/no/such/file.geo", 0.1, 1, MeshLimits{});
    EXPECT_EQ(mesh_to_bytes(sent), mesh_to_bytes(read));
    EXPECT_EQ(mesh_to_bytes(got), mesh_to_bytes(read));
}

TEST(MeshBroadcast, ProcessZerosInputErrorIsThrownOnEveryProcessWithTheSameMessage) {
    std::string wire;
    const LoopbackComm p0(0, wire), p1(1, wire);
    const std::string missing = kData + "/no_such_mesh.msh";
    std::string what0, key0;
    try {
        broadcast_mesh_reader(p0)(missing, 0, 1, MeshLimits{});
        ADD_FAILURE() << "process 0 read a missing file";
    } catch (const InputError& e) {
        what0 = e.what();
        key0 = e.key();
    }
    ASSERT_NE(what0.find("no_such_mesh.msh"), std::string::npos) << what0;
    try {
        broadcast_mesh_reader(p1)(missing, 0, 1, MeshLimits{});
        ADD_FAILURE() << "process 1 returned a mesh for process 0's error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.what(), what0);
        EXPECT_EQ(e.key(), key0);
    }
}

}  // namespace
}  // namespace fdem
