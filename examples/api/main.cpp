// fdem as a library: a program that builds or loads a model through the public API
// (include/fdem/*.hpp), runs it with fdem::Simulation (the CLI's run loop: run-time checks,
// output, checkpoints) and prints its energies and the state hash.
//
//   fdem_api_demo                         build a block dropped on a slab in code, run 0.1 s
//   fdem_api_demo SCENARIO [END_TIME [OUT]]  load a TOML scenario, run to its end time (or
//                                            END_TIME s); with OUT: output files and checkpoints
//
// With a scenario, the last line is "hash <16 hex digits>", the same hash as
//   fdem run SCENARIO --end-time END_TIME --quiet --print-hash
// because both perform the same steps (tests/package/tests.cmake compares the two).
// Exit codes as the CLI: 0 success, 1 simulation failure, 2 input error.
#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <fdem/fdem.hpp>  // umbrella header: build, scenario, simulate, state, output, version

namespace {

/// A 0.2 m x 0.1 m elastic block thrown at (0.5, -1) m/s onto a fixed 1 m x 0.1 m slab, under
/// gravity, with the smooth contact and no friction or damping: the total energy is conserved.
fdem::Scenario build_in_code() {
    fdem::Scenario sc;
    sc.path = "(built in code)";
    fdem::Model& m = sc.model;
    fdem::Material mat;
    mat.name = "rubber";
    mat.density = 1000.0;      // kg/m^3
    mat.youngs_modulus = 1e7;  // Pa
    mat.poisson_ratio = 0.3;
    m.materials.push_back(mat);
    m.gravity = {0.0, -9.81};  // m/s^2

    // each body from a structured rectangle mesh; every connected component becomes a body
    auto add_rectangle = [&m](const fdem::MeshData& mesh, const char* name, bool fixed,
                              fdem::Vec2 v) {
        std::vector<int32_t> tris(mesh.tris.size());
        std::iota(tris.begin(), tris.end(), 0);
        fdem::BodyOptions opt;
        opt.name = name;
        opt.material = 0;
        opt.fixed = fixed;
        opt.velocity = v;
        fdem::add_bodies(m, mesh, tris, opt);
        m.group_names.push_back(name);
    };
    add_rectangle(fdem::make_rectangle_mesh(0.0, 0.0, 1.0, 0.1, 20, 2), "slab", true, {});
    add_rectangle(fdem::make_rectangle_mesh(0.3, 0.11, 0.2, 0.1, 8, 4), "block", false,
                  {0.5, -1.0});

    m.contact.algorithm = fdem::ContactAlgorithm::Smooth;  // penalty 0 = 5 E_min (default)
    fdem::finalize_model(m);                               // masses, geometry, contact topology

    sc.run.stable_dt = fdem::stable_time_step(m, &sc.run.limiting_tri);
    sc.run.dt = 0.2 * sc.run.stable_dt;  // s
    sc.run.end_time = 0.1;               // s
    return sc;
}

// Run with fdem::Simulation, the run loop of `fdem run`: energies where they are read, the
// [checks] (energy balance, penetration, NaN/inversion), output and checkpoints when out is given.
int run(fdem::Scenario sc, const std::string& out) {
    fdem::Simulation sim(std::move(sc));
    const fdem::Model& m = sim.model();
    const fdem::State& s = sim.state();
    const fdem::RunSettings& rs = sim.settings();
    std::printf("fdem       %s (headers %d.%d.%d)\n", fdem::kVersion, FDEM_VERSION_MAJOR,
                FDEM_VERSION_MINOR, FDEM_VERSION_PATCH);
    std::printf("scenario   %s\n", sim.name().c_str());
    std::printf("model      %d bodies, %d nodes, %d triangles\n", m.num_bodies(), m.num_nodes(),
                m.num_tris());
    std::printf("dt         %.4g s (stable limit %.4g s), %" PRId64 " steps\n", s.dt, rs.stable_dt,
                sim.steps_to(rs.end_time));
    if (!out.empty()) {
        sim.open_output(out);                         // VTU + PVD, history.csv, failure.vtu
        sim.set_checkpoint_every(rs.end_time / 4.0);  // out/checkpoint.fdck
    }
    sim.set_warning_handler([](const std::string& w) { std::fprintf(stderr, "%s\n", w.c_str()); });

    // a callback every 1000 steps; returning false would stop the run there
    sim.run_to_end(
        [](fdem::Simulation& sm) {
            std::printf("progress   step %" PRId64 ", t = %.4g s, E = %.6g J/m\n", sm.state().step,
                        sm.state().time, sm.state().energy.total());
            return true;
        },
        1000);

    const fdem::Energy& e = s.energy;
    std::printf("energy     kinetic %.6g, strain %.6g, contact %.6g, dissipated %.6g J/m\n",
                e.kinetic, e.strain, e.contact, e.dissipated_viscous + e.dissipated_contact);
    const fdem::EnergyMonitor& mon = sim.energy_monitor();
    std::printf(
        "balance    max |E_total - E_0| = %.3g J/m = %.3g %% of the energy scale %.6g J/m\n",
        mon.max_error, mon.scale > 0 ? 100.0 * mon.max_error / mon.scale : 0.0, mon.scale);
    if (!out.empty()) {
        // restart from the last checkpoint written (at end_time): the same bits
        fdem::Simulation again(fdem::load_scenario(sim.name()));
        again.settings().end_time = rs.end_time;
        again.restore_checkpoint(sim.checkpoint_path());
        std::printf("restart    from %s: hash %s\n", sim.checkpoint_path().c_str(),
                    again.state_hash() == sim.state_hash() ? "equal" : "DIFFERENT");
    }
    std::printf("state      step %" PRId64 ", t = %.6g s\n", s.step, s.time);
    std::printf("hash %016" PRIx64 "\n", sim.state_hash());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        fdem::Scenario sc;
        std::string out;
        if (argc > 3) out = argv[3];
        if (argc > 1) {
            sc = fdem::load_scenario(argv[1]);  // InputError on bad input
            if (argc > 2) {
                char* end = nullptr;
                sc.run.end_time = std::strtod(argv[2], &end);
                if (*end != '\0' || !(sc.run.end_time > 0)) {
                    std::fprintf(stderr, "error: END_TIME '%s' is not a positive number of s\n",
                                 argv[2]);
                    return 2;
                }
            }
        } else {
            sc = build_in_code();
        }
        return run(std::move(sc), out);
    } catch (const fdem::InputError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    } catch (const fdem::SimulationError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
