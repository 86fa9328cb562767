#include "io/mesh_bytes.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace fdem {
namespace {

constexpr uint64_t kMagic = 0x3173656268736d66ULL;  // "fmshbes1"

struct Out {
    std::string s;
    template <class T>
    void pod(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        s.append(reinterpret_cast<const char*>(&v), sizeof(T));
    }
    void str(const std::string& v) {
        pod(static_cast<uint64_t>(v.size()));
        s.append(v);
    }
    template <class T>
    void vec(const std::vector<T>& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        pod(static_cast<uint64_t>(v.size()));
        if (!v.empty()) s.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    }
};

struct In {
    std::string_view s;
    size_t at = 0;
    void need(uint64_t n) const {
        if (n > s.size() - at) throw std::runtime_error("mesh bytes: truncated");
    }
    template <class T>
    T pod() {
        need(sizeof(T));
        T v;
        std::memcpy(&v, s.data() + at, sizeof(T));
        at += sizeof(T);
        return v;
    }
    std::string str() {
        const auto n = pod<uint64_t>();
        need(n);
        std::string v(s.substr(at, n));
        at += n;
        return v;
    }
    template <class T>
    std::vector<T> vec() {
        const auto n = pod<uint64_t>();
        if (n > (s.size() - at) / sizeof(T)) throw std::runtime_error("mesh bytes: truncated");
        std::vector<T> v(n);
        if (n > 0) std::memcpy(v.data(), s.data() + at, n * sizeof(T));
        at += n * sizeof(T);
        return v;
    }
};

}  // namespace

std::string mesh_to_bytes(const MeshData& m) {
    Out o;
    o.pod(kMagic);
    o.str(m.file);
    o.vec(m.nodes);
    o.vec(m.tris);
    o.vec(m.tri_mid);
    o.vec(m.tri_tag);
    o.vec(m.lines);
    o.vec(m.line_mid);
    o.vec(m.line_tag);
    o.vec(m.points);
    o.vec(m.point_tag);
    o.pod(static_cast<uint64_t>(m.physical.size()));
    for (const auto& [name, dt] : m.physical) {
        o.str(name);
        o.pod(static_cast<int32_t>(dt.first));
        o.pod(static_cast<int32_t>(dt.second));
    }
    o.pod(static_cast<uint64_t>(m.groups.size()));
    for (const PhysicalGroup& g : m.groups) {
        o.str(g.name);
        o.pod(static_cast<int32_t>(g.dim));
        o.pod(static_cast<int32_t>(g.tag));
        o.vec(g.elements);
    }
    return std::move(o.s);
}

MeshData mesh_from_bytes(std::string_view bytes) {
    In in{bytes};
    if (in.pod<uint64_t>() != kMagic) throw std::runtime_error("mesh bytes: not a mesh");
    MeshData m;
    m.file = in.str();
    m.nodes = in.vec<Vec2>();
    m.tris = in.vec<std::array<int32_t, 3>>();
    m.tri_mid = in.vec<std::array<int32_t, 3>>();
    m.tri_tag = in.vec<int32_t>();
    m.lines = in.vec<std::array<int32_t, 2>>();
    m.line_mid = in.vec<int32_t>();
    m.line_tag = in.vec<int32_t>();
    m.points = in.vec<int32_t>();
    m.point_tag = in.vec<int32_t>();
    const auto n_physical = in.pod<uint64_t>();
    for (uint64_t i = 0; i < n_physical; ++i) {
        std::string name = in.str();
        const int dim = in.pod<int32_t>();
        const int tag = in.pod<int32_t>();
        m.physical.emplace(std::move(name), std::make_pair(dim, tag));
    }
    const auto n_groups = in.pod<uint64_t>();
    if (n_groups > bytes.size()) throw std::runtime_error("mesh bytes: truncated");
    m.groups.resize(n_groups);
    for (PhysicalGroup& g : m.groups) {
        g.name = in.str();
        g.dim = in.pod<int32_t>();
        g.tag = in.pod<int32_t>();
        g.elements = in.vec<int32_t>();
    }
    if (in.at != bytes.size()) throw std::runtime_error("mesh bytes: trailing data");
    return m;
}

}  // namespace fdem
