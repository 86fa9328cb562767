// VTU/PVD writer: cell quantities against closed forms, and the binary file layout read back
// byte by byte (the real VTK reader check is tests/output/check_vtu.py).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fdem/build.hpp"
#include "fdem/error.hpp"
#include "fdem/mesh.hpp"
#include "fdem/output.hpp"
#include "fdem/simulate.hpp"

namespace fdem {
namespace {

namespace fs = std::filesystem;

// A unit square made of two triangles, one body, one plane-strain material:
//
//   3 ------ 2
//   |      / |     triangles (0, 1, 2) and (0, 2, 3), counter-clockwise
//   |    /   |
//   0 ------ 1     X0 = (0,0), X1 = (1,0), X2 = (1,1), X3 = (0,1)  [m]
Model unit_square(Real E = 1e9, Real nu = 0.25) {
    Model m;
    Material mat;
    mat.name = "rock";
    mat.density = 2500;
    mat.youngs_modulus = E;
    mat.poisson_ratio = nu;
    // theory eq. 2.5, plane strain
    mat.mu = E / (2 * (1 + nu));
    mat.lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
    m.materials.push_back(mat);
    m.node_x0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.node_body = {0, 0, 0, 0};
    m.tri_nodes = {{0, 1, 2}, {0, 2, 3}};
    m.tri_body = {0, 0};
    m.tri_material = {0, 0};
    for (const auto& n : m.tri_nodes) {
        const Vec2 X0 = m.node_x0[n[0]], X1 = m.node_x0[n[1]], X2 = m.node_x0[n[2]];
        m.tri_dm_inv.push_back(inverse(columns(X1 - X0, X2 - X0)));
        m.tri_area0.push_back(signed_area(X0, X1, X2));
    }
    Body b;
    b.name = "square";
    b.node_end = 4;
    b.tri_end = 2;
    m.bodies.push_back(b);
    return m;
}

/// State with x = F X + c and recognisable per-node values.
State deformed(const Model& m, const Mat2& F, Vec2 c = {}) {
    State s;
    const size_t n = static_cast<size_t>(m.num_nodes());
    s.x.resize(n);
    s.v.resize(n);
    s.f.resize(n);
    s.f_contact.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const Real r = static_cast<Real>(i);
        s.x[i] = F * m.node_x0[i] + c;
        s.v[i] = {r, -r};
        s.f[i] = {10 * r, 20 * r};
        s.f_contact[i] = {-r, 0.5};
    }
    return s;
}

/// A fresh directory per test under gtest's temporary directory.
fs::path test_dir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    fs::path dir = fs::path(::testing::TempDir()) /
                   (std::string("fdem_io_") + info->test_suite_name() + "_" + info->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string read_all(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// Parsed appended-data VTU: DataArray attributes by name (in file order) and the raw block.
struct ParsedVtu {
    struct Arr {
        std::string section, name, type;
        int components = 0;
        long tuples = 0;
        uint64_t offset = 0;
    };
    std::vector<Arr> arrays;
    std::string header;
    std::string appended;  ///< bytes after the '_' marker
    const Arr& get(const std::string& section, const std::string& name) const {
        for (const Arr& a : arrays) {
            if (a.section == section && a.name == name) return a;
        }
        throw std::runtime_error("array not found: " + section + "/" + name);
    }
    /// The byte count header and the payload of an array.
    std::pair<uint64_t, std::string> payload(const Arr& a) const {
        uint64_t n = 0;
        std::memcpy(&n, appended.data() + a.offset, sizeof n);
        return {n, appended.substr(a.offset + sizeof n, n)};
    }
};

ParsedVtu parse_vtu(const std::string& text) {
    ParsedVtu out;
    const size_t mark = text.find("<AppendedData encoding=\"raw\">");
    const size_t underscore = text.find('_', mark);
    out.header = text.substr(0, mark);
    out.appended = text.substr(underscore + 1);
    const std::regex section_re(R"(<(FieldData|PointData|CellData|Points|Cells)[ >])");
    const std::regex arr_re(
        R"re(<DataArray type="(\w+)" Name="([^"]+)" NumberOfComponents="(\d+)"[^>]*NumberOfTuples="(\d+)" format="appended" offset="(\d+)"/>)re");
    std::string section;
    std::istringstream lines(out.header);
    for (std::string line; std::getline(lines, line);) {
        std::smatch m;
        if (std::regex_search(line, m, section_re)) section = m[1];
        if (std::regex_search(line, m, arr_re)) {
            out.arrays.push_back(
                {section, m[2], m[1], std::stoi(m[3]), std::stol(m[4]), std::stoull(m[5])});
        }
    }
    return out;
}

template <class T>
std::vector<T> as(const std::string& bytes) {
    std::vector<T> v(bytes.size() / sizeof(T));
    std::memcpy(v.data(), bytes.data(), v.size() * sizeof(T));
    return v;
}

// ---- tri_fields ---------------------------------------------------------------------------------

TEST(TriFields, UniaxialStretchMatchesClosedForm) {
    // F = diag(1 + e, 1): J = 1 + e, B - I = diag((1+e)^2 - 1, 0) (spec §3.1)
    const Model m = unit_square();
    const Real e = 0.01;
    const State s = deformed(m, {1 + e, 0, 0, 1});
    const Real lam = m.materials[0].lambda, mu = m.materials[0].mu, J = 1 + e;
    const Real sxx = mu / J * ((1 + e) * (1 + e) - 1) + 0.5 * lam * (J - 1 / J);
    const Real syy = 0.5 * lam * (J - 1 / J);
    for (TriId t = 0; t < 2; ++t) {
        const TriFields r = tri_fields(m, s, t);
        // F from rounded positions: a few ulp, amplified only by coefficients ~E -> ~1e-15 E;
        // 1e-12 E is a 1000x margin
        const Real tol = 1e-12 * 1e9;
        EXPECT_NEAR(r.stress.xx, sxx, tol);
        EXPECT_NEAR(r.stress.yy, syy, tol);
        EXPECT_NEAR(r.stress.xy, 0.0, tol);
        EXPECT_NEAR(r.stress.yx, 0.0, tol);
        EXPECT_NEAR(r.strain.xx, 0.5 * ((1 + e) * (1 + e) - 1), 1e-15);  // ulp-level, see above
        EXPECT_NEAR(r.strain.yy, 0.0, 1e-15);
        EXPECT_NEAR(r.von_mises, std::sqrt(sxx * sxx - sxx * syy + syy * syy), tol);
    }
}

TEST(TriFields, SmallStrainLimitIsLinearElasticity) {
    // e = 1e-7: sigma_xx -> (lambda + 2 mu) e with relative error O(e)
    const Model m = unit_square();
    const Real e = 1e-7;
    const State s = deformed(m, {1 + e, 0, 0, 1});
    const Real lam = m.materials[0].lambda, mu = m.materials[0].mu;
    const TriFields r = tri_fields(m, s, 0);
    // O(e) nonlinearity (1e-7) + cancellation of F - I (1e-16 / 1e-7 = 1e-9): 1e-6 relative
    EXPECT_NEAR(r.stress.xx, (lam + 2 * mu) * e, 1e-6 * (lam + 2 * mu) * e);
    EXPECT_NEAR(r.stress.yy, lam * e, 1e-6 * (lam + 2 * mu) * e);
}

TEST(TriFields, RigidRotationAndTranslationAreStressFree) {
    const Model m = unit_square();
    const Real a = 0.7;  // rad
    const State s = deformed(m, {std::cos(a), -std::sin(a), std::sin(a), std::cos(a)}, {3, -2});
    for (TriId t = 0; t < 2; ++t) {
        const TriFields r = tri_fields(m, s, t);
        // cos/sin and F carry ulp errors; sigma ~ E * 1e-16 -> 1e-12 E is a wide bound
        for (Real v : {r.stress.xx, r.stress.xy, r.stress.yx, r.stress.yy, r.von_mises}) {
            EXPECT_NEAR(v, 0.0, 1e-12 * 1e9);
        }
        for (Real v : {r.strain.xx, r.strain.xy, r.strain.yy}) {
            EXPECT_NEAR(v, 0.0, 1e-14);
        }
    }
}

// ---- write_vtu
// -----------------------------------------------------------------------------------

TEST(WriteVtu, AppendedLayoutAndValuesReadBack) {
    const fs::path dir = test_dir();
    const Model m = unit_square();
    State s = deformed(m, {1.1, 0.2, 0, 0.9}, {0.5, 0.25});
    s.time = 0.125;
    s.step = 42;
    const fs::path file = dir / "frame.vtu";
    write_vtu(file.string(), m, s);

    const std::string text = read_all(file);
    ASSERT_EQ(text.rfind("<?xml version=\"1.0\"?>\n", 0), 0u);
    EXPECT_NE(text.find("header_type=\"UInt64\""), std::string::npos);
    EXPECT_NE(text.find("byte_order=\"LittleEndian\""), std::string::npos);
    EXPECT_NE(text.find("NumberOfPoints=\"4\" NumberOfCells=\"2\""), std::string::npos);
    EXPECT_FALSE(fs::exists(file.string() + ".tmp")) << "temporary file left behind";

    const ParsedVtu v = parse_vtu(text);

    // every array in file order: offsets are contiguous [UInt64 count][payload] records and the
    // declared tuples x components x type size equals the count header
    const std::map<std::string, size_t> size_of = {
        {"Float64", 8}, {"Int32", 4}, {"Int64", 8}, {"UInt8", 1}};
    uint64_t expected_offset = 0;
    for (const auto& a : v.arrays) {
        EXPECT_EQ(a.offset, expected_offset) << a.name;
        const auto [count, bytes] = v.payload(a);
        EXPECT_EQ(count, static_cast<uint64_t>(a.tuples) * a.components * size_of.at(a.type))
            << a.name;
        expected_offset += 8 + count;
    }
    EXPECT_EQ(v.appended.substr(expected_offset), "\n  </AppendedData>\n</VTKFile>\n");

    // expected arrays with their shapes
    const std::vector<std::tuple<std::string, std::string, int, long>> want = {
        {"FieldData", "TIME", 1, 1},         {"FieldData", "CYCLE", 1, 1},
        {"PointData", "displacement", 3, 4}, {"PointData", "velocity", 3, 4},
        {"PointData", "force", 3, 4},        {"PointData", "contact_force", 3, 4},
        {"PointData", "body", 1, 4},         {"CellData", "stress", 9, 2},
        {"CellData", "strain", 9, 2},        {"CellData", "von_mises", 1, 2},
        {"CellData", "body", 1, 2},          {"CellData", "material", 1, 2},
        {"Points", "Points", 3, 4},          {"Cells", "connectivity", 1, 6},
        {"Cells", "offsets", 1, 2},          {"Cells", "types", 1, 2}};
    for (const auto& [sec, name, nc, nt] : want) {
        const auto& a = v.get(sec, name);
        EXPECT_EQ(a.components, nc) << name;
        EXPECT_EQ(a.tuples, nt) << name;
    }

    // values: written from doubles without conversion, so compared exactly
    EXPECT_EQ(as<double>(v.payload(v.get("FieldData", "TIME")).second), std::vector<double>{0.125});
    EXPECT_EQ(as<int64_t>(v.payload(v.get("FieldData", "CYCLE")).second), std::vector<int64_t>{42});
    const auto pts = as<double>(v.payload(v.get("Points", "Points")).second);
    const auto disp = as<double>(v.payload(v.get("PointData", "displacement")).second);
    const auto force = as<double>(v.payload(v.get("PointData", "force")).second);
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(pts[3 * i], s.x[i].x);
        EXPECT_EQ(pts[3 * i + 1], s.x[i].y);
        EXPECT_EQ(pts[3 * i + 2], 0.0);
        EXPECT_EQ(disp[3 * i], s.x[i].x - m.node_x0[i].x);
        EXPECT_EQ(disp[3 * i + 1], s.x[i].y - m.node_x0[i].y);
        EXPECT_EQ(force[3 * i + 1], 20.0 * static_cast<double>(i));
    }
    EXPECT_EQ(as<int32_t>(v.payload(v.get("Cells", "connectivity")).second),
              (std::vector<int32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(as<int64_t>(v.payload(v.get("Cells", "offsets")).second),
              (std::vector<int64_t>{3, 6}));
    EXPECT_EQ(v.payload(v.get("Cells", "types")).second, std::string("\x05\x05"));

    // stress tensor layout: row-major 3x3, in-plane block = tri_fields, z row/column zero
    const auto stress = as<double>(v.payload(v.get("CellData", "stress")).second);
    for (TriId t = 0; t < 2; ++t) {
        const TriFields r = tri_fields(m, s, t);
        const double* p = &stress[9 * static_cast<size_t>(t)];
        EXPECT_EQ(p[0], r.stress.xx);
        EXPECT_EQ(p[1], r.stress.xy);
        EXPECT_EQ(p[3], r.stress.yx);
        EXPECT_EQ(p[4], r.stress.yy);
        for (int k : {2, 5, 6, 7, 8})
            EXPECT_EQ(p[k], 0.0);
    }
}

TEST(WriteVtu, LargeMeshCrossesChunkBoundaries) {
    // more tuples than one 4096-tuple chunk, so connectivity chunks start inside a triangle
    Model m;
    Material mat;
    mat.mu = 1;
    m.materials.push_back(mat);
    const int n = 3000;  // triangles: 9000 connectivity entries = 3 chunks
    for (int k = 0; k < n; ++k) {
        const Real x0 = k;
        const NodeId b = m.num_nodes();
        m.node_x0.insert(m.node_x0.end(), {{x0, 0}, {x0 + 1, 0}, {x0, 1}});
        m.node_body.insert(m.node_body.end(), 3, 0);
        m.tri_nodes.push_back({b, b + 1, b + 2});
        m.tri_body.push_back(0);
        m.tri_material.push_back(0);
        m.tri_dm_inv.push_back(identity2());
        m.tri_area0.push_back(0.5);
    }
    const State s = deformed(m, identity2());
    const fs::path file = test_dir() / "big.vtu";
    write_vtu(file.string(), m, s);
    const ParsedVtu v = parse_vtu(read_all(file));
    const auto conn = as<int32_t>(v.payload(v.get("Cells", "connectivity")).second);
    ASSERT_EQ(conn.size(), 3u * n);
    for (int k = 0; k < 3 * n; ++k)
        ASSERT_EQ(conn[static_cast<size_t>(k)], k) << k;
    const auto pts = as<double>(v.payload(v.get("Points", "Points")).second);
    ASSERT_EQ(pts.size(), 9u * n);
    EXPECT_EQ(pts[3 * (3 * n - 2)], static_cast<double>(n));  // node 1 of the last triangle
}

// Pieces of a distributed run (spec D13): the unit square's two triangles split between two
// processes by the owner of their first node; each piece holds its triangle, the nodes it uses
// in local numbering, and node_id / tri_id / rank to merge back; values are the serial ones at
// those ids; the .pvtu lists the pieces with the pieces' arrays.
TEST(WriteVtu, PiecesHoldTheirTrianglesWithGlobalIds) {
    const fs::path dir = test_dir();
    const Model m = unit_square();  // triangles (0, 1, 2) and (0, 2, 3)
    State s = deformed(m, {1.1, 0.2, 0, 0.9}, {0.5, 0.25});
    // triangle 1 starts at node 0 as well: move it to process 1 by owning node 0 there
    const std::vector<int32_t> owner = {1, 0, 0, 0};
    const VtuPiece p0 = make_vtu_piece(m, owner, 0), p1 = make_vtu_piece(m, owner, 1);
    EXPECT_TRUE(p0.tris.empty());
    EXPECT_EQ(p1.tris, (std::vector<int32_t>{0, 1}));
    const std::vector<int32_t> owner2 = {0, 0, 1, 1};
    const VtuPiece a = make_vtu_piece(m, owner2, 0), b = make_vtu_piece(m, owner2, 1);
    EXPECT_EQ(a.tris, (std::vector<int32_t>{0, 1}));  // both start at node 0
    EXPECT_TRUE(b.tris.empty());
    // a piece with one triangle: the second one, by a model whose triangle 1 starts at node 2
    Model m2 = m;
    m2.tri_nodes[1] = {2, 3, 0};
    const VtuPiece q = make_vtu_piece(m2, owner2, 1);
    EXPECT_EQ(q.tris, (std::vector<int32_t>{1}));
    EXPECT_EQ(q.nodes, (std::vector<int32_t>{0, 2, 3}));
    EXPECT_EQ(q.connectivity, (std::vector<int32_t>{1, 2, 0}));

    const fs::path file = dir / "p0001.vtu";
    write_vtu_piece(file.string(), m2, s, q);
    const ParsedVtu v = parse_vtu(read_all(file));
    EXPECT_EQ(as<int32_t>(v.payload(v.get("PointData", "node_id")).second),
              (std::vector<int32_t>{0, 2, 3}));
    EXPECT_EQ(as<int32_t>(v.payload(v.get("CellData", "tri_id")).second), std::vector<int32_t>{1});
    EXPECT_EQ(as<int32_t>(v.payload(v.get("CellData", "rank")).second), std::vector<int32_t>{1});
    EXPECT_EQ(as<int32_t>(v.payload(v.get("Cells", "connectivity")).second),
              (std::vector<int32_t>{1, 2, 0}));
    EXPECT_EQ(as<int64_t>(v.payload(v.get("Cells", "offsets")).second), std::vector<int64_t>{3});
    const auto pts = as<double>(v.payload(v.get("Points", "Points")).second);
    const auto force = as<double>(v.payload(v.get("PointData", "force")).second);
    ASSERT_EQ(pts.size(), 9u);
    for (size_t k = 0; k < 3; ++k) {
        const size_t i = static_cast<size_t>(q.nodes[k]);
        EXPECT_EQ(pts[3 * k], s.x[i].x);
        EXPECT_EQ(pts[3 * k + 1], s.x[i].y);
        EXPECT_EQ(force[3 * k + 1], s.f[i].y);
    }
    const auto stress = as<double>(v.payload(v.get("CellData", "stress")).second);
    EXPECT_EQ(stress[0], tri_fields(m2, s, 1).stress.xx);

    const fs::path pvtu = dir / "frame.pvtu";
    write_pvtu(pvtu.string(), m2, s, {"frame/p0000.vtu", "frame/p0001.vtu"});
    const std::string text = read_all(pvtu);
    EXPECT_NE(text.find("<VTKFile type=\"PUnstructuredGrid\""), std::string::npos);
    EXPECT_NE(text.find("<Piece Source=\"frame/p0001.vtu\"/>"), std::string::npos);
    EXPECT_NE(text.find("<PDataArray type=\"Int32\" Name=\"node_id\" NumberOfComponents=\"1\"/>"),
              std::string::npos);
    EXPECT_NE(text.find("Name=\"tri_id\""), std::string::npos);
    EXPECT_NE(text.find("Name=\"stress\" NumberOfComponents=\"9\""), std::string::npos);
}

TEST(WriteVtu, ExtraFieldsAreAppendedAndTwoComponentsPadded) {
    const Model m = unit_square();
    const State s = deformed(m, identity2());
    const std::vector<Real> dist = {0.0, 0.5, 1.0, 1.5};
    const std::vector<Real> dir = {1, 2, 3, 4, 5, 6, 7, 8};
    const std::vector<Real> tag = {7, 9};
    const ExtraField point[] = {{"distance", 1, dist}, {"normal", 2, dir}};
    const ExtraField cell[] = {{"tag", 1, tag}};
    const fs::path file = test_dir() / "extra.vtu";
    write_vtu(file.string(), m, s, point, cell);

    const ParsedVtu v = parse_vtu(read_all(file));
    EXPECT_EQ(as<double>(v.payload(v.get("PointData", "distance")).second), dist);
    EXPECT_EQ(v.get("PointData", "normal").components, 3);
    EXPECT_EQ(as<double>(v.payload(v.get("PointData", "normal")).second),
              (std::vector<double>{1, 2, 0, 3, 4, 0, 5, 6, 0, 7, 8, 0}));
    EXPECT_EQ(as<double>(v.payload(v.get("CellData", "tag")).second), tag);
}

TEST(WriteVtu, WrongExtraFieldSizeThrowsAndKeepsOldFile) {
    const Model m = unit_square();
    const State s = deformed(m, identity2());
    const fs::path file = test_dir() / "frame.vtu";
    write_vtu(file.string(), m, s);
    const std::string before = read_all(file);

    const std::vector<Real> too_short = {1.0, 2.0, 3.0};  // 4 nodes needed
    const ExtraField point[] = {{"distance", 1, too_short}};
    try {
        write_vtu(file.string(), m, s, point);
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("'distance' has 3 values, expected 4 tuples"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_EQ(read_all(file), before);
    EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
}

TEST(WriteVtu, UnwritableDirectoryIsASimulationErrorNamingTheFile) {
    const Model m = unit_square();
    State s = deformed(m, identity2());
    s.step = 7;
    const std::string path = (test_dir() / "no_such_dir" / "frame.vtu").string();
    try {
        write_vtu(path, m, s);
        FAIL() << "expected SimulationError";
    } catch (const SimulationError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(e.step(), 7);
        EXPECT_NE(msg.find("no_such_dir/frame.vtu"), std::string::npos) << msg;
        EXPECT_NE(msg.find("No such file or directory"), std::string::npos) << msg;
    }
}

// ---- PvdSeries
// -----------------------------------------------------------------------------------

TEST(PvdSeries, RewrittenCompleteAfterEveryFrame) {
    const fs::path dir = test_dir();
    const fs::path pvd = dir / "series.pvd";
    PvdSeries series(pvd.string());

    series.add(0.0, "frame_000000.vtu");
    const std::string one = read_all(pvd);
    EXPECT_NE(one.find(R"(<DataSet timestep="0" group="" part="0" file="frame_000000.vtu"/>)"),
              std::string::npos)
        << one;
    EXPECT_NE(one.find("</VTKFile>\n"), std::string::npos);

    // 0.1 + 0.2 is not 0.3: the 17 significant digits keep the exact double
    series.add(0.1 + 0.2, "a&b.vtu");
    const std::string two = read_all(pvd);
    EXPECT_NE(two.find("frame_000000.vtu"), std::string::npos);
    EXPECT_NE(two.find(R"(timestep="0.30000000000000004")"), std::string::npos) << two;
    EXPECT_NE(two.find(R"(file="a&amp;b.vtu")"), std::string::npos) << two;
    EXPECT_EQ(series.frames().size(), 2u);
    EXPECT_FALSE(fs::exists(pvd.string() + ".tmp"));
}

// With contact on, the nodal contact distance (paper eqs. 1-2) is written as point data. On a
// 4 x 2 structured rectangle of 1 x 0.5 m every interior node lies one cell (0.25 m) from the
// nearest face, and boundary nodes have distance 0.
TEST(WriteVtu, ContactDistanceIsWrittenWhenContactIsOn) {
    Model m;
    Material mat;
    mat.name = "m";
    mat.density = 1000;
    mat.youngs_modulus = 1e9;
    m.materials.push_back(mat);
    const MeshData mesh = make_rectangle_mesh(0, 0, 1, 0.5, 4, 2);
    std::vector<int32_t> all(mesh.tris.size());
    for (size_t i = 0; i < all.size(); ++i)
        all[i] = static_cast<int32_t>(i);
    BodyOptions opt;
    opt.name = "r";
    add_bodies(m, mesh, all, opt);
    m.contact.algorithm = ContactAlgorithm::Smooth;
    finalize_model(m);
    State s = make_state(m, 1e-6);
    const fs::path file = test_dir() / "contact_distance.vtu";
    write_vtu(file.string(), m, s);

    const ParsedVtu v = parse_vtu(read_all(file));
    const std::vector<double> d =
        as<double>(v.payload(v.get("PointData", "contact_distance")).second);
    ASSERT_EQ(d.size(), static_cast<size_t>(m.num_nodes()));
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        const Vec2 p = m.node_x0[i];
        const bool boundary = p.x < 1e-12 || p.y < 1e-12 || p.x > 1 - 1e-12 || p.y > 0.5 - 1e-12;
        EXPECT_NEAR(d[i], boundary ? 0.0 : 0.25, 1e-12) << "node " << i;
    }
}

}  // namespace
}  // namespace fdem
