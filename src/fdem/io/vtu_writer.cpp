// VTU frame and PVD series writers (docs/output.md).
//
// File layout (VTK XML UnstructuredGrid, "appended" raw binary):
//   <VTKFile ... header_type="UInt64"> XML header with one <DataArray format="appended"
//   offset="k"/> per array </...> <AppendedData encoding="raw">_ then, per array in the same
//   order, a UInt64 byte count followed by the little-endian values.
// The header is small (a few kB); the arrays are converted in fixed-size chunks into one reusable
// buffer and written with fwrite, so memory use does not grow with the mesh beyond that buffer.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>

#include <fmt/format.h>

#include "element/composite.hpp"
#include "element/cst.hpp"
#include "fdem/error.hpp"
#include "fdem/output.hpp"
#include "io/atomic_file.hpp"
#include "io/fracture_output.hpp"
#include "material/hyperelastic.hpp"

static_assert(std::endian::native == std::endian::little,
              "the VTU writer writes raw native values and declares LittleEndian");

namespace fdem {

TriFields tri_fields(const Model& m, const State& s, TriId t) {
    // F = Ds Dm^-1 (theory eq. 3.1); elastic Cauchy stress (theory eq. 2.2, spec §3.1).
    // The viscous part eta D is not included: it needs v at the same time level as x, which the
    // staggered central-difference state does not hold (docs/output.md).
    // Sub-triangles of composite elements carry their isochoric stress plus the composite's
    // pressure (theory eq. 3.8).
    const Mat2 F = deformation_gradient(m, s.x.data(), t);
    const Material& mat = m.materials[static_cast<size_t>(m.tri_material[t])];
    TriFields out;
    out.stress =
        is_composite_tri(m, t) ? composite_stress(m, s.x.data(), t) : cauchy_stress(mat, F);
    out.strain = green_lagrange(F);
    const Mat2& sg = out.stress;
    // von Mises of the in-plane tensor with sigma_zz = 0 (plane-stress form)
    out.von_mises = std::sqrt(sg.xx * sg.xx - sg.xx * sg.yy + sg.yy * sg.yy + 3.0 * sg.xy * sg.xy);
    return out;
}

namespace {

enum class VtkType { Float64, Int32, Int64, UInt8 };

const char* type_name(VtkType t) {
    switch (t) {
        case VtkType::Float64:
            return "Float64";
        case VtkType::Int32:
            return "Int32";
        case VtkType::Int64:
            return "Int64";
        case VtkType::UInt8:
            return "UInt8";
    }
    return "";
}

size_t type_size(VtkType t) {
    switch (t) {
        case VtkType::Float64:
            return 8;
        case VtkType::Int32:
            return 4;
        case VtkType::Int64:
            return 8;
        case VtkType::UInt8:
            return 1;
    }
    return 0;
}

/// Fills tuples [begin, end) into out (tuple-major, components contiguous, native type).
using FillFn = std::function<void(int64_t begin, int64_t end, unsigned char* out)>;

/// One appended data array: its XML description and how to produce its bytes.
struct Array {
    std::string name;
    VtkType type = VtkType::Float64;
    int components = 1;
    int64_t tuples = 0;
    FillFn fill;
    const char* const* component_names = nullptr;  ///< components entries, or nullptr
    uint64_t bytes() const {
        return static_cast<uint64_t>(tuples) * static_cast<uint64_t>(components) * type_size(type);
    }
};

/// Escape the five XML special characters of an attribute value (names, file names).
std::string xml_escape(const std::string& in) {
    std::string out;
    out.reserve(in.size());
    for (const char c : in) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

constexpr const char* kTensorNames[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};

/// 3-component vector array (z = 0) from a Vec2 array.
Array vec_array(std::string name, const std::vector<Vec2>& v) {
    const Vec2* p = v.data();
    return {std::move(name),
            VtkType::Float64,
            3,
            static_cast<int64_t>(v.size()),
            [p](int64_t b, int64_t e, unsigned char* out) {
                double* o = reinterpret_cast<double*>(out);
                for (int64_t i = b; i < e; ++i) {
                    *o++ = p[i].x;
                    *o++ = p[i].y;
                    *o++ = 0.0;
                }
            },
            nullptr};
}

/// Int32 scalar array from an id array.
Array id_array(std::string name, const std::vector<int32_t>& v) {
    const int32_t* p = v.data();
    return {std::move(name),
            VtkType::Int32,
            1,
            static_cast<int64_t>(v.size()),
            [p](int64_t b, int64_t e, unsigned char* out) {
                std::memcpy(out, p + b, static_cast<size_t>(e - b) * sizeof(int32_t));
            },
            nullptr};
}

/// 2x2 in-plane tensor written as a full 3x3 tensor (row-major, z row/column = 0).
void put_tensor(double*& o, const Mat2& a) {
    const double t[9] = {a.xx, a.xy, 0.0, a.yx, a.yy, 0.0, 0.0, 0.0, 0.0};
    std::memcpy(o, t, sizeof(t));
    o += 9;
}

/// A user-supplied extra field; 2-component fields are padded to 3 (z = 0).
Array extra_array(const ExtraField& f, int64_t expected_tuples, const char* where) {
    if (f.components < 1 || f.values.size() != static_cast<size_t>(expected_tuples) *
                                                   static_cast<size_t>(f.components)) {
        throw std::invalid_argument(fmt::format(
            "write_vtu: extra {} field '{}' has {} values, expected {} tuples x {} components",
            where, f.name, f.values.size(), expected_tuples, f.components));
    }
    const Real* p = f.values.data();
    const int nc = f.components;
    if (nc == 2) {
        return {f.name,
                VtkType::Float64,
                3,
                expected_tuples,
                [p](int64_t b, int64_t e, unsigned char* out) {
                    double* o = reinterpret_cast<double*>(out);
                    for (int64_t i = b; i < e; ++i) {
                        *o++ = p[2 * i];
                        *o++ = p[2 * i + 1];
                        *o++ = 0.0;
                    }
                },
                nullptr};
    }
    return {f.name,
            VtkType::Float64,
            nc,
            expected_tuples,
            [p, nc](int64_t b, int64_t e, unsigned char* out) {
                std::memcpy(out, p + b * nc, static_cast<size_t>((e - b) * nc) * sizeof(double));
            },
            nullptr};
}

/// XML line of one DataArray; offset is its position in the appended block.
std::string data_array_xml(const Array& a, uint64_t offset, const char* indent) {
    std::string out = fmt::format(R"({}<DataArray type="{}" Name="{}" NumberOfComponents="{}")",
                                  indent, type_name(a.type), xml_escape(a.name), a.components);
    if (a.component_names != nullptr) {
        for (int c = 0; c < a.components; ++c) {
            out += fmt::format(R"( ComponentName{}="{}")", c, a.component_names[c]);
        }
    }
    out += fmt::format(R"( NumberOfTuples="{}" format="appended" offset="{}"/>)", a.tuples, offset);
    out += '\n';
    return out;
}

/// The arrays of a frame, in file order, and the storage their fill functions read.
struct FrameArrays {
    std::vector<Array> field, point, cell, geom;
    std::vector<int32_t> composite_base;
    std::vector<Real> damage;
    int64_t points = 0, cells = 0;
    FrameArrays() = default;
    FrameArrays(const FrameArrays&) = delete;  // the fill functions point into the storage
};

void build_arrays(const Model& m, const State& s, std::span<const ExtraField> extra_point,
                  std::span<const ExtraField> extra_cell, FrameArrays& A) {
    const int64_t nn = m.num_nodes();
    const int64_t nt = m.num_tris();
    A.points = nn;
    A.cells = nt;
    const Vec2* X = m.node_x0.data();
    const Vec2* x = s.x.data();

    // -- the arrays, in file order --------------------------------------------------------------

    std::vector<Array>& field = A.field;
    std::vector<Array>& point = A.point;
    std::vector<Array>& cell = A.cell;
    std::vector<Array>& geom = A.geom;
    const double time = s.time;
    const int64_t cycle = s.step;
    auto scalar = [](double v) {
        return [v](int64_t, int64_t, unsigned char* out) { std::memcpy(out, &v, sizeof v); };
    };
    field.push_back({"TIME", VtkType::Float64, 1, 1, scalar(time), nullptr});
    field.push_back({"TimeValue", VtkType::Float64, 1, 1, scalar(time), nullptr});
    field.push_back(
        {"CYCLE", VtkType::Int64, 1, 1,
         [cycle](int64_t, int64_t, unsigned char* out) { std::memcpy(out, &cycle, sizeof cycle); },
         nullptr});

    // point data
    point.push_back({"displacement", VtkType::Float64, 3, nn,
                     [X, x](int64_t b, int64_t e, unsigned char* out) {
                         double* o = reinterpret_cast<double*>(out);
                         for (int64_t i = b; i < e; ++i) {
                             *o++ = x[i].x - X[i].x;
                             *o++ = x[i].y - X[i].y;
                             *o++ = 0.0;
                         }
                     },
                     nullptr});
    point.push_back(vec_array("velocity", s.v));
    point.push_back(vec_array("force", s.f));
    point.push_back(vec_array("contact_force", s.f_contact));
    point.push_back(id_array("body", m.node_body));
    // the nodal contact distance d_i of paper eqs. 1-2 (0 on the boundary); ParaView's linear
    // interpolation of it over each triangle is the distance field of paper eq. 3 wherever the
    // element needed no virtual-node split (theory §6)
    const ContactTopology& ct = s.topology;
    if (m.contact.algorithm != ContactAlgorithm::None &&
        static_cast<int64_t>(ct.node_dist.size()) >= nn) {
        const Real* dist = ct.node_dist.data();
        point.push_back({"contact_distance", VtkType::Float64, 1, nn,
                         [dist](int64_t b, int64_t e, unsigned char* out) {
                             double* o = reinterpret_cast<double*>(out);
                             for (int64_t i = b; i < e; ++i)
                                 *o++ = dist[i];
                         },
                         nullptr});
    }
    for (const ExtraField& f : extra_point) {
        point.push_back(extra_array(f, nn, "point"));
    }

    // cell data (tensors recomputed per array: cheap next to the I/O, and no per-frame storage)
    cell.push_back({"stress", VtkType::Float64, 9, nt,
                    [&m, &s](int64_t b, int64_t e, unsigned char* out) {
                        double* o = reinterpret_cast<double*>(out);
                        for (int64_t t = b; t < e; ++t) {
                            put_tensor(o, tri_fields(m, s, static_cast<TriId>(t)).stress);
                        }
                    },
                    kTensorNames});
    cell.push_back({"strain", VtkType::Float64, 9, nt,
                    [&m, &s](int64_t b, int64_t e, unsigned char* out) {
                        double* o = reinterpret_cast<double*>(out);
                        for (int64_t t = b; t < e; ++t) {
                            put_tensor(o, tri_fields(m, s, static_cast<TriId>(t)).strain);
                        }
                    },
                    kTensorNames});
    cell.push_back({"von_mises", VtkType::Float64, 1, nt,
                    [&m, &s](int64_t b, int64_t e, unsigned char* out) {
                        double* o = reinterpret_cast<double*>(out);
                        for (int64_t t = b; t < e; ++t) {
                            *o++ = tri_fields(m, s, static_cast<TriId>(t)).von_mises;
                        }
                    },
                    nullptr});
    cell.push_back(id_array("body", m.tri_body));
    cell.push_back(id_array("material", m.tri_material));
    // composite elements (theory §3.5): the id of the composite owning each sub-triangle,
    // numbered over the model in triangle order (-1 for CST triangles); only written when the
    // model has a composite body
    std::vector<int32_t>& composite_base = A.composite_base;
    composite_base.assign(static_cast<size_t>(m.num_bodies()), -1);
    int32_t n_composites = 0;
    for (size_t b = 0; b < composite_base.size(); ++b) {
        const Body& body = m.bodies[b];
        if (body.element == ElementKind::Composite6) {
            composite_base[b] = n_composites;
            n_composites += (body.tri_end - body.tri_begin) / 4;
        }
    }
    if (n_composites > 0) {
        cell.push_back({"composite", VtkType::Int32, 1, nt,
                        [&m, &composite_base](int64_t b, int64_t e, unsigned char* out) {
                            for (int64_t t = b; t < e; ++t) {
                                const BodyId id = m.tri_body[static_cast<size_t>(t)];
                                const int32_t base = composite_base[static_cast<size_t>(id)];
                                const int32_t c =
                                    base < 0
                                        ? -1
                                        : base + (static_cast<int32_t>(t) -
                                                  m.bodies[static_cast<size_t>(id)].tri_begin) /
                                                     4;
                                std::memcpy(out + (t - b) * 4, &c, sizeof c);
                            }
                        },
                        nullptr});
    }
    // fracture (spec fracture.md §8): the fragment of every triangle (State::tri_fragment) and
    // the largest frozen damage of the joints on its edges; only for models with joints, so
    // other frames keep their bytes
    std::vector<Real>& damage = A.damage;
    if (!m.joints.nodes.empty() && static_cast<int64_t>(s.tri_fragment.size()) == nt) {
        cell.push_back(id_array("fragment", s.tri_fragment));
        damage.resize(static_cast<size_t>(nt));
        triangle_damage(m, s, joint_triangles(m), damage);
        const Real* d = damage.data();
        cell.push_back({"damage", VtkType::Float64, 1, nt,
                        [d](int64_t b, int64_t e, unsigned char* out) {
                            std::memcpy(out, d + b, static_cast<size_t>(e - b) * sizeof(double));
                        },
                        nullptr});
    }
    for (const ExtraField& f : extra_cell) {
        cell.push_back(extra_array(f, nt, "cell"));
    }

    // geometry and topology
    geom.push_back(vec_array("Points", s.x));
    const auto* tri = m.tri_nodes.data();
    geom.push_back({"connectivity", VtkType::Int32, 1, 3 * nt,
                    [tri](int64_t b, int64_t e, unsigned char* out) {
                        // tuples are node slots; a chunk may start inside a triangle
                        int32_t* o = reinterpret_cast<int32_t*>(out);
                        for (int64_t k = b; k < e; ++k) {
                            *o++ = tri[k / 3][static_cast<size_t>(k % 3)];
                        }
                    },
                    nullptr});
    geom.push_back({"offsets", VtkType::Int64, 1, nt,
                    [](int64_t b, int64_t e, unsigned char* out) {
                        int64_t* o = reinterpret_cast<int64_t*>(out);
                        for (int64_t t = b; t < e; ++t) {
                            *o++ = 3 * (t + 1);
                        }
                    },
                    nullptr});
    geom.push_back({"types", VtkType::UInt8, 1, nt,
                    [](int64_t b, int64_t e, unsigned char* out) {
                        std::memset(out, 5, static_cast<size_t>(e - b));  // VTK_TRIANGLE
                    },
                    nullptr});
}

/// a's tuples at the indices index[0 .. n) (a piece's nodes or triangles, spec D13)
Array select(const Array& a, const std::vector<int32_t>& index) {
    Array r = a;
    r.tuples = static_cast<int64_t>(index.size());
    const size_t tb = static_cast<size_t>(a.components) * type_size(a.type);
    r.fill = [fill = a.fill, &index, tb](int64_t b, int64_t e, unsigned char* out) {
        for (int64_t k = b; k < e; ++k) {
            const int64_t i = index[static_cast<size_t>(k)];
            fill(i, i + 1, out + static_cast<size_t>(k - b) * tb);
        }
    };
    return r;
}

/// The arrays of piece p only: its triangles and the nodes they use, numbered locally, plus
/// node_id, tri_id and rank (spec D13: the ids merge pieces back into the serial frame).
void restrict_to_piece(const VtuPiece& p, FrameArrays& A) {
    for (Array& a : A.point)
        a = select(a, p.nodes);
    for (Array& a : A.cell)
        a = select(a, p.tris);
    const int32_t* nodes = p.nodes.data();
    const int32_t* tris = p.tris.data();
    A.point.push_back({"node_id", VtkType::Int32, 1, static_cast<int64_t>(p.nodes.size()),
                       [nodes](int64_t b, int64_t e, unsigned char* out) {
                           std::memcpy(out, nodes + b, static_cast<size_t>(e - b) * 4);
                       },
                       nullptr});
    A.cell.push_back({"tri_id", VtkType::Int32, 1, static_cast<int64_t>(p.tris.size()),
                      [tris](int64_t b, int64_t e, unsigned char* out) {
                          std::memcpy(out, tris + b, static_cast<size_t>(e - b) * 4);
                      },
                      nullptr});
    const int32_t rank = p.rank;
    A.cell.push_back({"rank", VtkType::Int32, 1, static_cast<int64_t>(p.tris.size()),
                      [rank](int64_t b, int64_t e, unsigned char* out) {
                          for (int64_t k = b; k < e; ++k)
                              std::memcpy(out + (k - b) * 4, &rank, 4);
                      },
                      nullptr});
    A.geom[0] = select(A.geom[0], p.nodes);
    const int32_t* conn = p.connectivity.data();
    A.geom[1].tuples = static_cast<int64_t>(p.connectivity.size());
    A.geom[1].fill = [conn](int64_t b, int64_t e, unsigned char* out) {
        std::memcpy(out, conn + b, static_cast<size_t>(e - b) * 4);
    };
    A.geom[2].tuples = A.geom[3].tuples = static_cast<int64_t>(p.tris.size());
    A.points = static_cast<int64_t>(p.nodes.size());
    A.cells = static_cast<int64_t>(p.tris.size());
}

void write_frame(const std::string& path, const Model& m, const State& s, const FrameArrays& A) {
    const std::vector<Array>& field = A.field;
    const std::vector<Array>& point = A.point;
    const std::vector<Array>& cell = A.cell;
    const std::vector<Array>& geom = A.geom;
    const int64_t nn = A.points;
    const int64_t nt = A.cells;

    // -- XML header ----------------------------------------------------------------------------

    uint64_t offset = 0;
    auto place = [&offset](const Array& a, const char* indent) {
        std::string xml = data_array_xml(a, offset, indent);
        offset += sizeof(uint64_t) + a.bytes();
        return xml;
    };
    std::string h;
    h.reserve(4096);
    h += "<?xml version=\"1.0\"?>\n";
    h += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n";
    h += "  <UnstructuredGrid>\n";
    h += "    <FieldData>\n";
    for (const Array& a : field)
        h += place(a, "      ");
    // body names indexed by body id (the `body` point and cell arrays), inline: VTK writes a
    // String array as the byte values of the names, each followed by 0 (vtkXMLWriter, ASCII)
    h += fmt::format(
        "      <Array type=\"String\" Name=\"body_name\" NumberOfTuples=\"{}\" "
        "format=\"ascii\">\n       ",
        m.bodies.size());
    for (const Body& b : m.bodies) {
        for (const char c : b.name)
            h += fmt::format(" {}", static_cast<unsigned>(static_cast<unsigned char>(c)));
        h += " 0";
    }
    h += "\n      </Array>\n";
    h += "    </FieldData>\n";
    h += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", nn, nt);
    h += "      <PointData Vectors=\"velocity\">\n";
    for (const Array& a : point)
        h += place(a, "        ");
    h += "      </PointData>\n";
    h += "      <CellData Scalars=\"von_mises\" Tensors=\"stress\">\n";
    for (const Array& a : cell)
        h += place(a, "        ");
    h += "      </CellData>\n";
    h += "      <Points>\n";
    h += place(geom[0], "        ");
    h += "      </Points>\n";
    h += "      <Cells>\n";
    for (size_t k = 1; k < geom.size(); ++k)
        h += place(geom[k], "        ");
    h += "      </Cells>\n";
    h += "    </Piece>\n";
    h += "  </UnstructuredGrid>\n";
    h += "  <AppendedData encoding=\"raw\">\n   _";

    // -- write: header, then each array as [UInt64 byte count][raw values] -----------------------

    try {
        AtomicFile file(path);
        file.write(h);

        constexpr int64_t kChunkTuples = 4096;
        std::vector<unsigned char> buffer;
        auto emit = [&](const Array& a) {
            const uint64_t n = a.bytes();
            file.write(&n, sizeof n);
            const size_t tuple_bytes = static_cast<size_t>(a.components) * type_size(a.type);
            buffer.resize(std::max(buffer.size(), static_cast<size_t>(kChunkTuples) * tuple_bytes));
            for (int64_t b = 0; b < a.tuples; b += kChunkTuples) {
                const int64_t e = std::min(a.tuples, b + kChunkTuples);
                a.fill(b, e, buffer.data());
                file.write(buffer.data(), static_cast<size_t>(e - b) * tuple_bytes);
            }
        };
        for (const auto* group : {&field, &point, &cell, &geom}) {
            for (const Array& a : *group)
                emit(a);
        }
        file.write(std::string("\n  </AppendedData>\n</VTKFile>\n"));
        file.commit();
    } catch (const std::runtime_error& e) {
        throw SimulationError(s.step, s.time, path, e.what());
    }
}

/// <PDataArray .../> of a's name, type and components (no data: the pieces hold it)
std::string pdata_array_xml(const Array& a, const char* indent) {
    std::string out = fmt::format(R"({}<PDataArray type="{}" Name="{}" NumberOfComponents="{}")",
                                  indent, type_name(a.type), xml_escape(a.name), a.components);
    if (a.component_names != nullptr) {
        for (int c = 0; c < a.components; ++c)
            out += fmt::format(R"( ComponentName{}="{}")", c, a.component_names[c]);
    }
    return out + "/>\n";
}

}  // namespace

void write_vtu(const std::string& path, const Model& m, const State& s,
               std::span<const ExtraField> extra_point, std::span<const ExtraField> extra_cell) {
    FrameArrays A;
    build_arrays(m, s, extra_point, extra_cell, A);
    write_frame(path, m, s, A);
}

VtuPiece make_vtu_piece(const Model& m, const std::vector<int32_t>& node_owner, int32_t rank) {
    VtuPiece p;
    p.rank = rank;
    std::vector<int32_t> local(static_cast<size_t>(m.num_nodes()), -1);
    for (TriId t = 0; t < m.num_tris(); ++t) {
        const auto& tn = m.tri_nodes[static_cast<size_t>(t)];
        if (node_owner[static_cast<size_t>(tn[0])] != rank) continue;  // its first node's owner
        p.tris.push_back(t);
        for (const NodeId i : tn)
            local[static_cast<size_t>(i)] = 0;
    }
    for (NodeId i = 0; i < m.num_nodes(); ++i) {
        if (local[static_cast<size_t>(i)] == 0) {
            local[static_cast<size_t>(i)] = static_cast<int32_t>(p.nodes.size());
            p.nodes.push_back(i);
        }
    }
    for (const TriId t : p.tris) {
        for (const NodeId i : m.tri_nodes[static_cast<size_t>(t)])
            p.connectivity.push_back(local[static_cast<size_t>(i)]);
    }
    return p;
}

void write_vtu_piece(const std::string& path, const Model& m, const State& s, const VtuPiece& piece,
                     std::span<const ExtraField> extra_point,
                     std::span<const ExtraField> extra_cell) {
    FrameArrays A;
    build_arrays(m, s, extra_point, extra_cell, A);
    restrict_to_piece(piece, A);
    write_frame(path, m, s, A);
}

void write_pvtu(const std::string& path, const Model& m, const State& s,
                const std::vector<std::string>& sources, std::span<const ExtraField> extra_point,
                std::span<const ExtraField> extra_cell) {
    FrameArrays A;
    build_arrays(m, s, extra_point, extra_cell, A);
    const VtuPiece none;
    restrict_to_piece(none, A);  // the arrays' names and types as the pieces have them
    std::string h;
    h += "<?xml version=\"1.0\"?>\n";
    h += "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n";
    h += "  <PUnstructuredGrid GhostLevel=\"0\">\n";
    h += "    <PPointData Vectors=\"velocity\">\n";
    for (const Array& a : A.point)
        h += pdata_array_xml(a, "      ");
    h += "    </PPointData>\n";
    h += "    <PCellData Scalars=\"von_mises\" Tensors=\"stress\">\n";
    for (const Array& a : A.cell)
        h += pdata_array_xml(a, "      ");
    h += "    </PCellData>\n";
    h += "    <PPoints>\n";
    h += pdata_array_xml(A.geom[0], "      ");
    h += "    </PPoints>\n";
    for (const std::string& src : sources)
        h += fmt::format("    <Piece Source=\"{}\"/>\n", xml_escape(src));
    h += "  </PUnstructuredGrid>\n";
    h += "</VTKFile>\n";
    try {
        AtomicFile file(path);
        file.write(h);
        file.commit();
    } catch (const std::runtime_error& e) {
        throw SimulationError(s.step, s.time, path, e.what());
    }
}

// ---- PvdSeries
// ------------------------------------------------------------------------------------

void PvdSeries::add(Real time, const std::string& relative_file) {
    frames_.emplace_back(time, relative_file);

    // rewrite the whole collection: a few hundred bytes per frame, atomically replaced
    std::string xml;
    xml += "<?xml version=\"1.0\"?>\n";
    xml += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
    xml += "  <Collection>\n";
    for (const auto& [t, file] : frames_) {
        // %.17g: ParaView sorts and matches frames by this value, keep it exact
        xml +=
            fmt::format("    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
                        t, xml_escape(file));
    }
    xml += "  </Collection>\n";
    xml += "</VTKFile>\n";
    try {
        AtomicFile out(path_);
        out.write(xml);
        out.commit();
    } catch (const std::runtime_error& e) {
        throw SimulationError(-1, time, path_, e.what());
    }
}

}  // namespace fdem
