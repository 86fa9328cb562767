// Fracture output (io/fracture_output.hpp; spec fracture.md §8; docs/output.md).
#include "io/fracture_output.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <numbers>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>

#include "fdem/error.hpp"
#include "io/atomic_file.hpp"

static_assert(std::endian::native == std::endian::little,
              "the joint VTU writer writes raw native values and declares LittleEndian");

namespace fdem {

namespace fs = std::filesystem;

std::vector<std::array<TriId, 2>> joint_triangles(const Model& m) {
    const int32_t nn = m.num_nodes();
    const int32_t nt = m.num_tris();
    // triangles of every node (CSR)
    std::vector<int32_t> begin(static_cast<size_t>(nn) + 1, 0);
    for (const auto& t : m.tri_nodes)
        for (const NodeId n : t)
            ++begin[static_cast<size_t>(n) + 1];
    for (size_t i = 1; i < begin.size(); ++i)
        begin[i] += begin[i - 1];
    std::vector<TriId> tris(static_cast<size_t>(begin.back()));
    std::vector<int32_t> fill(begin.begin(), begin.end() - 1);
    for (TriId t = 0; t < nt; ++t)
        for (const NodeId n : m.tri_nodes[static_cast<size_t>(t)])
            tris[static_cast<size_t>(fill[static_cast<size_t>(n)]++)] = t;
    // the triangle with both nodes of an edge
    auto find = [&](NodeId a, NodeId b) {
        for (int32_t k = begin[static_cast<size_t>(a)]; k < begin[static_cast<size_t>(a) + 1];
             ++k) {
            const TriId t = tris[static_cast<size_t>(k)];
            const auto& tn = m.tri_nodes[static_cast<size_t>(t)];
            if (tn[0] == b || tn[1] == b || tn[2] == b) return t;
        }
        return static_cast<TriId>(kNone);
    };
    std::vector<std::array<TriId, 2>> out(m.joints.nodes.size());
    for (size_t j = 0; j < out.size(); ++j) {
        const auto& n = m.joints.nodes[j];
        out[j] = {find(n[0], n[1]), find(n[3], n[2])};
    }
    return out;
}

void triangle_damage(const Model& m, const State& s,
                     std::span<const std::array<TriId, 2>> joint_tris, std::span<Real> out) {
    std::fill(out.begin(), out.end(), 0.0);
    const size_t nj = std::min(joint_tris.size(), s.joints.d_max.size());
    for (size_t j = 0; j < nj; ++j) {
        const auto& d = s.joints.d_max[j];
        const Real dj = std::max({d[0], d[1], d[2]});
        for (const TriId t : joint_tris[j]) {
            if (t == kNone) continue;
            Real& o = out[static_cast<size_t>(t)];
            o = std::max(o, dj);
        }
    }
    (void)m;
}

// ---- joints_NNNNNN.vtu ---------------------------------------------------------------------

namespace {

// One appended array: name, VTK type name, components, raw little-endian bytes.
struct RawArray {
    std::string name;
    const char* type;
    int components;
    std::vector<unsigned char> bytes;
};

template <class T>
RawArray raw(std::string name, const char* type, int components, const std::vector<T>& v) {
    RawArray a{std::move(name), type, components, {}};
    a.bytes.resize(v.size() * sizeof(T));
    if (!v.empty()) std::memcpy(a.bytes.data(), v.data(), a.bytes.size());
    return a;
}

}  // namespace

int32_t write_joints_vtu(const std::string& path, const Model& m, const State& s, bool all) {
    const Joints& J = m.joints;
    const JointState& js = s.joints;
    std::vector<int32_t> ids;
    for (int32_t j = 0; j < J.num_joints(); ++j) {
        if (all || js.status[static_cast<size_t>(j)] != JointStatus::Intact) ids.push_back(j);
    }
    const size_t nc = ids.size();
    std::vector<double> points(6 * nc);
    std::vector<int32_t> joint(nc), state(nc), mode(nc), conn(2 * nc);
    std::vector<int64_t> offsets(nc);
    std::vector<uint8_t> types(nc, 3);  // VTK_LINE
    std::vector<double> damage(nc), break_time(nc), opening(nc), slip(nc), work(nc), length(nc);
    const Vec2* x = s.x.data();
    for (size_t c = 0; c < nc; ++c) {
        const auto j = static_cast<size_t>(ids[c]);
        const auto& n = J.nodes[j];
        const Vec2 x0 = x[n[0]], x1 = x[n[1]], x2 = x[n[2]], x3 = x[n[3]];
        // mid-line: from the middle of the pair 0-3 to the middle of 1-2
        points[6 * c + 0] = 0.5 * (x0.x + x3.x);
        points[6 * c + 1] = 0.5 * (x0.y + x3.y);
        points[6 * c + 2] = 0.0;
        points[6 * c + 3] = 0.5 * (x1.x + x2.x);
        points[6 * c + 4] = 0.5 * (x1.y + x2.y);
        points[6 * c + 5] = 0.0;
        conn[2 * c] = static_cast<int32_t>(2 * c);
        conn[2 * c + 1] = static_cast<int32_t>(2 * c + 1);
        offsets[c] = static_cast<int64_t>(2 * (c + 1));
        joint[c] = ids[c];
        state[c] = static_cast<int32_t>(js.status[j]);
        mode[c] = static_cast<int32_t>(js.mode[j]);
        const auto& d = js.d_max[j];
        damage[c] = std::max({d[0], d[1], d[2]});
        const int64_t bs = js.break_step[j];
        break_time[c] = bs >= 0 ? static_cast<double>(bs) * s.dt
                                : (js.status[j] == JointStatus::Broken ? 0.0 : -1.0);
        // separation at the mid-point (theory eqs. 9.1, 9.2): e along the joint, n into A
        const Real ex = 0.5 * (x1.x + x2.x - x0.x - x3.x), ey = 0.5 * (x1.y + x2.y - x0.y - x3.y);
        const Real h = std::sqrt(ex * ex + ey * ey);
        const Real dx = 0.5 * (x0.x - x3.x + x1.x - x2.x), dy = 0.5 * (x0.y - x3.y + x1.y - x2.y);
        if (h > 0) {
            opening[c] = (-ey * dx + ex * dy) / h;
            slip[c] = (ex * dx + ey * dy) / h;
        }
        work[c] = js.work[j];
        length[c] = J.length0[j];
    }

    std::vector<RawArray> field, cell, geom;
    field.push_back(raw("TIME", "Float64", 1, std::vector<double>{s.time}));
    field.push_back(raw("TimeValue", "Float64", 1, std::vector<double>{s.time}));
    field.push_back(raw("CYCLE", "Int64", 1, std::vector<int64_t>{s.step}));
    cell.push_back(raw("joint", "Int32", 1, joint));
    cell.push_back(raw("state", "Int32", 1, state));
    cell.push_back(raw("damage", "Float64", 1, damage));
    cell.push_back(raw("mode", "Int32", 1, mode));
    cell.push_back(raw("break_time", "Float64", 1, break_time));
    cell.push_back(raw("opening", "Float64", 1, opening));
    cell.push_back(raw("slip", "Float64", 1, slip));
    cell.push_back(raw("dissipated", "Float64", 1, work));
    cell.push_back(raw("length", "Float64", 1, length));
    geom.push_back(raw("Points", "Float64", 3, points));
    geom.push_back(raw("connectivity", "Int32", 1, conn));
    geom.push_back(raw("offsets", "Int64", 1, offsets));
    geom.push_back(raw("types", "UInt8", 1, types));

    uint64_t offset = 0;
    auto place = [&offset](const RawArray& a, const char* indent) {
        const size_t size =
            std::string_view(a.type) == "Int64" || std::string_view(a.type) == "Float64" ? 8
            : std::string_view(a.type) == "UInt8"                                        ? 1
                                                                                         : 4;
        const size_t tuples = a.bytes.size() / (size * static_cast<size_t>(a.components));
        std::string xml = fmt::format(
            "{}<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" "
            "NumberOfTuples=\"{}\" format=\"appended\" offset=\"{}\"/>\n",
            indent, a.type, a.name, a.components, tuples, offset);
        offset += sizeof(uint64_t) + a.bytes.size();
        return xml;
    };
    std::string h;
    h += "<?xml version=\"1.0\"?>\n";
    h += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n";
    h += "  <UnstructuredGrid>\n    <FieldData>\n";
    for (const RawArray& a : field)
        h += place(a, "      ");
    h += "    </FieldData>\n";
    h += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", 2 * nc, nc);
    h += "      <PointData>\n      </PointData>\n";
    h += "      <CellData Scalars=\"damage\">\n";
    for (const RawArray& a : cell)
        h += place(a, "        ");
    h += "      </CellData>\n      <Points>\n";
    h += place(geom[0], "        ");
    h += "      </Points>\n      <Cells>\n";
    for (size_t k = 1; k < geom.size(); ++k)
        h += place(geom[k], "        ");
    h += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
    h += "  <AppendedData encoding=\"raw\">\n   _";
    try {
        AtomicFile file(path);
        file.write(h);
        for (const auto* group : {&field, &cell, &geom}) {
            for (const RawArray& a : *group) {
                const uint64_t n = a.bytes.size();
                file.write(&n, sizeof n);
                if (n > 0) file.write(a.bytes.data(), a.bytes.size());
            }
        }
        file.write(std::string("\n  </AppendedData>\n</VTKFile>\n"));
        file.commit();
    } catch (const std::runtime_error& e) {
        throw SimulationError(s.step, s.time, path, e.what());
    }
    return static_cast<int32_t>(nc);
}

// ---- cracks.csv ----------------------------------------------------------------------------

namespace {

constexpr const char* kCracksHeader = "step,time,joint,x,y,h,mode,work";
constexpr const char* kFragmentsHeader =
    "step,time,fragment,triangles,mass,area,diameter,x,y,vx,vy,kinetic,fragments,"
    "largest_fraction";

int64_t count_broken(const JointState& js) {
    int64_t n = 0;
    for (const JointStatus st : js.status)
        n += st == JointStatus::Broken ? 1 : 0;
    return n;
}

}  // namespace

CracksWriter::CracksWriter(const std::string& path, const Model& m, const State& s, bool restart)
    : csv_(restart ? CsvSeries(path, kCracksHeader, s.step - 1) : CsvSeries(path, kCracksHeader)),
      broken_seen_(count_broken(s.joints)) {
    (void)m;
}

void CracksWriter::after_step(const Model& m, const State& s, int64_t step_before,
                              Real time_before) {
    const JointState& js = s.joints;
    const int64_t broken = count_broken(js);  // a byte compare per joint: vectorised
    if (broken == broken_seen_) return;
    broken_seen_ = broken;
    line_.clear();
    auto out = std::back_inserter(line_);
    bool first = true;
    const Vec2* x = s.x.data();
    for (int32_t j = 0; j < m.joints.num_joints(); ++j) {
        const auto k = static_cast<size_t>(j);
        if (js.break_step[k] != step_before) continue;
        const auto& n = m.joints.nodes[k];
        const Real cx = 0.25 * (x[n[0]].x + x[n[1]].x + x[n[2]].x + x[n[3]].x);
        const Real cy = 0.25 * (x[n[0]].y + x[n[1]].y + x[n[2]].y + x[n[3]].y);
        if (!first) line_ += '\n';
        first = false;
        fmt::format_to(out, "{},{:.17g},{},{:.17g},{:.17g},{:.17g},{},{:.17g}", step_before,
                       time_before, j, cx, cy, m.joints.length0[k], static_cast<int>(js.mode[k]),
                       js.work[k]);
    }
    if (!first) csv_.write_line(line_, s.step, s.time);
}

// ---- fragments.csv -------------------------------------------------------------------------

FragmentsWriter::FragmentsWriter(const std::string& path, const Model& m, int64_t resume_step)
    : csv_(resume_step < 0 ? CsvSeries(path, kFragmentsHeader)
                           : CsvSeries(path, kFragmentsHeader, resume_step)),
      acc_(static_cast<size_t>(m.num_tris())),
      node_frag_(static_cast<size_t>(m.num_nodes()), kNone) {}

void FragmentsWriter::write(const Model& m, const State& s) {
    const int32_t nt = m.num_tris();
    if (static_cast<int32_t>(s.tri_fragment.size()) != nt) return;
    const TriId* frag = s.tri_fragment.data();
    // pass over the triangles: a fragment's id is its smallest triangle, so it is met first at
    // that triangle and reset there
    for (TriId t = 0; t < nt; ++t) {
        const TriId f = frag[t];
        Acc& a = acc_[static_cast<size_t>(f)];
        if (f == t) a = Acc{};
        ++a.tris;
        a.area += m.tri_area0[static_cast<size_t>(t)];
        for (const NodeId n : m.tri_nodes[static_cast<size_t>(t)])
            node_frag_[static_cast<size_t>(n)] = f;
    }
    // pass over the nodes: lumped masses (a node copy lies in one fragment)
    for (NodeId n = 0; n < m.num_nodes(); ++n) {
        const TriId f = node_frag_[static_cast<size_t>(n)];
        if (f == kNone) continue;
        Acc& a = acc_[static_cast<size_t>(f)];
        const Real mass = m.node_mass[static_cast<size_t>(n)];
        const Vec2 xn = s.x[static_cast<size_t>(n)], vn = s.v[static_cast<size_t>(n)];
        a.mass += mass;
        a.mx += mass * xn.x;
        a.my += mass * xn.y;
        a.px += mass * vn.x;
        a.py += mass * vn.y;
        a.ke += 0.5 * mass * (vn.x * vn.x + vn.y * vn.y);
    }
    Acc total;
    int64_t count = 0;
    Real largest = 0;
    for (TriId t = 0; t < nt; ++t) {
        if (frag[t] != t) continue;
        const Acc& a = acc_[static_cast<size_t>(t)];
        ++count;
        largest = std::max(largest, a.mass);
        total.tris += a.tris;
        total.mass += a.mass;
        total.area += a.area;
        total.mx += a.mx;
        total.my += a.my;
        total.px += a.px;
        total.py += a.py;
        total.ke += a.ke;
    }
    const Real fraction = total.mass > 0 ? largest / total.mass : 0;
    block_.clear();
    auto out = std::back_inserter(block_);
    auto row = [&](int64_t id, const Acc& a) {
        const Real inv = a.mass > 0 ? 1 / a.mass : 0;
        fmt::format_to(out,
                       "{},{:.17g},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},"
                       "{:.17g},{},{:.17g}",
                       s.step, s.time, id, a.tris, a.mass, a.area,
                       std::sqrt(4 * a.area / std::numbers::pi), a.mx * inv, a.my * inv, a.px * inv,
                       a.py * inv, a.ke, count, fraction);
    };
    row(-1, total);
    for (TriId t = 0; t < nt; ++t) {
        if (frag[t] != t) continue;
        block_ += '\n';
        row(t, acc_[static_cast<size_t>(t)]);
    }
    csv_.write_line(block_, s.step, s.time);
}

// ---- FractureOutput ------------------------------------------------------------------------

std::string FractureOutput::joint_file_of(const std::string& frame_file) {
    const fs::path p(frame_file);
    std::string name = p.filename().string();
    if (name.rfind("frame_", 0) == 0) name.replace(0, 6, "joints_");
    return (p.parent_path() / name).string();
}

FractureOutput::FractureOutput(const std::string& dir, const Model& m, const State& s,
                               const FractureSettings& settings, bool vtu, bool restart,
                               const std::vector<std::pair<Real, std::string>>& frames)
    : dir_(dir),
      settings_(settings),
      vtu_(vtu),
      cracks_((fs::path(dir) / "cracks.csv").string(), m, s, restart) {
    const fs::path out = dir;
    fragments_ = std::make_unique<FragmentsWriter>((out / "fragments.csv").string(), m,
                                                   restart ? s.step : -1);
    if (vtu_ && settings_.output_joints != JointOutput::None) {
        joints_pvd_ = std::make_unique<PvdSeries>((out / "joints.pvd").string());
        std::error_code ec;
        for (const auto& [t, file] : frames) {
            const std::string jf = joint_file_of(file);
            if (fs::exists(out / jf, ec)) joints_pvd_->add(t, jf);
        }
    }
}

void FractureOutput::write_output(const Model& m, const State& s, int64_t frame, bool last) {
    if (joints_pvd_) {
        const std::string name = fmt::format("joints_{:06d}.vtu", frame);
        write_joints_vtu((fs::path(dir_) / name).string(), m, s,
                         settings_.output_joints == JointOutput::All);
        joints_pvd_->add(s.time, name);
    }
    if (settings_.fragments == FragmentOutput::Interval || last) fragments_->write(m, s);
}

std::vector<std::string> FractureOutput::changed_headers() const {
    std::vector<std::string> out;
    if (cracks_.header_changed()) out.push_back((fs::path(dir_) / "cracks.csv").string());
    if (fragments_->header_changed()) out.push_back((fs::path(dir_) / "fragments.csv").string());
    return out;
}

}  // namespace fdem
