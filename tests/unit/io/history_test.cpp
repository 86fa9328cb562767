// CSV history: exact header, bit-exact values, energy_error against the first row, flush per row.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fdem/error.hpp"
#include "fdem/output.hpp"

namespace fdem {
namespace {

namespace fs = std::filesystem;

fs::path test_file(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path dir =
        fs::path(::testing::TempDir()) / (std::string("fdem_history_") + info->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir / name;
}

std::vector<std::string> read_lines(const fs::path& p) {
    std::ifstream in(p);
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);)
        out.push_back(line);
    return out;
}

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream ss(line);
    for (std::string item; std::getline(ss, item, ',');)
        out.push_back(item);
    return out;
}

constexpr const char* kHeader =
    "step,time,kinetic,strain,contact,work_gravity,work_external,dissipated_viscous,"
    "dissipated_contact,total,energy_error,active_contacts";

TEST(HistoryWriter, HeaderAndBitExactRowsFlushedAtOnce) {
    const fs::path file = test_file("history.csv");
    const Model m;
    State s;
    HistoryWriter h(file.string());
    EXPECT_EQ(read_lines(file), std::vector<std::string>{kHeader});

    // row 0: values that need all 17 digits to round-trip
    s.step = 0;
    s.time = 0.1 + 0.2;
    s.energy.kinetic = 1.0 / 3.0;
    s.energy.strain = 2.0 / 7.0;
    s.energy.contact = 1e-300;
    s.energy.work_gravity = 0.125;
    s.energy.work_external = -0.5;
    s.energy.dissipated_viscous = 3.0;
    s.energy.dissipated_contact = 1e20;
    s.contact.active_contacts = 5;
    h.write(m, s);
    const Real total0 = s.energy.total();

    // row 1: energy moved between terms and a drift of 0.25 J/m (exact in binary)
    s.step = 100;
    s.time = 1e-3;
    s.energy.kinetic = 0.0;
    s.energy.dissipated_viscous = 3.0 + 1.0 / 3.0 + 0.25;
    s.contact.active_contacts = 0;
    h.write(m, s);
    const Real total1 = s.energy.total();

    // no close: every row must already be on disk (flushed per row)
    const auto lines = read_lines(file);
    ASSERT_EQ(lines.size(), 3u);
    const auto r0 = split(lines[1]);
    const auto r1 = split(lines[2]);
    ASSERT_EQ(r0.size(), 12u);
    ASSERT_EQ(r1.size(), 12u);

    EXPECT_EQ(r0[0], "0");
    EXPECT_EQ(std::strtod(r0[1].c_str(), nullptr), 0.1 + 0.2);
    EXPECT_EQ(std::strtod(r0[2].c_str(), nullptr), 1.0 / 3.0);
    EXPECT_EQ(std::strtod(r0[3].c_str(), nullptr), 2.0 / 7.0);
    EXPECT_EQ(std::strtod(r0[4].c_str(), nullptr), 1e-300);
    EXPECT_EQ(std::strtod(r0[5].c_str(), nullptr), 0.125);
    EXPECT_EQ(std::strtod(r0[6].c_str(), nullptr), -0.5);
    EXPECT_EQ(std::strtod(r0[7].c_str(), nullptr), 3.0);
    EXPECT_EQ(std::strtod(r0[8].c_str(), nullptr), 1e20);
    EXPECT_EQ(std::strtod(r0[9].c_str(), nullptr), total0);
    EXPECT_EQ(r0[10], "0");  // energy_error is relative to the first row
    EXPECT_EQ(r0[11], "5");

    EXPECT_EQ(r1[0], "100");
    EXPECT_EQ(std::strtod(r1[9].c_str(), nullptr), total1);
    EXPECT_EQ(std::strtod(r1[10].c_str(), nullptr), total1 - total0);
    EXPECT_EQ(r1[11], "0");
}

TEST(HistoryWriter, EnergyErrorIsDriftOfTheBalance) {
    // kinetic -> strain exchange conserves the total; a 0.5 J/m gravity work without a matching
    // energy gain shows up as energy_error = -0.5 (total = ... - work_gravity)
    const fs::path file = test_file("history.csv");
    const Model m;
    State s;
    HistoryWriter h(file.string());
    s.energy.kinetic = 4.0;
    h.write(m, s);
    s.energy.kinetic = 1.0;
    s.energy.strain = 3.0;
    h.write(m, s);
    s.energy.work_gravity = 0.5;
    h.write(m, s);
    const auto lines = read_lines(file);
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(split(lines[1])[10], "0");
    EXPECT_EQ(split(lines[2])[10], "0");
    EXPECT_EQ(split(lines[3])[10], "-0.5");
    EXPECT_EQ(split(lines[3])[9], "3.5");
}

TEST(HistoryWriter, UnwritablePathIsASimulationError) {
    const fs::path file = test_file("x") / "missing_dir" / "history.csv";
    try {
        HistoryWriter h(file.string());
        FAIL() << "expected SimulationError";
    } catch (const SimulationError& e) {
        EXPECT_NE(std::string(e.what()).find("missing_dir/history.csv"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace fdem

namespace fdem {
namespace {

// A model with joints: seven more columns after the pinned ones, with the joint energy, W_frac,
// softening and broken counts, the crack length (sum of h_0 of broken joints), the number of
// fragments (triangles that label their own fragment) and the largest fragment's share of the
// fracture bodies' mass. Body 0 (fracture): triangles 0 and 1 share nodes 1, 2 (fragment 0,
// nodes 0-3, mass 1 + 2 + 3 + 4 = 10), triangle 2 alone (nodes 4-6, 3 x 0.5 = 1.5), triangles 3
// and 4 joined by a joint (fragment 3, nodes 7-12, 6 x 1 = 6); body 1 (no fracture, mass 3000)
// is a fragment too but not in the fraction: 10 / 17.5 = 4/7.
TEST(History, FractureColumns) {
    const fs::path dir = fs::path(::testing::TempDir()) / "fdem_history_fracture";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path p = dir / "history.csv";
    Model m;
    m.joints.nodes = {{0, 1, 2, 3}, {0, 1, 2, 3}, {0, 1, 2, 3}};
    m.joints.length0 = {0.5, 0.25, 2.0};
    m.node_x0.assign(16, Vec2{0, 0});
    m.node_mass = {1, 2, 3, 4, 0.5, 0.5, 0.5, 1, 1, 1, 1, 1, 1, 1000, 1000, 1000};
    m.tri_nodes = {{0, 1, 2}, {1, 3, 2}, {4, 5, 6}, {7, 8, 9}, {10, 11, 12}, {13, 14, 15}};
    Body b0;
    b0.fracture = true;
    b0.node_end = 13;
    b0.tri_end = 5;
    Body b1;
    b1.node_begin = 13;
    b1.node_end = 16;
    b1.tri_begin = 5;
    b1.tri_end = 6;
    m.bodies = {b0, b1};
    State s;
    s.energy.joint = 0.125;
    s.energy.fracture = 3.5;
    s.joints.status = {JointStatus::Broken, JointStatus::Softening, JointStatus::Broken};
    s.tri_fragment = {0, 0, 2, 3, 3, 5};
    {
        HistoryWriter w(p.string(), true);
        w.prepare(m);
        w.write(m, s);
    }
    const std::vector<std::string> lines = read_lines(p);
    ASSERT_EQ(lines.size(), 2u);
    const std::vector<std::string> head = split(lines[0]);
    const std::vector<std::string> row = split(lines[1]);
    ASSERT_EQ(head.size(), 19u);
    ASSERT_EQ(row.size(), 19u);
    EXPECT_EQ(head[11], "active_contacts");
    const std::vector<std::string> cols = {"energy.joint",  "energy.fracture", "joints.softening",
                                           "joints.broken", "crack_length",    "fragments"};
    const std::vector<std::string> vals = {"0.125", "3.5", "1", "2", "2.5", "4"};
    for (size_t k = 0; k < 6; ++k) {
        EXPECT_EQ(head[12 + k], cols[k]);
        EXPECT_EQ(row[12 + k], vals[k]) << cols[k];
    }
    EXPECT_EQ(head[18], "largest_fragment_mass_fraction");
    EXPECT_EQ(std::stod(row[18]), 4.0 / 7.0);  // %.17g reads back exact; 10/17.5 rounds as 4/7
}

}  // namespace
}  // namespace fdem
