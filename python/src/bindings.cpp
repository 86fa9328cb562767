// The Python module `fdem` (its compiled part `fdem._fdem`): pybind11 bindings of the public C++
// API (include/fdem/). All bindings live in this one file (spec parallel-and-python.md §6.2 P1) so
// that a later switch to nanobind is mechanical. docs/python.md documents the API.
//
// Views (spec P4): array properties return NumPy arrays that point at the std::vector storage of
// the Simulation's State and Model (allocated once, never reallocated during a run, kept at the
// same address across restore_checkpoint), with the owning Python object as their base, so a view
// keeps the Simulation alive, costs no copy and shows the values of every later step. Arrays whose
// writes would bypass invariants (x, forces, Model arrays) are read-only.
//
// GIL (spec P6): step() and run() release the GIL while C++ steps; a Python callback of run()
// takes it back only for its call, and every 256 steps run() takes it to look for Ctrl-C
// (PyErr_CheckSignals), which stops the run after that step and raises KeyboardInterrupt.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <exception>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "fdem/build.hpp"
#include "fdem/error.hpp"
#include "fdem/measure.hpp"
#include "fdem/mesh.hpp"
#include "fdem/model.hpp"
#include "fdem/output.hpp"
#include "fdem/scenario.hpp"
#include "fdem/simulate.hpp"
#include "fdem/simulation.hpp"
#include "fdem/state.hpp"
#include "fdem/version.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace {

// ---- errors (spec P6) ---------------------------------------------------------------------------

py::handle g_input_error;       // fdem.InputError(ValueError)
py::handle g_simulation_error;  // fdem.SimulationError(RuntimeError)

void translate(std::exception_ptr p) {
    try {
        if (p) std::rethrow_exception(p);
    } catch (const fdem::InputError& e) {
        py::object exc = py::reinterpret_borrow<py::object>(g_input_error)(e.what());
        exc.attr("file") = e.location().file;
        exc.attr("line") = e.location().line;
        exc.attr("column") = e.location().column;
        exc.attr("key") = e.key();
        exc.attr("message") = e.message();
        PyErr_SetObject(g_input_error.ptr(), exc.ptr());
    } catch (const fdem::SimulationError& e) {
        py::object exc = py::reinterpret_borrow<py::object>(g_simulation_error)(e.what());
        exc.attr("step") = e.step();
        exc.attr("time") = e.time();
        exc.attr("entity") = e.entity();
        PyErr_SetObject(g_simulation_error.ptr(), exc.ptr());
    }
}

// ---- zero-copy views (spec P4)
// -------------------------------------------------------------------

void set_readonly(py::array& a) {
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
}

/// An (n, cols) view of n records of `cols` contiguous T each, starting at data, owned by base.
template <class T>
py::array view(py::handle base, const void* data, size_t n, size_t cols, bool writeable) {
    std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(n)};
    std::vector<py::ssize_t> strides{static_cast<py::ssize_t>(cols * sizeof(T))};
    if (cols > 1) {
        shape.push_back(static_cast<py::ssize_t>(cols));
        strides.push_back(static_cast<py::ssize_t>(sizeof(T)));
    }
    // an empty vector's data() may be null: NumPy wants a valid pointer for a view
    static T dummy{};
    const T* ptr = n > 0 ? static_cast<const T*>(data) : &dummy;
    py::array a(py::dtype::of<T>(), shape, strides, ptr, base);
    if (!writeable) set_readonly(a);
    return a;
}

py::array vec2_view(py::handle base, const std::vector<fdem::Vec2>& v, bool writeable) {
    static_assert(sizeof(fdem::Vec2) == 2 * sizeof(double));
    return view<double>(base, v.data(), v.size(), 2, writeable);
}

template <class T>
py::array scalar_view(py::handle base, const std::vector<T>& v) {
    return view<T>(base, v.data(), v.size(), 1, false);
}

/// Copy an (n, 2) float array into dst (n must equal dst.size()).
void copy_vec2(const py::array_t<double, py::array::c_style | py::array::forcecast>& a,
               std::vector<fdem::Vec2>& dst, const char* what) {
    if (a.ndim() != 2 || a.shape(1) != 2 || static_cast<size_t>(a.shape(0)) != dst.size()) {
        throw py::value_error(std::string(what) + ": expected an array of shape (" +
                              std::to_string(dst.size()) + ", 2)");
    }
    const double* p = a.data();
    for (size_t i = 0; i < dst.size(); ++i) {
        if (!std::isfinite(p[2 * i]) || !std::isfinite(p[2 * i + 1])) {
            throw py::value_error(std::string(what) + ": row " + std::to_string(i) +
                                  " is not finite");
        }
    }
    std::memcpy(static_cast<void*>(dst.data()), p, dst.size() * sizeof(fdem::Vec2));
}

py::tuple vec(fdem::Vec2 v) {
    return py::make_tuple(v.x, v.y);
}

// ---- meshes from arrays
// ---------------------------------------------------------------------------

/// A MeshData from NumPy arrays: nodes (n, 2) [m], triangles (m, 3) or (m, 6) (Gmsh order:
/// corners then mid-edge nodes), groups: name -> node ids (k,) (a point group), node pairs (k, 2)
/// (a curve group of line elements), and triangle_groups: name -> triangle ids (a surface group).
fdem::MeshData mesh_from_arrays(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& nodes,
    const py::array_t<int64_t, py::array::c_style | py::array::forcecast>& tris,
    const py::dict& groups, const py::dict& tri_groups, const std::string& name) {
    using IdArray = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;
    auto fail = [&](const std::string& key, const std::string& msg) {
        throw fdem::InputError({name, 0, 0}, key, msg);
    };
    if (nodes.ndim() != 2 || nodes.shape(1) != 2) {
        fail("nodes",
             "nodes: expected an array of shape (n, 2) [m], got " + std::to_string(nodes.ndim()) +
                 " dimensions" +
                 (nodes.ndim() == 2 ? " with " + std::to_string(nodes.shape(1)) + " columns" : ""));
    }
    if (tris.ndim() != 2 || (tris.shape(1) != 3 && tris.shape(1) != 6)) {
        fail("triangles",
             "triangles: expected an integer array of shape (m, 3) (3-node) or "
             "(m, 6) (6-node, corners then mid-edge nodes)");
    }
    fdem::MeshData mesh;
    mesh.file = name;
    const auto nn = static_cast<size_t>(nodes.shape(0));
    mesh.nodes.resize(nn);
    for (size_t i = 0; i < nn; ++i) {
        const double x = nodes.at(i, 0), y = nodes.at(i, 1);
        if (!std::isfinite(x) || !std::isfinite(y)) {
            fail("nodes", "nodes: row " + std::to_string(i) + " is not finite");
        }
        mesh.nodes[i] = {x, y};
    }
    auto node_id = [&](int64_t v, const std::string& what, size_t row) {
        if (v < 0 || static_cast<size_t>(v) >= nn) {
            fail(what, what + ": row " + std::to_string(row) + " refers to node " +
                           std::to_string(v) + "; expected a node id in [0, " + std::to_string(nn) +
                           ")");
        }
        return static_cast<int32_t>(v);
    };
    const auto nt = static_cast<size_t>(tris.shape(0));
    if (nt == 0) fail("triangles", "triangles: the mesh has no triangle");
    const bool order2 = tris.shape(1) == 6;
    mesh.tris.resize(nt);
    if (order2) mesh.tri_mid.resize(nt);
    for (size_t t = 0; t < nt; ++t) {
        for (int k = 0; k < 3; ++k) {
            mesh.tris[t][static_cast<size_t>(k)] = node_id(tris.at(t, k), "triangles", t);
            if (order2) {
                mesh.tri_mid[t][static_cast<size_t>(k)] =
                    node_id(tris.at(t, k + 3), "triangles", t);
            }
        }
    }
    mesh.tri_tag.assign(nt, 0);
    int tag = 0;
    for (const auto& item : tri_groups) {
        const std::string gname = py::str(item.first);
        const auto ids = item.second.cast<IdArray>();
        fdem::PhysicalGroup g{gname, 2, ++tag, {}};
        if (ids.ndim() != 1) fail(gname, "triangle group '" + gname + "': expected a 1-D array");
        for (py::ssize_t i = 0; i < ids.shape(0); ++i) {
            const int64_t t = ids.at(i);
            if (t < 0 || static_cast<size_t>(t) >= nt) {
                fail(gname, "triangle group '" + gname + "': entry " + std::to_string(i) +
                                " refers to triangle " + std::to_string(t) +
                                "; expected a triangle id in [0, " + std::to_string(nt) + ")");
            }
            g.elements.push_back(static_cast<int32_t>(t));
            if (mesh.tri_tag[static_cast<size_t>(t)] == 0) {
                mesh.tri_tag[static_cast<size_t>(t)] = g.tag;
            }
        }
        std::sort(g.elements.begin(), g.elements.end());
        g.elements.erase(std::unique(g.elements.begin(), g.elements.end()), g.elements.end());
        mesh.physical[gname] = {2, g.tag};
        mesh.groups.push_back(std::move(g));
    }
    int point_tag = 0, line_tag = 0;
    for (const auto& item : groups) {
        const std::string gname = py::str(item.first);
        const auto ids = item.second.cast<IdArray>();
        if (mesh.physical.count(gname) != 0) {
            fail(gname, "group '" + gname + "' is given twice (as a node and a triangle group)");
        }
        if (ids.ndim() == 1) {
            fdem::PhysicalGroup g{gname, 0, ++point_tag, {}};
            for (py::ssize_t i = 0; i < ids.shape(0); ++i) {
                g.elements.push_back(static_cast<int32_t>(mesh.points.size()));
                mesh.points.push_back(
                    node_id(ids.at(i), "group '" + gname + "'", static_cast<size_t>(i)));
                mesh.point_tag.push_back(g.tag);
            }
            mesh.physical[gname] = {0, g.tag};
            mesh.groups.push_back(std::move(g));
        } else if (ids.ndim() == 2 && ids.shape(1) == 2) {
            fdem::PhysicalGroup g{gname, 1, ++line_tag, {}};
            for (py::ssize_t i = 0; i < ids.shape(0); ++i) {
                const std::string what = "group '" + gname + "'";
                g.elements.push_back(static_cast<int32_t>(mesh.lines.size()));
                mesh.lines.push_back({node_id(ids.at(i, 0), what, static_cast<size_t>(i)),
                                      node_id(ids.at(i, 1), what, static_cast<size_t>(i))});
                mesh.line_tag.push_back(g.tag);
            }
            mesh.physical[gname] = {1, g.tag};
            mesh.groups.push_back(std::move(g));
        } else {
            fail(gname, "group '" + gname +
                            "': expected node ids of shape (k,) (a point group) or node pairs "
                            "of shape (k, 2) (a curve group)");
        }
    }
    std::sort(mesh.groups.begin(), mesh.groups.end(),
              [](const fdem::PhysicalGroup& a, const fdem::PhysicalGroup& b) {
                  return a.dim != b.dim ? a.dim < b.dim : a.tag < b.tag;
              });
    return mesh;
}

py::array mesh_nodes(const fdem::MeshData& m) {
    py::array_t<double> a({static_cast<py::ssize_t>(m.nodes.size()), py::ssize_t{2}});
    if (!m.nodes.empty()) std::memcpy(a.mutable_data(), m.nodes.data(), m.nodes.size() * 16);
    return a;
}

py::array mesh_triangles(const fdem::MeshData& m) {
    const size_t cols = m.second_order() ? 6 : 3;
    py::array_t<int32_t> a(
        {static_cast<py::ssize_t>(m.tris.size()), static_cast<py::ssize_t>(cols)});
    auto r = a.mutable_unchecked<2>();
    for (size_t t = 0; t < m.tris.size(); ++t) {
        for (size_t k = 0; k < 3; ++k) {
            r(static_cast<py::ssize_t>(t), static_cast<py::ssize_t>(k)) = m.tris[t][k];
            if (cols == 6) {
                r(static_cast<py::ssize_t>(t), static_cast<py::ssize_t>(k + 3)) = m.tri_mid[t][k];
            }
        }
    }
    return a;
}

// ---- the simulation
// -------------------------------------------------------------------------------

/// fdem::Simulation plus what the Python API adds: the measured sets (per-body resultants).
struct PySimulation {
    fdem::Simulation sim;
    std::unique_ptr<fdem::Resultants> resultants;  // built on first use

    explicit PySimulation(fdem::Simulation s) : sim(std::move(s)) {}

    const fdem::Resultants& sets() {
        if (!resultants) resultants = std::make_unique<fdem::Resultants>(sim.model());
        return *resultants;
    }
};

py::dict energy_dict(const fdem::Energy& e) {
    py::dict d;
    d["time"] = e.time;
    d["kinetic"] = e.kinetic;
    d["strain"] = e.strain;
    d["contact"] = e.contact;
    d["work_gravity"] = e.work_gravity;
    d["work_external"] = e.work_external;
    d["dissipated_viscous"] = e.dissipated_viscous;
    d["dissipated_contact"] = e.dissipated_contact;
    d["joint"] = e.joint;        // E_joint, theory eq. 9.18
    d["fracture"] = e.fracture;  // W_frac, theory eq. 9.19
    d["total"] = e.total();
    return d;
}

/// (n_tris, 2, 2) array of one tensor of tri_fields() (stress or strain) for every triangle.
py::array_t<double> tensor_field(const PySimulation& s, fdem::Mat2 fdem::TriFields::*member) {
    const auto& m = s.sim.model();
    py::array_t<double> a({static_cast<py::ssize_t>(m.num_tris()), py::ssize_t{2}, py::ssize_t{2}});
    auto r = a.mutable_unchecked<3>();
    for (fdem::TriId t = 0; t < m.num_tris(); ++t) {
        const fdem::Mat2 v = fdem::tri_fields(m, s.sim.state(), t).*member;
        r(t, 0, 0) = v.xx;
        r(t, 0, 1) = v.xy;
        r(t, 1, 0) = v.yx;
        r(t, 1, 1) = v.yy;
    }
    return a;
}

const char* status_name(fdem::RunStatus s) {
    switch (s) {
        case fdem::RunStatus::Reached:
            return "reached";
        case fdem::RunStatus::Stopped:
            return "stopped";
        case fdem::RunStatus::CallbackStopped:
            return "callback_stopped";
    }
    return "?";
}

/// The largest divisor of n that is at most 256: how often run() hands control back to Python
/// (the callback's `every` must stay a multiple of it, so the callback sees the steps it asked
/// for).
int64_t signal_stride(int64_t every) {
    if (every <= 256) return every;
    for (int64_t d = 256; d > 1; --d) {
        if (every % d == 0) return d;
    }
    return 1;
}

/// Run to step count `target` (a time), releasing the GIL; the callback runs with the GIL held.
py::dict run_impl(PySimulation& ps, double until, const py::object& callback, int64_t every,
                  py::handle self) {
    if (every < 1) throw py::value_error("every must be >= 1");
    const bool has_cb = !callback.is_none();
    const int64_t stride = has_cb ? signal_stride(every) : 256;
    std::exception_ptr py_error;  // a Python exception of the callback or KeyboardInterrupt
    fdem::RunResult res;
    {
        // The C++ callback runs every `stride` steps: takes the GIL, looks for Ctrl-C, and calls
        // the Python callback on multiples of `every`.
        auto cb = [&](fdem::Simulation& s) -> bool {
            py::gil_scoped_acquire gil;
            try {
                if (PyErr_CheckSignals() != 0) throw py::error_already_set();
                if (has_cb && s.state().step % every == 0) {
                    py::object r = callback(self);
                    if (!r.is_none() && !r.cast<bool>()) return false;
                }
            } catch (...) {
                py_error = std::current_exception();
                return false;
            }
            return true;
        };
        py::gil_scoped_release release;
        // a Python callback may read sim.energy: evaluate every energy on its steps
        res = ps.sim.run(until, cb, stride, has_cb);
    }
    if (py_error) std::rethrow_exception(py_error);
    py::dict d;
    d["status"] = status_name(res.status);
    d["steps"] = res.steps;
    return d;
}

/// The supports ([[boundary]] entries) of one name "body/group": a handle on their controls
/// State::bc_velocity / bc_enabled (spec P5; several Model::bcs entries may share the name, e.g.
/// time windows: a control sets all of them).
struct Support {
    py::object owner;  // the Python Simulation
    std::string name;
    std::vector<size_t> indices;  // into Model::bcs

    PySimulation& ps() const { return owner.cast<PySimulation&>(); }
};

}  // namespace

PYBIND11_MODULE(_fdem, mod) {
    mod.doc() =
        "fdem: 2-D combined finite-discrete element simulator with the smooth contact of Lei et "
        "al. (2020).\n\nCompiled core of the `fdem` package; see help(fdem) and docs/python.md.";
    mod.attr("__version__") = FDEM_VERSION;

    static py::exception<fdem::InputError> input_error(mod, "InputError", PyExc_ValueError);
    static py::exception<fdem::SimulationError> simulation_error(mod, "SimulationError",
                                                                 PyExc_RuntimeError);
    g_input_error = input_error;
    g_simulation_error = simulation_error;
    input_error.doc() =
        "Bad input (scenario, mesh, arguments): the CLI's message (exit code 2 there).\n"
        "Attributes: file, line, column (1-based, 0 = unknown), key, message.";
    simulation_error.doc() =
        "The physics failed during a run (NaN, inverted element, energy blow-up): the CLI's "
        "message (exit code 1 there).\nAttributes: step, time [s], entity.";
    py::register_exception_translator(&translate);

    // ---- Mesh -------------------------------------------------------------------------------
    py::class_<fdem::MeshData>(mod, "Mesh",
                               "A triangle mesh with named physical groups, before it becomes "
                               "bodies: read from Gmsh, generated, or given as NumPy arrays.")
        .def(py::init(&mesh_from_arrays), "nodes"_a, "triangles"_a, "groups"_a = py::dict(),
             "triangle_groups"_a = py::dict(), "name"_a = "<arrays>",
             "Mesh from arrays: nodes (n, 2) [m]; triangles (m, 3), or (m, 6) for 6-node "
             "triangles in Gmsh order (corners, then the mid-edge nodes of edges 0-1, 1-2, 2-0); "
             "groups: name -> node ids (k,) (a point group) or node pairs (k, 2) (a curve "
             "group), for [[boundary]] / [[load]] / [[probe]] 'group'; triangle_groups: name -> "
             "triangle ids (a surface group, for [[body]] 'group'). Raises fdem.InputError for "
             "bad shapes or ids.")
        .def_static(
            "read",
            [](const std::string& path, double mesh_size, int order) {
                return fdem::read_mesh(path, mesh_size, order);
            },
            "path"_a, "mesh_size"_a = 0.0, "order"_a = 1,
            "Read a Gmsh .msh (2.2/4.1) or mesh a .geo with element size mesh_size [m] (order 2: "
            "6-node triangles). Raises fdem.InputError naming the file.")
        .def_static("rectangle", &fdem::make_rectangle_mesh, "x0"_a, "y0"_a, "width"_a, "height"_a,
                    "nx"_a, "ny"_a, "alternate"_a = false,
                    "Structured rectangle [x0, x0+width] x [y0, y0+height] [m] of nx x ny cells, "
                    "two triangles each. Groups: curves 'bottom', 'right', 'top', 'left'; surface "
                    "'domain'.")
        .def_property_readonly("nodes", &mesh_nodes, "(n, 2) node positions [m] (a copy)")
        .def_property_readonly("triangles", &mesh_triangles,
                               "(m, 3) or (m, 6) node ids of the triangles (a copy)")
        .def_property_readonly(
            "groups",
            [](const fdem::MeshData& m) {
                py::dict d;
                for (const auto& g : m.groups) {
                    d[py::str(g.name)] = g.dim == 0 ? "point" : g.dim == 1 ? "curve" : "surface";
                }
                return d;
            },
            "physical group name -> 'point', 'curve' or 'surface'")
        .def_readonly("file", &fdem::MeshData::file, "file or name, for messages")
        .def("__repr__", [](const fdem::MeshData& m) {
            return "<fdem.Mesh '" + m.file + "': " + std::to_string(m.nodes.size()) + " nodes, " +
                   std::to_string(m.tris.size()) + " triangles, " +
                   std::to_string(m.groups.size()) + " groups>";
        });

    // ---- State and Model views -------------------------------------------------------------
    py::class_<fdem::State>(mod, "State",
                            "What a step writes. Array properties are zero-copy NumPy views of "
                            "the simulation's memory, valid for its life and updated by every "
                            "step.")
        .def_readonly("step", &fdem::State::step, "completed steps")
        .def_readonly("time", &fdem::State::time, "simulated time t^n [s]")
        .def_readonly("dt", &fdem::State::dt, "time step [s]")
        .def_property_readonly(
            "x",
            [](py::object self) { return vec2_view(self, self.cast<fdem::State&>().x, false); },
            "(n_nodes, 2) positions x^n [m]; read-only view (change with Simulation.set_positions)")
        .def_property_readonly(
            "v", [](py::object self) { return vec2_view(self, self.cast<fdem::State&>().v, true); },
            "(n_nodes, 2) velocities v^{n-1/2} before a step, v^{n+1/2} after [m/s]; a WRITABLE "
            "view: assign between steps to change velocities (supports overwrite their nodes)")
        .def_property_readonly(
            "f",
            [](py::object self) { return vec2_view(self, self.cast<fdem::State&>().f, false); },
            "(n_nodes, 2) total nodal force of the last step [N/m]; read-only view")
        .def_property_readonly(
            "f_contact",
            [](py::object self) {
                return vec2_view(self, self.cast<fdem::State&>().f_contact, false);
            },
            "(n_nodes, 2) contact part of f [N/m]; read-only view")
        .def_property_readonly(
            "bc_reaction",
            [](py::object self) {
                return vec2_view(self, self.cast<fdem::State&>().bc_reaction, false);
            },
            "(n_slots, 2) reaction of each supported node in the last step [N/m] (theory eq. "
            "8.1), per support in Model order then its nodes; read-only view")
        .def_property_readonly(
            "bc_velocity",
            [](py::object self) {
                return vec2_view(self, self.cast<fdem::State&>().bc_velocity, true);
            },
            "(n_supports, 2) prescribed velocity of each support in Model order [m/s]; a "
            "WRITABLE view (the controls; sim.supports[name].velocity sets it by name)")
        .def_property_readonly(
            "bc_enabled",
            [](py::object self) {
                const auto& e = self.cast<fdem::State&>().bc_enabled;
                return view<uint8_t>(self, e.data(), e.size(), 1, true);
            },
            "(n_supports,) uint8 on/off switch of each support (1 = active in its window); "
            "WRITABLE view")
        // fracture (docs/theory.md §9): empty arrays for a model without joints
        .def_property_readonly(
            "joint_status",
            [](py::object self) {
                const auto& a = self.cast<fdem::State&>().joints.status;
                static_assert(sizeof(fdem::JointStatus) == 1);
                return view<uint8_t>(self, a.data(), a.size(), 1, false);
            },
            "(n_joints,) uint8 status of each joint: 0 intact, 1 softening, 2 broken (theory "
            "§9.4); read-only view")
        .def_property_readonly(
            "joint_damage",
            [](py::object self) {
                const auto& a = self.cast<fdem::State&>().joints.d_max;
                return view<double>(self, a.data(), a.size(), 3, false);
            },
            "(n_joints, 3) frozen damage D_max at the joint's three integration points (theory "
            "eq. 9.9, §9.4; >= 1: no cohesion there); read-only view")
        .def_property_readonly(
            "joint_mode",
            [](py::object self) {
                const auto& a = self.cast<fdem::State&>().joints.mode;
                static_assert(sizeof(fdem::JointMode) == 1);
                return view<uint8_t>(self, a.data(), a.size(), 1, false);
            },
            "(n_joints,) uint8 mode of a broken joint: 1 I, 2 II, 3 mixed, 0 not broken; "
            "read-only view")
        .def_property_readonly(
            "joint_break_step",
            [](py::object self) {
                return scalar_view(self, self.cast<fdem::State&>().joints.break_step);
            },
            "(n_joints,) int64 step at which each joint broke (-1: not broken); read-only view")
        .def_property_readonly(
            "joint_work",
            [](py::object self) {
                return scalar_view(self, self.cast<fdem::State&>().joints.work);
            },
            "(n_joints,) work W_J done on each joint so far [J/m] (theory eq. 9.17); its sum "
            "over broken joints per broken length is the audit's Gamma (eq. 9.20); read-only "
            "view")
        .def_property_readonly(
            "tri_fragment",
            [](py::object self) {
                return scalar_view(self, self.cast<fdem::State&>().tri_fragment);
            },
            "(n_tris,) int32 fragment of each triangle: its smallest triangle id, connected over "
            "shared nodes and joints that are not broken (theory §9, spec fracture.md §4.1); "
            "empty without joints; read-only view");

    py::class_<fdem::Model>(mod, "Model",
                            "What does not change during a run. Array properties are read-only "
                            "zero-copy NumPy views.")
        .def_property_readonly("num_nodes", &fdem::Model::num_nodes, "number of nodes")
        .def_property_readonly("num_tris", &fdem::Model::num_tris, "number of triangles")
        .def_property_readonly("num_bodies", &fdem::Model::num_bodies,
                               "number of bodies (discrete elements)")
        .def_property_readonly(
            "node_x0",
            [](py::object self) {
                return vec2_view(self, self.cast<fdem::Model&>().node_x0, false);
            },
            "(n_nodes, 2) reference positions [m]")
        .def_property_readonly(
            "node_mass",
            [](py::object self) { return scalar_view(self, self.cast<fdem::Model&>().node_mass); },
            "(n_nodes,) lumped mass per unit thickness [kg/m]")
        .def_property_readonly(
            "node_body",
            [](py::object self) { return scalar_view(self, self.cast<fdem::Model&>().node_body); },
            "(n_nodes,) owning body id")
        .def_property_readonly(
            "tri_nodes",
            [](py::object self) {
                const auto& t = self.cast<fdem::Model&>().tri_nodes;
                return view<int32_t>(self, t.data(), t.size(), 3, false);
            },
            "(n_tris, 3) node ids of each triangle, counter-clockwise (int32)")
        .def_property_readonly(
            "tri_body",
            [](py::object self) { return scalar_view(self, self.cast<fdem::Model&>().tri_body); },
            "(n_tris,) owning body id")
        .def_property_readonly(
            "joint_nodes",
            [](py::object self) {
                const auto& j = self.cast<fdem::Model&>().joints.nodes;
                return view<int32_t>(self, j.data(), j.size(), 4, false);
            },
            "(n_joints, 4) node ids of each cohesive joint (int32; theory eq. 9.1: 0, 1 on one "
            "triangle counter-clockwise, 3, 2 on the other; 0 faces 3 and 1 faces 2); empty "
            "without [material.fracture]")
        .def_property_readonly(
            "joint_length0",
            [](py::object self) {
                return scalar_view(self, self.cast<fdem::Model&>().joints.length0);
            },
            "(n_joints,) reference length h_0 of each joint [m]")
        .def_property_readonly(
            "tri_material",
            [](py::object self) {
                return scalar_view(self, self.cast<fdem::Model&>().tri_material);
            },
            "(n_tris,) material index")
        .def_property_readonly(
            "tri_area0",
            [](py::object self) { return scalar_view(self, self.cast<fdem::Model&>().tri_area0); },
            "(n_tris,) reference area [m^2]")
        .def_property_readonly(
            "body_names",
            [](const fdem::Model& m) {
                std::vector<std::string> n;
                for (const auto& b : m.bodies)
                    n.push_back(b.name);
                return n;
            },
            "scenario name of each body (pieces of one entry share it)")
        .def_property_readonly(
            "material_names",
            [](const fdem::Model& m) {
                std::vector<std::string> n;
                for (const auto& x : m.materials)
                    n.push_back(x.name);
                return n;
            },
            "name of each material")
        .def_property_readonly(
            "gravity", [](const fdem::Model& m) { return vec(m.gravity); },
            "gravity (gx, gy) [m/s^2]");

    // ---- Support controls ------------------------------------------------------------------
    py::class_<Support>(mod, "Support",
                        "Controls of the supports of one boundary group (sim.supports[name]): "
                        "read by the next step, saved in checkpoints.")
        .def_readonly("name", &Support::name, "'body/group'")
        .def_property(
            "velocity",
            [](const Support& s) { return vec(s.ps().sim.state().bc_velocity[s.indices.front()]); },
            [](const Support& s, std::pair<double, double> v) {
                if (!std::isfinite(v.first) || !std::isfinite(v.second)) {
                    throw py::value_error("support velocity must be finite");
                }
                for (size_t k : s.indices)
                    s.ps().sim.state().bc_velocity[k] = {v.first, v.second};
            },
            "prescribed velocity (vx, vy) [m/s] from the next step on; only the components the "
            "support holds are used (see components). Setting it sets every support of this "
            "name; the work it does is booked as for a support window boundary (theory §4.3)")
        .def_property(
            "active",
            [](const Support& s) { return s.ps().sim.state().bc_enabled[s.indices.front()] != 0; },
            [](const Support& s, bool on) {
                for (size_t k : s.indices)
                    s.ps().sim.state().bc_enabled[k] = on ? 1 : 0;
            },
            "False switches the support off (its nodes move freely); True lets it act again "
            "inside its start/end window")
        .def_property_readonly(
            "components",
            [](const Support& s) {
                const auto& bc = s.ps().sim.model().bcs[s.indices.front()];
                std::vector<std::string> c;
                if (bc.has_x) c.emplace_back("x");
                if (bc.has_y) c.emplace_back("y");
                return c;
            },
            "the velocity components the support prescribes")
        .def_property_readonly(
            "windows",
            [](const Support& s) {
                std::vector<std::pair<double, double>> w;
                for (size_t k : s.indices) {
                    const auto& bc = s.ps().sim.model().bcs[k];
                    w.emplace_back(bc.start, bc.end);
                }
                return w;
            },
            "(start, end) [s] of each support of this name")
        .def_property_readonly(
            "nodes",
            [](const Support& s) {
                std::vector<int32_t> n;
                for (size_t k : s.indices) {
                    const auto& bc = s.ps().sim.model().bcs[k];
                    n.insert(n.end(), bc.nodes.begin(), bc.nodes.end());
                }
                std::sort(n.begin(), n.end());
                n.erase(std::unique(n.begin(), n.end()), n.end());
                return py::array_t<int32_t>(static_cast<py::ssize_t>(n.size()), n.data());
            },
            "node ids of the support (a copy)")
        .def("__repr__", [](const Support& s) {
            const fdem::Vec2 v = s.ps().sim.state().bc_velocity[s.indices.front()];
            return "<fdem.Support '" + s.name + "': velocity (" + std::to_string(v.x) + ", " +
                   std::to_string(v.y) + ") m/s, " +
                   (s.ps().sim.state().bc_enabled[s.indices.front()] != 0 ? "active" : "off") + ">";
        });

    // ---- Simulation ------------------------------------------------------------------------
    py::class_<PySimulation>(mod, "Simulation",
                             "A scenario being run: owns the Model and the State and runs the "
                             "loop of `fdem run` (checks, output, checkpoints).")
        .def_static(
            "from_toml",
            [](const std::string& path) {
                return std::make_unique<PySimulation>(fdem::Simulation::from_file(path));
            },
            "path"_a,
            "Load a TOML scenario file (docs/scenario.md). Raises fdem.InputError with the "
            "CLI's message (file:line:column, key, value, expectation).")
        .def_static(
            "from_string",
            [](const std::string& text, const std::string& name, const std::string& base_dir,
               const std::map<std::string, fdem::MeshData>& meshes) {
                return std::make_unique<PySimulation>(fdem::Simulation(
                    fdem::load_scenario_from_string(text, name, base_dir, &meshes)));
            },
            "text"_a, "name"_a = "<string>", "base_dir"_a = ".",
            "meshes"_a = std::map<std::string, fdem::MeshData>{},
            "Load a scenario from TOML text. base_dir resolves relative mesh paths; name appears "
            "in messages; meshes: name -> fdem.Mesh, used by [[body]] entries whose 'mesh' is "
            "one of these names instead of a file.")
        .def_property_readonly(
            "model", [](PySimulation& s) -> const fdem::Model& { return s.sim.model(); },
            py::return_value_policy::reference_internal, "the fdem.Model (read-only)")
        .def_property_readonly(
            "state", [](PySimulation& s) -> fdem::State& { return s.sim.state(); },
            py::return_value_policy::reference_internal, "the fdem.State (views)")
        .def_property_readonly(
            "name", [](const PySimulation& s) { return s.sim.name(); }, "scenario file or name")
        .def_property_readonly(
            "time", [](const PySimulation& s) { return s.sim.state().time; }, "simulated time [s]")
        .def_property_readonly(
            "step_count", [](const PySimulation& s) { return s.sim.state().step; },
            "completed steps")
        .def_property_readonly(
            "dt", [](const PySimulation& s) { return s.sim.settings().dt; }, "time step [s]")
        .def_property_readonly(
            "stable_dt", [](const PySimulation& s) { return s.sim.settings().stable_dt; },
            "stable time step computed at load [s]")
        .def_property(
            "end_time", [](const PySimulation& s) { return s.sim.settings().end_time; },
            [](PySimulation& s, double t) {
                if (!(t > 0) || !std::isfinite(t)) throw py::value_error("end_time must be > 0");
                s.sim.settings().end_time = t;
            },
            "end of the run [s] (run() without until goes there; the final frame and "
            "checkpoint are written there)")
        .def(
            "step",
            [](PySimulation& s, int64_t n) {
                if (n < 0) throw py::value_error("n must be >= 0");
                py::gil_scoped_release release;
                for (int64_t i = 0; i < n; ++i)
                    s.sim.step();
            },
            "n"_a = 1,
            "Take n steps (checks, output and checkpoints when due, every energy evaluated). "
            "The GIL is released. Raises fdem.SimulationError.")
        .def(
            "run",
            [](py::object self, std::optional<double> until, std::optional<int64_t> steps,
               py::object callback, int64_t every) {
                auto& s = self.cast<PySimulation&>();
                if (until && steps) throw py::value_error("give until or steps, not both");
                double t = until ? *until : s.sim.settings().end_time;
                if (steps) {
                    if (*steps < 0) throw py::value_error("steps must be >= 0");
                    // steps_to(k dt) == k: ceil(k - 1e-9) for the rounded k dt / dt
                    t = static_cast<double>(s.sim.state().step + *steps) * s.sim.settings().dt;
                }
                return run_impl(s, t, callback, every, self);
            },
            "until"_a = py::none(), "steps"_a = py::none(), "callback"_a = py::none(),
            "every"_a = 1,
            "Step to the time `until` [s] (default: end_time) or `steps` more steps, as `fdem "
            "run` does (checks, output, checkpoints). The GIL is released while C++ steps. "
            "callback(sim) is called after every step whose number is a multiple of `every`, "
            "with the GIL held; returning False stops the run. Ctrl-C stops after the current "
            "step and raises KeyboardInterrupt. Returns {'status': 'reached' | 'stopped' | "
            "'callback_stopped', 'steps': n}. Raises fdem.SimulationError.")
        .def(
            "request_stop", [](PySimulation& s) { s.sim.request_stop(); },
            "Ask a running run() (e.g. in another thread) to stop after its current step.")
        .def(
            "check", [](const PySimulation& s) { s.sim.check(); },
            "NaN/Inf, inverted elements, runaway velocities: raises fdem.SimulationError.")
        .def(
            "state_hash",
            [](const PySimulation& s) {
                char buf[17];
                std::snprintf(buf, sizeof buf, "%016llx",
                              static_cast<unsigned long long>(s.sim.state_hash()));
                return std::string(buf);
            },
            "hash of the state as 16 hex digits: equals `fdem run --print-hash` for the same run")
        .def_property_readonly(
            "energy", [](const PySimulation& s) { return energy_dict(s.sim.state().energy); },
            "energies of the last step [J/m]: kinetic, strain, contact, work_gravity, "
            "work_external, dissipated_viscous, dissipated_contact, total (balance: total "
            "stays constant) and the time they belong to")
        .def_property(
            "timing_on", [](const PySimulation& s) { return s.sim.state().timing.on; },
            [](PySimulation& s, bool on) { s.sim.state().timing.on = on; },
            "record the wall time of each phase of the steps (sim.timing; off by default: the "
            "step then reads no clock). No result depends on it.")
        .def_property_readonly(
            "timing",
            [](const PySimulation& s) {
                const fdem::StepTiming& t = s.sim.state().timing;
                py::dict d;
                d["steps"] = t.steps;
                for (int k = 0; k < fdem::kStepPhases; ++k)
                    d[fdem::kStepPhaseKeys[k]] = t.seconds[k];
                return d;
            },
            "wall seconds per phase of the steps timed since timing_on was set or "
            "reset_timing() (docs/output.md \"Console output\": elements, joints, broad_phase, "
            "narrow_phase, contact_apply, node_update, communication) and their number, steps")
        .def(
            "reset_timing", [](PySimulation& s) { s.sim.state().timing.reset(); },
            "zero sim.timing")
        .def_property_readonly(
            "warnings",
            [](const PySimulation& s) {
                return py::make_tuple(s.sim.first_warning(), s.sim.warnings());
            },
            "(first warning of the run-time checks or '', number of steps that warned)")
        .def(
            "set_positions",
            [](PySimulation& s,
               const py::array_t<double, py::array::c_style | py::array::forcecast>& x) {
                copy_vec2(x, s.sim.state().x, "set_positions");
                s.sim.state().contact.need_rebuild = true;
            },
            "x"_a, "Copy (n_nodes, 2) positions [m] into the state and flag a broad-phase rebuild.")
        .def(
            "set_velocities",
            [](PySimulation& s,
               const py::array_t<double, py::array::c_style | py::array::forcecast>& v) {
                copy_vec2(v, s.sim.state().v, "set_velocities");
            },
            "v"_a, "Copy (n_nodes, 2) velocities [m/s] into the state (state.v is also writable).")
        .def(
            "stress",
            [](const PySimulation& s) { return tensor_field(s, &fdem::TriFields::stress); },
            "(n_tris, 2, 2) Cauchy stress of each triangle [Pa] (a new array: derived data)")
        .def(
            "strain",
            [](const PySimulation& s) { return tensor_field(s, &fdem::TriFields::strain); },
            "(n_tris, 2, 2) Green-Lagrange strain of each triangle [-] (a new array)")
        .def(
            "von_mises",
            [](const PySimulation& s) {
                const auto& m = s.sim.model();
                py::array_t<double> a(static_cast<py::ssize_t>(m.num_tris()));
                auto r = a.mutable_unchecked<1>();
                for (fdem::TriId t = 0; t < m.num_tris(); ++t) {
                    r(t) = fdem::tri_fields(m, s.sim.state(), t).von_mises;
                }
                return a;
            },
            "(n_tris,) in-plane von Mises stress of each triangle [Pa] (a new array)")
        .def(
            "resultants",
            [](PySimulation& s) {
                const fdem::Resultants& r = s.sets();
                std::vector<fdem::SetValues> vals(static_cast<size_t>(r.num_sets()));
                const fdem::IntervalImpulses none = r.make_impulses();
                r.evaluate(s.sim.model(), s.sim.state(), none, vals.data());
                py::dict d;
                for (int32_t k = 0; k < r.num_sets(); ++k) {
                    const fdem::SetValues& v = vals[static_cast<size_t>(k)];
                    d[py::str(r.name(k))] =
                        py::dict("u"_a = vec(v.u), "v"_a = vec(v.v), "contact"_a = vec(v.contact),
                                 "reaction"_a = vec(v.reaction));
                }
                return d;
            },
            "Per [[body]] entry and per boundary group ('body/group'): mean displacement u [m] "
            "and velocity v [m/s] (mass-weighted), contact resultant and support reaction of the "
            "last step [N/m] (theory §8; the columns of bodies.csv)")
        .def_property_readonly(
            "supports",
            [](py::object self) {
                auto& ps = self.cast<PySimulation&>();
                py::dict d;
                const auto& bcs = ps.sim.model().bcs;
                for (size_t k = 0; k < bcs.size(); ++k) {
                    const py::str name(bcs[k].name);
                    if (d.contains(name)) continue;
                    Support sup{self, bcs[k].name, {}};
                    for (size_t j = k; j < bcs.size(); ++j) {
                        if (bcs[j].name == bcs[k].name) sup.indices.push_back(j);
                    }
                    d[name] = sup;
                }
                return d;
            },
            "dict 'body/group' -> fdem.Support: the [[boundary]] supports, whose velocity and "
            "on/off switch may be changed between steps (controls, saved in checkpoints)")
        .def(
            "open_output", [](PySimulation& s, const std::string& dir) { s.sim.open_output(dir); },
            "dir"_a = "",
            "Write VTU frames + series.pvd, history.csv, bodies.csv, probes.csv and checkpoints "
            "into dir (default: the scenario's [output] dir) as `fdem run` does.")
        .def(
            "set_checkpoint_every",
            [](PySimulation& s, double seconds) { s.sim.set_checkpoint_every(seconds); },
            "seconds"_a, "Write a checkpoint every `seconds` of simulated time (needs output).")
        .def(
            "save_checkpoint",
            [](PySimulation& s, const std::string& path) { s.sim.save_checkpoint(path); }, "path"_a,
            "Write the complete state to path; a restore continues bit for bit.")
        .def(
            "restore_checkpoint",
            [](PySimulation& s, const std::string& path) { s.sim.restore_checkpoint(path); },
            "path"_a,
            "Continue from a checkpoint of the same model and dt (views stay valid). Raises "
            "fdem.InputError if it belongs to another model.")
        .def(
            "write_vtu",
            [](const PySimulation& s, const std::string& path) {
                fdem::write_vtu(path, s.sim.model(), s.sim.state());
            },
            "path"_a, "Write the current state as one VTU file (ParaView).")
        .def("__repr__", [](const PySimulation& s) {
            const auto& m = s.sim.model();
            return "<fdem.Simulation '" + s.sim.name() + "': " + std::to_string(m.num_nodes()) +
                   " nodes, " + std::to_string(m.num_tris()) + " triangles, " +
                   std::to_string(m.num_bodies()) +
                   " bodies, t = " + std::to_string(s.sim.state().time) + " s, step " +
                   std::to_string(s.sim.state().step) + ">";
        });
}
