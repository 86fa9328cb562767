// Writes a VTU/PVD series of known, homogeneous deformations for tests/output/check_vtu.py, which
// reads it back with the real VTK reader and compares with values it computes analytically from
// the same command-line arguments (tests/output/tests.cmake passes both programs the same lists).
//
// usage: fdem_write_known_state OUT_DIR --body x0,y0,w,h,nx,ny,E,nu,strain|stress ...
//                                       --frame t,Fxx,Fxy,Fyx,Fyy,cx,cy ...
//
// Every body is a structured rectangle with its own nodes (node j*(nx+1)+i of the body at
// (x0 + w i/nx, y0 + h j/ny)), each cell split along its a-c diagonal:
//
//     d ---- c
//     |    / |      triangles (a, b, c) and (a, c, d), counter-clockwise
//     |  /   |
//     a ---- b
//
// Frame k places every node at x = F X + c. Node/cell fields that are not derived from x are
// simple functions of the global node index i, triangle index t and frame k (see check_vtu.py):
//   velocity = (k + 0.5 i, -0.25 i), force = (1000 i, k - 2000 i), contact_force = (-i, 3 k),
//   extra point "distance" = 0.1 i, extra 2-vector point "normal" = (i, -i), extra cell
//   "cell_id" = t. It also writes OUT_DIR/history.csv with one row per frame (for the plot test).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "fdem/build.hpp"
#include "fdem/output.hpp"

namespace {

std::vector<double> parse_list(const std::string& s, size_t n, const char* what) {
    std::vector<double> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ',')) {
        if (item == "strain") {
            out.push_back(0);
        } else if (item == "stress") {
            out.push_back(1);
        } else {
            out.push_back(std::stod(item));
        }
    }
    if (out.size() != n) {
        std::fprintf(stderr, "%s '%s': expected %zu comma-separated values\n", what, s.c_str(), n);
        std::exit(2);
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace fdem;
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s OUT_DIR --body ... --frame ...\n", argv[0]);
        return 2;
    }
    const std::string out_dir = argv[1];
    std::vector<std::vector<double>> bodies, frames;
    for (int a = 2; a + 1 < argc; a += 2) {
        const std::string opt = argv[a];
        if (opt == "--body") {
            bodies.push_back(parse_list(argv[a + 1], 9, "--body"));
        } else if (opt == "--frame") {
            frames.push_back(parse_list(argv[a + 1], 7, "--frame"));
        } else {
            std::fprintf(stderr, "unknown option %s\n", opt.c_str());
            return 2;
        }
    }

    try {
        // fresh output directory, so a stale frame of an earlier run cannot pass the check
        std::filesystem::remove_all(out_dir);
        std::filesystem::create_directories(out_dir);

        // build the model by hand: one material per body
        Model m;
        for (const auto& b : bodies) {
            const int nx = static_cast<int>(b[4]), ny = static_cast<int>(b[5]);
            Material mat;
            mat.name = "mat" + std::to_string(m.materials.size());
            mat.density = 1000;
            mat.youngs_modulus = b[6];
            mat.poisson_ratio = b[7];
            mat.plane = b[8] == 0 ? PlaneMode::Strain : PlaneMode::Stress;
            compute_lame(mat);
            const int32_t mat_id = static_cast<int32_t>(m.materials.size());
            m.materials.push_back(mat);

            Body body;
            body.name = "body" + std::to_string(m.bodies.size());
            body.material = mat_id;
            body.node_begin = m.num_nodes();
            body.tri_begin = m.num_tris();
            const BodyId bid = m.num_bodies();
            for (int j = 0; j <= ny; ++j) {
                for (int i = 0; i <= nx; ++i) {
                    m.node_x0.push_back({b[0] + b[2] * i / nx, b[1] + b[3] * j / ny});
                    m.node_body.push_back(bid);
                }
            }
            for (int j = 0; j < ny; ++j) {
                for (int i = 0; i < nx; ++i) {
                    const NodeId a0 = body.node_begin + j * (nx + 1) + i;
                    const NodeId b0 = a0 + 1, c0 = a0 + nx + 2, d0 = a0 + nx + 1;
                    for (const auto& tri :
                         {std::array<NodeId, 3>{a0, b0, c0}, std::array<NodeId, 3>{a0, c0, d0}}) {
                        m.tri_nodes.push_back(tri);
                        m.tri_body.push_back(bid);
                        m.tri_material.push_back(mat_id);
                    }
                }
            }
            body.node_end = m.num_nodes();
            body.tri_end = m.num_tris();
            m.bodies.push_back(body);
        }
        for (const auto& n : m.tri_nodes) {
            const Vec2 X0 = m.node_x0[n[0]], X1 = m.node_x0[n[1]], X2 = m.node_x0[n[2]];
            m.tri_dm_inv.push_back(inverse(columns(X1 - X0, X2 - X0)));
            m.tri_area0.push_back(signed_area(X0, X1, X2));
        }

        // extra fields exercising the extension interface
        const size_t nn = static_cast<size_t>(m.num_nodes());
        const size_t nt = static_cast<size_t>(m.num_tris());
        std::vector<Real> distance(nn), normal(2 * nn), cell_id(nt);
        for (size_t i = 0; i < nn; ++i) {
            distance[i] = 0.1 * static_cast<Real>(i);
            normal[2 * i] = static_cast<Real>(i);
            normal[2 * i + 1] = -static_cast<Real>(i);
        }
        for (size_t t = 0; t < nt; ++t)
            cell_id[t] = static_cast<Real>(t);
        const ExtraField extra_point[] = {{"distance", 1, distance}, {"normal", 2, normal}};
        const ExtraField extra_cell[] = {{"cell_id", 1, cell_id}};

        State s;
        s.x.resize(nn);
        s.v.resize(nn);
        s.f.resize(nn);
        s.f_contact.resize(nn);
        PvdSeries pvd(out_dir + "/series.pvd");
        HistoryWriter history(out_dir + "/history.csv");
        for (size_t k = 0; k < frames.size(); ++k) {
            const auto& fr = frames[k];
            const Mat2 F{fr[1], fr[2], fr[3], fr[4]};
            const Vec2 c{fr[5], fr[6]};
            const Real kk = static_cast<Real>(k);
            for (size_t i = 0; i < nn; ++i) {
                const Real ii = static_cast<Real>(i);
                s.x[i] = F * m.node_x0[i] + c;
                s.v[i] = {kk + 0.5 * ii, -0.25 * ii};
                s.f[i] = {1000.0 * ii, kk - 2000.0 * ii};
                s.f_contact[i] = {-ii, 3.0 * kk};
            }
            s.time = fr[0];
            s.step = static_cast<int64_t>(10 * k);
            char name[64];
            std::snprintf(name, sizeof name, "frame_%06zu.vtu", k);
            write_vtu(out_dir + "/" + name, m, s, extra_point, extra_cell);
            pvd.add(s.time, name);

            // history row k: energies that trade kinetic for strain with a small drift
            // (total = 10 + 0.001 k^2 J/m), so the plot has every curve and a balance error
            s.energy.kinetic = 10.0 - kk;
            s.energy.strain = kk;
            s.energy.contact = 0.5 * kk;
            s.energy.work_gravity = 0.25 * kk;
            s.energy.work_external = 0.25 * kk;
            s.energy.dissipated_viscous = 0.0;
            s.energy.dissipated_contact = 0.001 * kk * kk;
            s.contact.active_contacts = static_cast<int32_t>(k);
            history.write(m, s);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
