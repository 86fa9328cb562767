// Structural pre-check of ASCII MSH 2 files (msh_precheck.hpp).
#include "io/msh_precheck.hpp"

#include <fstream>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "fdem/error.hpp"

namespace fdem::io {

namespace {

/// Nodes per MSH 2 element type (Gmsh reference manual, "MSH file format version 2"); 0 for a
/// type this check does not know (then the element line is left to Gmsh's own checks).
int nodes_of_type(long type) {
    static const int n[] = {0, 2,  3,  4,  4, 8,  6,  5,  3,  6,  9, 10, 27, 18, 14, 1,
                            8, 20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5,  6,  20, 35, 56};
    return type >= 1 && type < static_cast<long>(std::size(n)) ? n[type] : 0;
}

/// Whitespace-separated integers of a line; false if a field is not an integer.
bool integers(const std::string& line, std::vector<long>& out) {
    out.clear();
    std::istringstream in(line);
    std::string tok;
    while (in >> tok) {
        size_t used = 0;
        long v = 0;
        try {
            v = std::stol(tok, &used);
        } catch (...) {
            return false;
        }
        if (used != tok.size()) return false;
        out.push_back(v);
    }
    return true;
}

}  // namespace

void precheck_msh(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) {
        if (!l.empty() && l.back() == '\r') l.pop_back();
        lines.push_back(std::move(l));
    }
    auto fail = [&](size_t i, const std::string& msg) {
        throw InputError({path, static_cast<int>(i + 1), 0}, "",
                         fmt::format("malformed mesh file '{}': {}", path, msg),
                         i < lines.size() ? lines[i] : std::string());
    };
    // only ASCII MSH 2.x: "$MeshFormat" / "2.2 0 8"
    if (lines.size() < 2 || lines[0] != "$MeshFormat") return;
    std::istringstream fmt_line(lines[1]);
    std::string version;
    int file_type = -1;
    fmt_line >> version >> file_type;
    if (version.empty() || version[0] != '2' || file_type != 0) return;

    std::vector<long> v;
    for (size_t i = 0; i < lines.size(); ++i) {
        if (lines[i] == "$Elements") {
            if (i + 1 >= lines.size() || !integers(lines[i + 1], v) || v.size() != 1 || v[0] < 0 ||
                static_cast<size_t>(v[0]) > lines.size() - i - 2) {
                fail(i + 1, "the $Elements count must be the number of element lines that follow");
            }
            const long n = v[0];
            for (long k = 0; k < n; ++k) {
                const size_t j = i + 2 + static_cast<size_t>(k);
                if (!integers(lines[j], v) || v.size() < 3 || v[2] < 0) {
                    fail(j,
                         "an $Elements line must be 'id type ntags tags... nodes...' (integers)");
                }
                const int nn = nodes_of_type(v[1]);
                if (nn == 0) {
                    fail(j, fmt::format("element {} has unknown element type {}", v[0], v[1]));
                }
                const size_t want = 3 + static_cast<size_t>(v[2]) + static_cast<size_t>(nn);
                if (v.size() != want) {
                    fail(j, fmt::format("element {} of type {} with {} tags needs {} fields "
                                        "({} node ids), the line has {}",
                                        v[0], v[1], v[2], want, nn, v.size()));
                }
            }
            i += 1 + static_cast<size_t>(n);
        }
    }
}

}  // namespace fdem::io
