// Mesh input through the Gmsh C++ API: .msh (2.2 / 4.1, ASCII or binary) and .geo (meshed here).
// Gmsh keeps global state and is not thread-safe: every read holds one process-wide mutex and
// runs a complete initialize() ... finalize() cycle, so no Gmsh state leaks from one read to the
// next (options such as Mesh.MeshSizeMax included).
#include <gmsh.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <regex>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "fdem/error.hpp"
#include "fdem/mesh.hpp"
#include "io/msh_precheck.hpp"

namespace fdem {

namespace {

// Gmsh element types fdem understands (Gmsh reference manual, "MSH file format").
constexpr int kLine2 = 1;
constexpr int kTriangle3 = 2;
constexpr int kLine3 = 8;      // second order: end nodes 0, 1, then the mid node 2
constexpr int kTriangle6 = 9;  // second order: corners 0, 1, 2, then mid-edge 3 (0-1), 4, 5
constexpr int kPoint1 = 15;

std::mutex& gmsh_mutex() {
    static std::mutex m;
    return m;
}

/// Line `line` (1-based) of a text file, without the newline; "" if unavailable.
std::string file_line(const std::string& path, int line) {
    if (line <= 0) {
        return {};
    }
    std::ifstream in(path, std::ios::binary);
    std::string s;
    for (int i = 1; i <= line && std::getline(in, s); ++i) {
        if (i == line) {
            if (!s.empty() && s.back() == '\r') {
                s.pop_back();
            }
            // binary sections are not worth echoing
            const bool printable = std::all_of(s.begin(), s.end(), [](unsigned char c) {
                return c == '\t' || (c >= 32 && c < 127);
            });
            return printable && s.size() < 200 ? s : std::string{};
        }
    }
    return {};
}

/// 1-based line of the first line equal to `header` (e.g. "$Elements"); 0 if absent.
/// Section headers are text even in binary .msh files.
int section_line(const std::string& path, const std::string& header) {
    std::ifstream in(path, std::ios::binary);
    std::string s;
    for (int i = 1; std::getline(in, s); ++i) {
        if (!s.empty() && s.back() == '\r') {
            s.pop_back();
        }
        if (s == header) {
            return i;
        }
    }
    return 0;
}

bool is_msh(const std::string& path) {
    return std::filesystem::path(path).extension() == ".msh";
}

/// An InputError located at a .msh section header (Gmsh's own messages carry no line).
[[noreturn]] void fail_at_section(const std::string& path, const std::string& header,
                                  const std::string& msg) {
    const int line = is_msh(path) ? section_line(path, header) : 0;
    throw InputError({path, line, 0}, "", msg, file_line(path, line));
}

/// A .msh file that ends inside a section (the last "$Name" line has no "$EndName" after it):
/// an InputError at that header saying the file is truncated; nothing if the file is complete.
/// Gmsh's own message for such a file is often only "Error loading 'file.msh'".
void check_truncated(const std::string& path, const std::string& gmsh_text) {
    std::ifstream in(path, std::ios::binary);
    std::string s, open_name;
    int open_line = 0;
    for (int i = 1; std::getline(in, s); ++i) {
        if (!s.empty() && s.back() == '\r') {
            s.pop_back();
        }
        if (s.size() < 2 || s[0] != '$') {
            continue;
        }
        if (s.rfind("$End", 0) == 0) {
            if (s.substr(4) == open_name) {
                open_name.clear();
            }
        } else if (std::all_of(s.begin() + 1, s.end(),
                               [](unsigned char c) { return std::isalnum(c) != 0; })) {
            open_name = s.substr(1);
            open_line = i;
        }
    }
    if (!open_name.empty()) {
        throw InputError({path, open_line, 0}, "",
                         fmt::format("cannot read mesh file '{}': the file ends inside section "
                                     "${} (no ${} follows): it is truncated or incomplete; write "
                                     "it again (Gmsh: File > Export, or gmsh -2){}",
                                     path, open_name, "End" + open_name,
                                     gmsh_text.empty() ? "" : " (Gmsh: " + gmsh_text + ")"),
                         file_line(path, open_line));
    }
}

/// Turn a Gmsh error text into an InputError naming the file and, when Gmsh says it, the line.
/// Gmsh reports .geo errors as "'file.geo', line 7: syntax error (;)".
[[noreturn]] void fail_from_gmsh(const std::string& path, std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) {
        text.pop_back();
    }
    if (text.rfind("Error: ", 0) == 0) {
        text = text.substr(7);
    }
    if (is_msh(path)) {
        check_truncated(path, text);
    }
    static const std::regex with_line(R"('([^']*)', line (\d+)\s*:\s*(.*))");
    std::smatch m;
    if (std::regex_match(text, m, with_line)) {
        const int line = std::stoi(m[2].str());
        throw InputError({path, line, 0}, "",
                         fmt::format("cannot read mesh file '{}': {}", path, m[3].str()),
                         file_line(path, line));
    }

    // .msh reader messages name the section ("Could not read nodes"): point at its header
    std::string lower = text;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const std::string msg = fmt::format("cannot read mesh file '{}': {}", path, text);
    // "Wrong node index" is what the MSH 2 reader says about an element's node
    if (lower.find("element") != std::string::npos ||
        lower.find("node index") != std::string::npos) {
        fail_at_section(path, "$Elements", msg);
    }
    if (lower.find("node") != std::string::npos) {
        fail_at_section(path, "$Nodes", msg);
    }
    if (lower.find("entit") != std::string::npos) {
        fail_at_section(path, "$Entities", msg);
    }
    if (lower.find("format") != std::string::npos || lower.find("version") != std::string::npos) {
        fail_at_section(path, "$MeshFormat", msg);
    }
    throw InputError({path, 0, 0}, "", msg);
}

std::string element_name(int type) {
    std::string name;
    int dim = 0, order = 0, num_nodes = 0, num_primary = 0;
    std::vector<double> local;
    gmsh::model::mesh::getElementProperties(type, name, dim, order, num_nodes, local, num_primary);
    return name;
}

/// Scoped Gmsh session: initialize quietly, collect log messages, always finalize. Gmsh's
/// General.NumThreads calls omp_set_num_threads() for the calling thread: without restoring
/// it, every parallel region of the run after a mesh read would take one thread.
class GmshSession {
public:
    GmshSession() : omp_threads_(omp_get_max_threads()) {
        // "-v 2": errors and warnings reach the logger, nothing reaches the terminal
        const char* args[] = {"fdem", "-v", "2"};
        gmsh::initialize(3, const_cast<char**>(args), /*readConfigFiles=*/false);
        gmsh::option::setNumber("General.Terminal", 0);
        gmsh::option::setNumber("General.NumThreads", 1);  // deterministic meshing
        gmsh::logger::start();
    }
    ~GmshSession() {
        try {
            gmsh::logger::stop();
            gmsh::finalize();
        } catch (...) {
            // finalize failing leaves nothing for us to clean up
        }
        omp_set_num_threads(omp_threads_);  // (Gmsh set it to General.NumThreads)
    }
    GmshSession(const GmshSession&) = delete;
    GmshSession& operator=(const GmshSession&) = delete;

    /// First logged error since start, "" if none (Gmsh logs some errors without throwing).
    static std::string first_error() {
        std::vector<std::string> log;
        gmsh::logger::get(log);
        for (const std::string& s : log) {
            if (s.rfind("Error", 0) == 0) {
                return s;
            }
        }
        return {};
    }

private:
    int omp_threads_;  ///< the caller's OpenMP thread count before Gmsh changed it
};

/// Read the current Gmsh model into mesh (called inside a session). names: the physical names
/// as read by fdem (the file Gmsh read had no $PhysicalNames), nullptr: Gmsh's own.
void extract(MeshData& mesh, const std::map<std::pair<int, int>, std::string>* names = nullptr) {
    const std::string& path = mesh.file;

    // nodes: Gmsh tags are arbitrary positive integers -> dense 0-based ids
    std::vector<std::size_t> node_tags;
    std::vector<double> coord, param;
    gmsh::model::mesh::getNodes(node_tags, coord, param, -1, -1, false, false);
    std::unordered_map<std::size_t, int32_t> node_id;
    node_id.reserve(node_tags.size());
    mesh.nodes.resize(node_tags.size());
    for (std::size_t i = 0; i < node_tags.size(); ++i) {
        const double z = coord[3 * i + 2];
        if (z != 0.0) {
            fail_at_section(path, "$Nodes",
                            fmt::format("mesh file '{}': node {} has z = {:g}; fdem is 2-D and "
                                        "needs every node in the plane z = 0",
                                        path, node_tags[i], z));
        }
        if (!std::isfinite(coord[3 * i]) || !std::isfinite(coord[3 * i + 1])) {
            fail_at_section(path, "$Nodes",
                            fmt::format("mesh file '{}': node {} has the coordinates ({:g}, {:g}); "
                                        "expected finite numbers in m",
                                        path, node_tags[i], coord[3 * i], coord[3 * i + 1]));
        }
        mesh.nodes[i] = {coord[3 * i], coord[3 * i + 1]};
        node_id[node_tags[i]] = static_cast<int32_t>(i);
    }
    auto to_id = [&](std::size_t tag, std::size_t elem_tag) {
        const auto it = node_id.find(tag);
        if (it == node_id.end()) {
            fail_at_section(path, "$Elements",
                            fmt::format("mesh file '{}': element {} references node {}, which "
                                        "$Nodes does not define",
                                        path, elem_tag, tag));
        }
        return it->second;
    };

    // elements, entity by entity, so physical groups (sets of entities) map to element ranges
    // MSH 2.2 repeats an element once per physical group it belongs to: merge elements with
    // the same node set, or a triangle in two surface groups would become two overlapping ones
    std::map<std::pair<int, int>, std::vector<int32_t>> entity_elems;
    std::map<std::array<int32_t, 3>, int32_t> seen_tri;
    std::map<std::array<int32_t, 2>, int32_t> seen_line;
    std::map<int32_t, int32_t> seen_point;
    std::vector<std::array<int32_t, 3>> tri_mid;  // -1 for 3-node triangles
    std::vector<int32_t> line_mid;
    std::vector<int> tri_type, line_type;  // Gmsh type of each kept element, for the order check
    auto sorted3 = [](std::array<int32_t, 3> a) {
        std::sort(a.begin(), a.end());
        return a;
    };
    auto sorted2 = [](std::array<int32_t, 2> a) {
        std::sort(a.begin(), a.end());
        return a;
    };
    gmsh::vectorpair entities;
    gmsh::model::getEntities(entities);
    // highest dimension first, so an unsupported element is reported as the 2-D element the
    // user meshed (6-node triangle) rather than its boundary (3-node line)
    std::stable_sort(entities.begin(), entities.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    for (const auto& [dim, tag] : entities) {
        std::vector<int> types;
        std::vector<std::vector<std::size_t>> elem_tags, elem_nodes;
        gmsh::model::mesh::getElements(types, elem_tags, elem_nodes, dim, tag);
        std::vector<int32_t>& mine = entity_elems[{dim, tag}];
        for (std::size_t k = 0; k < types.size(); ++k) {
            const int type = types[k];
            const auto& et = elem_tags[k];
            const auto& en = elem_nodes[k];
            if (et.empty()) {
                continue;
            }
            if (type == kTriangle3 || type == kTriangle6) {
                // corners first (dedup key), then the mid-edge nodes of a 6-node triangle
                const std::size_t nn = type == kTriangle6 ? 6 : 3;
                for (std::size_t e = 0; e < et.size(); ++e) {
                    const std::size_t o = nn * e;
                    const std::array<int32_t, 3> t = {to_id(en[o], et[e]), to_id(en[o + 1], et[e]),
                                                      to_id(en[o + 2], et[e])};
                    const auto [it, added] =
                        seen_tri.emplace(sorted3(t), static_cast<int32_t>(mesh.tris.size()));
                    if (added) {
                        mesh.tris.push_back(t);
                        tri_mid.push_back(nn == 6 ? std::array<int32_t, 3>{to_id(en[o + 3], et[e]),
                                                                           to_id(en[o + 4], et[e]),
                                                                           to_id(en[o + 5], et[e])}
                                                  : std::array<int32_t, 3>{-1, -1, -1});
                        tri_type.push_back(type);
                    }
                    mine.push_back(it->second);
                }
            } else if (type == kLine2 || type == kLine3) {
                const std::size_t nn = type == kLine3 ? 3 : 2;
                for (std::size_t e = 0; e < et.size(); ++e) {
                    const std::size_t o = nn * e;
                    const std::array<int32_t, 2> l = {to_id(en[o], et[e]), to_id(en[o + 1], et[e])};
                    const auto [it, added] =
                        seen_line.emplace(sorted2(l), static_cast<int32_t>(mesh.lines.size()));
                    if (added) {
                        mesh.lines.push_back(l);
                        line_mid.push_back(nn == 3 ? to_id(en[o + 2], et[e]) : -1);
                        line_type.push_back(type);
                    }
                    mine.push_back(it->second);
                }
            } else if (type == kPoint1) {
                for (std::size_t e = 0; e < et.size(); ++e) {
                    const int32_t n = to_id(en[e], et[e]);
                    const auto [it, added] =
                        seen_point.emplace(n, static_cast<int32_t>(mesh.points.size()));
                    if (added) {
                        mesh.points.push_back(n);
                    }
                    mine.push_back(it->second);
                }
            } else {
                // never ignore an element silently: it would be a hole in a body
                const std::string name = element_name(type);
                std::string hint =
                    "use first- or second-order triangles (3-node or 6-node; gmsh -order 1 or 2";
                if (name.find("Quadrilateral") != std::string::npos) {
                    hint += "; for .geo files remove Recombine";
                }
                hint += ")";
                fail_at_section(path, "$Elements",
                                fmt::format("mesh file '{}': element {} has type {} ({}), which "
                                            "is not supported; {}",
                                            path, et[0], type, name, hint));
            }
        }
    }
    // one order for the whole mesh: a body cannot mix 3-node and 6-node triangles (a 3-node
    // neighbour would leave the mid-edge node of a shared edge hanging)
    const bool second = !tri_type.empty() && tri_type[0] == kTriangle6;
    const int want_tri = second ? kTriangle6 : kTriangle3;
    const int want_line = second ? kLine3 : kLine2;
    for (std::size_t t = 0; t < tri_type.size(); ++t) {
        if (tri_type[t] != want_tri) {
            fail_at_section(path, "$Elements",
                            fmt::format("mesh file '{}' mixes 3-node and 6-node triangles (type 2 "
                                        "and 9); a mesh must be entirely first or second order "
                                        "(gmsh -order 1 or -order 2)",
                                        path));
        }
    }
    for (std::size_t l = 0; l < line_type.size(); ++l) {
        if (!tri_type.empty() && line_type[l] != want_line) {
            fail_at_section(path, "$Elements",
                            fmt::format("mesh file '{}' has {} triangles but {} lines (type {}); "
                                        "lines must have the order of the triangles (gmsh "
                                        "-order {})",
                                        path, second ? "6-node" : "3-node",
                                        line_type[l] == kLine3 ? "3-node" : "2-node", line_type[l],
                                        second ? 2 : 1));
        }
    }
    if (second) {
        mesh.tri_mid = std::move(tri_mid);
        if (!mesh.lines.empty()) {
            mesh.line_mid = std::move(line_mid);
        }
    }
    mesh.tri_tag.assign(mesh.tris.size(), 0);
    mesh.line_tag.assign(mesh.lines.size(), 0);
    mesh.point_tag.assign(mesh.points.size(), 0);

    // physical groups: the entities of every group from one pass over the entities (Gmsh 4.8's
    // getEntitiesForPhysicalGroup walks all entities on every call, which made a mesh with one
    // group per block quadratic in the blocks: issue #16 item 4)
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    std::sort(groups.begin(), groups.end());
    std::map<std::pair<int, int>, std::vector<int>> group_entities;
    for (const auto& [dim, tag] : entities) {
        std::vector<int> phys;
        gmsh::model::getPhysicalGroupsForEntity(dim, tag, phys);
        for (const int p : phys) {
            group_entities[{dim, std::abs(p)}].push_back(tag);  // a sign marks a reversed entity
        }
    }
    for (const auto& [dim, tag] : groups) {
        if (dim > 2) {
            continue;  // 3-D groups cannot contain supported elements (rejected above)
        }
        PhysicalGroup g;
        g.dim = dim;
        g.tag = tag;
        if (names) {
            const auto it = names->find({dim, tag});
            g.name = it == names->end() ? std::string() : it->second;
        } else {
            gmsh::model::getPhysicalName(dim, tag, g.name);
        }
        const auto ge = group_entities.find({dim, tag});
        const std::vector<int> none;
        for (const int e : ge == group_entities.end() ? none : ge->second) {
            const auto it = entity_elems.find({dim, e});
            if (it != entity_elems.end()) {
                g.elements.insert(g.elements.end(), it->second.begin(), it->second.end());
            }
        }
        std::sort(g.elements.begin(), g.elements.end());
        g.elements.erase(std::unique(g.elements.begin(), g.elements.end()), g.elements.end());

        // first physical tag of each element, kept for simple per-element tagging
        std::vector<int32_t>& first = dim == 2   ? mesh.tri_tag
                                      : dim == 1 ? mesh.line_tag
                                                 : mesh.point_tag;
        for (const int32_t e : g.elements) {
            if (first[e] == 0) {
                first[e] = tag;
            }
        }
        if (!g.name.empty()) {
            mesh.physical[g.name] = {dim, tag};
        }
        mesh.groups.push_back(std::move(g));
    }

    if (mesh.tris.empty()) {
        throw InputError({path, 0, 0}, "",
                         fmt::format("mesh file '{}' contains no triangles (Gmsh element type 2); "
                                     "a body needs a meshed 2-D surface{}",
                                     path,
                                     std::filesystem::path(path).extension() == ".geo"
                                         ? " (define a Plane Surface in the .geo file)"
                                         : ""));
    }
}

}  // namespace

MeshData read_mesh(const std::string& path, Real mesh_size, int order) {
    return read_mesh(path, mesh_size, order, MeshLimits{});
}

namespace {

/// From this many physical names on, a .msh file is read with its names taken by fdem: Gmsh 4.8
/// looks every name up among all earlier ones (GModel::setPhysicalName), O(names^2): 0.3 s at
/// 10^4 names, 2 s at 3 10^4 (issue #16 item 4); below, the cost is a few ms.
constexpr size_t kOwnNamesFrom = 1000;

/// Read the .msh file at path (held by the Gmsh mutex) through a temporary copy without its
/// $PhysicalNames section, the names coming from names. False, with mesh untouched, on any
/// problem (the caller then reads the file itself, so every message is the usual one).
bool read_msh_with_own_names(const std::string& path, const io::MshPhysicalNames& names,
                             MeshData& mesh) {
    std::string data;
    {
        std::ifstream in(path, std::ios::binary);
        data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    if (!(names.section_begin < names.section_end && names.section_end <= data.size())) {
        return false;
    }
    data.erase(names.section_begin, names.section_end - names.section_begin);
    static std::atomic<unsigned> counter{0};
    std::error_code ec;
    const std::filesystem::path copy =
        std::filesystem::temp_directory_path(ec) /
        fmt::format("fdem-{}-{}-{}", static_cast<long>(::getpid()), counter++,
                    std::filesystem::path(path).filename().string());
    if (ec) return false;
    struct Remove {
        const std::filesystem::path& p;
        ~Remove() {
            std::error_code e;
            std::filesystem::remove(p, e);
        }
    } remove{copy};
    {
        std::ofstream out(copy, std::ios::binary);
        out.write(data.data(), static_cast<std::streamsize>(data.size()));
        if (!out) return false;
    }
    data = std::string();
    try {
        GmshSession session;
        gmsh::open(copy.string());
        if (!GmshSession::first_error().empty()) return false;
        MeshData read;
        read.file = path;
        extract(read, &names.names);
        mesh = std::move(read);
        return true;
    } catch (...) {
        return false;
    }
}

}  // namespace

namespace {

/// Ends the process with exit code 2 and `message` on stderr unless destroyed within `seconds`
/// (Gmsh 4.8 has no time limit of its own and cannot be interrupted safely from outside).
class Watchdog {
public:
    Watchdog(Real seconds, std::string message)
        : thread_([this, seconds, msg = std::move(message)] {
              std::unique_lock<std::mutex> lock(mutex_);
              if (!cv_.wait_for(lock, std::chrono::duration<double>(seconds),
                                [this] { return done_; })) {
                  std::fputs(msg.c_str(), stderr);
                  std::fflush(stderr);
                  std::_Exit(2);
              }
          }) {}
    ~Watchdog() {
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            done_ = true;
        }
        cv_.notify_all();
        thread_.join();
    }
    Watchdog(const Watchdog&) = delete;
    Watchdog& operator=(const Watchdog&) = delete;

private:
    std::mutex mutex_;
    std::condition_variable cv_;
    bool done_ = false;
    std::thread thread_;
};

}  // namespace

MeshData read_mesh(const std::string& path, Real mesh_size, int order, const MeshLimits& limits) {
    MeshData mesh;
    mesh.file = path;

    // Gmsh reports a missing file only in its log, so check first
    const std::filesystem::path p(path);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) {
        const bool exists = std::filesystem::exists(p, ec);
        throw InputError({path, 0, 0}, "",
                         fmt::format("cannot open mesh file '{}': {}", path,
                                     exists ? "not a regular file" : "No such file"));
    }
    {
        std::ifstream probe(path, std::ios::binary);
        if (!probe) {
            throw InputError(
                {path, 0, 0}, "",
                fmt::format("cannot open mesh file '{}': {}", path, std::strerror(errno)));
        }
    }
    const std::string ext = p.extension().string();
    if (ext != ".msh" && ext != ".geo") {
        throw InputError({path, 0, 0}, "",
                         fmt::format("mesh file '{}' has extension '{}'; expected .msh (Gmsh mesh) "
                                     "or .geo (Gmsh geometry)",
                                     path, ext));
    }
    if (!std::isfinite(mesh_size) || mesh_size < 0) {
        throw InputError({path, 0, 0}, "mesh_size",
                         fmt::format("mesh size for '{}' must be >= 0 (0 keeps the file's own "
                                     "sizes), got {:g}",
                                     path, mesh_size));
    }

    io::MshPhysicalNames names;
    if (ext == ".msh") {
        io::precheck_msh(path, &names);  // Gmsh 4.8 crashes on some malformed MSH 2 element lines
    }
    const std::lock_guard<std::mutex> lock(gmsh_mutex());
    if (names.plain && names.entries >= kOwnNamesFrom &&
        read_msh_with_own_names(path, names, mesh)) {
        return mesh;
    }
    std::unique_ptr<Watchdog> watchdog;
    if (ext == ".geo") {
        watchdog = std::make_unique<Watchdog>(
            limits.time_limit,
            fmt::format("{}: error: Gmsh did not finish reading and meshing '{}' within "
                        "{:g} s ([[body]] mesh_time_limit); the .geo may loop forever, or the mesh "
                        "is too fine: check the file, a coarser mesh_size, or raise "
                        "mesh_time_limit\n",
                        path, path, limits.time_limit));
    }
    GmshSession session;
    try {
        gmsh::open(path);
        if (std::string err = GmshSession::first_error(); !err.empty()) {
            fail_from_gmsh(path, err);
        }
        if (ext == ".geo") {
            if (mesh_size > 0) {
                gmsh::option::setNumber("Mesh.MeshSizeMax", mesh_size);
                // estimate before meshing: a too-fine mesh makes Gmsh abort the process from its
                // own threads after minutes, where no handler reaches (issue #12 item 7)
                double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
                gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
                const double area = std::max(0.0, x1 - x0) * std::max(0.0, y1 - y0);
                const double estimate = 2.0 * area / (mesh_size * mesh_size);
                if (std::isfinite(area) && estimate > limits.max_triangles) {
                    throw InputError(
                        {path, 0, 0}, "max_triangles",
                        fmt::format("mesh_size = {:g} m on '{}' (bounding box {:g} m x {:g} m) "
                                    "makes about {:.3g} triangles (2 x area / mesh_size^2), more "
                                    "than max_triangles = {:g}; expected a coarser mesh_size "
                                    "(>= {:.3g} m), or raise [[body]] max_triangles if this mesh "
                                    "is intended",
                                    mesh_size, path, x1 - x0, y1 - y0, estimate,
                                    limits.max_triangles,
                                    std::sqrt(2.0 * area / limits.max_triangles)));
                }
            }
            gmsh::model::mesh::generate(2);
            if (order == 2) {
                gmsh::model::mesh::setOrder(2);  // 6-node triangles for composite elements
            }
            if (std::string err = GmshSession::first_error(); !err.empty()) {
                fail_from_gmsh(path, err);
            }
        }
        extract(mesh);
    } catch (const InputError&) {
        throw;
    } catch (const std::string& err) {
        // Gmsh 4.8 throws its last error message as a std::string
        fail_from_gmsh(path, err);
    } catch (const std::exception& e) {
        fail_from_gmsh(path, e.what());
    } catch (...) {
        std::string err;
        gmsh::logger::getLastError(err);
        fail_from_gmsh(path, err.empty() ? "unknown Gmsh error" : err);
    }
    return mesh;
}

}  // namespace fdem
