// Binary checkpoints (checkpoint.hpp): serialise State + run bookkeeping, refuse foreign files.
#include "io/checkpoint.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <type_traits>

#include <fmt/format.h>

#include "fdem/error.hpp"
#include "fdem/simulate.hpp"
#include "fdem/version.hpp"
#include "fracture/joints.hpp"
#include "integrate/fracture_update.hpp"
#include "io/atomic_file.hpp"

namespace fdem {

namespace {

constexpr char kMagic[8] = {'F', 'D', 'E', 'M', 'C', 'K', 'P', 'T'};
constexpr uint32_t kEndianMarker = 0x01020304u;
constexpr uint64_t kFnvOffset = 1469598103934665603ull;
constexpr uint64_t kFnvPrime = 1099511628211ull;

uint64_t fnv1a(uint64_t h, const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) {
        h ^= p[i];
        h *= kFnvPrime;
    }
    return h;
}

// ---- sinks: the same field-by-field code feeds the file buffer and the model hash ----------

/// Appends bytes to a buffer.
struct Writer {
    std::vector<unsigned char> buf;
    void bytes(const void* p, size_t n) {
        const auto* c = static_cast<const unsigned char*>(p);
        buf.insert(buf.end(), c, c + n);
    }
};

/// Feeds bytes to FNV-1a.
struct Hasher {
    uint64_t h = kFnvOffset;
    void bytes(const void* p, size_t n) { h = fnv1a(h, p, n); }
};

template <class Sink, class T>
void put(Sink& o, const T& v) {
    if constexpr (std::is_same_v<T, bool>) {
        const uint8_t b = v ? 1 : 0;
        o.bytes(&b, 1);
    } else if constexpr (std::is_enum_v<T>) {
        const int32_t e = static_cast<int32_t>(v);
        o.bytes(&e, sizeof e);
    } else if constexpr (std::is_arithmetic_v<T>) {
        o.bytes(&v, sizeof v);
    } else if constexpr (std::is_same_v<T, Vec2>) {
        put(o, v.x);
        put(o, v.y);
    } else if constexpr (std::is_same_v<T, Mat2>) {
        put(o, v.xx);
        put(o, v.xy);
        put(o, v.yx);
        put(o, v.yy);
    } else if constexpr (std::is_same_v<T, std::string>) {
        put(o, static_cast<uint64_t>(v.size()));
        o.bytes(v.data(), v.size());
    } else {
        static_assert(sizeof(T) == 0, "no serialisation for this type");
    }
}

template <class Sink, class T, size_t N>
void put(Sink& o, const std::array<T, N>& a) {
    for (const T& e : a)
        put(o, e);
}

template <class Sink, class T>
void put(Sink& o, const std::vector<T>& a) {
    put(o, static_cast<uint64_t>(a.size()));
    for (const T& e : a)
        put(o, e);
}

template <class Sink>
void put(Sink& o, const PairHistory& h) {
    put(o, h.s);
    put(o, h.d_max);
    put(o, h.d_prev);
    put(o, h.stored);
    put(o, h.f_damp);
    put(o, h.depth_ratio);
    put(o, h.d0);
    put(o, h.unloading);
    put(o, h.sub);
}

template <class Sink>
void put(Sink& o, const ActiveContact& a) {
    put(o, a.node);
    put(o, a.body);
    put(o, a.h);
}

template <class Sink>
void put(Sink& o, const ContactParams& p) {
    put(o, p.penalty);
    put(o, p.alpha);
    put(o, p.beta);
    put(o, p.length_scale);
    put(o, p.damping);
    put(o, p.damp_normal_only);
    put(o, p.friction);
    put(o, p.tangential_penalty);
    put(o, p.unloading);
}

template <class Sink>
void put(Sink& o, const JointLaw& L) {
    for (const Real r :
         {L.ft, L.c, L.tan_phi, L.p, L.ps, L.GI, L.GII, L.Iz, L.half_p_over_ft, L.half_ps})
        put(o, r);
    put(o, L.curve);
    put(o, L.length_rule);
    put(o, L.failure_points);
    // since format 12, only when not the default (the model hashes of older scenarios unchanged)
    if (L.mixed != MixedMode::Independent) put(o, L.mixed);
}

template <class Sink>
void put(Sink& o, const Energy& e) {
    put(o, e.time);
    put(o, e.kinetic);
    put(o, e.strain);
    put(o, e.contact);
    put(o, e.work_gravity);
    put(o, e.work_external);
    put(o, e.work_external_pending);
    put(o, e.dissipated_viscous);
    put(o, e.dissipated_contact);
}

// an exact sum (theory §4.4): its normalised words, so equal sums write equal bytes
template <class Sink>
void put(Sink& o, const ExactSum& e) {
    ExactSum n = e;
    n.normalise();
    for (int k = 0; k < ExactSum::kWords; ++k)
        put(o, n.words()[k]);
    put(o, n.has_special());
    put(o, n.special());
}

// ---- the payload: one function per direction, fields in the same order --------------------

template <class Sink>
void put_state(Sink& o, const State& s) {
    put(o, s.step);
    put(o, s.time);
    put(o, s.dt);
    put(o, s.x);
    put(o, s.v);
    put(o, s.f);
    put(o, s.f_contact);
    put(o, s.energy);
    put(o, s.energy.joint);     // since format 7 (not in put(Energy): state_hash() hashes
    put(o, s.energy.fracture);  // them only for models with joints)
    put(o, s.next_kick);
    put(o, s.need_energy);
    put(o, s.bc_velocity);  // controls (since format 6)
    put(o, s.bc_enabled);
    // joint history (since format 8; empty arrays without joints); node_sector, tri_fragment
    // and the topology are rebuilt from it on restore
    const JointState& js = s.joints;
    put(o, js.d_max);
    put(o, js.status);
    put(o, js.mode_bits);
    put(o, js.mode);
    put(o, js.break_step);
    put(o, js.work);
    put(o, js.f_prev);
    put(o, js.d_prev);
    put(o, js.dn_max);  // since format 12 (empty unless a law is MixedMode::Proportional)
    put(o, js.ds_max);
    put(o, js.an_min);  // since format 13 (eq. 9.32; sized with dn_max)
    put(o, js.as_min);
    put(o, js.total_work);
    put(o, js.total_work_sum);  // since format 11, as energy_sums
    put(o, s.energy_sums.work_external);
    put(o, s.energy_sums.dissipated_viscous);
    put(o, s.energy_sums.dissipated_contact);
    // scratch_bc_v, scratch_sums: rewritten before being read in every step (not saved)

    const ContactState& c = s.contact;
    put(o, c.active_contacts);
    put(o, c.deep_penetrations);
    put(o, c.lost_inside);
    // lost_node, lost_body, lost_depth_ratio: reset and rewritten by every step before
    // check_run reads them (not saved)
    put(o, c.max_depth_ratio);
    put(o, c.total_deep_penetrations);
    put(o, c.total_lost_inside);
    put(o, c.max_depth_ratio_ever);
    put(o, c.rebuilds);
    put(o, c.skin_used);
    put(o, c.need_rebuild);
    put(o, c.cand.node);
    put(o, c.cand.body);
    put(o, c.cand.begin);
    put(o, c.cand.tri);
    // broad-phase grid: kept although it is rebuilt with the candidates, so that a future
    // incremental broad phase cannot silently lose information across a restart
    put(o, c.broad.tri_center);
    put(o, c.broad.tri_radius);
    put(o, c.broad.tri_cell);
    put(o, c.broad.cell_start);
    put(o, c.broad.cell_items);
    // query: the grid's fill cursor, then the hit list of the last target queried: scratch,
    // and in a distributed run the last target is each process's own; zeros of its size, so
    // that the file is the same for every process count. (in_contact: narrow-phase scratch;
    // broad.part, part_hits: the per-thread lists of the queries; not saved.)
    put(o, std::vector<int32_t>(c.broad.query.size(), 0));
    put(o, c.active);
    put(o, c.active_next);
    put(o, c.xv);
    put(o, c.vv);
    // pair_out, apply_part: per-step scratch (not saved)

    // baseline A: couples with their friction history and the Verlet skin
    const LegacyTriangleState& l = c.legacy;
    put(o, static_cast<uint64_t>(l.couples.size()));
    for (const LegacyCouple& cp : l.couples) {
        put(o, cp.a);
        put(o, cp.b);
        for (Real sl : cp.slide)
            put(o, sl);
    }
    put(o, l.skin_used);
    put(o, l.need_rebuild);
    put(o, l.rebuilds);
    put(o, l.active);
    // l.next, grid scratch and per-couple results: rewritten before being read (not saved)
}

template <class Sink>
void put_progress(Sink& o, const RunProgress& p) {
    put(o, p.frame);
    put(o, p.next_output);
    put(o, p.energy.has_reference);
    put(o, p.energy.e0);
    put(o, p.energy.scale);
    put(o, p.energy.max_error);
    put(o, static_cast<uint64_t>(p.frames.size()));
    for (const auto& [t, file] : p.frames) {
        put(o, t);
        put(o, file);
    }
    put(o, p.impulses.contact);
    put(o, p.impulses.reaction);
    put(o, p.impulses.time);
}

/// Bounds-checked reader over the file bytes; every failure is an InputError naming the file.
class Reader {
public:
    Reader(const std::string& path, const std::vector<unsigned char>& buf, size_t end)
        : path_(path), buf_(buf), end_(end) {}

    [[noreturn]] void fail(const std::string& what) const {
        throw InputError({path_, 0, 0}, "--restart",
                         fmt::format("checkpoint '{}' is unusable: {}", path_, what));
    }

    void bytes(void* p, size_t n) {
        if (n > end_ - pos_) fail("the file is truncated");
        std::memcpy(p, buf_.data() + pos_, n);
        pos_ += n;
    }
    size_t remaining() const { return end_ - pos_; }

    template <class T>
    void get(T& v) {
        if constexpr (std::is_same_v<T, bool>) {
            uint8_t b = 0;
            bytes(&b, 1);
            if (b > 1) fail("a flag is neither 0 nor 1 (corrupt file)");
            v = b != 0;
        } else if constexpr (std::is_enum_v<T>) {
            int32_t e = 0;  // written as int32 (put)
            bytes(&e, sizeof e);
            if (e < 0 || e > 255) fail("an enum value is out of range (corrupt file)");
            v = static_cast<T>(e);
        } else if constexpr (std::is_arithmetic_v<T>) {
            bytes(&v, sizeof v);
        } else if constexpr (std::is_same_v<T, std::array<Real, 3>> ||
                             std::is_same_v<T, std::array<Real, 4>>) {
            for (Real& e : v)
                get(e);
        } else if constexpr (std::is_same_v<T, Vec2>) {
            get(v.x);
            get(v.y);
        } else if constexpr (std::is_same_v<T, std::string>) {
            const uint64_t n = count(1);
            v.resize(n);
            bytes(v.data(), n);
        } else if constexpr (std::is_same_v<T, PairHistory>) {
            get(v.s);
            get(v.d_max);
            get(v.d_prev);
            get(v.stored);
            get(v.f_damp);
            get(v.depth_ratio);
            get(v.d0);
            get(v.unloading);
            get(v.sub);
        } else if constexpr (std::is_same_v<T, ActiveContact>) {
            get(v.node);
            get(v.body);
            get(v.h);
        } else if constexpr (std::is_same_v<T, Energy>) {
            get(v.time);
            get(v.kinetic);
            get(v.strain);
            get(v.contact);
            get(v.work_gravity);
            get(v.work_external);
            get(v.work_external_pending);
            get(v.dissipated_viscous);
            get(v.dissipated_contact);
        } else {
            static_assert(sizeof(T) == 0, "no deserialisation for this type");
        }
    }

    /// An element count, checked against the bytes left (min_size bytes per element).
    uint64_t count(size_t min_size) {
        uint64_t n = 0;
        get(n);
        if (min_size > 0 && n > remaining() / min_size) fail("an array length is corrupt");
        return n;
    }

    /// An exact sum (put(ExactSum)): 67 words, the flag, the non-finite part.
    void get(ExactSum& e) {
        int64_t w[ExactSum::kWords];
        for (int64_t& x : w)
            get(x);
        bool special = false;
        double value = 0;
        get(special);
        get(value);
        e.assign(w, special, value);
    }

    /// A vector of any length (assign keeps the capacity reserved by make_state()).
    template <class T>
    void get(std::vector<T>& a) {
        const uint64_t n = count(1);
        a.resize(n);
        for (T& e : a)
            get(e);
    }

    /// A vector whose length must equal expected (per-node arrays).
    template <class T>
    void get_sized(std::vector<T>& a, size_t expected, const char* name) {
        const uint64_t n = count(1);
        if (n != expected) {
            fail(fmt::format("'{}' has {} entries, the model has {}", name, n, expected));
        }
        a.resize(n);
        for (T& e : a)
            get(e);
    }

private:
    std::string path_;
    const std::vector<unsigned char>& buf_;
    size_t end_;
    size_t pos_ = 0;
};

}  // namespace

uint64_t model_hash(const Model& m, const ContactTopology& t, Real dt) {
    Hasher h;
    put(h, dt);
    put(h, m.node_x0);
    put(h, m.node_v0);
    put(h, m.node_mass);
    put(h, m.node_inv_mass);
    put(h, m.node_body);
    put(h, m.tri_nodes);
    put(h, m.tri_body);
    put(h, m.tri_material);
    put(h, m.tri_dm_inv);
    put(h, m.tri_area0);
    put(h, m.tri_eta);
    put(h, static_cast<uint64_t>(m.bodies.size()));
    for (const Body& b : m.bodies) {
        put(h, b.group);
        put(h, b.material);
        put(h, b.fixed);
        put(h, b.element);
        put(h, b.node_begin);
        put(h, b.node_end);
        put(h, b.tri_begin);
        put(h, b.tri_end);
    }
    put(h, static_cast<uint64_t>(m.materials.size()));
    for (const Material& mat : m.materials) {
        put(h, mat.density);
        put(h, mat.youngs_modulus);
        put(h, mat.poisson_ratio);
        put(h, mat.plane);
        put(h, mat.viscosity);
        put(h, mat.damping_ratio);
        put(h, mat.lambda);
        put(h, mat.mu);
    }
    put(h, static_cast<uint64_t>(m.bcs.size()));
    for (const BoundaryCondition& bc : m.bcs) {
        put(h, bc.nodes);
        put(h, bc.has_x);
        put(h, bc.has_y);
        put(h, bc.velocity);
        put(h, bc.start);
        put(h, bc.end);
    }
    put(h, static_cast<uint64_t>(m.kicks.size()));
    for (const VelocityKick& k : m.kicks) {
        put(h, k.group);
        put(h, k.time);
        put(h, k.has_x);
        put(h, k.has_y);
        put(h, k.velocity);
    }
    put(h, static_cast<uint64_t>(m.loads.size()));
    for (const Load& ld : m.loads) {
        put(h, ld.kind);
        put(h, ld.vector);
        put(h, ld.pressure);
        put(h, ld.time_function.kind);
        put(h, ld.time_function.ramp_time);
        put(h, ld.time_function.table);
        put(h, ld.edges);
        put(h, ld.edge_length0);
        put(h, ld.nodes);
        if (!ld.node_share.empty()) put(h, ld.node_share);  // jointed vertices only
    }
    put(h, m.mass_damping.coefficient);
    put(h, m.mass_damping.until);
    put(h, m.gravity);
    const ContactModel& c = m.contact;
    put(h, c.algorithm);
    put(h, c.params);
    put(h, static_cast<uint64_t>(c.resolved.size()));
    for (const ContactParams& p : c.resolved)
        put(h, p);
    put(h, c.material_class);
    put(h, c.buffer);
    put(h, c.two_way);
    put(h, c.m_bar);
    put(h, c.deep_ratio_limit);
    put(h, c.scaling);
    if (!m.joints.nodes.empty()) {
        // fracture: the topology changes as joints break and is rebuilt from the saved joint
        // state, so the hash takes the joints (from which it follows) instead
        const Joints& J = m.joints;
        put(h, J.nodes);
        put(h, J.length0);
        put(h, J.law);
        put(h, static_cast<uint64_t>(J.laws.size()));
        for (const JointLaw& L : J.laws)
            put(h, L);
        put(h, m.node_vertex);
        put(h, m.prebroken_joints);
        return h.h;
    }
    put(h, t.node_scale);
    put(h, t.edge_scale);
    put(h, t.node_dist);
    put(h, t.virt_parent);
    put(h, t.virt_weight);
    put(h, t.sub_tri);
    put(h, t.sub_body);
    return h.h;
}

uint64_t state_hash(const State& s) {
    Hasher h;
    put(h, s.x);
    put(h, s.v);
    put(h, s.energy);
    // the joint energies only where there are joints: a model without fracture hashes exactly
    // what it did before they existed (the demo hash is a regression canary across versions)
    if (!s.joints.status.empty()) {
        put(h, s.energy.joint);
        put(h, s.energy.fracture);
    }
    return h.h;
}

void write_checkpoint(const std::string& path, const Model& m, const State& s,
                      const RunProgress& progress) {
    Writer w;
    w.bytes(kMagic, sizeof kMagic);
    put(w, kCheckpointFormat);
    put(w, kEndianMarker);
    put(w, std::string(FDEM_VERSION));
    put(w, model_hash(m, s.topology, s.dt));
    put_state(w, s);
    put_progress(w, progress);
    put(w, fnv1a(kFnvOffset, w.buf.data(), w.buf.size()));
    try {
        AtomicFile f(path);
        f.write(w.buf.data(), w.buf.size());
        f.commit();
    } catch (const std::runtime_error& e) {
        throw SimulationError(s.step, s.time, path,
                              fmt::format("cannot write checkpoint: {}", e.what()));
    }
}

void read_checkpoint(const std::string& path, const Model& m, State& s, RunProgress& progress) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw InputError(
            {path, 0, 0}, "--restart",
            fmt::format("cannot open checkpoint '{}': {}", path, std::strerror(errno)));
    }
    const std::vector<unsigned char> buf((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
    constexpr size_t kTrailer = sizeof(uint64_t);
    Reader r(path, buf, buf.size() >= kTrailer ? buf.size() - kTrailer : 0);

    // header: magic, format, byte order, version, model
    char magic[sizeof kMagic] = {};
    if (buf.size() < sizeof kMagic + kTrailer) r.fail("not an fdem checkpoint (file too short)");
    r.bytes(magic, sizeof magic);
    if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) {
        r.fail("not an fdem checkpoint (wrong magic bytes)");
    }
    uint64_t stored_sum = 0;
    std::memcpy(&stored_sum, buf.data() + buf.size() - kTrailer, kTrailer);
    if (stored_sum != fnv1a(kFnvOffset, buf.data(), buf.size() - kTrailer)) {
        r.fail("checksum mismatch (the file is truncated or corrupt)");
    }
    uint32_t format = 0, endian = 0;
    r.get(format);
    if (format != kCheckpointFormat) {
        r.fail(fmt::format("checkpoint format {} is not supported by this fdem (format {})", format,
                           kCheckpointFormat));
    }
    r.get(endian);
    if (endian != kEndianMarker) r.fail("written on a machine with another byte order");
    std::string version;
    r.get(version);
    if (version != FDEM_VERSION) {
        r.fail(fmt::format("written by fdem {}, this is fdem {}; rerun from t = 0", version,
                           FDEM_VERSION));
    }
    uint64_t hash = 0;
    r.get(hash);
    if (hash != model_hash(m, s.topology, s.dt)) {
        r.fail(
            fmt::format("it was written for a different model or time step (model hash "
                        "{:016x}, this scenario gives {:016x}): the scenario, a mesh or dt "
                        "changed since; rerun from t = 0 or restore the original scenario",
                        hash, model_hash(m, s.topology, s.dt)));
    }

    // state
    const size_t nn = static_cast<size_t>(m.num_nodes());
    r.get(s.step);
    r.get(s.time);
    Real dt = 0;
    r.get(dt);
    if (dt != s.dt) r.fail(fmt::format("its dt = {} differs from the scenario's {}", dt, s.dt));
    r.get_sized(s.x, nn, "x");
    r.get_sized(s.v, nn, "v");
    r.get_sized(s.f, nn, "f");
    r.get_sized(s.f_contact, nn, "f_contact");
    r.get(s.energy);
    r.get(s.energy.joint);
    r.get(s.energy.fracture);
    r.get(s.next_kick);
    r.get(s.need_energy);
    if (s.step < 0 || s.next_kick < 0 || s.next_kick > static_cast<int32_t>(m.kicks.size())) {
        r.fail("step or kick counter out of range (corrupt file)");
    }
    r.get_sized(s.bc_velocity, m.bcs.size(), "bc_velocity");
    r.get_sized(s.bc_enabled, m.bcs.size(), "bc_enabled");
    for (uint8_t e : s.bc_enabled) {
        if (e > 1) r.fail("a support's bc_enabled is neither 0 nor 1 (corrupt file)");
    }
    {
        JointState& js = s.joints;
        const size_t nj = static_cast<size_t>(m.joints.num_joints());
        r.get_sized(js.d_max, nj, "joints.d_max");
        r.get_sized(js.status, nj, "joints.status");
        r.get_sized(js.mode_bits, nj, "joints.mode_bits");
        r.get_sized(js.mode, nj, "joints.mode");
        r.get_sized(js.break_step, nj, "joints.break_step");
        r.get_sized(js.work, nj, "joints.work");
        r.get_sized(js.f_prev, nj, "joints.f_prev");
        r.get_sized(js.d_prev, nj, "joints.d_prev");
        // sized by make_joint_state for this model: nj with a MixedMode::Proportional law, else 0
        const size_t nm = js.dn_max.size();
        r.get_sized(js.dn_max, nm, "joints.dn_max");
        r.get_sized(js.ds_max, nm, "joints.ds_max");
        r.get_sized(js.an_min, nm, "joints.an_min");
        r.get_sized(js.as_min, nm, "joints.as_min");
        r.get(js.total_work);
        r.get(js.total_work_sum);
        r.get(s.energy_sums.work_external);
        r.get(s.energy_sums.dissipated_viscous);
        r.get(s.energy_sums.dissipated_contact);
        for (size_t j = 0; j < nj; ++j) {
            if (static_cast<uint8_t>(js.status[j]) > 2 || static_cast<uint8_t>(js.mode[j]) > 3)
                r.fail("a joint status or mode is out of range (corrupt file)");
        }
        refresh_softening_cache(m.joints, js);  // z(D_max), not saved
        rebuild_fracture_views(m, s);           // sectors, fragments, topology of the saved cracks
    }

    ContactState& c = s.contact;
    r.get(c.active_contacts);
    r.get(c.deep_penetrations);
    r.get(c.lost_inside);
    r.get(c.max_depth_ratio);
    r.get(c.total_deep_penetrations);
    r.get(c.total_lost_inside);
    r.get(c.max_depth_ratio_ever);
    r.get(c.rebuilds);
    r.get(c.skin_used);
    r.get(c.need_rebuild);
    r.get(c.cand.node);
    r.get(c.cand.body);
    r.get(c.cand.begin);
    r.get(c.cand.tri);
    c.box_list_valid = false;   // (scratch: the contactor list of the old candidates)
    c.apply_lists.threads = 0;  // (scratch: the apply's lists of the old candidates)
    c.fc_sparse = false;        // (f_contact was read: the next step clears every node)
    r.get(c.broad.tri_center);
    r.get(c.broad.tri_radius);
    r.get(c.broad.tri_cell);
    r.get(c.broad.cell_start);
    r.get(c.broad.cell_items);
    r.get(c.broad.query);
    r.get(c.active);
    r.get(c.active_next);
    r.get(c.xv);
    r.get(c.vv);
    LegacyTriangleState& l = c.legacy;
    l.couples.resize(r.count(2 * sizeof(TriId) + 6 * sizeof(Real)));
    for (LegacyCouple& cp : l.couples) {
        r.get(cp.a);
        r.get(cp.b);
        for (Real& sl : cp.slide)
            r.get(sl);
    }
    r.get(l.skin_used);
    r.get(l.need_rebuild);
    r.get(l.rebuilds);
    r.get(l.active);

    // ids read back must index the model (a corrupt file must not crash the contact code)
    const int32_t nb = m.num_bodies(), ncn = s.topology.target_end();  // target ids
    const int32_t nsub = s.topology.num_sub_tris();
    const auto bad_id = [](int32_t id, int32_t n) { return id < 0 || id >= n; };
    bool ok = c.cand.node.size() == c.cand.body.size() &&
              (c.cand.node.empty() ? c.cand.begin.size() <= 1
                                   : c.cand.begin.size() == c.cand.node.size() + 1) &&
              c.xv.size() == static_cast<size_t>(s.topology.num_virtual()) &&
              c.vv.size() == c.xv.size();
    for (size_t p = 0; ok && p < c.cand.node.size(); ++p) {
        ok = !bad_id(c.cand.node[p], ncn) && !bad_id(c.cand.body[p], nb);
    }
    for (size_t p = 0; ok && p < c.cand.begin.size(); ++p) {
        ok = c.cand.begin[p] >= 0 && static_cast<size_t>(c.cand.begin[p]) <= c.cand.tri.size() &&
             (p == 0 || c.cand.begin[p] >= c.cand.begin[p - 1]);
    }
    for (size_t k = 0; ok && k < c.cand.tri.size(); ++k)
        ok = !bad_id(c.cand.tri[k], nsub);
    for (size_t k = 0; ok && k < c.active.size(); ++k) {
        ok = !bad_id(c.active[k].node, ncn) && !bad_id(c.active[k].body, nb);
    }
    for (const LegacyCouple& cp : l.couples) {
        ok = ok && !bad_id(cp.a, m.num_tris()) && !bad_id(cp.b, m.num_tris());
    }
    if (!ok) r.fail("contact candidate or history ids out of range (corrupt file)");

    // run bookkeeping
    r.get(progress.frame);
    r.get(progress.next_output);
    r.get(progress.energy.has_reference);
    r.get(progress.energy.e0);
    r.get(progress.energy.scale);
    r.get(progress.energy.max_error);
    const uint64_t nf = r.count(sizeof(Real) + sizeof(uint64_t));
    progress.frames.resize(nf);
    for (auto& [t, file] : progress.frames) {
        r.get(t);
        r.get(file);
    }
    // bodies.csv impulses since its last row: one per measured set (Resultants), or none when
    // the run wrote no bodies.csv
    const uint64_t ni = r.count(2 * sizeof(Real));
    progress.impulses.contact.resize(ni);
    for (Vec2& q : progress.impulses.contact)
        r.get(q);
    const uint64_t nr = r.count(2 * sizeof(Real));
    if (nr != ni) r.fail("bodies.csv impulses of different lengths (corrupt file)");
    progress.impulses.reaction.resize(nr);
    for (Vec2& q : progress.impulses.reaction)
        r.get(q);
    r.get(progress.impulses.time);
    if (r.remaining() != 0) r.fail("unexpected bytes after the payload");
}

}  // namespace fdem
