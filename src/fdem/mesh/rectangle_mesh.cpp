// Structured rectangle mesh for tests, benchmarks and examples (no Gmsh needed).
#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "fdem/mesh.hpp"

namespace fdem {

//  node (i, j) = j (nx + 1) + i; cell (i, j) is split along one diagonal:
//
//   (i,j+1) +-----+ (i+1,j+1)      alternate: cells with odd i + j use the other diagonal
//           |   / |
//           | /   |
//     (i,j) +-----+ (i+1,j)
//
// Both triangles are counter-clockwise. Lines run counter-clockwise around the boundary.
MeshData make_rectangle_mesh(Real x0, Real y0, Real w, Real h, int nx, int ny, bool alternate) {
    if (!(w > 0) || !(h > 0) || nx < 1 || ny < 1) {
        throw std::invalid_argument("make_rectangle_mesh: need w > 0, h > 0, nx >= 1, ny >= 1");
    }
    MeshData mesh;
    mesh.file = "rectangle";
    const int stride = nx + 1;
    auto id = [stride](int i, int j) { return static_cast<int32_t>(j * stride + i); };

    // nodes, row by row from the bottom
    mesh.nodes.reserve(static_cast<size_t>((nx + 1) * (ny + 1)));
    for (int j = 0; j <= ny; ++j) {
        for (int i = 0; i <= nx; ++i) {
            mesh.nodes.push_back({x0 + w * i / nx, y0 + h * j / ny});
        }
    }

    // two counter-clockwise triangles per cell
    PhysicalGroup domain{"domain", 2, 1, {}};
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const int32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if (alternate && (i + j) % 2 == 1) {
                mesh.tris.push_back({a, b, d});
                mesh.tris.push_back({b, c, d});
            } else {
                mesh.tris.push_back({a, b, c});
                mesh.tris.push_back({a, c, d});
            }
        }
    }
    mesh.tri_tag.assign(mesh.tris.size(), 1);
    for (int32_t t = 0; t < static_cast<int32_t>(mesh.tris.size()); ++t) {
        domain.elements.push_back(t);
    }

    // boundary lines: bottom (tag 1), right (2), top (3), left (4)
    PhysicalGroup sides[4] = {
        {"bottom", 1, 1, {}}, {"right", 1, 2, {}}, {"top", 1, 3, {}}, {"left", 1, 4, {}}};
    auto add_line = [&](int side, int32_t p, int32_t q) {
        sides[side].elements.push_back(static_cast<int32_t>(mesh.lines.size()));
        mesh.lines.push_back({p, q});
        mesh.line_tag.push_back(side + 1);
    };
    for (int i = 0; i < nx; ++i) {
        add_line(0, id(i, 0), id(i + 1, 0));
    }
    for (int j = 0; j < ny; ++j) {
        add_line(1, id(nx, j), id(nx, j + 1));
    }
    for (int i = nx; i > 0; --i) {
        add_line(2, id(i, ny), id(i - 1, ny));
    }
    for (int j = ny; j > 0; --j) {
        add_line(3, id(0, j), id(0, j - 1));
    }

    for (auto& s : sides) {
        mesh.physical[s.name] = {s.dim, s.tag};
    }
    mesh.physical[domain.name] = {2, 1};
    for (auto& s : sides) {
        mesh.groups.push_back(std::move(s));
    }
    mesh.groups.push_back(std::move(domain));
    return mesh;
}

// Mid-edge nodes are appended after the corner nodes, one per edge, in order of first use by
// the triangles (then the boundary lines reuse them): edge (p, q) is keyed by (min, max).
MeshData make_rectangle_mesh_order2(Real x0, Real y0, Real w, Real h, int nx, int ny,
                                    bool alternate) {
    MeshData mesh = make_rectangle_mesh(x0, y0, w, h, nx, ny, alternate);
    std::map<std::pair<int32_t, int32_t>, int32_t> mid;
    auto mid_node = [&](int32_t p, int32_t q) {
        const auto key = std::minmax(p, q);
        const auto [it, added] = mid.emplace(key, static_cast<int32_t>(mesh.nodes.size()));
        if (added) {
            mesh.nodes.push_back(0.5 * (mesh.nodes[p] + mesh.nodes[q]));
        }
        return it->second;
    };
    mesh.tri_mid.reserve(mesh.tris.size());
    for (const auto& t : mesh.tris) {
        mesh.tri_mid.push_back({mid_node(t[0], t[1]), mid_node(t[1], t[2]), mid_node(t[2], t[0])});
    }
    mesh.line_mid.reserve(mesh.lines.size());
    for (const auto& l : mesh.lines) {
        mesh.line_mid.push_back(mid_node(l[0], l[1]));
    }
    mesh.file = "rectangle (order 2)";
    return mesh;
}

}  // namespace fdem
