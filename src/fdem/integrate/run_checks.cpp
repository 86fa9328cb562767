// Run-level failure checks (run_checks.hpp).
#include "integrate/run_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "fdem/error.hpp"

namespace fdem {

namespace {
constexpr int64_t kEnergyCheckFirstStep = 16;  ///< first step at which the energy drift counts
constexpr Real kEnergyFloorFraction = 1e-12;   ///< floor / largest energy (theory eq. 4.9)
}  // namespace

Real energy_floor(const Model& m) {
    // elastic part: sum over movable triangles of A0 (lambda + 2 mu) / 2, the strain energy
    // of a unit uniaxial strain; gravity part: every movable mass falling by the diagonal L of
    // the model's bounding box (theory eq. 4.9)
    Real elastic = 0;
    for (TriId t = 0; t < m.num_tris(); ++t) {
        if (m.bodies[m.tri_body[t]].fixed) continue;
        const Material& mt = m.materials[m.tri_material[t]];
        elastic += 0.5 * m.tri_area0[t] * (mt.lambda + 2.0 * mt.mu);
    }
    Real mass = 0;
    Vec2 lo{std::numeric_limits<Real>::infinity(), std::numeric_limits<Real>::infinity()};
    Vec2 hi = -1.0 * lo;
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        if (m.node_inv_mass[i] > 0) mass += m.node_mass[i];
        lo = {std::min(lo.x, m.node_x0[i].x), std::min(lo.y, m.node_x0[i].y)};
        hi = {std::max(hi.x, m.node_x0[i].x), std::max(hi.y, m.node_x0[i].y)};
    }
    const Real diag = m.num_nodes() > 0 ? norm(hi - lo) : 0.0;
    const Real floor = kEnergyFloorFraction * (elastic + mass * norm(m.gravity) * diag);
    return std::isfinite(floor) ? floor : 0.0;
}

std::string check_run(const Model& m, const State& s, const RunSettings& run, EnergyMonitor& mon) {
    const CheckSettings& c = run.checks;
    std::string warning;

    // penetration beyond the contact layer (spec §4.6 depth limit)
    const ContactState& cs = s.contact;
    if (c.penetration != PenetrationCheck::Off && cs.lost_inside > 0) {
        std::string what = fmt::format(
            "{} target node(s) passed through the contact layer into the body they touched "
            "(deepest d / layer = {:.3g})",
            cs.lost_inside, cs.max_depth_ratio);
        // the deepest of them (contact/contact.cpp records it), with body names for the user
        const NodeId j = cs.lost_node;
        const BodyId into = cs.lost_body;
        const ContactTopology& ct = s.topology;
        if (j >= 0 && j < ct.target_end() && into >= 0 && into < m.num_bodies()) {
            const BodyId bj = m.node_body[target_node(ct, j)];
            const Vec2 xj = target_point(ct, s.x.data(), j);
            // an edge target (docs/theory.md §6.12) is named by its edge's end nodes
            const std::string who =
                j < m.num_nodes()
                    ? fmt::format("node {}", j)
                    : fmt::format(
                          "the midpoint of boundary edge {}-{}",
                          ct.boundary_edges[static_cast<size_t>(j - ct.edge_target_base)][0],
                          ct.boundary_edges[static_cast<size_t>(j - ct.edge_target_base)][1]);
            what += fmt::format(
                "; {} (body {} \"{}\", at ({:.6g}, {:.6g}) m, d / layer = {:.3g} when last "
                "in contact) is inside body {} \"{}\"",
                who, bj, m.bodies[bj].name, xj.x, xj.y, cs.lost_depth_ratio, into,
                m.bodies[into].name);
        }
        what += "; the contact force is lost there";
        const std::string remedy = fmt::format(
            "reduce dt (now {:.3g} s, stable limit {:.3g} s) or increase the contact penalty "
            "([contact] penalty); set [checks] penetration = \"warn\" to continue anyway",
            s.dt, run.stable_dt);
        if (c.penetration == PenetrationCheck::Fail) {
            throw SimulationError(s.step, s.time, "contact", what + "; " + remedy);
        }
        warning = fmt::format("warning: step {} (t = {:.6g} s): contact: {}", s.step, s.time, what);
    }

    // energy balance (docs/theory.md §4): the total is conserved up to the time discretisation;
    // checked on the steps that evaluated the strain energy (State::need_energy)
    if (!s.need_energy) return warning;
    const Energy& e = s.energy;
    const Real total = e.total();
    if (!mon.has_reference) {
        mon.has_reference = true;
        mon.e0 = total;
    }
    if (!(mon.floor > 0)) mon.floor = energy_floor(m);  // derived from m: not checkpointed
    mon.scale = std::max({mon.scale, mon.floor, e.kinetic + e.strain + e.contact,
                          std::abs(e.work_gravity), std::abs(e.work_external)});
    const Real err = std::abs(total - mon.e0);
    mon.max_error = std::max(mon.max_error, err);
    if (!std::isfinite(total)) {
        throw SimulationError(
            s.step, s.time, "energy",
            fmt::format("total energy is not finite; the run is unstable: reduce dt (now {:.3g} s, "
                        "stable limit {:.3g} s)",
                        s.dt, run.stable_dt));
    }
    // from kEnergyCheckFirstStep on: a support or kick acting from t = 0 has an O(dt) start-up
    // error in its work that is large relative to the still tiny energy scale of the first
    // steps (example 02: 65 % at step 2, 1 % from step 30 on)
    if (c.energy_tolerance > 0 && s.step >= kEnergyCheckFirstStep && mon.scale > 0 &&
        err > c.energy_tolerance * mon.scale) {
        throw SimulationError(
            s.step, s.time, "energy",
            fmt::format("total energy drifted by {:.4g} J/m = {:.3g} % of the energy scale "
                        "{:.4g} J/m (limit {:.3g} %, [checks] energy_tolerance = {}); the run is "
                        "unstable or too coarse: reduce dt (now {:.3g} s, stable limit {:.3g} s) "
                        "or add contact damping",
                        err, 100.0 * err / mon.scale, mon.scale, 100.0 * c.energy_tolerance,
                        c.energy_tolerance, s.dt, run.stable_dt));
    }
    return warning;
}

}  // namespace fdem
