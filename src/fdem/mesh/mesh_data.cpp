// Queries on a raw MeshData (include/fdem/mesh.hpp).
#include <algorithm>

#include "fdem/mesh.hpp"

namespace fdem {

std::vector<int32_t> MeshData::group_nodes(const PhysicalGroup& g) const {
    std::vector<int32_t> out;
    for (const int32_t e : g.elements) {
        if (g.dim == 2) {
            out.insert(out.end(), tris[e].begin(), tris[e].end());
            if (!tri_mid.empty()) out.insert(out.end(), tri_mid[e].begin(), tri_mid[e].end());
        } else if (g.dim == 1) {
            out.insert(out.end(), lines[e].begin(), lines[e].end());
            if (!line_mid.empty()) out.push_back(line_mid[e]);
        } else {
            out.push_back(points[e]);
        }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

}  // namespace fdem
