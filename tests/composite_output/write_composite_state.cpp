// Writes one VTU frame of a composite body and a CST body under a known homogeneous deformation
// for check_composite_vtu.py, which reads it back with the real VTK reader (issue #7).
//
// usage: fdem_write_composite_state OUT.vtu Fxx,Fxy,Fyx,Fyy
//
// Bodies (E = 1 GPa, nu = 0.45, plane strain, built by the library's own mesh -> model path):
//   0: composite, make_rectangle_mesh_order2(0, 0, 2, 1, 2, 1): 4 composites, 16 sub-triangles
//   1: CST, make_rectangle_mesh(3, 0, 1, 1, 1, 1): 2 triangles
// Every node is placed at x = F X.
#include <cstdio>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "fdem/build.hpp"
#include "fdem/output.hpp"
#include "fdem/simulate.hpp"

int main(int argc, char** argv) {
    using namespace fdem;
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s OUT.vtu Fxx,Fxy,Fyx,Fyy\n", argv[0]);
        return 2;
    }
    std::vector<double> F;
    std::stringstream ss(argv[2]);
    for (std::string item; std::getline(ss, item, ',');)
        F.push_back(std::stod(item));
    if (F.size() != 4) {
        std::fprintf(stderr, "F needs 4 comma-separated values\n");
        return 2;
    }
    try {
        Model m;
        Material mat;
        mat.name = "soft";
        mat.density = 1000;
        mat.youngs_modulus = 1e9;
        mat.poisson_ratio = 0.45;
        m.materials.push_back(mat);
        auto all = [](const MeshData& mesh) {
            std::vector<int32_t> ids(mesh.tris.size());
            for (size_t i = 0; i < ids.size(); ++i)
                ids[i] = static_cast<int32_t>(i);
            return ids;
        };
        BodyOptions opt;
        opt.name = "composite";
        const MeshData q = make_rectangle_mesh_order2(0, 0, 2, 1, 2, 1);
        add_bodies(m, q, all(q), opt);
        opt.name = "cst";
        const MeshData l = make_rectangle_mesh(3, 0, 1, 1, 1, 1);
        add_bodies(m, l, all(l), opt);
        finalize_model(m);

        State s = make_state(m, 1e-6);
        const Mat2 Fm = {F[0], F[1], F[2], F[3]};
        for (NodeId i = 0; i < m.num_nodes(); ++i)
            s.x[i] = Fm * m.node_x0[i];
        write_vtu(argv[1], m, s, {}, {});
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
