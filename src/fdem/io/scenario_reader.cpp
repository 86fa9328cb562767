// Scenario files (TOML, docs/scenario.md): parse, validate every key with its source location,
// read the meshes, build the Model and choose the time step.
//
// Order of work: TOML syntax -> [simulation] -> [output] -> [[material]] -> [[body]] (meshes
// read once per file and size) -> [[boundary]] -> [[load]] -> [[kick]] -> [damping] -> [contact] ->
// finalize_model() -> stable dt check. Every problem is an InputError at the key concerned.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include <fmt/format.h>

#include "contact/checks.hpp"
#include "contact/contact.hpp"
#include "fdem/build.hpp"
#include "fdem/error.hpp"
#include "fdem/mesh.hpp"
#include "fdem/scenario.hpp"
#include "fracture/joints.hpp"
#include "fracture/sectors.hpp"
#include "io/toml_fields.hpp"
#include "model/renumber.hpp"

namespace fdem {

namespace {

/// Default fractions of dt = "auto" without dt_fraction (docs/theory.md §6.9): of the element
/// limit (eq. 5.3) and of the contact limit (eq. 6.15).
constexpr Real kDefaultElementFraction = 0.5;
constexpr Real kDefaultContactFraction = 0.2;

using io::Bounds;
using io::Fields;
using io::SourceText;
namespace fs = std::filesystem;

const std::vector<std::string> kTopKeys = {"simulation", "output", "material", "body",
                                           "boundary",   "load",   "kick",     "damping",
                                           "contact",    "checks", "probe",    "fracture"};
const std::vector<std::string> kContactLawKeys = {"penalty",  "alpha",
                                                  "beta",     "length_scale",
                                                  "damping",  "damp_normal_only",
                                                  "friction", "tangential_penalty",
                                                  "unloading"};

const std::vector<std::string> kMaterialFractureKeys = {
    "tensile_strength",   "cohesion",        "friction_angle", "fracture_energy_I",
    "fracture_energy_II", "penalty",         "shear_penalty",  "softening",
    "softening_length",   "irreversibility", "failure_points", "residual_friction",
    "allow_coarse",       "mixed_mode"};

/// Optional sub-table: nullptr when absent; error when the key holds something else.
const toml::table* sub_table(const SourceText& src, const toml::table& root, const char* key) {
    const toml::node* n = root.get(key);
    if (!n) {
        return nullptr;
    }
    if (!n->is_table()) {
        io::fail_at(src, *n, key,
                    fmt::format("'{}' must be a table (write [{}] on its own line), got {} {}", key,
                                key, io::describe_type(*n), io::describe_value(*n)));
    }
    return n->as_table();
}

/// Array of tables ([[key]]); empty when absent.
std::vector<const toml::table*> table_array(const SourceText& src, const toml::table& parent,
                                            const char* key, const std::string& shown) {
    std::vector<const toml::table*> out;
    const toml::node* n = parent.get(key);
    if (!n) {
        return out;
    }
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables()) {
        io::fail_at(src, *n, key,
                    fmt::format("'{}' must be an array of tables: write [[{}]] once per entry, "
                                "got {}",
                                shown, shown, io::describe_type(*n)));
    }
    for (const toml::node& e : *a) {
        out.push_back(e.as_table());
    }
    return out;
}

/// Scenario-relative path as shown in messages.
std::string resolve(const std::string& base_dir, const std::string& rel) {
    fs::path p(rel);
    if (p.is_relative() && !base_dir.empty() && base_dir != ".") {
        p = fs::path(base_dir) / p;
    }
    return p.lexically_normal().string();
}

/// Largest "nice" value <= v with 3 significant digits (for "use dt <= ...").
Real round_down_3(Real v) {
    if (!(v > 0) || !std::isfinite(v)) {
        return v;
    }
    const Real scale = std::pow(10.0, std::floor(std::log10(v)) - 2);
    Real r = std::floor(v / scale) * scale;
    while (r > v) {
        r -= scale;  // guard against the division rounding up
    }
    return r;
}

struct BodyEntry {
    std::string name;
    const toml::table* table = nullptr;
    int mesh = 0;           ///< index into the mesh cache
    bool fixed = false;     ///< fixed = true
    MeshNodeMap node_map;   ///< mesh node -> model node (kNone if not in this body)
    BodyId body_begin = 0;  ///< the bodies made from this entry: [body_begin, body_end)
    BodyId body_end = 0;    ///< (valid until finalize_model; renumbering keeps them)
};

struct LoadedMesh {
    std::string path;
    Real size = 0;
    int order = 1;           ///< 2: a .geo meshed with 6-node triangles (element = "composite")
    bool in_memory = false;  ///< given to load_scenario_from_string, not read from a file
    MeshData data;
    std::vector<int> tri_owner;  ///< body entry using each triangle, -1 if none
    /// name -> indices into data.groups of the groups with that name, ascending (one lookup
    /// per entry instead of a scan of every group: a mesh may have a group per block)
    std::unordered_map<std::string, std::vector<size_t>> groups_by_name;

    const std::vector<size_t>& named(const std::string& name) const {
        static const std::vector<size_t> none;
        const auto it = groups_by_name.find(name);
        return it == groups_by_name.end() ? none : it->second;
    }
};

std::string group_kind(int dim) {
    return dim == 0 ? "point" : dim == 1 ? "curve" : "surface";
}

std::string available_groups(const MeshData& mesh) {
    std::vector<std::string> names;
    for (const PhysicalGroup& g : mesh.groups) {
        if (!g.name.empty()) {
            names.push_back(fmt::format("\"{}\" ({})", g.name, group_kind(g.dim)));
        }
    }
    if (names.empty()) {
        return "the mesh has no named physical groups";
    }
    std::string out = "available: ";
    for (size_t i = 0; i < names.size(); ++i) {
        out += (i ? ", " : "") + names[i];
    }
    return out;
}

std::vector<std::string> group_names(const MeshData& mesh) {
    std::vector<std::string> out;
    for (const PhysicalGroup& g : mesh.groups) {
        if (!g.name.empty()) {
            out.push_back(g.name);
        }
    }
    return out;
}

class ScenarioReader {
public:
    ScenarioReader(const SourceText& src, std::string base_dir, const MeshStore* memory,
                   const MeshReader& read_meshes)
        : src_(src), base_dir_(std::move(base_dir)), memory_(memory), read_meshes_(read_meshes) {}

    Scenario read(const toml::table& root) {
        Scenario sc;
        sc.path = src_.name;
        m_ = &sc.model;
        Fields top(src_, root, "scenario", "", kTopKeys);

        read_simulation(top, sc);
        read_output(root, sc);
        read_checks(root, sc);
        read_materials(root, sc.model);
        read_bodies(root, sc.model);
        check_joint_lengths(sc.model);
        read_fracture(root, sc);
        read_boundaries(root, sc.model);
        read_loads(root, sc.model);
        read_kicks(root, sc.model);
        read_damping(root, sc.model);
        read_contact(root, sc);

        // derived data (the model builder's own checks keep their messages)
        try {
            std::vector<int32_t> node_new;
            finalize_model(sc.model, node_new);
            // the entries' mesh-node maps follow the spatial renumbering (a [[probe]] group is
            // looked up through them after this; a body of >= 4096 triangles is renumbered)
            for (BodyEntry& e : bodies_) {
                for (NodeId& n : e.node_map.model_nodes)
                    n = node_new[static_cast<size_t>(n)];
            }
            // the contact topology of the bodies as loaded, without welds: for the stable time
            // step, every joint face of a body with fracture a boundary (any joint may break,
            // and its faces' nodes become contact targets: the bound holds after any breaks)
            topo_ = build_topology(sc.model);
            // and as make_state() builds State::topology, for the checks of the geometry at
            // t = 0: bodies with fracture welded over their joints, every one intact but the
            // pre-broken ones (against topo_, the initial-overlap check measured a point's depth
            // to the nearest joint face, over all of them per point)
            if (!sc.model.joints.nodes.empty()) {
                std::vector<JointStatus> status(sc.model.joints.nodes.size(), JointStatus::Intact);
                for (const int32_t j : sc.model.prebroken_joints)
                    status[static_cast<size_t>(j)] = JointStatus::Broken;
                std::vector<NodeId> sectors;
                compute_node_sectors(sc.model, status, sectors);
                build_topology(sc.model, sectors, topo_welded_);
            }
        } catch (const InputError& e) {
            if (!e.location().file.empty()) {
                throw;
            }
            throw InputError({src_.name, 0, 0}, e.key(), e.message());
        }
        check_contact_geometry(sc);
        choose_dt(sc);
        check_step_count(sc.run, end_time_loc_, "simulation.end_time",
                         src_.line(end_time_loc_.line));
        check_times(sc);
        read_probes(root, sc);
        return sc;
    }

private:
    // ---- [simulation] ----------------------------------------------------------------------
    void read_simulation(const Fields& top, Scenario& sc) {
        const toml::table* t = sub_table(src_, top.table(), "simulation");
        if (!t) {
            throw InputError({src_.name, 0, 0}, "simulation",
                             "missing required table [simulation] (end_time, dt)");
        }
        Fields f(src_, *t, "[simulation]", "simulation",
                 {"end_time", "dt", "dt_fraction", "gravity", "max_steps"});
        RunSettings& run = sc.run;
        run.end_time = f.real("end_time", std::nullopt, "s", Bounds::positive());
        end_time_loc_ = f.location("end_time");
        run.max_steps = f.real("max_steps", run.max_steps, "", Bounds::at_least(1.0));
        if (!std::isfinite(run.max_steps) || run.max_steps > 9e18) {
            f.fail(*f.node("max_steps"), "max_steps",
                   fmt::format("[simulation]: max_steps must be a step count in [1, 9e18], got {}",
                               run.max_steps));
        }

        // dt: a positive number or "auto"
        const toml::node* dt = f.node("dt");
        if (!dt) {
            f.fail_missing("dt", "time step in s, > 0, or \"auto\"");
        }
        dt_loc_ = f.location("dt");
        if (const auto s = dt->value<std::string>()) {
            if (*s != "auto") {
                f.fail(*dt, "dt",
                       fmt::format("dt must be a number in s (> 0) or \"auto\", got \"{}\"", *s));
            }
            run.dt_auto = true;
        } else {
            run.dt = f.real("dt", std::nullopt, "s", Bounds::positive());
        }
        if (f.has("dt_fraction") && !run.dt_auto) {
            f.fail(*f.node("dt_fraction"), "dt_fraction",
                   "dt_fraction only applies with dt = \"auto\"; remove it or set dt = \"auto\"");
        }
        // not given: 0 here, chosen by choose_dt() (0.5 of the element limit, 0.2 of the
        // contact limit, docs/theory.md §6.9)
        run.dt_fraction =
            f.has("dt_fraction") ? f.real("dt_fraction", 0.5, "", {0.0, 1.0, true, false}) : 0.0;
        sc.model.gravity = f.vec2("gravity", Vec2{0, 0}, "m/s^2");
    }

    // ---- [output] --------------------------------------------------------------------------
    void read_output(const toml::table& root, Scenario& sc) {
        const toml::table* t = sub_table(src_, root, "output");
        if (!t) {
            return;
        }
        Fields f(src_, *t, "[output]", "output", {"interval", "dir", "vtu", "bodies", "merge"});
        OutputSettings& o = sc.run.output;
        o.interval = f.real("interval", 0.0, "s", Bounds::positive());
        interval_loc_ = f.location("interval");
        o.dir = f.string("dir", std::string("out"));
        o.vtu = f.boolean("vtu", true);
        o.bodies = f.boolean("bodies", true);
        o.merge = f.boolean("merge", false);
    }

    // ---- [checks] ---------------------------------------------------------------------------
    void read_checks(const toml::table& root, Scenario& sc) {
        const toml::table* t = sub_table(src_, root, "checks");
        if (!t) {
            return;
        }
        Fields f(src_, *t, "[checks]", "checks", {"energy_tolerance", "penetration"});
        CheckSettings& c = sc.run.checks;
        c.energy_tolerance = f.real("energy_tolerance", 0.1, "", Bounds::non_negative());
        const std::string p = f.choice("penetration", std::string("fail"), {"fail", "warn", "off"});
        c.penetration = p == "fail"   ? PenetrationCheck::Fail
                        : p == "warn" ? PenetrationCheck::Warn
                                      : PenetrationCheck::Off;
    }

    // ---- [[material]] ----------------------------------------------------------------------
    void read_materials(const toml::table& root, Model& m) {
        const auto tables = table_array(src_, root, "material", "material");
        if (tables.empty()) {
            throw InputError({src_.name, 0, 0}, "material",
                             "no [[material]] defined; every body needs a material");
        }
        std::map<std::string, int> first_line;
        for (size_t i = 0; i < tables.size(); ++i) {
            Fields f(src_, *tables[i], fmt::format("[[material]] #{}", i + 1),
                     fmt::format("material[{}]", i),
                     {"name", "density", "youngs_modulus", "poisson_ratio", "plane", "viscosity",
                      "damping_ratio", "fracture"});
            Material mat;
            mat.name = f.string("name", std::nullopt);
            f.set_context(fmt::format("material \"{}\"", mat.name));
            if (const auto it = first_line.find(mat.name); it != first_line.end()) {
                f.fail(*f.node("name"), "name",
                       fmt::format("duplicate material name \"{}\" (first defined on line {})",
                                   mat.name, it->second));
            }
            first_line[mat.name] = f.location("name").line;
            mat.density = f.real("density", std::nullopt, "kg/m^3", Bounds::positive());
            mat.youngs_modulus = f.real("youngs_modulus", std::nullopt, "Pa", Bounds::positive());
            mat.poisson_ratio = f.real("poisson_ratio", std::nullopt, "", {0.0, 0.5, false, true});
            mat.plane = f.choice("plane", std::string("strain"), {"strain", "stress"}) == "strain"
                            ? PlaneMode::Strain
                            : PlaneMode::Stress;
            mat.viscosity = f.real("viscosity", 0.0, "Pa s", Bounds::non_negative());
            mat.damping_ratio = f.real("damping_ratio", 0.0, "", Bounds::non_negative());
            compute_lame(mat);
            fracture_tables_.push_back(nullptr);
            if (f.has("fracture")) {
                read_material_fracture(f, i, mat);
            }
            material_names_.push_back(mat.name);
            m.materials.push_back(mat);
        }
    }

    /// [material.fracture] of material i (docs/scenario.md; spec fracture.md §10; the law of
    /// docs/theory.md §9).
    void read_material_fracture(const Fields& mf, size_t i, Material& mat) {
        const toml::node& n = *mf.node("fracture");
        if (!n.is_table()) {
            mf.fail(n, "fracture",
                    fmt::format("fracture must be a table (write [material.fracture] on its own "
                                "line after the material's keys), got {} {}",
                                io::describe_type(n), io::describe_value(n)));
        }
        fracture_tables_.back() = n.as_table();
        Fields f(src_, *n.as_table(), fmt::format("material \"{}\" [material.fracture]", mat.name),
                 fmt::format("material[{}].fracture", i), kMaterialFractureKeys);
        JointMaterial& j = mat.fracture;
        j.tensile_strength = f.real("tensile_strength", std::nullopt, "Pa", Bounds::positive());
        j.cohesion = f.real("cohesion", std::nullopt, "Pa", Bounds::positive());
        constexpr Real kPi = 3.14159265358979323846;
        j.friction_angle =
            f.real("friction_angle", std::nullopt, "degrees", {0.0, 90.0, false, true}) *
            (kPi / 180.0);
        j.fracture_energy_I =
            f.real("fracture_energy_I", std::nullopt, "J/m^2", Bounds::positive());
        j.fracture_energy_II =
            f.real("fracture_energy_II", std::nullopt, "J/m^2", Bounds::positive());
        // penalties: a stress in Pa, or "auto" (p = 10 E, p_s = p; spec fracture.md §12.6)
        const auto penalty = [&](const char* key, Real automatic, const char* auto_text) {
            const toml::node* p = f.node(key);
            if (p == nullptr) {
                return automatic;
            }
            if (p->is_string()) {
                if (p->value<std::string>().value_or("") != "auto") {
                    f.fail(*p, key,
                           fmt::format("{} must be a number in Pa (> 0) or \"auto\" ({}), got {}",
                                       key, auto_text, io::describe_value(*p)));
                }
                return automatic;
            }
            return f.real(key, std::nullopt, "Pa", Bounds::positive());
        };
        j.penalty = penalty("penalty", 10.0 * mat.youngs_modulus, "10 x youngs_modulus");
        j.shear_penalty = penalty("shear_penalty", j.penalty, "= penalty");
        j.softening = f.choice("softening", std::string("evans-marathe"),
                               {"evans-marathe", "linear"}) == "linear"
                          ? SofteningCurve::Linear
                          : SofteningCurve::EvansMarathe;
        const std::string rule = f.choice("softening_length", std::string("exact"),
                                          {"exact", "total", "y-geo", "solidity"});
        j.softening_length = rule == "exact"   ? SofteningLength::Exact
                             : rule == "total" ? SofteningLength::Total
                             : rule == "y-geo" ? SofteningLength::YGeo
                                               : SofteningLength::Solidity;
        const std::string irr =
            f.choice("irreversibility", std::string("frozen"), {"frozen", "none", "y-geo"});
        if (irr != "frozen") {
            f.fail(*f.node("irreversibility"), "irreversibility",
                   fmt::format("irreversibility = \"{}\" is not implemented; only \"frozen\" is "
                               "(per integration point the largest damage reached is kept, "
                               "docs/theory.md §9.4)",
                               irr));
        }
        j.irreversibility = Irreversibility::Frozen;
        j.mixed_mode = f.choice("mixed_mode", std::string("proportional"),
                                {"independent", "proportional"}) == "proportional"
                           ? MixedMode::Proportional
                           : MixedMode::Independent;
        const Real points = f.real("failure_points", 2.0, "", {1.0, 3.0, false, false});
        if (points != std::floor(points)) {
            f.fail(*f.node("failure_points"), "failure_points",
                   fmt::format("failure_points must be an integer 1, 2 or 3 (integration points "
                               "with D >= 1 that break a joint), got {}",
                               io::describe_value(*f.node("failure_points"))));
        }
        j.failure_points = static_cast<int32_t>(points);
        const Real mu_r = f.real("residual_friction", 0.0, "", Bounds::non_negative());
        if (mu_r != 0) {
            f.fail(*f.node("residual_friction"), "residual_friction",
                   fmt::format("residual_friction = {} is not implemented; only 0 (no friction on "
                               "a softening joint in compression, as Y, Y-Geo and Solidity; a "
                               "broken joint's faces get their friction from [contact])",
                               io::describe_value(*f.node("residual_friction"))));
        }
        j.allow_coarse = f.boolean("allow_coarse", false);
        mat.has_fracture = true;
    }

    int material_index(const Fields& f, std::string_view key) const {
        const std::string name = f.string(key, std::nullopt);
        const auto it = std::find(material_names_.begin(), material_names_.end(), name);
        if (it == material_names_.end()) {
            const std::string guess = io::closest(name, material_names_);
            f.fail(*f.node(key), key,
                   fmt::format("unknown material \"{}\"; defined materials: {}{}", name,
                               io::quoted_list(material_names_),
                               guess.empty() ? "" : fmt::format("; did you mean \"{}\"?", guess)));
        }
        return static_cast<int>(it - material_names_.begin());
    }

    // ---- [[body]] --------------------------------------------------------------------------
    /// order = 2 meshes a .geo with 6-node triangles; a .msh keeps the order it was written with.
    int load_mesh(const Fields& f, int order) {
        const std::string rel = f.string("mesh", std::nullopt);
        if (memory_ != nullptr) {
            if (const auto it = memory_->find(rel); it != memory_->end()) {
                return load_memory_mesh(f, rel, it->second);
            }
        }
        const std::string path = resolve(base_dir_, rel);
        const std::string ext = fs::path(path).extension().string();
        if (ext != ".msh" && ext != ".geo") {
            f.fail(*f.node("mesh"), "mesh",
                   fmt::format("mesh must be a Gmsh .msh or .geo file, got \"{}\"", rel));
        }
        Real size = 0;
        MeshLimits limits;
        if (ext == ".geo") {
            size = f.real("mesh_size", std::nullopt, "m", Bounds::positive());
            limits.max_triangles =
                f.real("max_triangles", limits.max_triangles, "", Bounds::at_least(1.0));
            limits.time_limit =
                f.real("mesh_time_limit", limits.time_limit, "s", Bounds::positive());
        } else {
            for (const char* k : {"mesh_size", "max_triangles", "mesh_time_limit"}) {
                if (f.has(k)) {
                    f.fail(*f.node(k), k,
                           fmt::format("{} only applies to .geo files (a .msh file is already "
                                       "meshed)",
                                       k));
                }
            }
        }
        std::error_code ec;
        if (!fs::exists(path, ec)) {
            f.fail(*f.node("mesh"), "mesh",
                   fmt::format("cannot open mesh file '{}': No such file", path));
        }
        if (ext != ".geo") {
            order = 1;  // the file decides
        }
        for (size_t i = 0; i < meshes_.size(); ++i) {
            if (meshes_[i].path == path && meshes_[i].size == size && meshes_[i].order == order) {
                return static_cast<int>(i);
            }
        }
        LoadedMesh lm;
        lm.path = path;
        lm.size = size;
        lm.order = order;
        try {
            lm.data = read_meshes_ ? read_meshes_(path, size, order, limits)
                                   : read_mesh(path, size, order, limits);
        } catch (const InputError& e) {
            if (e.key() != "max_triangles") throw;
            throw InputError(f.location("mesh_size"), f.full_key("mesh_size"),
                             fmt::format("{}: {}", f.context(), e.message()),
                             src_.line(f.location("mesh_size").line));
        }
        return add_loaded(std::move(lm));
    }

    /// Append a read mesh with its triangle owners and group index; its index in meshes_.
    int add_loaded(LoadedMesh lm) {
        lm.tri_owner.assign(lm.data.tris.size(), -1);
        for (size_t g = 0; g < lm.data.groups.size(); ++g) {
            lm.groups_by_name[lm.data.groups[g].name].push_back(g);
        }
        meshes_.push_back(std::move(lm));
        return static_cast<int>(meshes_.size() - 1);
    }

    /// mesh = "<name>" of a mesh given in memory (load_scenario_from_string's `meshes`): used as
    /// it is, like an already meshed .msh file; its name stands for the path in messages.
    int load_memory_mesh(const Fields& f, const std::string& name, const MeshData& data) {
        for (const char* k : {"mesh_size", "max_triangles", "mesh_time_limit"}) {
            if (f.has(k)) {
                f.fail(*f.node(k), k,
                       fmt::format("{} only applies to .geo files (mesh \"{}\" is given in "
                                   "memory, already meshed)",
                                   k, name));
            }
        }
        for (size_t i = 0; i < meshes_.size(); ++i) {
            if (meshes_[i].path == name && meshes_[i].in_memory) {
                return static_cast<int>(i);
            }
        }
        LoadedMesh lm;
        lm.path = name;
        lm.in_memory = true;
        lm.data = data;
        if (lm.data.file.empty()) {
            lm.data.file = name;
        }
        return add_loaded(std::move(lm));
    }

    void read_bodies(const toml::table& root, Model& m) {
        const auto tables = table_array(src_, root, "body", "body");
        if (tables.empty()) {
            throw InputError({src_.name, 0, 0}, "body", "no [[body]] defined");
        }
        for (size_t i = 0; i < tables.size(); ++i) {
            Fields f(
                src_, *tables[i], fmt::format("[[body]] #{}", i + 1), fmt::format("body[{}]", i),
                {"name", "mesh", "mesh_size", "group", "material", "velocity", "fixed", "element",
                 "pieces", "angular_velocity", "velocity_gradient", "origin", "piece_motion",
                 "max_triangles", "mesh_time_limit", "fracture", "fracture_group", "prebroken"});
            BodyEntry entry;
            entry.name = f.string("name", std::nullopt);
            entry.table = tables[i];
            f.set_context(fmt::format("body \"{}\"", entry.name));
            if (const auto it = body_by_name_.find(entry.name); it != body_by_name_.end()) {
                const BodyEntry& other = bodies_[it->second];
                f.fail(*f.node("name"), "name",
                       fmt::format("duplicate body name \"{}\" (first defined on line {})",
                                   entry.name, other.table->get("name")->source().begin.line));
            }
            BodyOptions opt;
            opt.name = entry.name;
            opt.material = material_index(f, "material");
            opt.velocity = f.vec2("velocity", Vec2{0, 0}, "m/s");
            opt.fixed = f.boolean("fixed", false);
            // (angular_velocity and velocity_gradient: read_velocity_field)
            for (const char* k : {"velocity"}) {
                if (opt.fixed && f.has(k)) {
                    f.fail(*f.node(k), k,
                           fmt::format("{} contradicts fixed = true (a fixed body keeps every "
                                       "node at its initial position); remove {}, or fixed and "
                                       "prescribe the motion with a [[boundary]] velocity",
                                       k, k));
                }
            }
            entry.fixed = opt.fixed;
            read_velocity_field(f, opt);
            // element formulation (docs/scenario.md): omitted = from the mesh (6-node triangles
            // -> composite, 3-node -> cst); "composite" meshes a .geo at order 2
            if (f.has("element")) {
                opt.element = f.choice("element", std::nullopt, {"cst", "composite"}) == "cst"
                                  ? ElementKind::Cst
                                  : ElementKind::Composite6;
            }
            const bool composite = opt.element == ElementKind::Composite6;
            entry.mesh = load_mesh(f, composite ? 2 : 1);
            LoadedMesh& lm = meshes_[static_cast<size_t>(entry.mesh)];
            if (composite && !lm.data.second_order()) {
                f.fail(*f.node("element"), "element",
                       fmt::format("element = \"composite\" needs 6-node triangles (Gmsh type 9), "
                                   "but mesh '{}' has 3-node triangles; expected a second-order "
                                   "mesh (gmsh -2 -order 2, or a .geo file, which is then meshed "
                                   "at order 2) or element = \"cst\"",
                                   lm.path));
            }

            // triangles: all of the mesh, or those of one surface physical group
            std::vector<int32_t> tris;
            if (f.has("group")) {
                const std::string g = f.string("group", std::nullopt);
                const PhysicalGroup* pg = nullptr;
                for (const size_t k : lm.named(g)) {
                    if (lm.data.groups[k].dim == 2) {
                        pg = &lm.data.groups[k];
                    }
                }
                if (!pg) {
                    for (const PhysicalGroup& cand : lm.data.groups) {
                        if (cand.name == g) {
                            f.fail(*f.node("group"), "group",
                                   fmt::format("\"{}\" is a {} physical group of mesh '{}', "
                                               "but a body is made of triangles: expected a "
                                               "surface group (Physical Surface); {}",
                                               g, group_kind(cand.dim), lm.path,
                                               available_groups(lm.data)));
                        }
                    }
                    const std::string guess = io::closest(g, group_names(lm.data));
                    f.fail(*f.node("group"), "group",
                           fmt::format(
                               "mesh '{}' has no surface physical group \"{}\"{}; {}", lm.path, g,
                               guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess),
                               available_groups(lm.data)));
                }
                tris = pg->elements;
                if (tris.empty()) {
                    f.fail(*f.node("group"), "group",
                           fmt::format("physical group \"{}\" of mesh '{}' contains no triangles",
                                       g, lm.path));
                }
            } else {
                tris.resize(lm.data.tris.size());
                for (size_t t = 0; t < tris.size(); ++t) {
                    tris[t] = static_cast<int32_t>(t);
                }
            }
            // a .geo read at orders 1 and 2 has the same triangles (setOrder only adds nodes):
            // selections must be disjoint across both copies
            std::vector<LoadedMesh*> same_file;
            for (LoadedMesh& other : meshes_) {
                if (other.path == lm.path && other.size == lm.size &&
                    other.tri_owner.size() == lm.tri_owner.size()) {
                    same_file.push_back(&other);
                }
            }
            for (const int32_t t : tris) {
                int owner = -1;
                for (const LoadedMesh* o : same_file) {
                    owner = std::max(owner, o->tri_owner[static_cast<size_t>(t)]);
                }
                if (owner >= 0) {
                    f.fail(f.has("group") ? *f.node("group") : *f.node("mesh"), "group",
                           fmt::format("triangles of mesh '{}' are already used by body \"{}\"; "
                                       "select disjoint physical groups with 'group'",
                                       lm.path, bodies_[static_cast<size_t>(owner)].name));
                }
            }
            for (const int32_t t : tris) {
                lm.tri_owner[static_cast<size_t>(t)] = static_cast<int>(i);
            }
            read_body_fracture(f, lm, tris, m, opt);
            // pieces (docs/scenario.md): "one" = the selection must be one connected piece (a
            // disconnected mesh is usually a modelling error); "separate" = every connected
            // piece becomes its own discrete element (a pack of grains meshed together)
            const bool separate =
                f.choice("pieces", std::string("one"), {"one", "separate"}) == "separate";
            const BodyId first_body = m.num_bodies();
            entry.node_map = add_bodies_mapped(m, lm.data, tris, opt);
            entry.body_begin = first_body;
            entry.body_end = m.num_bodies();
            if (!separate && m.num_bodies() - first_body > 1) {
                const Body& second = m.bodies[static_cast<size_t>(first_body) + 1];
                const Vec2 at = m.node_x0[static_cast<size_t>(second.node_begin)];
                f.fail(*f.node(f.has("group") ? "group" : "mesh"),
                       f.has("group") ? "group" : "mesh",
                       fmt::format("the triangles selected from mesh '{}' form {} disconnected "
                                   "pieces (the second one has a node at ({:g}, {:g}) m); expected "
                                   "one connected piece: connect the mesh (Gmsh: Coherence Mesh;), "
                                   "select one piece with 'group', or set pieces = \"separate\" "
                                   "to make every piece its own discrete element",
                                   lm.path, m.num_bodies() - first_body, at.x, at.y));
            }
            check_duplicate_nodes(f, lm, entry.node_map, m);
            body_by_name_.emplace(entry.name, bodies_.size());
            bodies_.push_back(std::move(entry));
        }
    }

    /// Fracture keys of a [[body]] entry (docs/scenario.md; spec fracture.md §10): fracture,
    /// fracture_group (a surface group: joints on the internal edges between its triangles; a
    /// curve group: joints on its edges only), prebroken (curve groups broken at t = 0).
    void read_body_fracture(const Fields& f, const LoadedMesh& lm, const std::vector<int32_t>& tris,
                            const Model& m, BodyOptions& opt) {
        const Material& mat = m.materials[static_cast<size_t>(opt.material)];
        const bool composite =
            opt.element ? *opt.element == ElementKind::Composite6 : lm.data.second_order();
        bool want = false;
        if (f.has("fracture")) {
            want = f.boolean("fracture", std::nullopt);
            if (want && !mat.has_fracture) {
                f.fail(*f.node("fracture"), "fracture",
                       fmt::format("fracture = true needs the joint parameters of material "
                                   "\"{}\", but it has no [material.fracture] table; add one "
                                   "(tensile_strength, cohesion, friction_angle, "
                                   "fracture_energy_I, fracture_energy_II) or remove fracture",
                                   mat.name));
            }
            if (want && opt.fixed) {
                f.fail(*f.node("fracture"), "fracture",
                       "fracture = true on a fixed body (fixed = true): a fixed body never "
                       "deforms, so it cannot crack; remove one of them");
            }
        } else {
            // default: the material's [material.fracture] switches joints on; a fixed body
            // never fractures (it never deforms)
            want = mat.has_fracture && !opt.fixed;
        }
        for (const char* k : {"fracture_group", "prebroken"}) {
            if (!want && f.has(k)) {
                f.fail(*f.node(k), k,
                       fmt::format("{} only applies to a body with fracture, but body \"{}\" has "
                                   "none ({}); remove {}",
                                   k, opt.name,
                                   f.has("fracture") ? "fracture = false"
                                   : opt.fixed       ? "it is fixed"
                                                     : fmt::format("material \"{}\" has no "
                                                                         "[material.fracture]",
                                                                   mat.name),
                                   k));
            }
        }
        if (!want) {
            return;
        }
        if (composite) {
            const char* at = f.has("fracture") ? "fracture" : f.has("element") ? "element" : "mesh";
            f.fail(*f.node(at), at,
                   fmt::format("fracture{} is not available for composite (6-node) elements yet "
                               "(spec fracture.md §12.12); set element = \"cst\" (every 6-node "
                               "triangle split into 4 CSTs) or fracture = false",
                               f.has("fracture") ? " = true"
                                                 : fmt::format(" (on by default: material "
                                                               "\"{}\" has [material.fracture])",
                                                               mat.name)));
        }
        opt.fracture = true;
        const MeshData& mesh = lm.data;

        // the triangles as the model will have them (a 6-node triangle as its 4 CSTs), in mesh
        // node ids, and their undirected edges -> number of triangles using them
        const auto csts = [&](int32_t t) {
            const auto& c = mesh.tris[static_cast<size_t>(t)];
            std::vector<std::array<int32_t, 3>> out;
            if (!mesh.second_order()) {
                out.push_back(c);
            } else {
                const auto& mid = mesh.tri_mid[static_cast<size_t>(t)];
                out = {{c[0], mid[0], mid[2]},
                       {mid[0], c[1], mid[1]},
                       {mid[2], mid[1], c[2]},
                       {mid[0], mid[1], mid[2]}};
            }
            return out;
        };
        const auto count_edges = [&](const std::vector<int32_t>& sel) {
            std::map<std::pair<int32_t, int32_t>, int> count;
            for (const int32_t t : sel) {
                for (const auto& c : csts(t)) {
                    for (int k = 0; k < 3; ++k) {
                        const int32_t a = c[static_cast<size_t>(k)],
                                      b = c[static_cast<size_t>((k + 1) % 3)];
                        ++count[{std::min(a, b), std::max(a, b)}];
                    }
                }
            }
            return count;
        };
        const std::map<std::pair<int32_t, int32_t>, int> edge_count = count_edges(tris);
        Real longest = 0;
        const auto measure = [&](int32_t a, int32_t b) {
            longest = std::max(longest, norm(mesh.nodes[static_cast<size_t>(b)] -
                                             mesh.nodes[static_cast<size_t>(a)]));
        };
        // the edges of the curve groups named by key `key` (value `name`), checked to be
        // internal edges of the selection; 3-node lines give their two halves
        const auto curve_edges = [&](const toml::node& at, const char* key, const std::string& name,
                                     std::vector<std::array<int32_t, 2>>& out) {
            bool any = false;
            for (const size_t g : lm.named(name)) {
                const PhysicalGroup& pg = mesh.groups[g];
                if (pg.dim != 1) continue;
                for (const int32_t e : pg.elements) {
                    const auto& l = mesh.lines[static_cast<size_t>(e)];
                    std::vector<std::array<int32_t, 2>> pieces;
                    if (mesh.line_mid.empty()) {
                        pieces.push_back(l);
                    } else {
                        const int32_t mid = mesh.line_mid[static_cast<size_t>(e)];
                        pieces = {{l[0], mid}, {mid, l[1]}};
                    }
                    for (const auto& [a, b] : pieces) {
                        const auto it = edge_count.find({std::min(a, b), std::max(a, b)});
                        if (it == edge_count.end()) continue;  // another part of the mesh
                        if (it->second != 2) {
                            const Vec2 xa = mesh.nodes[static_cast<size_t>(a)],
                                       xb = mesh.nodes[static_cast<size_t>(b)];
                            f.fail(at, key,
                                   fmt::format("the edge from ({:g}, {:g}) to ({:g}, {:g}) m of "
                                               "curve group \"{}\" is on the boundary of body "
                                               "\"{}\"; joints exist only on internal edges "
                                               "(between two triangles of the body)",
                                               xa.x, xa.y, xb.x, xb.y, name, opt.name));
                        }
                        any = true;
                        out.push_back({a, b});
                        measure(a, b);
                    }
                }
            }
            if (!any) {
                f.fail(at, key,
                       fmt::format("curve group \"{}\" of mesh '{}' has no edge inside body "
                                   "\"{}\" (it lies on another part of the mesh)",
                                   name, lm.path, opt.name));
            }
        };
        // a group name: must exist; kind 2 (surface) or 1 (curve) allowed as `kinds` says
        const auto find_group = [&](const toml::node& at, const char* key, const std::string& name,
                                    bool surface_ok) -> int {
            int dim = -1;
            for (const size_t g : lm.named(name)) {
                dim = std::max(dim, mesh.groups[g].dim);
            }
            if (dim < 0) {
                const std::string guess = io::closest(name, group_names(mesh));
                f.fail(
                    at, key,
                    fmt::format("mesh '{}' has no physical group \"{}\"{}; {}", lm.path, name,
                                guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess),
                                available_groups(mesh)));
            }
            if (dim == 0 || (dim == 2 && !surface_ok)) {
                f.fail(
                    at, key,
                    fmt::format("\"{}\" is a {} physical group of mesh '{}', but {} needs {}; {}",
                                name, group_kind(dim), lm.path, key,
                                surface_ok ? "a surface group (joints on the internal edges "
                                             "between its triangles) or a curve group (joints "
                                             "on its edges)"
                                           : "curve groups (the edges broken at t = 0)",
                                available_groups(mesh)));
            }
            return dim;
        };

        if (f.has("fracture_group")) {
            const std::string g = f.string("fracture_group", std::nullopt);
            const toml::node& at = *f.node("fracture_group");
            if (find_group(at, "fracture_group", g, true) == 2) {
                std::vector<char> in_body(mesh.tris.size(), 0);
                for (const int32_t t : tris)
                    in_body[static_cast<size_t>(t)] = 1;
                for (const size_t k : lm.named(g)) {
                    if (mesh.groups[k].dim != 2) continue;
                    for (const int32_t t : mesh.groups[k].elements) {
                        if (in_body[static_cast<size_t>(t)]) opt.fracture_tris.push_back(t);
                    }
                }
                std::sort(opt.fracture_tris.begin(), opt.fracture_tris.end());
                opt.fracture_tris.erase(
                    std::unique(opt.fracture_tris.begin(), opt.fracture_tris.end()),
                    opt.fracture_tris.end());
                if (opt.fracture_tris.empty()) {
                    f.fail(at, "fracture_group",
                           fmt::format("surface group \"{}\" of mesh '{}' has no triangle of "
                                       "body \"{}\"",
                                       g, lm.path, opt.name));
                }
                // joints on the internal edges between two triangles of the group
                for (const auto& [e, count] : count_edges(opt.fracture_tris)) {
                    if (count == 2) measure(e.first, e.second);
                }
            } else {
                curve_edges(at, "fracture_group", g, opt.joint_edges);
            }
        } else {
            for (const auto& [e, count] : edge_count) {
                if (count == 2) measure(e.first, e.second);
            }
        }
        if (const toml::node* n = f.node("prebroken")) {
            const toml::array* a = n->as_array();
            bool ok = a != nullptr && !a->empty();
            for (size_t k = 0; ok && k < a->size(); ++k)
                ok = a->get(k)->is_string();
            if (!ok) {
                f.fail(*n, "prebroken",
                       fmt::format("prebroken must be a non-empty list of curve group names, "
                                   "e.g. [\"notch\"], got {}",
                                   io::describe_value(*n)));
            }
            for (const toml::node& e : *a) {
                const std::string g = e.value<std::string>().value_or("");
                find_group(e, "prebroken", g, false);
                curve_edges(e, "prebroken", g, opt.prebroken_edges);
            }
        }
        auto& lj = longest_joint_[opt.material];
        if (longest > lj.first) lj = {longest, opt.name};
    }

    /// Joint lengths against the softening rule of their material (docs/theory.md §9.3): with
    /// "total", the softening branch must have a positive length, G_I > (2/3) f_t o_p =
    /// (4/3) h f_t^2 / p (eqs. 9.4, 9.12); with "exact", h <= h_max (eq. 9.14, its
    /// well-posedness) unless allow_coarse, as finalize_model() requires (here with the location
    /// of the table).
    void check_joint_lengths(const Model& m) const {
        for (const auto& [mi, longest] : longest_joint_) {
            const auto& [h, body] = longest;
            const Material& mat = m.materials[static_cast<size_t>(mi)];
            const JointMaterial& j = mat.fracture;
            const toml::table& t = *fracture_tables_[static_cast<size_t>(mi)];
            Fields f(src_, t, fmt::format("material \"{}\" [material.fracture]", mat.name),
                     fmt::format("material[{}].fracture", mi), kMaterialFractureKeys);
            const Real ft = j.tensile_strength;
            if (j.softening_length == SofteningLength::Total) {
                const Real elastic = 4.0 / 3.0 * h * ft * ft / j.penalty;  // (2/3) f_t o_p
                if (!(j.fracture_energy_I > elastic)) {
                    f.fail(*t.get("softening_length"), "softening_length",
                           fmt::format("softening_length = \"total\" needs fracture_energy_I > "
                                       "(2/3) f_t o_p = (4/3) h f_t^2 / p for every joint, but "
                                       "the longest joint (h = {:.4g} m, in body \"{}\") gives "
                                       "{:.4g} J/m^2 >= fracture_energy_I = {:g} J/m^2 (the "
                                       "pre-peak branch alone dissipates more than G_I); refine "
                                       "the mesh, raise penalty, or use \"exact\"",
                                       h, body, elastic, j.fracture_energy_I));
                }
            }
            if (j.softening_length == SofteningLength::Exact && !j.allow_coarse) {
                const Real h_max = joint_max_length(j);  // eq. 9.14
                if (h > h_max) {
                    f.fail_table(fmt::format(
                        "the longest joint (h = {:.4g} m, in body \"{}\") is longer than h_max = "
                        "p G_I / (4 I_z f_t^2) = {:.4g} m (docs/theory.md eq. 9.14: the exact "
                        "softening branch would be shorter than 2 o_p); refine the mesh to "
                        "h <= {:.4g} m, raise penalty or fracture_energy_I, or set allow_coarse "
                        "= true",
                        h, body, h_max, h_max));
                }
            }
        }
    }

    // ---- [fracture] (global, optional) ------------------------------------------------------
    void read_fracture(const toml::table& root, Scenario& sc) {
        const toml::table* t = sub_table(src_, root, "fracture");
        if (!t) {
            return;
        }
        Fields f(src_, *t, "[fracture]", "fracture",
                 {"crack_contact", "ramp_steps", "contact_targets", "output_joints", "fragments"});
        if (f.choice("crack_contact", std::string("self"), {"self", "pairs"}) == "pairs") {
            f.fail(*f.node("crack_contact"), "crack_contact",
                   "crack_contact = \"pairs\" (broken joints as node-pair contacts with a force "
                   "ramp) is not implemented; only \"self\" is (crack faces meet by the smooth "
                   "contact of the body with itself, rule X of docs/theory.md §9)");
        }
        if (f.has("ramp_steps")) {
            f.fail(*f.node("ramp_steps"), "ramp_steps",
                   "ramp_steps only applies with crack_contact = \"pairs\", which is not "
                   "implemented; remove ramp_steps");
        }
        if (f.choice("contact_targets", std::string("copies"), {"copies", "sector"}) == "sector") {
            f.fail(*f.node("contact_targets"), "contact_targets",
                   "contact_targets = \"sector\" (one contact evaluation per logical vertex) is "
                   "not implemented; only \"copies\" is (every node copy is a target with its "
                   "own mass)");
        }
        const std::string joints =
            f.choice("output_joints", std::string("damaged"), {"damaged", "all", "none"});
        sc.run.fracture.output_joints = joints == "damaged" ? JointOutput::Damaged
                                        : joints == "all"   ? JointOutput::All
                                                            : JointOutput::None;
        sc.run.fracture.fragments =
            f.choice("fragments", std::string("interval"), {"interval", "end"}) == "end"
                ? FragmentOutput::End
                : FragmentOutput::Interval;
        if (longest_joint_.empty()) {
            const SourceLocation at = f.location("");
            sc.warnings.push_back(fmt::format(
                "{}:{}:{}: warning: [fracture] is given but no body has fracture (no material "
                "with [material.fracture] is used by a body that is not fixed); it has no effect",
                at.file, at.line, at.column));
        }
    }

    /// Initial velocity field of a [[body]] entry beyond 'velocity' (docs/scenario.md, theory
    /// eq. 5.5): angular_velocity, velocity_gradient, origin, piece_motion.
    static void read_velocity_field(const Fields& f, BodyOptions& opt) {
        opt.angular_velocity = f.real("angular_velocity", 0.0, "rad/s", Bounds::any());
        if (const toml::node* n = f.node("velocity_gradient")) {
            const std::string what =
                "a 2x2 matrix [[dvx/dx, dvx/dy], [dvy/dx, dvy/dy]] of finite numbers in 1/s";
            const toml::array* rows = n->as_array();
            Real g[2][2] = {};
            bool ok = rows && rows->size() == 2;
            for (size_t r = 0; ok && r < 2; ++r) {
                const toml::array* row = rows->get(r)->as_array();
                ok = row && row->size() == 2;
                for (size_t c = 0; ok && c < 2; ++c) {
                    ok = row->get(c)->is_number();
                    if (ok) {
                        g[r][c] = row->get(c)->value<double>().value_or(0.0);
                        ok = std::isfinite(g[r][c]);
                    }
                }
            }
            if (!ok) {
                f.fail(*n, "velocity_gradient",
                       fmt::format("velocity_gradient must be {}, got {}", what,
                                   io::describe_value(*n)));
            }
            opt.velocity_gradient = Mat2{g[0][0], g[0][1], g[1][0], g[1][1]};
        }
        const Mat2& G = opt.velocity_gradient;
        const bool field =
            opt.angular_velocity != 0 || G.xx != 0 || G.xy != 0 || G.yx != 0 || G.yy != 0;
        if (const toml::node* n = f.node("origin")) {
            if (!field) {
                f.fail(*n, "origin",
                       "origin is the point about which angular_velocity and velocity_gradient "
                       "act, but neither is given (or both are zero); remove origin or give one "
                       "of them");
            }
            if (n->is_string()) {
                if (n->value<std::string>().value_or("") != "centroid") {
                    f.fail(*n, "origin",
                           fmt::format("origin must be [x, y] in m or \"centroid\" (each "
                                       "piece's own mass centre), got {}",
                                       io::describe_value(*n)));
                }
                opt.origin_centroid = true;
            } else {
                opt.origin = f.vec2("origin", std::nullopt, "m");
                opt.origin_centroid = false;
            }
        }
        if (const toml::node* n = f.node("piece_motion")) {
            if (!field) {
                f.fail(*n, "piece_motion",
                       "piece_motion says how angular_velocity and velocity_gradient move each "
                       "piece, but neither is given (or both are zero); remove piece_motion or "
                       "give one of them");
            }
            opt.rigid_pieces =
                f.choice("piece_motion", std::nullopt, {"affine", "rigid"}) == "rigid";
        }
        if (field && f.boolean("fixed", false)) {
            const char* key = opt.angular_velocity != 0 ? "angular_velocity" : "velocity_gradient";
            f.fail(*f.node(key), key,
                   fmt::format("{} sets an initial velocity, but fixed = true holds every node "
                               "of the body at rest; remove one of them",
                               key));
        }
    }

    /// Two nodes at the same position inside one body (after the split into connected
    /// components) are a hidden crack: usually two meshes pasted without merging their nodes.
    /// Coincident nodes of different bodies are fine (bodies touching at t = 0).
    static void check_duplicate_nodes(const Fields& f, const LoadedMesh& lm,
                                      const MeshNodeMap& node_map, const Model& m) {
        struct Key {
            BodyId body;
            Vec2 x;
            int32_t mesh_node;
        };
        std::vector<Key> keys;
        keys.reserve(node_map.mesh_nodes.size());
        for (size_t k = 0; k < node_map.mesh_nodes.size(); ++k) {
            const int32_t i = node_map.mesh_nodes[k];
            keys.push_back({m.node_body[static_cast<size_t>(node_map.model_nodes[k])],
                            lm.data.nodes[static_cast<size_t>(i)], i});
        }
        const auto less = [](const Key& a, const Key& b) {
            if (a.body != b.body) return a.body < b.body;
            if (a.x.x != b.x.x) return a.x.x < b.x.x;
            if (a.x.y != b.x.y) return a.x.y < b.x.y;
            return a.mesh_node < b.mesh_node;
        };
        std::sort(keys.begin(), keys.end(), less);
        for (size_t k = 1; k < keys.size(); ++k) {
            const Key& a = keys[k - 1];
            const Key& b = keys[k];
            if (a.body == b.body && a.x.x == b.x.x && a.x.y == b.x.y) {
                f.fail(*f.node("mesh"), "mesh",
                       fmt::format("mesh '{}' has two distinct nodes at the same position ({:g}, "
                                   "{:g}) in one body (nodes #{} and #{} in file order): the "
                                   "elements around them are not connected, a hidden crack; "
                                   "merge duplicate nodes (Gmsh: Coherence Mesh;)",
                                   lm.path, a.x.x, a.x.y, a.mesh_node + 1, b.mesh_node + 1));
            }
        }
    }

    static NodeId first_node(const BodyEntry& e) {
        // the model node of the lowest mesh node, as the first in mesh order
        return e.node_map.model_nodes.empty() ? 0 : e.node_map.model_nodes.front();
    }

    int body_index(const Fields& f, std::string_view key) const {
        const std::string name = f.string(key, std::nullopt);
        if (const auto it = body_by_name_.find(name); it != body_by_name_.end()) {
            return static_cast<int>(it->second);
        }
        std::vector<std::string> names;
        for (const BodyEntry& e : bodies_) {
            names.push_back(e.name);
        }
        const std::string guess = io::closest(name, names);
        f.fail(
            *f.node(key), key,
            fmt::format("unknown body \"{}\"; defined bodies: {}{}", name, io::quoted_list(names),
                        guess.empty() ? "" : fmt::format("; did you mean \"{}\"?", guess)));
    }

    // ---- [[boundary]] ----------------------------------------------------------------------
    void read_boundaries(const toml::table& root, Model& m) {
        const auto tables = table_array(src_, root, "boundary", "boundary");
        for (size_t i = 0; i < tables.size(); ++i) {
            Fields f(src_, *tables[i], fmt::format("[[boundary]] #{}", i + 1),
                     fmt::format("boundary[{}]", i),
                     {"body", "group", "fix", "velocity", "components", "start", "end"});
            const int b = body_index(f, "body");
            const BodyEntry& entry = bodies_[static_cast<size_t>(b)];
            const std::string group = f.string("group", std::nullopt);
            f.set_context(fmt::format("boundary \"{}\" of body \"{}\"", group, entry.name));

            BoundaryCondition bc;
            bc.name = entry.name + "/" + group;

            // what is prescribed: fix = [...] or velocity = [vx, vy] (+ components)
            if (f.has("fix") == f.has("velocity")) {
                f.fail_table(
                    "give exactly one of 'fix' (components held at zero velocity) or "
                    "'velocity' (prescribed velocity [vx, vy] in m/s)");
            }
            if (f.has("fix")) {
                if (f.has("components")) {
                    f.fail(*f.node("components"), "components",
                           "'components' goes with 'velocity'; with 'fix' list the components "
                           "in 'fix' itself");
                }
                f.components("fix", std::nullopt, bc.has_x, bc.has_y);
            } else {
                bc.velocity = f.vec2("velocity", std::nullopt, "m/s");
                f.components("components", std::pair{true, true}, bc.has_x, bc.has_y);
                const Real vx = bc.has_x ? bc.velocity.x : 0.0, vy = bc.has_y ? bc.velocity.y : 0.0;
                boundary_speeds_.push_back({f.location("velocity"), f.full_key("velocity"),
                                            f.context(), std::sqrt(vx * vx + vy * vy),
                                            static_cast<size_t>(b)});
            }
            bc.start = f.real("start", 0.0, "s", Bounds::non_negative());
            bc.end =
                f.real("end", std::numeric_limits<Real>::infinity(), "s", Bounds::non_negative());
            if (f.has("end") && !(bc.end > bc.start)) {
                f.fail(*f.node("end"), "end",
                       fmt::format("end must be > start = {} s, got {}", bc.start, bc.end));
            }

            bc.nodes = group_nodes(f, entry, group);
            m.bcs.push_back(std::move(bc));
        }
    }

    // ---- [[load]] --------------------------------------------------------------------------
    /// Time function keys of a [[load]] (docs/scenario.md, theory eq. 4.8).
    static TimeFunction read_time_function(const Fields& f) {
        TimeFunction tf;
        const std::string kind =
            f.choice("time_function", std::string("constant"), {"constant", "ramp", "table"});
        if (kind != "ramp" && f.has("ramp_time")) {
            f.fail(*f.node("ramp_time"), "ramp_time",
                   fmt::format("ramp_time only applies with time_function = \"ramp\" (here "
                               "\"{}\"); remove it or set time_function = \"ramp\"",
                               kind));
        }
        if (kind != "table" && f.has("table")) {
            f.fail(*f.node("table"), "table",
                   fmt::format("table only applies with time_function = \"table\" (here "
                               "\"{}\"); remove it or set time_function = \"table\"",
                               kind));
        }
        if (kind == "ramp") {
            tf.kind = TimeFunction::Kind::Ramp;
            tf.ramp_time = f.real("ramp_time", std::nullopt, "s", Bounds::positive());
        } else if (kind == "table") {
            tf.kind = TimeFunction::Kind::Table;
            const toml::node* n = f.node("table");
            const std::string what =
                "a list of [time in s, factor] pairs with strictly increasing times, e.g. "
                "[[0, 0], [0.01, 1]]";
            if (!n) {
                f.fail_missing("table", what);
            }
            const toml::array* a = n->as_array();
            if (!a || a->empty()) {
                f.fail(*n, "table",
                       fmt::format("table must be {}, got {}", what, io::describe_value(*n)));
            }
            for (size_t k = 0; k < a->size(); ++k) {
                const toml::node& e = *a->get(k);
                const toml::array* p = e.as_array();
                if (!p || p->size() != 2 || !p->get(0)->is_number() || !p->get(1)->is_number()) {
                    f.fail(e, "table",
                           fmt::format("table entry {} must be [time in s, factor], got {}", k + 1,
                                       io::describe_value(e)));
                }
                const Real t = p->get(0)->value<double>().value_or(0.0);
                const Real v = p->get(1)->value<double>().value_or(0.0);
                if (!std::isfinite(t) || !std::isfinite(v)) {
                    f.fail(e, "table",
                           fmt::format("table entry {} must be finite, got {}", k + 1,
                                       io::describe_value(e)));
                }
                if (!tf.table.empty() && !(t > tf.table.back()[0])) {
                    f.fail(e, "table",
                           fmt::format("table times must be strictly increasing, but entry {} "
                                       "has t = {} s after t = {} s",
                                       k + 1, t, tf.table.back()[0]));
                }
                tf.table.push_back({t, v});
            }
        }
        return tf;
    }

    void read_loads(const toml::table& root, Model& m) {
        const auto tables = table_array(src_, root, "load", "load");
        for (size_t i = 0; i < tables.size(); ++i) {
            Fields f(src_, *tables[i], fmt::format("[[load]] #{}", i + 1),
                     fmt::format("load[{}]", i),
                     {"body", "group", "traction", "pressure", "force", "time_function",
                      "ramp_time", "table"});
            const int b = body_index(f, "body");
            const BodyEntry& entry = bodies_[static_cast<size_t>(b)];
            const LoadedMesh& lm = meshes_[static_cast<size_t>(entry.mesh)];
            const MeshData& mesh = lm.data;
            const std::string group = f.string("group", std::nullopt);
            f.set_context(fmt::format("load on \"{}\" of body \"{}\"", group, entry.name));

            Load ld;
            ld.name = entry.name + "/" + group;
            const int given = int(f.has("traction")) + int(f.has("pressure")) + int(f.has("force"));
            if (given != 1) {
                f.fail_table(
                    "give exactly one of 'traction' ([tx, ty] in Pa on the edges of a curve "
                    "group), 'pressure' (in Pa, normal to the current edges of a curve group, "
                    "positive pushing into the body) or 'force' ([fx, fy] in N/m, the resultant "
                    "on the nodes of a group)");
            }
            if (f.has("traction")) {
                ld.kind = LoadKind::Traction;
                ld.vector = f.vec2("traction", std::nullopt, "Pa");
            } else if (f.has("pressure")) {
                ld.kind = LoadKind::Pressure;
                ld.pressure = f.real("pressure", std::nullopt, "Pa", Bounds::any());
            } else {
                ld.kind = LoadKind::Force;
                ld.vector = f.vec2("force", std::nullopt, "N/m");
            }
            ld.time_function = read_time_function(f);

            // a load on a fixed body would do nothing: say so instead
            bool fixed = true;
            for (BodyId k = entry.body_begin; k < entry.body_end; ++k) {
                if (!m.bodies[static_cast<size_t>(k)].fixed) fixed = false;
            }
            if (fixed) {
                f.fail(*f.node("body"), "body",
                       fmt::format("body \"{}\" is fixed (fixed = true), so a load on it would "
                                   "do nothing; load a body that can move",
                                   entry.name));
            }

            bool found = false, curve = false;
            for (const size_t k : lm.named(group)) {
                found = true;
                curve = curve || mesh.groups[k].dim == 1;
            }
            if (!found) {
                const std::string guess = io::closest(group, group_names(mesh));
                f.fail(
                    *f.node("group"), "group",
                    fmt::format("mesh '{}' has no physical group \"{}\"{}; {}", mesh.file, group,
                                guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess),
                                available_groups(mesh)));
            }
            if (ld.kind == LoadKind::Force) {
                for (const size_t k : lm.named(group)) {
                    for (const int32_t n : mesh.group_nodes(mesh.groups[k])) {
                        const NodeId id = entry.node_map[n];
                        if (id != kNone) ld.nodes.push_back(id);
                    }
                }
                // every copy of a jointed vertex (the shares: finalize_model, theory eq. 4.9)
                add_node_copies(m_, entry, ld.nodes);
                if (ld.nodes.empty()) {
                    f.fail(*f.node("group"), "group",
                           fmt::format("physical group \"{}\" selects none of the nodes of body "
                                       "\"{}\" (it lies on another part of mesh '{}')",
                                       group, entry.name, mesh.file));
                }
            } else {
                if (!curve) {
                    f.fail(*f.node("group"), "group",
                           fmt::format("{} acts on boundary edges, but physical group \"{}\" of "
                                       "mesh '{}' is not a curve group (its line elements are "
                                       "the loaded edges); use a Physical Curve, or 'force' for "
                                       "a point group",
                                       ld.kind == LoadKind::Traction ? "traction" : "pressure",
                                       group, mesh.file));
                }
                load_edges(f, m, entry, lm, group, ld);
            }
            m.loads.push_back(std::move(ld));
        }
    }

    /// The node that stands for the mesh vertex of node n: the smallest of its copies with
    /// fracture (Model::node_vertex), n itself otherwise.
    static NodeId vertex(const Model& m, NodeId n) {
        return m.node_vertex.empty() ? n : m.node_vertex[static_cast<size_t>(n)];
    }

    /// The boundary edges of body entry b under the line elements of curve group `group`,
    /// oriented counter-clockwise around the body (Load::edges); a 3-node line gives its two
    /// halves, the edges of the sub-triangles. Every edge must be on the body's boundary.
    void load_edges(const Fields& f, const Model& m, const BodyEntry& entry, const LoadedMesh& lm,
                    const std::string& group, Load& ld) const {
        const MeshData& mesh = lm.data;
        // directed boundary edges of the entry's triangles: an undirected edge used by exactly
        // one triangle, kept in that triangle's counter-clockwise direction
        std::map<std::pair<NodeId, NodeId>, std::pair<int, std::array<NodeId, 2>>> edges;
        for (BodyId bi = entry.body_begin; bi < entry.body_end; ++bi) {
            const Body& body = m.bodies[static_cast<size_t>(bi)];
            for (TriId t = body.tri_begin; t < body.tri_end; ++t) {
                const auto& n = m.tri_nodes[static_cast<size_t>(t)];
                for (int k = 0; k < 3; ++k) {
                    const NodeId p = n[static_cast<size_t>(k)],
                                 q = n[static_cast<size_t>((k + 1) % 3)];
                    // keyed by mesh vertex: the node copies of a vertex (fracture) are one
                    const NodeId wp = vertex(m, p), wq = vertex(m, q);
                    auto& e = edges[{std::min(wp, wq), std::max(wp, wq)}];
                    ++e.first;
                    e.second = {p, q};
                }
            }
        }
        const auto add = [&](int32_t mp, int32_t mq) {
            const NodeId p0 = entry.node_map[mp];
            const NodeId q0 = entry.node_map[mq];
            if (p0 == kNone || q0 == kNone) return;  // another part of the mesh
            const NodeId p = vertex(m, p0), q = vertex(m, q0);
            const auto it = edges.find({std::min(p, q), std::max(p, q)});
            const Vec2 a = mesh.nodes[static_cast<size_t>(mp)],
                       c = mesh.nodes[static_cast<size_t>(mq)];
            if (it == edges.end() || it->second.first != 1) {
                f.fail(*f.node("group"), "group",
                       fmt::format("the edge from ({:g}, {:g}) to ({:g}, {:g}) m of physical group "
                                   "\"{}\" is {} of body \"{}\", not on its boundary; a "
                                   "traction or pressure needs a curve on the body's outline",
                                   a.x, a.y, c.x, c.y, group,
                                   it == edges.end() ? "not an edge of the triangles"
                                                     : "inside (shared by two triangles)",
                                   entry.name));
            }
            const std::array<NodeId, 2> d = it->second.second;
            ld.edges.push_back(d);
            ld.edge_length0.push_back(
                norm(m.node_x0[static_cast<size_t>(d[1])] - m.node_x0[static_cast<size_t>(d[0])]));
        };
        for (const size_t k : lm.named(group)) {
            const PhysicalGroup& g = mesh.groups[k];
            if (g.dim != 1) continue;
            for (const int32_t e : g.elements) {
                const auto& l = mesh.lines[static_cast<size_t>(e)];
                if (mesh.line_mid.empty()) {
                    add(l[0], l[1]);
                } else {
                    add(l[0], mesh.line_mid[static_cast<size_t>(e)]);
                    add(mesh.line_mid[static_cast<size_t>(e)], l[1]);
                }
            }
        }
        if (ld.edges.empty()) {
            f.fail(*f.node("group"), "group",
                   fmt::format("physical group \"{}\" selects none of the edges of body \"{}\" "
                               "(it lies on another part of mesh '{}')",
                               group, entry.name, mesh.file));
        }
    }

    // The model nodes of body entry `entry` in every physical group named `group` of its mesh
    // (point, curve or surface), ascending; an error at key "group" if the mesh has no such
    // group or the group selects none of the entry's nodes.
    std::vector<NodeId> group_nodes(const Fields& f, const BodyEntry& entry,
                                    const std::string& group) const {
        const LoadedMesh& lm = meshes_[static_cast<size_t>(entry.mesh)];
        const MeshData& mesh = lm.data;
        std::vector<int32_t> mesh_nodes;
        std::vector<NodeId> surface_copies;  // fracture: the copies of a surface group's triangles
        bool found = false;
        for (const size_t k : lm.named(group)) {
            found = true;
            const PhysicalGroup& g = mesh.groups[k];
            if (g.dim == 2 && has_fracture(m_, entry)) {
                add_surface_copies(*m_, entry, mesh, g.elements, surface_copies);
                continue;
            }
            const auto n = mesh.group_nodes(g);
            mesh_nodes.insert(mesh_nodes.end(), n.begin(), n.end());
        }
        if (!found) {
            const std::string guess = io::closest(group, group_names(mesh));
            f.fail(*f.node("group"), "group",
                   fmt::format("mesh '{}' has no physical group \"{}\"{}; {}", mesh.file, group,
                               guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess),
                               available_groups(mesh)));
        }
        std::vector<NodeId> nodes;
        for (const int32_t n : mesh_nodes) {
            const NodeId id = entry.node_map[n];
            if (id != kNone) {
                nodes.push_back(id);
            }
        }
        add_node_copies(m_, entry, nodes);
        if (!surface_copies.empty()) {
            nodes.insert(nodes.end(), surface_copies.begin(), surface_copies.end());
            std::sort(nodes.begin(), nodes.end());
            nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
        }
        if (nodes.empty()) {
            f.fail(*f.node("group"), "group",
                   fmt::format("physical group \"{}\" selects none of the nodes of body "
                               "\"{}\" (it lies on another part of mesh '{}')",
                               group, entry.name, mesh.file));
        }
        return nodes;
    }

    /// True when a body of the entry has fracture (node copies, Model::node_vertex).
    static bool has_fracture(const Model* m, const BodyEntry& entry) {
        if (m == nullptr || m->node_vertex.size() != static_cast<size_t>(m->num_nodes()))
            return false;
        for (BodyId b = entry.body_begin; b < entry.body_end; ++b) {
            if (m->bodies[static_cast<size_t>(b)].fracture) return true;
        }
        return false;
    }

    /// With fracture, the nodes of a surface group are the copies its own triangles use: a
    /// vertex on the group's border also has copies in triangles outside it (across a jointed
    /// edge), which a support on the group must leave free. Model triangles are matched to the
    /// group's mesh triangles (their 4 sub-triangles for a 6-node mesh) by their corner
    /// positions, which the node copies keep exactly.
    static void add_surface_copies(const Model& m, const BodyEntry& entry, const MeshData& mesh,
                                   const std::vector<int32_t>& elements, std::vector<NodeId>& out) {
        using Key = std::array<Real, 6>;
        const auto key = [](Vec2 a, Vec2 b, Vec2 c) {
            std::array<Vec2, 3> v{a, b, c};
            std::sort(v.begin(), v.end(),
                      [](Vec2 p, Vec2 q) { return p.x < q.x || (p.x == q.x && p.y < q.y); });
            return Key{v[0].x, v[0].y, v[1].x, v[1].y, v[2].x, v[2].y};
        };
        std::set<Key> keys;
        const auto x = [&](int32_t i) { return mesh.nodes[static_cast<size_t>(i)]; };
        for (const int32_t t : elements) {
            const auto& c = mesh.tris[static_cast<size_t>(t)];
            if (!mesh.second_order()) {
                keys.insert(key(x(c[0]), x(c[1]), x(c[2])));
                continue;
            }
            const auto& d = mesh.tri_mid[static_cast<size_t>(t)];
            keys.insert(key(x(c[0]), x(d[0]), x(d[2])));
            keys.insert(key(x(d[0]), x(c[1]), x(d[1])));
            keys.insert(key(x(d[2]), x(d[1]), x(c[2])));
            keys.insert(key(x(d[0]), x(d[1]), x(d[2])));
        }
        for (BodyId b = entry.body_begin; b < entry.body_end; ++b) {
            const Body& body = m.bodies[static_cast<size_t>(b)];
            for (TriId t = body.tri_begin; t < body.tri_end; ++t) {
                const auto& n = m.tri_nodes[static_cast<size_t>(t)];
                const auto p = [&](int k) { return m.node_x0[static_cast<size_t>(n[k])]; };
                if (keys.count(key(p(0), p(1), p(2)))) out.insert(out.end(), n.begin(), n.end());
            }
        }
    }

    /// nodes (one model node per mesh vertex, from the entry's node map), sorted and unique,
    /// plus every other node copy of the same vertices: with fracture a vertex has one copy per
    /// run of its triangle fan between jointed edges (Model::node_vertex maps each copy to the
    /// smallest), and a support or probe on the vertex must act on all of them.
    static void add_node_copies(const Model* m, const BodyEntry& entry,
                                std::vector<NodeId>& nodes) {
        if (m != nullptr && !m->node_vertex.empty() &&
            m->node_vertex.size() == static_cast<size_t>(m->num_nodes())) {
            std::vector<NodeId> reps;
            for (const NodeId n : nodes)
                reps.push_back(m->node_vertex[static_cast<size_t>(n)]);
            std::sort(reps.begin(), reps.end());
            for (BodyId b = entry.body_begin; b < entry.body_end; ++b) {
                const Body& body = m->bodies[static_cast<size_t>(b)];
                if (!body.fracture) continue;
                for (NodeId k = body.node_begin; k < body.node_end; ++k) {
                    if (std::binary_search(reps.begin(), reps.end(),
                                           m->node_vertex[static_cast<size_t>(k)])) {
                        nodes.push_back(k);
                    }
                }
            }
        }
        std::sort(nodes.begin(), nodes.end());
        nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    }

    // ---- [[probe]] (after finalize_model: nearest nodes need the built model) ---------------
    void read_probes(const toml::table& root, Scenario& sc) {
        const Model& m = sc.model;
        const auto tables = table_array(src_, root, "probe", "probe");
        std::map<std::string, int> first_line;
        for (size_t i = 0; i < tables.size(); ++i) {
            Fields f(src_, *tables[i], fmt::format("[[probe]] #{}", i + 1),
                     fmt::format("probe[{}]", i), {"name", "position", "body", "group"});
            ProbeSpec p;
            p.name = f.string("name", std::nullopt);
            if (p.name.empty()) {
                f.fail(*f.node("name"), "name", "probe name must not be empty");
            }
            f.set_context(fmt::format("probe \"{}\"", p.name));
            if (const auto it = first_line.find(p.name); it != first_line.end()) {
                f.fail(*f.node("name"), "name",
                       fmt::format("duplicate probe name \"{}\" (first defined on line {})", p.name,
                                   it->second));
            }
            first_line[p.name] = f.location("name").line;
            if (f.has("position") && f.has("group")) {
                f.fail(*f.node("group"), "group",
                       "give either 'position' (the nearest node) or 'group' (a physical group "
                       "of the body's mesh), not both");
            }
            if (f.has("group") && !f.has("body")) {
                f.fail(*f.node("group"), "group",
                       "'group' needs 'body': the [[body]] whose mesh has the group");
            }
            if (!f.has("position") && !f.has("body")) {
                f.fail_table(
                    "give 'position' = [x, y] in m (the nearest node), 'body' (a whole body "
                    "entry) or 'body' and 'group' (a physical group of its mesh)");
            }
            const int entry = f.has("body") ? body_index(f, "body") : -1;
            if (f.has("position")) {
                p.kind = ProbeSpec::Kind::Node;
                p.position = f.vec2("position", std::nullopt, "m");
                NodeId node = kNone;
                TriId tri = kNone;
                locate_probe(m, p.position, entry, node, tri);
                p.nodes = {node};
                p.tris = {tri};
            } else if (f.has("group")) {
                p.kind = ProbeSpec::Kind::Group;
                const std::string group = f.string("group", std::nullopt);
                p.nodes = group_nodes(f, bodies_[static_cast<size_t>(entry)], group);
                p.tris = probe_triangles(m, p.nodes);
            } else {
                p.kind = ProbeSpec::Kind::Body;
                for (const Body& b : m.bodies) {
                    if (b.group != entry) continue;
                    for (NodeId n = b.node_begin; n < b.node_end; ++n)
                        p.nodes.push_back(n);
                    for (TriId t = b.tri_begin; t < b.tri_end; ++t)
                        p.tris.push_back(t);
                }
            }
            sc.run.output.probes.push_back(std::move(p));
        }
    }

    // ---- [[kick]] --------------------------------------------------------------------------
    void read_kicks(const toml::table& root, Model& m) {
        const auto tables = table_array(src_, root, "kick", "kick");
        for (size_t i = 0; i < tables.size(); ++i) {
            Fields f(src_, *tables[i], fmt::format("[[kick]] #{}", i + 1),
                     fmt::format("kick[{}]", i), {"body", "time", "velocity", "components"});
            VelocityKick k;
            k.group = body_index(f, "body");
            if (bodies_[static_cast<size_t>(k.group)].fixed) {
                f.fail(*f.node("body"), "body",
                       fmt::format("body \"{}\" is fixed (fixed = true): a kick would not move "
                                   "it; expected a body that is not fixed",
                                   bodies_[static_cast<size_t>(k.group)].name));
            }
            f.set_context(
                fmt::format("kick of body \"{}\"", bodies_[static_cast<size_t>(k.group)].name));
            k.time = f.real("time", std::nullopt, "s", Bounds::non_negative());
            kick_entries_.push_back({f.location("time"), f.full_key("time"), f.context(), k.time});
            k.velocity = f.vec2("velocity", std::nullopt, "m/s");
            f.components("components", std::pair{true, true}, k.has_x, k.has_y);
            m.kicks.push_back(k);
        }
    }

    // ---- [damping] -------------------------------------------------------------------------
    void read_damping(const toml::table& root, Model& m) {
        const toml::table* t = sub_table(src_, root, "damping");
        if (!t) {
            return;
        }
        Fields f(src_, *t, "[damping]", "damping", {"mass_proportional", "until"});
        m.mass_damping.coefficient =
            f.real("mass_proportional", std::nullopt, "1/s", Bounds::non_negative());
        m.mass_damping.until = f.real("until", std::nullopt, "s", Bounds::non_negative());
    }

    // ---- [contact] -------------------------------------------------------------------------
    /// Law keys of [contact] or of a [[contact.pair]], on top of base.
    ContactParams read_law(const Fields& f, ContactParams p) const {
        if (f.has("penalty")) {
            p.penalty = f.real("penalty", std::nullopt, "Pa", Bounds::positive());
        }
        p.alpha = f.real("alpha", p.alpha, "", Bounds::at_least(1.0));
        p.beta = f.real("beta", p.beta, "", Bounds::at_least(1.0));
        if (p.beta < p.alpha) {
            const char* key = f.has("beta") ? "beta" : "alpha";
            f.fail(*f.node(key), key,
                   fmt::format("beta must be >= alpha (unloading at least as stiff as "
                               "loading), got alpha = {}, beta = {}",
                               p.alpha, p.beta));
        }
        p.length_scale = f.real("length_scale", p.length_scale, "m", Bounds::positive());
        p.damping = f.real("damping", p.damping, "N s/m^2", Bounds::non_negative());
        p.damp_normal_only = f.boolean("damp_normal_only", p.damp_normal_only);
        p.friction = f.real("friction", p.friction, "", Bounds::non_negative());
        if (f.has("tangential_penalty")) {
            p.tangential_penalty =
                f.real("tangential_penalty", std::nullopt, "Pa", Bounds::positive());
        }
        if (f.has("unloading")) {
            p.unloading =
                f.choice("unloading", std::nullopt, {"continuous", "literal"}) == "continuous"
                    ? UnloadingLaw::Continuous
                    : UnloadingLaw::Literal;
        }
        return p;
    }

    /// Without [contact]: smooth contact with the documented defaults as soon as two bodies can
    /// meet (at least two bodies, at least one not fixed); none otherwise (issue #12 item 11: a
    /// disk fell through a slab because contact was off unless written).
    void read_contact(const toml::table& root, Scenario& sc) {
        Model& m = sc.model;
        const toml::table* t = sub_table(src_, root, "contact");
        if (!t) {
            const bool movable = std::any_of(m.bodies.begin(), m.bodies.end(),
                                             [](const Body& b) { return !b.fixed; });
            const bool on = m.bodies.size() >= 2 && movable;
            m.contact.algorithm = on ? ContactAlgorithm::Smooth : ContactAlgorithm::None;
            sc.contact_default = true;
            return;
        }
        std::vector<std::string> keys = {"algorithm",    "buffer",         "two_way",
                                         "scaling",      "pair",           "composite_special_case",
                                         "edge_targets", "initial_overlap"};
        keys.insert(keys.end(), kContactLawKeys.begin(), kContactLawKeys.end());
        Fields f(src_, *t, "[contact]", "contact", keys);
        ContactModel& c = m.contact;
        const std::string alg = f.choice("algorithm", std::nullopt,
                                         {"none", "smooth", "legacy-triangle", "legacy-boundary"});
        c.algorithm = alg == "none"              ? ContactAlgorithm::None
                      : alg == "smooth"          ? ContactAlgorithm::Smooth
                      : alg == "legacy-triangle" ? ContactAlgorithm::LegacyTriangle
                                                 : ContactAlgorithm::LegacyBoundary;
        c.params = read_law(f, ContactParams{});
        if (f.has("buffer")) {
            c.buffer = f.real("buffer", std::nullopt, "m", Bounds::positive());
        }
        c.two_way = f.boolean("two_way", true);
        // midpoints of the boundary edges as targets too (docs/theory.md §6.12)
        c.edge_targets = f.boolean("edge_targets", true);
        // bodies overlapping at t = 0: refused at load unless a prestress is intended (§6.14)
        if (f.has("initial_overlap")) {
            c.allow_initial_overlap =
                f.choice("initial_overlap", std::nullopt, {"error", "allow"}) == "allow";
        }
        // target force scale: paper eq. 19 (mass) or tributary length (docs/theory.md §6.11)
        if (f.has("scaling")) {
            c.scaling = f.choice("scaling", std::nullopt, {"mass", "length"}) == "mass"
                            ? ContactScaling::Mass
                            : ContactScaling::Length;
        }
        // 6-node composite elements with 2 or 3 boundary edges: paper §2.4 option (b) "fan" or
        // option (a) "split" (docs/theory.md §6.1.1)
        if (f.has("composite_special_case")) {
            c.composite_special_case =
                f.choice("composite_special_case", std::nullopt, {"fan", "split"}) == "fan"
                    ? CompositeSpecialCase::Fan
                    : CompositeSpecialCase::Split;
        }

        // per material pair overrides
        const auto pairs = table_array(src_, *t, "pair", "contact.pair");
        if (pairs.empty()) {
            return;
        }
        // line of the pair entry that set each (ordered) pair; only the pairs that are set
        std::map<std::pair<int, int>, int> set_by;
        std::vector<std::string> pair_keys = {"materials"};
        pair_keys.insert(pair_keys.end(), kContactLawKeys.begin(), kContactLawKeys.end());
        for (size_t i = 0; i < pairs.size(); ++i) {
            Fields p(src_, *pairs[i], fmt::format("[[contact.pair]] #{}", i + 1),
                     fmt::format("contact.pair[{}]", i), pair_keys);
            const toml::node* mats = p.node("materials");
            if (!mats) {
                p.fail_missing("materials", "two material names, e.g. [\"steel\", \"rock\"]");
            }
            const toml::array* a = mats->as_array();
            if (!a || a->size() != 2 || !a->get(0)->is_string() || !a->get(1)->is_string()) {
                p.fail(*mats, "materials",
                       fmt::format("materials must be two material names, e.g. [\"steel\", "
                                   "\"rock\"], got {}",
                                   io::describe_value(*mats)));
            }
            int idx[2];
            for (int k = 0; k < 2; ++k) {
                const std::string name = a->get(static_cast<size_t>(k))->as_string()->get();
                const auto it = std::find(material_names_.begin(), material_names_.end(), name);
                if (it == material_names_.end()) {
                    const std::string guess = io::closest(name, material_names_);
                    p.fail(*a->get(static_cast<size_t>(k)), "materials",
                           fmt::format(
                               "unknown material \"{}\"; defined materials: {}{}", name,
                               io::quoted_list(material_names_),
                               guess.empty() ? "" : fmt::format("; did you mean \"{}\"?", guess)));
                }
                idx[k] = static_cast<int>(it - material_names_.begin());
            }
            p.set_context(fmt::format("contact pair (\"{}\", \"{}\")", material_names_[idx[0]],
                                      material_names_[idx[1]]));
            if (const auto it = set_by.find({idx[0], idx[1]}); it != set_by.end()) {
                p.fail(*mats, "materials",
                       fmt::format("this material pair is already set on line {}", it->second));
            }
            const ContactParams law = read_law(p, c.params);
            c.pair_overrides.push_back({idx[0], idx[1], law});
            if (idx[1] != idx[0]) {
                c.pair_overrides.push_back({idx[1], idx[0], law});
            }
            set_by[{idx[0], idx[1]}] = set_by[{idx[1], idx[0]}] = p.location("materials").line;
        }
    }

    // ---- time step -------------------------------------------------------------------------
    void choose_dt(Scenario& sc) {
        RunSettings& run = sc.run;
        const Model& m = sc.model;
        TriId tri = kNone;
        const Real stable = stable_time_step(m, topo_, &tri);
        run.stable_dt = stable;
        run.limiting_tri = tri;
        // the cohesive joints' own bound (theory eq. 9.16); +inf without joints
        const Real joint_dt = joint_critical_dt(m.joints, m.node_mass);
        const std::string line = src_.line(dt_loc_.line);
        std::string limit;  // what sets the stable limit, for messages
        if (tri != kNone) {
            const size_t t = static_cast<size_t>(tri);
            const Material& mat = m.materials[static_cast<size_t>(m.tri_material[t])];
            const auto& n = m.tri_nodes[t];
            const Vec2 c = (m.node_x0[n[0]] + m.node_x0[n[1]] + m.node_x0[n[2]]) / 3.0;
            limit = fmt::format(
                "triangle {} at ({:.4g}, {:.4g}) of body \"{}\", material \"{}\" (youngs_modulus "
                "= {:g} Pa, density = {:g} kg/m^3)",
                tri, c.x, c.y, m.bodies[static_cast<size_t>(m.tri_body[t])].name, mat.name,
                mat.youngs_modulus, mat.density);
        } else if (joint_dt < contact_stable_dt(m, topo_)) {
            Real p = 0;
            for (const Material& mat : m.materials) {
                if (mat.has_fracture) {
                    p = std::max({p, mat.fracture.penalty, mat.fracture.shear_penalty});
                }
            }
            limit = fmt::format(
                "the cohesive joints (largest penalty p = {:g} Pa; docs/theory.md "
                "eq. 9.16)",
                p);
        } else {
            Real kn = m.contact.params.penalty;
            for (const ContactParams& p : m.contact.resolved) {
                kn = std::max(kn, p.penalty);
            }
            limit = fmt::format("the contact penalty (largest k_n = {:g} Pa)", kn);
        }
        if (run.dt_auto) {
            if (!std::isfinite(stable)) {
                throw InputError(dt_loc_, "simulation.dt",
                                 "[simulation]: dt = \"auto\" needs a stable time step limit, but "
                                 "no body moves and contact is off; give dt in s",
                                 line);
            }
            if (run.dt_fraction > 0) {
                run.dt = run.dt_fraction * stable;
            } else {
                // default: 0.5 of the element limit (eq. 5.3) but 0.2 of the contact limit
                // (eq. 6.15): the linear bound of the contact is right (0.90 of 2 / omega_max
                // measured by power iteration), but a penalty spring that switches on and off
                // gains energy at omega_max dt ~ 0.9 (docs/theory.md §6.9). With joints the
                // element limit is that of elements and joints together, which act on the
                // same nodes (Weyl: 1/dt^2 adds up, eqs. 6.17, 9.16)
                const Real contact = contact_stable_dt(m, topo_);
                Real element = element_stable_time_step(m);
                if (std::isfinite(joint_dt)) {
                    element = std::isfinite(element) ? 1.0 / std::sqrt(1.0 / (element * element) +
                                                                       1.0 / (joint_dt * joint_dt))
                                                     : joint_dt;
                }
                run.dt =
                    std::min(kDefaultElementFraction * element, kDefaultContactFraction * contact);
                run.dt_fraction = run.dt / stable;
            }
            run.dt_cause =
                fmt::format("dt = \"auto\" = {:.3g} x the stable limit {:.4g} s set by {}",
                            run.dt_fraction, stable, limit);
            return;
        }
        run.dt_cause = fmt::format("dt = {:g} s is given in [simulation]", run.dt);
        if (run.dt > stable) {
            std::string what;
            if (tri != kNone) {
                // model ids are renumbered; the centroid lets the user find the element
                const size_t t = static_cast<size_t>(tri);
                const Body& b = m.bodies[static_cast<size_t>(m.tri_body[t])];
                const auto& n = m.tri_nodes[t];
                const Vec2 c = (m.node_x0[n[0]] + m.node_x0[n[1]] + m.node_x0[n[2]]) / 3.0;
                what = fmt::format(
                    "triangle {} at ({:.4g}, {:.4g}) of body \"{}\", material "
                    "\"{}\"",
                    tri, c.x, c.y, b.name,
                    m.materials[static_cast<size_t>(m.tri_material[t])].name);
            } else if (joint_dt < contact_stable_dt(m, topo_)) {
                what = "cohesive joint penalty";
            } else {
                what = "contact penalty";
            }
            throw InputError(dt_loc_, "simulation.dt",
                             fmt::format("[simulation]: dt = {:.4g} s exceeds the stable limit "
                                         "{:.4g} s ({}); use dt <= {:.3g} or dt = \"auto\"",
                                         run.dt, stable, what, round_down_3(stable)),
                             line);
        }
    }

    // ---- times of kicks and supports against end_time, output interval against dt ----------
    void check_times(Scenario& sc) {
        const RunSettings& run = sc.run;
        for (const KickEntry& k : kick_entries_) {
            if (k.time >= run.end_time) {
                throw InputError(k.loc, k.key,
                                 fmt::format("{}: time = {:g} s is not before end_time = {:g} s: "
                                             "the kick would never act; expected a time < "
                                             "end_time (or a longer end_time)",
                                             k.context, k.time, run.end_time),
                                 src_.line(k.loc.line));
            }
        }
        // a support faster than the P-wave speed of its material: the elements next to it
        // invert within a few steps whatever dt (theory eq. 5.3: the boundary moves more than
        // half an element per step at dt = 0.5 h / c_p); without this the run fails blaming dt
        for (const BoundarySpeed& b : boundary_speeds_) {
            const BodyEntry& entry = bodies_[b.body];
            const Material& mat = sc.model.materials[static_cast<size_t>(
                sc.model.bodies[static_cast<size_t>(sc.model.node_body[first_node(entry)])]
                    .material)];
            const Real cp = std::sqrt((mat.lambda + 2.0 * mat.mu) / mat.density);
            if (b.speed >= cp) {
                throw InputError(
                    b.loc, b.key,
                    fmt::format("{}: the prescribed speed {:g} m/s is not below the P-wave speed "
                                "c_p = {:.4g} m/s of material \"{}\": the elements next to the "
                                "boundary invert within a few steps whatever dt; expected a speed "
                                "< c_p (quasi-static loading: < 0.01 c_p); check the units",
                                b.context, b.speed, cp, mat.name),
                    src_.line(b.loc.line));
            }
        }
        if (run.output.interval > 0 && run.output.interval < run.dt) {
            sc.warnings.push_back(fmt::format(
                "{}:{}:{}: warning: [output]: interval = {:g} s is shorter than the time step dt "
                "= {:.4g} s: a frame is written after every step ({:.0f} frames); use interval "
                ">= dt, or omit it for 100 frames",
                src_.name, interval_loc_.line, interval_loc_.column, run.output.interval, run.dt,
                planned_steps(run)));
        }
    }

    struct BoundarySpeed {
        SourceLocation loc;
        std::string key;
        std::string context;
        Real speed = 0;
        size_t body = 0;  ///< index into bodies_
    };

    struct KickEntry {
        SourceLocation loc;
        std::string key;
        std::string context;
        Real time = 0;
    };

    const SourceText& src_;
    std::string base_dir_;
    const MeshStore* memory_ = nullptr;  ///< meshes given in memory (may be null)
    const MeshReader& read_meshes_;      ///< reads a mesh file (read_mesh when empty)
    SourceLocation dt_loc_;
    SourceLocation end_time_loc_;
    SourceLocation interval_loc_;
    std::vector<KickEntry> kick_entries_;
    std::vector<BoundarySpeed> boundary_speeds_;

    // load-time contact geometry (docs/theory.md §6.13-6.14): bodies overlapping at t = 0 are
    // an error at the [[body]] entry of the body that lies inside the other (unless
    // [contact] initial_overlap = "allow"); thin contact layers are a warning
    void check_contact_geometry(Scenario& sc) {
        const Model& m = sc.model;
        if (m.contact.algorithm == ContactAlgorithm::None) return;
        const ContactTopology& topo = m.joints.nodes.empty() ? topo_ : topo_welded_;
        // one warning per [[body]] entry (an entry with pieces = "separate" can make thousands of
        // bodies): its worst body (largest near_dist / dist), and how many others share the issue
        const std::vector<ThinLayer> thin = find_thin_layers(m, topo);
        std::vector<size_t> worst(bodies_.size(), thin.size());
        std::vector<int32_t> affected(bodies_.size(), 0);
        for (size_t k = 0; k < thin.size(); ++k) {
            const auto g = static_cast<size_t>(m.bodies[thin[k].body].group);
            ++affected[g];
            if (worst[g] == thin.size() ||
                thin[k].near_dist / thin[k].dist > thin[worst[g]].near_dist / thin[worst[g]].dist) {
                worst[g] = k;
            }
        }
        for (size_t g = 0; g < bodies_.size(); ++g) {
            if (worst[g] == thin.size()) continue;
            // "file:line:column: warning: ..." at the body's [[body]] entry
            const toml::table* e = bodies_[g].table;
            std::string more;
            if (affected[g] > 1) {
                more = fmt::format(" ({} other bodies of this [[body]] entry are thin too)",
                                   affected[g] - 1);
            }
            sc.warnings.push_back(fmt::format("{}:{}:{}: {}{}", src_.name, e->source().begin.line,
                                              e->source().begin.column,
                                              thin_layer_warning(m, topo, thin[worst[g]]), more));
        }
        if (m.contact.allow_initial_overlap) return;
        const InitialOverlap o = find_initial_overlap(m, topo);
        if (!o.found) return;
        const Body& a = m.bodies[o.body];
        const Body& b = m.bodies[o.other];
        const ContactTopology& cm = topo;
        std::string point;
        switch (o.point) {
            case InitialOverlap::Point::Node:
                point = fmt::format("node {}", o.node);
                break;
            case InitialOverlap::Point::EdgeMidpoint:
                point = fmt::format("the midpoint of boundary edge {}-{} (node {})",
                                    cm.boundary_edges[static_cast<size_t>(o.edge)][0],
                                    cm.boundary_edges[static_cast<size_t>(o.edge)][1], o.node);
                break;
            case InitialOverlap::Point::Centroid:
                point = fmt::format("the centroid of boundary element {} (node {})", o.tri, o.node);
                break;
        }
        const toml::table* entry = bodies_[static_cast<size_t>(a.group)].table;
        const SourceLocation loc{src_.name, static_cast<int>(entry->source().begin.line),
                                 static_cast<int>(entry->source().begin.column)};
        throw InputError(
            loc, "contact.initial_overlap",
            fmt::format("bodies {} \"{}\" and {} \"{}\" overlap at t = 0: {} of body {} at "
                        "({:.6g}, {:.6g}) m lies {:.3g} m inside body {} (touching counts up to "
                        "{:.3g} m = 1e-6 x the smallest element altitude); the contact penalty "
                        "would push them apart at once with energy that is not in the balance. "
                        "Move the meshes apart, or set [contact] initial_overlap = \"allow\" if "
                        "the prestress is intended",
                        o.body, a.name, o.other, b.name, point, o.body, o.where.x, o.where.y,
                        o.depth, o.other, o.tolerance),
            src_.line(loc.line));
    }
    const Model* m_ = nullptr;  ///< the model being built (for group_nodes)
    std::vector<std::string> material_names_;
    /// [material.fracture] table of each material (nullptr: none), for the checks that need
    /// the joint lengths of the bodies
    std::vector<const toml::table*> fracture_tables_;
    /// per material: the longest jointed mesh edge of its bodies [m] and the body it is in
    std::map<int, std::pair<Real, std::string>> longest_joint_;
    std::vector<BodyEntry> bodies_;
    std::unordered_map<std::string, size_t> body_by_name_;  ///< name -> index into bodies_
    std::vector<LoadedMesh> meshes_;
    ContactTopology topo_;         ///< topology of the loaded bodies, unwelded (stable dt)
    ContactTopology topo_welded_;  ///< with joints: the topology at t = 0 (geometry checks)
};

}  // namespace

Real planned_steps(const RunSettings& run) {
    return std::ceil(run.end_time / run.dt - 1e-9);
}

void check_step_count(const RunSettings& run, const SourceLocation& where, const std::string& key,
                      const std::string& source_line) {
    const Real steps = planned_steps(run);
    if (!(run.end_time >= run.dt)) {
        throw InputError(
            where, key,
            fmt::format("end_time = {:g} s is shorter than one time step ({}): the "
                        "run would take {:g} step(s); expected end_time >= dt = {:.4g} "
                        "s; check the units of end_time, youngs_modulus and density",
                        run.end_time, run.dt_cause, steps > 0 ? steps : 0.0, run.dt),
            source_line);
    }
    if (!(steps <= run.max_steps)) {
        throw InputError(
            where, key,
            fmt::format("end_time = {:g} s needs {:.3g} steps of dt = {:.4g} s, more than "
                        "[simulation] max_steps = {:g}; {}; check the units of end_time, dt, "
                        "youngs_modulus, density and the contact penalty, or raise max_steps if "
                        "this run is intended",
                        run.end_time, steps, run.dt, run.max_steps, run.dt_cause),
            source_line);
    }
}

Scenario load_scenario_from_string(const std::string& text, const std::string& name,
                                   const std::string& base_dir, const MeshStore* meshes,
                                   const MeshReader& read_meshes) {
    const SourceText src(name, text);
    toml::table root;
    try {
        root = toml::parse(text, std::string_view(name));
    } catch (const toml::parse_error& e) {
        const auto& b = e.source().begin;
        const int line = static_cast<int>(b.line), col = static_cast<int>(b.column);
        throw InputError({name, line, col}, "",
                         fmt::format("TOML syntax error: {}", e.description()), src.line(line));
    }
    ScenarioReader reader(src, base_dir, meshes, read_meshes);
    return reader.read(root);
}

Scenario load_scenario(const std::string& path, const MeshReader& read_meshes) {
    std::error_code dir_ec;
    if (fs::is_directory(path, dir_ec)) {
        throw InputError(
            {path, 0, 0}, "",
            fmt::format("cannot read scenario file '{}': it is a directory; expected "
                        "a TOML scenario file (e.g. {})",
                        path, (fs::path(path) / "scenario.toml").lexically_normal().string()));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        std::error_code ec;
        const bool exists = fs::exists(path, ec);
        throw InputError({path, 0, 0}, "",
                         fmt::format("cannot open scenario file '{}': {}", path,
                                     exists ? "permission denied or not a file" : "No such file"));
    }
    std::ostringstream text;
    text << in.rdbuf();
    std::string base = fs::path(path).parent_path().string();
    if (base.empty()) {
        base = ".";
    }
    return load_scenario_from_string(text.str(), path, base, nullptr, read_meshes);
}

}  // namespace fdem
