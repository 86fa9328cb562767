// Checkpoints (io/checkpoint.hpp): a restart continues bit for bit, equal states give equal
// files, and foreign files (other model, format, version, corrupt) are refused with a message.
#include "io/checkpoint.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "fdem/error.hpp"
#include "fdem/scenario.hpp"
#include "fdem/simulate.hpp"
#include "fdem/version.hpp"
#include "support/hash.hpp"
#include "support/scenes.hpp"

namespace fdem {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// Two bodies in frictional contact (tests/cli/restart.toml in small): a block thrown at
// (1, -1) m/s onto a fixed base lands after ~7 ms and slides under friction mu = 0.4.
const char* kScene = R"(
[simulation]
end_time = 0.02
dt = "auto"
dt_fraction = 0.3
gravity = [0.0, -9.81]
[[material]]
name = "rubber"
density = 1000.0
youngs_modulus = 1.0e7
poisson_ratio = 0.2
damping_ratio = 0.2
[[body]]
name = "base"
mesh = "block_on_base.geo"
mesh_size = 0.1
group = "base"
material = "rubber"
fixed = true
[[body]]
name = "block"
mesh = "block_on_base.geo"
mesh_size = 0.1
group = "block"
material = "rubber"
velocity = [1.0, -1.0]
[contact]
algorithm = "smooth"
friction = 0.4
damping = 2.0e4
damp_normal_only = true
)";

std::string temp_path(const std::string& name) {
    return (fs::temp_directory_path() / ("fdem_checkpoint_test_" + name)).string();
}

std::vector<unsigned char> read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<unsigned char>& b) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

/// The checkpoint trailer is FNV-1a of the bytes before it (to forge files with a valid checksum).
void fix_trailer(std::vector<unsigned char>& b) {
    const uint64_t h = scenes::fnv1a(b.data(), b.size() - 8);
    std::memcpy(b.data() + b.size() - 8, &h, 8);
}

bool same_bits(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec2)) == 0;
}

class CheckpointTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        sc_ = new Scenario(load_scenario_from_string(kScene, "scene.toml", FDEM_TEST_DATA_DIR));
    }
    static void TearDownTestSuite() {
        delete sc_;
        sc_ = nullptr;
    }
    static const Model& model() { return sc_->model; }
    static Real dt() { return sc_->run.dt; }
    static Scenario* sc_;
};
Scenario* CheckpointTest::sc_ = nullptr;

// The restart must reproduce the uninterrupted run exactly, with the friction springs and the
// contact candidates of the checkpoint step carried over.
TEST_F(CheckpointTest, RestartIsBitwiseIdenticalWithFrictionalContact) {
    const Model& m = model();
    // checkpoint 50 steps into the contact (landing at t ~ 10 ms), then 200 more steps
    State a = make_state(m, dt());
    while (a.contact.active_contacts == 0 && a.step < 5000)
        step(m, a);
    for (int i = 0; i < 50; ++i)
        step(m, a);
    const int64_t n_ckpt = a.step, n_total = a.step + 200;
    ASSERT_GT(a.contact.active_contacts, 0) << "the checkpoint must be taken during contact";
    bool sliding = false;
    for (const ActiveContact& c : a.contact.active)
        sliding = sliding || c.h.s != 0;
    ASSERT_TRUE(sliding) << "friction springs must carry history across the checkpoint";

    State ref = make_state(m, dt());
    while (ref.step < n_total)
        step(m, ref);

    RunProgress p;
    p.frame = 7;
    p.next_output = 0.125;
    p.energy = {true, 1.5, 2.5, 0.25};
    p.frames = {{0.0, "frame_000000.vtu"}, {0.01, "frame_000001.vtu"}};
    const std::string path = temp_path("restart.fdck");
    write_checkpoint(path, m, a, p);

    State b = make_state(m, dt());
    RunProgress q;
    read_checkpoint(path, m, b, q);
    EXPECT_EQ(b.step, n_ckpt);
    EXPECT_EQ(q.frame, 7);
    EXPECT_EQ(q.next_output, 0.125);
    EXPECT_EQ(q.energy.e0, 1.5);
    EXPECT_EQ(q.energy.max_error, 0.25);
    EXPECT_EQ(q.frames, p.frames);
    while (b.step < n_total)
        step(m, b);

    EXPECT_TRUE(same_bits(ref.x, b.x));
    EXPECT_TRUE(same_bits(ref.v, b.v));
    EXPECT_TRUE(same_bits(ref.f, b.f));
    EXPECT_EQ(std::memcmp(&ref.energy, &b.energy, sizeof(Energy)), 0);
    EXPECT_EQ(state_hash(ref), state_hash(b));
    EXPECT_EQ(ref.time, b.time);
    EXPECT_EQ(ref.contact.active_contacts, b.contact.active_contacts);
    fs::remove(path);
}

// No padding or uninitialised bytes reach the file: the same state gives the same bytes.
// Reading a checkpoint writes f_contact at every node, so the next step must clear every node
// (ContactState::fc_sparse false), not only the nodes the state's last applies reached: else
// the file's contact forces at other nodes would stay in f_contact (and in bodies.csv).
TEST(CheckpointContactForces, ReadingIntoARunningStateClearsEveryContactForce) {
    scenes::ParticleOptions o;
    o.nx = o.ny = 12;
    const Model m = scenes::make_particle_box(o);
    const Real dt = 0.5 * stable_time_step(m);
    State a = make_state(m, dt);
    while ((a.contact.active_contacts < 3 || !a.contact.fc_sparse) && a.step < 3000)
        step(m, a);
    ASSERT_GE(a.contact.active_contacts, 3);
    ASSERT_TRUE(a.contact.fc_sparse);
    const std::string path = temp_path("contact_forces.fdck");
    write_checkpoint(path, m, a, {});
    const std::vector<NodeId> at_checkpoint = a.contact.fc_nodes;
    for (int k = 0; k < 300; ++k)  // on: other pairs, another list
        step(m, a);
    ASSERT_TRUE(a.contact.fc_sparse);
    ASSERT_NE(a.contact.fc_nodes, at_checkpoint);
    RunProgress q;
    read_checkpoint(path, m, a, q);  // into the running state
    EXPECT_FALSE(a.contact.fc_sparse);
    State b = make_state(m, dt);
    read_checkpoint(path, m, b, q);
    for (int k = 0; k < 50; ++k) {
        step(m, a);
        step(m, b);
        ASSERT_TRUE(same_bits(a.f_contact, b.f_contact)) << "step " << k;
    }
    EXPECT_TRUE(same_bits(a.x, b.x));
    fs::remove(path);
}

TEST_F(CheckpointTest, EqualStatesGiveEqualFiles) {
    const Model& m = model();
    State s = make_state(m, dt());
    for (int i = 0; i < 250; ++i)
        step(m, s);
    const std::string p1 = temp_path("eq1.fdck"), p2 = temp_path("eq2.fdck");
    write_checkpoint(p1, m, s, {});
    State t = make_state(m, dt());
    RunProgress q;
    read_checkpoint(p1, m, t, q);
    write_checkpoint(p2, m, t, q);
    EXPECT_EQ(read_bytes(p1), read_bytes(p2));
    fs::remove(p1);
    fs::remove(p2);
}

std::string restart_error(const std::string& path, const Model& m, Real dt) {
    State s = make_state(m, dt);
    RunProgress p;
    try {
        read_checkpoint(path, m, s, p);
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "--restart");
        return e.what();
    }
    return "no error";
}

TEST_F(CheckpointTest, RefusesAnotherTimeStep) {
    const Model& m = model();
    const std::string path = temp_path("dt.fdck");
    write_checkpoint(path, m, make_state(m, dt()), {});
    EXPECT_THAT(restart_error(path, m, 0.5 * dt()),
                HasSubstr("it was written for a different model or time step"));
    fs::remove(path);
}

TEST_F(CheckpointTest, RefusesAnotherModel) {
    const std::string path = temp_path("model.fdck");
    write_checkpoint(path, model(), make_state(model(), dt()), {});
    Model other = model();
    other.gravity = {0.0, -9.80};
    EXPECT_THAT(restart_error(path, other, dt()),
                HasSubstr("it was written for a different model or time step (model hash"));
    fs::remove(path);
}

// The same 6-node mesh run as composites or as 4 plain CSTs per element has identical node and
// triangle arrays; only Body::element differs, and a restart across that switch must be refused.
TEST(CheckpointModelHash, DependsOnTheElementKind) {
    auto build = [](ElementKind kind) {
        Model m;
        m.materials.push_back(scenes::paper_material("rock", 1e9, 0.3));
        scenes::add_rectangle_order2(m, 0, 0, 1, 0.5, 2, 1, 0, kind);
        finalize_model(m);
        return m;
    };
    const Model composite = build(ElementKind::Composite6);
    const Model cst = build(ElementKind::Cst);
    ASSERT_EQ(composite.tri_nodes, cst.tri_nodes);  // the premise: only the kind differs
    EXPECT_NE(model_hash(composite, build_topology(composite), 1e-6),
              model_hash(cst, build_topology(cst), 1e-6));
}

// Layout: 8 magic bytes, u32 format, u32 endian marker, u64 length + version string.
TEST_F(CheckpointTest, RefusesAnotherFormatAndVersion) {
    const std::string path = temp_path("version.fdck");
    write_checkpoint(path, model(), make_state(model(), dt()), {});
    const std::vector<unsigned char> good = read_bytes(path);

    std::vector<unsigned char> b = good;
    const uint32_t format = kCheckpointFormat + 1;
    std::memcpy(b.data() + 8, &format, 4);
    fix_trailer(b);
    write_bytes(path, b);
    EXPECT_THAT(restart_error(path, model(), dt()),
                HasSubstr(fmt::format("checkpoint format {} is not supported by this fdem "
                                      "(format {})",
                                      kCheckpointFormat + 1, kCheckpointFormat)));

    // a checkpoint of the previous format (5: without the controls of State) is refused too
    b = good;
    const uint32_t old_format = kCheckpointFormat - 1;
    std::memcpy(b.data() + 8, &old_format, 4);
    fix_trailer(b);
    write_bytes(path, b);
    EXPECT_THAT(restart_error(path, model(), dt()),
                HasSubstr(fmt::format("checkpoint format {} is not supported by this fdem "
                                      "(format {})",
                                      kCheckpointFormat - 1, kCheckpointFormat)));

    b = good;
    b[24] = '9';  // first character of the version string
    fix_trailer(b);
    write_bytes(path, b);
    EXPECT_THAT(restart_error(path, model(), dt()),
                HasSubstr(std::string("this is fdem ") + FDEM_VERSION + "; rerun from t = 0"));
    fs::remove(path);
}

// A field added to State or ContactState changes these sizes: decide whether it carries
// information between steps, save it in checkpoint.cpp (put_state / read_checkpoint) if so, bump
// kCheckpointFormat, then update the sizes here (x86-64, libstdc++).
TEST(CheckpointLayout, StateStructsAreTheOnesTheCheckpointKnows) {
    // 48 -> 64: PairHistory::f_damp (the previous damping force, trapezoidal damping work,
    // theory eq. 6.10), saved since format 4
    // 64 -> 72: PairHistory::d0 (birth depth of a self pair, theory eq. 9.25), saved since
    // format 9
    // 72: PairHistory::sub (the last located sub-triangle, theory eq. 9.27) fills the padding
    // after unloading, saved since format 10
    EXPECT_EQ(sizeof(PairHistory), 72u) << "PairHistory changed: update io/checkpoint.cpp";
    EXPECT_EQ(sizeof(LegacyCouple), 56u) << "LegacyCouple changed: update io/checkpoint.cpp";
    EXPECT_EQ(sizeof(LegacyTriangleState), 320u)
        << "LegacyTriangleState changed: update io/checkpoint.cpp";
    // 768 -> 800 (State 1016 -> 1048): ContactState::body_box (per-step scratch of the narrow
    // phase's early reject) and box_reject (a test switch, default on) are not saved: neither
    // carries information between steps, and the reject does not change any result
    // 800 -> 824: ContactState::in_contact, the narrow phase's own list of pairs in contact
    // (per-step scratch, not saved), which it used to share with the broad phase (query, now
    // ContactState::broad.query, saved as before); the candidates and grid moved into
    // ContactState::cand / ::broad unchanged
    // 824 -> 848: ContactState::xw, the welded contactor positions of the step (theory eq.
    // 6.23; rewritten from x by every contact evaluation before it is read, not saved)
    // 848 -> 904: ContactState::rebase, rebase_body, rebase_pending (theory eq. 9.26: the old
    // topology's law depths, written by a break's rebuild and consumed by the contact pass of
    // the same step; empty or false between steps, not saved)
    // 904 -> 928: ContactState::apply_part (scratch of the contact apply with 2+ threads: the
    // per-thread sums of the step, not saved)
    // 928 -> 976: BroadPhaseScratch::part, part_hits (the per-thread lists of the parallel
    // queries, scratch, not saved)
    // 976 -> 1024: ContactState::box_bodies, box_mark, box_list_valid (the contactor bodies of
    // the candidates, whose boxes the narrow phase computes; scratch, cleared where the
    // candidates are read from a checkpoint, not saved)
    // 1024 -> 1056: ContactState::fc_nodes, fc_sparse (the nodes whose f_contact the last
    // applies reached, which the next step clears; scratch: reading a checkpoint writes
    // f_contact and sets fc_sparse false, not saved)
    // 1056 -> 1080: ContactState::xa (contactor positions by contact id for the locate loop;
    // filled every step by update_virtual_nodes(), scratch, not saved)
    // 1080 -> 1104: ContactState::apply_to (the threads' lists of the pairs whose forces reach
    // each thread's node range in the apply; per-step scratch, not saved)
    // 1104 -> 1128: ContactState::fc_mark (per-node marks of the fc_nodes listing, all zero
    // between applies; scratch, not saved)
    // 1128 -> 1232: ContactState::apply_to replaced by apply_lists (the slices and foreign
    // lists of the apply with 2+ threads, a function of the candidates built by the first apply
    // after a broad phase; scratch, cleared where the candidates are read, not saved)
    // 1232 -> 1256: ContactApplyLists::range_lo (the threads' node ranges, built with the lists;
    // scratch, not saved)
    EXPECT_EQ(sizeof(ContactState), 1256u) << "ContactState changed: update io/checkpoint.cpp";
    // 1048 -> 1072: State::scratch_load (the load forces of the current step, rewritten at the
    // start of every step from x^n; not saved)
    // 1072 -> 1096: State::bc_reaction (the supports' reactions of the last step, rewritten by
    // every step before bodies.csv reads them after it) is not saved
    // 1096 -> 1120: ContactState 800 -> 824 above
    // 1120 -> 1168: State::bc_velocity, bc_enabled (the controls), saved since format 6
    // 1168 -> 1864: State::topology (the contact topology, moved from the Model): not saved, a
    // function of the Model rebuilt by make_state() before the file is read; the model hash
    // covers the arrays it was built with
    // 1864 -> 2176: Energy::joint, fracture (saved since format 7); State::joints (JointState),
    // tri_fragment, node_sector (issue #14): empty until fracture is wired into the run; the
    // fracture wiring saves the joint history and rebuilds tri_fragment / node_sector from it
    // 2176 -> 2224: ContactTopology::body_self, node_weld (welded topology of bodies with
    // fracture, theory §6.15): part of State::topology, not saved (rebuilt from the Model and
    // State::node_sector)
    // 2224 -> 2368: ContactState 824 -> 848 above; ContactTopology::weld_group,
    // weld_group_begin, weld_copy, weld_share, weld_plain (theory eq. 6.23): part of
    // State::topology, not saved
    // 2368 -> 2424: ContactState 848 -> 904 above
    // 2424 -> 4632: State::energy_sums (3 ExactSum of 552 B) and JointState::total_work_sum,
    // the exact running sums of the integrated energies (theory §4.4), saved since format 11
    EXPECT_EQ(sizeof(ExactSum), 552u) << "ExactSum changed: update io/checkpoint.cpp";
    // 4632 -> 4704: ContactState 904 -> 976 above
    // 4704 -> 4752: ContactState 976 -> 1024 above
    // 4752 -> 4784: ContactState 1024 -> 1056 above
    // 4784 -> 4808: ContactState 1056 -> 1080 above
    // 4808 -> 4832: ContactState 1080 -> 1104 above
    // 4832 -> 4856: JointState::z_max, z(D_max) per joint point (theory §9.4): a cache of a
    // function of the saved d_max, not saved (the restore recomputes it)
    // 4856 -> 4904: JointState::dn_max, ds_max, the per-mode damage history of
    // mixed_mode = "proportional" (theory eq. 9.30), saved since format 12
    // 4904 -> 4952: JointState::an_min, as_min, the smallest shares reached (theory eq. 9.32),
    // saved since format 13
    // 4952 -> 4976: ContactState 1104 -> 1128 above
    // 4976 -> 5056: State::timing (wall time per phase of the steps; not saved: no part of the
    // run's state, restore_checkpoint() keeps the running one)
    // 5056 -> 5160: ContactState 1128 -> 1232 above
    // 5160 -> 5184: ContactState 1232 -> 1256 above
    // 5184 -> 5208: JointState::block_wait (which blocks of damaged joints go joint by joint for
    // a while: the choice of a path, which changes no bit; scratch, not saved)
    EXPECT_EQ(sizeof(State), 5208u) << "State changed: update io/checkpoint.cpp";
}

// Loads (theory §4.1): the half of the load work that belongs after t^n travels in
// work_external_pending, so a restart in the middle of a ramp is bitwise the uninterrupted run;
// another load is another model.
TEST(CheckpointLoads, RestartIsBitwiseIdenticalUnderAFollowerPressure) {
    const std::string text = R"([simulation]
end_time = 1.0
dt = 1e-5
[[material]]
name = "m"
density = 1000.0
youngs_modulus = 1e9
poisson_ratio = 0.25
[[body]]
name = "bar"
mesh = "loaded_bar.geo"
mesh_size = 0.05
material = "m"
[[load]]
body = "bar"
group = "right"
pressure = 1e6
time_function = "table"
table = [[0, 0], [0.004, 1]]
[[load]]
body = "bar"
group = "tip"
force = [0, 1e4]
)";
    const Scenario sc = load_scenario_from_string(text, "loads.toml", FDEM_TEST_DATA_DIR);
    const Model& m = sc.model;
    State ref = make_state(m, sc.run.dt);
    while (ref.step < 400)
        step(m, ref);
    State a = make_state(m, sc.run.dt);
    while (a.step < 250)
        step(m, a);
    ASSERT_NE(a.energy.work_external_pending, 0.0);
    const std::string path = temp_path("loads.fdck");
    write_checkpoint(path, m, a, {});
    State b = make_state(m, sc.run.dt);
    RunProgress q;
    read_checkpoint(path, m, b, q);
    while (b.step < 400)
        step(m, b);
    EXPECT_TRUE(same_bits(ref.x, b.x));
    EXPECT_TRUE(same_bits(ref.v, b.v));
    EXPECT_EQ(std::memcmp(&ref.energy, &b.energy, sizeof(Energy)), 0);

    std::string other = text;
    other.replace(other.find("pressure = 1e6"), 14, "pressure = 2e6");
    const Scenario sc2 = load_scenario_from_string(other, "loads.toml", FDEM_TEST_DATA_DIR);
    EXPECT_NE(model_hash(sc2.model, build_topology(sc2.model), sc.run.dt),
              model_hash(m, build_topology(m), sc.run.dt));
    fs::remove(path);
}

// Baseline A keeps its own history (couples with per-edge sliding distances): same contract.
TEST(CheckpointLegacy, RestartIsBitwiseIdenticalWithBaselineA) {
    std::string text = kScene;
    text.replace(text.find("\"smooth\""), 8, "\"legacy-triangle\"");
    const Scenario sc = load_scenario_from_string(text, "scene.toml", FDEM_TEST_DATA_DIR);
    const Model& m = sc.model;
    const int64_t n_total = 500, n_ckpt = 300;
    State ref = make_state(m, sc.run.dt);
    while (ref.step < n_total)
        step(m, ref);
    State a = make_state(m, sc.run.dt);
    while (a.step < n_ckpt)
        step(m, a);
    bool sliding = false;
    for (const LegacyCouple& c : a.contact.legacy.couples)
        for (Real sl : c.slide)
            sliding = sliding || sl != 0;
    ASSERT_TRUE(sliding) << "the checkpoint must carry baseline A sliding history";
    const std::string path = temp_path("legacy.fdck");
    write_checkpoint(path, m, a, {});
    State b = make_state(m, sc.run.dt);
    RunProgress q;
    read_checkpoint(path, m, b, q);
    while (b.step < n_total)
        step(m, b);
    EXPECT_TRUE(same_bits(ref.x, b.x));
    EXPECT_TRUE(same_bits(ref.v, b.v));
    EXPECT_EQ(std::memcmp(&ref.energy, &b.energy, sizeof(Energy)), 0);
    fs::remove(path);
}

// The controls (State::bc_velocity, bc_enabled) are part of the state: a checkpoint written right
// after a caller changed them restarts into a run that is bitwise the uninterrupted one.
TEST(CheckpointControls, RestartAfterAControlChangeIsBitwise) {
    scenes::BlockOptions o;
    o.num_tris = 512;
    o.clamp = true;
    o.gravity = true;
    Model m = scenes::make_block(o);
    m.bcs[0].velocity = {0.05, 0.0};  // bottom edge driven in x
    BoundaryCondition top;            // top edge held in x
    top.name = "top";
    top.nodes = scenes::select_nodes(m, 0, [](Vec2 p) { return p.y > 1 - 1e-12; });
    top.has_x = true;
    ASSERT_FALSE(top.nodes.empty());
    m.bcs.push_back(top);
    const Real dt = 0.5 * stable_time_step(m);
    const int64_t n_ckpt = 100, n_total = 300;

    State ref = make_state(m, dt);
    State a = make_state(m, dt);
    for (State* s : {&ref, &a}) {
        while (s->step < n_ckpt)
            step(m, *s);
        s->bc_velocity[0] = {-0.02, 0.03};
        s->bc_enabled[1] = 0;
    }
    while (ref.step < n_total)
        step(m, ref);
    const std::string path = temp_path("controls.fdck");
    write_checkpoint(path, m, a, {});

    State b = make_state(m, dt);  // controls as in the Model
    RunProgress q;
    read_checkpoint(path, m, b, q);
    EXPECT_EQ(b.bc_velocity[0].x, -0.02);
    EXPECT_EQ(b.bc_velocity[0].y, 0.03);
    EXPECT_EQ(b.bc_enabled[0], 1);
    EXPECT_EQ(b.bc_enabled[1], 0);
    while (b.step < n_total)
        step(m, b);
    EXPECT_TRUE(same_bits(ref.x, b.x));
    EXPECT_TRUE(same_bits(ref.v, b.v));
    EXPECT_EQ(std::memcmp(&ref.energy, &b.energy, sizeof(Energy)), 0);
    EXPECT_EQ(state_hash(ref), state_hash(b));

    // the same run without the change differs (the comparison above means something)
    State c = make_state(m, dt);
    while (c.step < n_total)
        step(m, c);
    EXPECT_NE(state_hash(c), state_hash(b));

    // a flag other than 0/1 is a corrupt file
    State bad = a;
    bad.bc_enabled[1] = 2;
    write_checkpoint(path, m, bad, {});
    EXPECT_THAT(restart_error(path, m, dt), HasSubstr("bc_enabled is neither 0 nor 1"));
    fs::remove(path);
}

// Every truncation point is refused with a message, never a crash.
TEST_F(CheckpointTest, EveryTruncationIsRefused) {
    const std::string path = temp_path("trunc.fdck");
    write_checkpoint(path, model(), make_state(model(), dt()), {});
    const std::vector<unsigned char> good = read_bytes(path);
    for (size_t n = 0; n < good.size(); n += 1 + n / 8) {
        write_bytes(path, std::vector<unsigned char>(good.begin(), good.begin() + n));
        EXPECT_THAT(restart_error(path, model(), dt()), HasSubstr("is unusable")) << n;
    }
    fs::remove(path);
}

}  // namespace
}  // namespace fdem
