// Fracture output (src/fdem/io/fracture_output.cpp, spec fracture.md §8, docs/output.md): a
// jointed bar read from a scenario, pulled apart by its end supports until joints break. Checks
// cracks.csv against the joint state, fragments.csv against the bar's mass (rho x area, not a
// sum the code under test makes), the joint and frame VTU files with the real VTK reader
// (/usr/bin/python3 + python3-vtk9), and that a restart reproduces the files of an
// uninterrupted run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "fdem/scenario.hpp"
#include "fdem/simulation.hpp"
#include "io/fracture_output.hpp"
#include "support/csv.hpp"

namespace fdem {
namespace {

namespace fs = std::filesystem;
using testing::read_csv;

// Bar [0, 1] x [0, 0.1] m (tests/data/loaded_bar.geo), every internal edge jointed; ends pulled
// at 0.05 m/s each: the stress reaches f_t = 1 MPa (strain f_t/E = 1e-3) after ~0.01 s, the first
// joints break at ~0.012 s.
constexpr Real kDensity = 2700, kArea = 1.0 * 0.1;
const std::string kScenario = R"([simulation]
end_time = 0.02
dt = 4e-6
[output]
interval = 0.002
[[material]]
name = "rock"
density = 2700.0
youngs_modulus = 1.0e9
poisson_ratio = 0.0
[material.fracture]
tensile_strength = 1.0e6
cohesion = 4.0e6
friction_angle = 30.0
fracture_energy_I = 10.0
fracture_energy_II = 100.0
penalty = 1.0e10
[[body]]
name = "bar"
mesh = "loaded_bar.geo"
mesh_size = 0.05
material = "rock"
[[boundary]]
body = "bar"
group = "left"
velocity = [-0.05, 0.0]
components = ["x"]
[[boundary]]
body = "bar"
group = "right"
velocity = [0.05, 0.0]
components = ["x"]
)";

Simulation make_sim(const std::string& text = kScenario) {
    return Simulation(load_scenario_from_string(text, "bar.toml", FDEM_TEST_DATA_DIR));
}

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) / name;
    fs::remove_all(dir);
    return dir;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string run_command(const std::string& cmd, int* status) {
    std::FILE* p = popen(cmd.c_str(), "r");
    std::string text;
    if (p == nullptr) {
        *status = -1;
        return text;
    }
    char buf[512];
    while (std::fgets(buf, sizeof buf, p) != nullptr)
        text += buf;
    *status = pclose(p);
    return text;
}

TEST(FractureOutput, PulledBarWritesCracksFragmentsAndJointFrames) {
    const fs::path dir = fresh_dir("fdem_fracture_output");
    Simulation sim = make_sim();
    sim.open_output(dir.string());
    sim.run_to_end();
    const Model& m = sim.model();
    const State& s = sim.state();
    ASSERT_GT(m.joints.num_joints(), 0);
    int32_t broken = 0, damaged = 0;
    for (const JointStatus st : s.joints.status) {
        broken += st == JointStatus::Broken ? 1 : 0;
        damaged += st != JointStatus::Intact ? 1 : 0;
    }
    ASSERT_GT(broken, 1) << "the bar must break for this test to mean anything";

    // cracks.csv: one row per broken joint, each matching the joint state, joint-id order per step
    const auto cracks = read_csv((dir / "cracks.csv").string());
    ASSERT_FALSE(cracks.empty());
    EXPECT_EQ(cracks[0],
              (std::vector<std::string>{"step", "time", "joint", "x", "y", "h", "mode", "work"}));
    EXPECT_EQ(static_cast<int32_t>(cracks.size()) - 1, broken);
    std::set<int32_t> seen;
    int64_t last_step = -1;
    int32_t last_joint = -1;
    for (size_t r = 1; r < cracks.size(); ++r) {
        const auto& row = cracks[r];
        ASSERT_EQ(row.size(), 8u);
        const int64_t step = std::stoll(row[0]);
        const int32_t j = std::stoi(row[2]);
        const auto k = static_cast<size_t>(j);
        EXPECT_TRUE(seen.insert(j).second) << "joint " << j << " listed twice";
        EXPECT_EQ(s.joints.status[k], JointStatus::Broken);
        EXPECT_EQ(s.joints.break_step[k], step);
        EXPECT_NEAR(std::stod(row[1]), static_cast<double>(step) * s.dt, 1e-9 * s.time);
        EXPECT_EQ(std::stoi(row[6]), static_cast<int>(s.joints.mode[k]));
        EXPECT_NE(std::stoi(row[6]), 0);
        EXPECT_EQ(std::stod(row[5]), m.joints.length0[k]);
        EXPECT_GT(std::stod(row[7]), 0.0);  // W_J at breaking: positive work
        // the mid-point lies on the bar (it is pulled apart along x only by ~2 mm)
        EXPECT_GT(std::stod(row[3]), -0.01);
        EXPECT_LT(std::stod(row[3]), 1.01);
        EXPECT_GE(std::stod(row[4]), -1e-6);
        EXPECT_LE(std::stod(row[4]), 0.1 + 1e-6);
        EXPECT_TRUE(step > last_step || (step == last_step && j > last_joint));
        last_step = step;
        last_joint = j;
    }

    // fragments.csv: per output time a summary row and rows whose masses add up to rho x area
    const auto frag = read_csv((dir / "fragments.csv").string());
    ASSERT_GT(frag.size(), 1u);
    ASSERT_EQ(frag[0].size(), 14u);
    EXPECT_EQ(frag[0][2], "fragment");
    struct Sum {
        Real mass = 0, summary_mass = 0;
        int64_t tris = 0, rows = 0, count = -1;
    };
    std::map<int64_t, Sum> per_step;
    for (size_t r = 1; r < frag.size(); ++r) {
        const auto& row = frag[r];
        ASSERT_EQ(row.size(), 14u);
        Sum& sum = per_step[std::stoll(row[0])];
        const int64_t id = std::stoll(row[2]);
        const Real mass = std::stod(row[4]), area = std::stod(row[5]);
        EXPECT_NEAR(std::stod(row[6]), std::sqrt(4 * area / M_PI), 1e-15);
        if (id < 0) {
            sum.summary_mass = mass;
            sum.count = std::stoll(row[12]);
            continue;
        }
        sum.mass += mass;
        sum.tris += std::stoll(row[3]);
        ++sum.rows;
    }
    EXPECT_EQ(static_cast<int64_t>(per_step.size()), sim.frames_written());
    const Real total = kDensity * kArea;
    for (const auto& [step, sum] : per_step) {
        EXPECT_NEAR(sum.mass, total, 1e-12 * total) << "step " << step;
        EXPECT_NEAR(sum.summary_mass, total, 1e-12 * total) << "step " << step;
        EXPECT_EQ(sum.tris, m.num_tris());
        EXPECT_EQ(sum.rows, sum.count);
    }
    std::set<TriId> ids(s.tri_fragment.begin(), s.tri_fragment.end());
    EXPECT_EQ(per_step.rbegin()->first, s.step);
    EXPECT_EQ(per_step.rbegin()->second.rows, static_cast<int64_t>(ids.size()));
    EXPECT_GT(ids.size(), 1u);

    // joint frames: one per frame, listed in joints.pvd
    const std::string pvd = slurp(dir / "joints.pvd");
    for (int64_t f = 0; f < sim.frames_written(); ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "joints_%06lld.vtu", static_cast<long long>(f));
        EXPECT_TRUE(fs::exists(dir / name)) << name;
        EXPECT_NE(pvd.find(name), std::string::npos) << name;
    }

    // the real VTK reader: arrays, counts, states of the last joint frame and the last frame
    char last[64];
    std::snprintf(last, sizeof last, "%06lld", static_cast<long long>(sim.frames_written() - 1));
    const fs::path script = dir / "check.py";
    std::ofstream(script) << R"(import sys
from vtkmodules.vtkCommonCore import vtkObject
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy
vtkObject.GlobalWarningDisplayOff()
def read(path):
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    if r.GetErrorCode() != 0:
        sys.exit("read error " + path)
    return r.GetOutput()
g = read(sys.argv[1])
cd = g.GetCellData()
names = [cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())]
print("joints", g.GetNumberOfCells(), g.GetNumberOfPoints(), ",".join(names))
print("lines", all(g.GetCellType(i) == 3 for i in range(g.GetNumberOfCells())))
st = vtk_to_numpy(cd.GetArray("state"))
print("broken", int((st == 2).sum()), "softening", int((st == 1).sum()))
f = read(sys.argv[2])
fd = f.GetCellData()
frag = vtk_to_numpy(fd.GetArray("fragment"))
dmg = vtk_to_numpy(fd.GetArray("damage"))
print("frame", len(set(frag.tolist())), fd.GetArray("fragment").GetDataTypeAsString(),
      fd.GetArray("damage").GetDataTypeAsString(), float(dmg.max()))
)";
    int status = 0;
    const std::string out =
        run_command("/usr/bin/python3 " + script.string() + " " +
                        (dir / (std::string("joints_") + last + ".vtu")).string() + " " +
                        (dir / (std::string("frame_") + last + ".vtu")).string() + " 2>&1",
                    &status);
    ASSERT_EQ(status, 0) << out;
    std::ostringstream expect;
    expect << "joints " << damaged << " " << 2 * damaged
           << " joint,state,damage,mode,break_time,opening,slip,dissipated,length\n"
           << "lines True\n"
           << "broken " << broken << " softening " << damaged - broken << "\n"
           << "frame " << ids.size() << " int double 1.0\n";
    EXPECT_EQ(out, expect.str());
}

// The per-triangle damage is the largest D_max over the joints on the triangle's edges: the
// triangles on either side of a joint carry at least its damage, and joint_triangles finds two
// distinct triangles that both contain the joint's face nodes.
TEST(FractureOutput, JointTrianglesAndDamage) {
    Simulation sim = make_sim();
    sim.run(0.016);
    const Model& m = sim.model();
    const State& s = sim.state();
    const auto jt = joint_triangles(m);
    ASSERT_EQ(jt.size(), m.joints.nodes.size());
    for (size_t j = 0; j < jt.size(); ++j) {
        ASSERT_NE(jt[j][0], kNone);
        ASSERT_NE(jt[j][1], kNone);
        EXPECT_NE(jt[j][0], jt[j][1]);
        const auto& n = m.joints.nodes[j];
        const auto has = [&](TriId t, NodeId a) {
            const auto& tn = m.tri_nodes[static_cast<size_t>(t)];
            return tn[0] == a || tn[1] == a || tn[2] == a;
        };
        EXPECT_TRUE(has(jt[j][0], n[0]) && has(jt[j][0], n[1]));
        EXPECT_TRUE(has(jt[j][1], n[2]) && has(jt[j][1], n[3]));
    }
    std::vector<Real> d(static_cast<size_t>(m.num_tris()));
    triangle_damage(m, s, jt, d);
    std::vector<Real> expect(d.size(), 0.0);
    for (size_t j = 0; j < jt.size(); ++j) {
        const auto& dm = s.joints.d_max[j];
        const Real dj = std::max({dm[0], dm[1], dm[2]});
        for (const TriId t : jt[j])
            expect[static_cast<size_t>(t)] = std::max(expect[static_cast<size_t>(t)], dj);
    }
    EXPECT_EQ(d, expect);
    EXPECT_EQ(*std::max_element(d.begin(), d.end()), 1.0);
}

// A run checkpointed between breaks, continued past more breaks (as if killed later), then
// restarted from the checkpoint: cracks.csv and fragments.csv equal the uninterrupted run's.
TEST(FractureOutput, RestartKeepsTheFilesOfTheUninterruptedRun) {
    const fs::path ref_dir = fresh_dir("fdem_fracture_ref");
    {
        Simulation sim = make_sim();
        sim.open_output(ref_dir.string());
        sim.run_to_end();
    }
    const fs::path dir = fresh_dir("fdem_fracture_restart");
    const std::string ck = (dir / "mid.fdck").string();
    int64_t rows_at_checkpoint = 0;
    {
        Simulation sim = make_sim();
        sim.open_output(dir.string());
        sim.run(0.0125);
        sim.save_checkpoint(ck);
        rows_at_checkpoint = static_cast<int64_t>(read_csv((dir / "cracks.csv").string()).size());
        sim.run(0.017);
        ASSERT_GT(static_cast<int64_t>(read_csv((dir / "cracks.csv").string()).size()),
                  rows_at_checkpoint)
            << "breaks after the checkpoint are needed for this test";
    }
    ASSERT_GT(rows_at_checkpoint, 1) << "breaks before the checkpoint are needed for this test";
    {
        Simulation sim = make_sim();
        sim.open_output(dir.string());
        sim.restore_checkpoint(ck);
        sim.run_to_end();
    }
    EXPECT_EQ(slurp(dir / "cracks.csv"), slurp(ref_dir / "cracks.csv"));
    EXPECT_EQ(slurp(dir / "fragments.csv"), slurp(ref_dir / "fragments.csv"));
    EXPECT_EQ(slurp(dir / "joints.pvd"), slurp(ref_dir / "joints.pvd"));
}

// fragments = "end" writes the table once; output_joints = "none" writes no joint frames;
// a model without joints writes none of the fracture files.
TEST(FractureOutput, SettingsAndModelsWithoutJoints) {
    {
        std::string text =
            kScenario + "[fracture]\noutput_joints = \"none\"\nfragments = \"end\"\n";
        const fs::path dir = fresh_dir("fdem_fracture_settings");
        Simulation sim = make_sim(text);
        sim.open_output(dir.string());
        sim.run_to_end();
        EXPECT_FALSE(fs::exists(dir / "joints.pvd"));
        EXPECT_FALSE(fs::exists(dir / "joints_000000.vtu"));
        const auto frag = read_csv((dir / "fragments.csv").string());
        ASSERT_GT(frag.size(), 1u);
        for (size_t r = 1; r < frag.size(); ++r)
            EXPECT_EQ(std::stoll(frag[r][0]), sim.state().step);
        EXPECT_TRUE(fs::exists(dir / "cracks.csv"));
    }
    {
        std::string text = kScenario;
        const size_t a = text.find("[material.fracture]"), b = text.find("[[body]]");
        text.erase(a, b - a);
        text.replace(text.find("end_time = 0.02"), 15, "end_time = 0.001");
        const fs::path dir = fresh_dir("fdem_fracture_none");
        Simulation sim = make_sim(text);
        ASSERT_EQ(sim.model().joints.num_joints(), 0);
        sim.open_output(dir.string());
        sim.run_to_end();
        EXPECT_TRUE(fs::exists(dir / "frame_000000.vtu"));
        for (const char* f : {"cracks.csv", "fragments.csv", "joints.pvd", "joints_000000.vtu"})
            EXPECT_FALSE(fs::exists(dir / f)) << f;
        const std::string frame = slurp(dir / "frame_000000.vtu");
        EXPECT_EQ(frame.find("Name=\"fragment\""), std::string::npos);
        EXPECT_EQ(frame.find("Name=\"damage\""), std::string::npos);
    }
}

}  // namespace
}  // namespace fdem
