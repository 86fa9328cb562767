// Structural pre-check of .msh files before Gmsh reads them (msh_precheck.hpp).
//
// The walker mirrors Gmsh 4.8's readers (GModelIO_MSH2.cpp, GModelIO_MSH4.cpp): sections are
// found by reading 255-byte fgets() chunks until one starts with '$' and are matched by prefix
// ("$NOxx" is a nodes section for MSH 2); ASCII values are read with scanf semantics (strtoull /
// strtod: leading blanks, a sign, saturation on overflow); binary blocks are fixed-size records.
// Whenever Gmsh would stop with its own error (a value it cannot scan, a short read), the walk
// stops too and Gmsh reports it; the walk only throws for values Gmsh would trust.
#include "io/msh_precheck.hpp"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "fdem/error.hpp"

namespace fdem::io {

namespace {

/// Largest node or element tag: Gmsh 4.8 looks nodes up by int (GModel::getMeshVertexByTag(int)),
/// a larger tag wraps to a negative index and crashes it.
constexpr uint64_t kMaxTag = INT_MAX;

/// Nodes per element type (Gmsh reference manual, "MSH file format"); 0 for a type this check
/// does not know (rejected: fdem supports only a few of the known ones anyway).
int nodes_of_type(long long type) {
    static const int n[] = {0, 2,  3,  4,  4, 8,  6,  5,  3,  6,  9, 10, 27, 18, 14, 1,
                            8, 20, 15, 13, 9, 10, 12, 15, 15, 21, 4, 5,  6,  20, 35, 56};
    return type >= 1 && type < static_cast<long long>(std::size(n)) ? n[type] : 0;
}

/// Whitespace-separated integers of a line, each within the int range Gmsh reads them into
/// (%d); false if a field is not such an integer.
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
        if (used != tok.size() || v < INT_MIN || v > INT_MAX) return false;
        out.push_back(v);
    }
    return true;
}

bool starts_with(const std::string& s, const char* prefix) {
    return s.compare(0, std::strlen(prefix), prefix) == 0;
}

/// Section header text for a message: without the line end, non-printable bytes as '?', cut.
std::string shown(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r'))
        s.pop_back();
    if (s.size() > 40) s = s.substr(0, 40) + "...";
    for (char& c : s) {
        if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    }
    return s;
}

class Walker {
public:
    Walker(const std::string& path, std::string data, MshPhysicalNames* names = nullptr)
        : path_(path), d_(std::move(data)), names_(names) {}

    void run() {
        std::string s;
        size_t at = 0;
        while (next_section(s, at)) {
            // Gmsh handles the line as a C string (&str[1]): it ends at a NUL byte
            std::string name = s.substr(1);
            name.resize(std::min(name.size(), name.find('\0')));
            bool go_on = true;
            if (starts_with(name, "MeshFormat")) {
                go_on = format(at);
            } else if (!format_seen_) {
                fail(at, fmt::format("the file must start with a $MeshFormat section (MSH 2.2 or "
                                     "4.1), found '{}'",
                                     shown(s)));
            } else if (unsupported(name)) {
                fail(at, fmt::format("section '{}' is not supported: fdem reads $MeshFormat, "
                                     "$PhysicalNames, $Entities, $Nodes and $Elements; save the "
                                     "mesh without it",
                                     shown(s)));
            } else if (msh4_ ? starts_with(name, "Nodes")
                             : starts_with(name, "NO") || starts_with(name, "Nodes")) {
                go_on = msh4_ ? (binary_ ? nodes4_binary(at) : nodes4_ascii(at)) : nodes2(at);
            } else if (msh4_ ? starts_with(name, "Elements")
                             : starts_with(name, "ELM") || starts_with(name, "Elements")) {
                go_on =
                    msh4_ ? (binary_ ? elements4_binary(at) : elements4_ascii(at)) : elements2(at);
            } else if (starts_with(name, "PhysicalNames")) {
                go_on = physical_names(at);
            } else if (msh4_ && binary_ && starts_with(name, "Entities")) {
                go_on = entities4_binary(at);
            }
            if (!go_on) return;  // Gmsh stops here with its own message
            // MSH 4 reader: skip to "$End<name>" (Gmsh compares from the second byte on)
            if (msh4_) {
                const std::string end = "End" + name;
                while (fgets(s) && s.compare(1, end.size(), end) != 0) {
                }
            }
        }
    }

private:
    const std::string& path_;
    std::string d_;                      ///< the whole file
    MshPhysicalNames* names_ = nullptr;  ///< collects the physical names if not null
    int name_sections_ = 0;
    size_t pos_ = 0;
    bool format_seen_ = false;
    bool binary_ = false;
    bool seen_tri3_ = false, seen_tri6_ = false;  ///< triangle orders met so far (MSH 2)
    bool swap_ = false;
    bool msh4_ = false;
    double version_ = 0;
    std::vector<int32_t> node_ids_;  ///< MSH 2: ids of the last $Nodes section
    bool ids_sorted_ = false;

    size_t left() const { return d_.size() - pos_; }

    int line_of(size_t off) const {
        off = std::min(off, d_.size());
        return 1 + static_cast<int>(std::count(d_.begin(), d_.begin() + off, '\n'));
    }

    /// The line holding byte off, if it is printable text (binary data is not echoed).
    std::string line_text(size_t off) const {
        off = std::min(off, d_.size());
        size_t begin = 0;
        if (off > 0) {
            const size_t b = d_.rfind('\n', off - 1);
            begin = b == std::string::npos ? 0 : b + 1;
        }
        size_t end = d_.find('\n', begin);
        if (end == std::string::npos) end = d_.size();
        std::string s = d_.substr(begin, end - begin);
        if (!s.empty() && s.back() == '\r') s.pop_back();
        const bool printable = std::all_of(
            s.begin(), s.end(), [](unsigned char c) { return c == '\t' || (c >= 32 && c < 127); });
        return printable && s.size() < 200 ? s : std::string{};
    }

    [[noreturn]] void fail(size_t off, const std::string& msg) const {
        throw InputError({path_, line_of(off), 0}, "",
                         fmt::format("malformed mesh file '{}': {}", path_, msg), line_text(off));
    }

    /// fgets(str, size, fp): the next line, at most size - 1 bytes, through '\n'. False if
    /// nothing is left or, when eof_fails (Gmsh's "|| feof(fp)"), the read hit the file end.
    bool fgets(std::string& s, size_t size = 256, bool eof_fails = true) {
        if (pos_ >= d_.size()) return false;
        size_t end = pos_;
        while (end < d_.size() && end - pos_ < size - 1) {
            if (d_[end++] == '\n') break;
        }
        s.assign(d_, pos_, end - pos_);
        pos_ = end;
        const bool hit_eof = s.back() != '\n' && s.size() < size - 1;
        return !(eof_fails && hit_eof);
    }

    /// Gmsh's section search: fgets chunks until one starts with '$' (at: its offset).
    bool next_section(std::string& s, size_t& at) {
        for (;;) {
            at = pos_;
            if (!fgets(s)) return false;
            if (s[0] == '$') return true;
        }
    }

    /// Skip blanks as scanf does before a number; the offset of what follows (for messages).
    size_t skip_ws() {
        while (pos_ < d_.size() && std::isspace(static_cast<unsigned char>(d_[pos_])))
            ++pos_;
        return pos_;
    }

    /// fscanf(fp, "%lu"): false if no number can be scanned (Gmsh fails there).
    bool scan_u64(uint64_t& v) {
        const char* b = d_.c_str() + pos_;
        char* e = nullptr;
        const unsigned long long x = std::strtoull(b, &e, 10);  // saturates like glibc scanf
        if (e == b) return false;
        v = x;
        pos_ += static_cast<size_t>(e - b);
        return true;
    }

    /// fscanf(fp, "%d"), range checked by the caller.
    bool scan_int(long long& v) {
        const char* b = d_.c_str() + pos_;
        char* e = nullptr;
        const long long x = std::strtoll(b, &e, 10);
        if (e == b) return false;
        v = x;
        pos_ += static_cast<size_t>(e - b);
        return true;
    }

    /// fscanf(fp, "%lf").
    bool scan_double() {
        const char* b = d_.c_str() + pos_;
        char* e = nullptr;
        (void)std::strtod(b, &e);
        if (e == b) return false;
        pos_ += static_cast<size_t>(e - b);
        return true;
    }

    bool read_i32(int32_t& v) {
        if (left() < 4) return false;
        uint32_t u = 0;
        std::memcpy(&u, d_.data() + pos_, 4);
        if (swap_) u = __builtin_bswap32(u);
        std::memcpy(&v, &u, 4);
        pos_ += 4;
        return true;
    }

    bool read_u64(uint64_t& v) {
        if (left() < 8) return false;
        std::memcpy(&v, d_.data() + pos_, 8);
        if (swap_) v = __builtin_bswap64(v);
        pos_ += 8;
        return true;
    }

    /// Sections Gmsh interprets but fdem does not read (their counts are trusted by Gmsh).
    bool unsupported(const std::string& name) const {
        static const char* both[] = {"Periodic", "NodeData", "ElementData", "ElementNodeData",
                                     "InterpolationScheme"};
        static const char* v4[] = {"PartitionedEntities", "GhostElements", "Parametrizations"};
        for (const char* p : both) {
            if (starts_with(name, p)) return true;
        }
        if (msh4_) {
            for (const char* p : v4) {
                if (starts_with(name, p)) return true;
            }
            return false;
        }
        return starts_with(name, "ParametricNodes");
    }

    /// $MeshFormat: "version file-type data-size", then for binary files the int 1.
    bool format(size_t at) {
        if (format_seen_) {
            fail(at, "a second $MeshFormat section; a file holds one mesh");
        }
        const size_t line_at = pos_;
        std::string line;
        double version = 0;
        int type = -1;
        unsigned long size = 0;
        if (!fgets(line) || std::sscanf(line.c_str(), "%lf %d %lu", &version, &type, &size) != 3) {
            fail(line_at,
                 "the line after $MeshFormat must be 'version file-type data-size', "
                 "e.g. '4.1 0 8'");
        }
        const bool v2 = version >= 2 && version < 3;
        if (!v2 && version != 4.1) {
            fail(line_at, fmt::format("MSH version {:g} is not supported; fdem reads MSH 2.2 "
                                      "and 4.1 (gmsh -format msh22 or msh41)",
                                      version));
        }
        if (type != 0 && type != 1) {
            fail(line_at, fmt::format("file type {}; expected 0 (ASCII) or 1 (binary)", type));
        }
        if (type == 1 && size != 8) {
            fail(line_at, fmt::format("binary data size {}; expected 8 (8-byte doubles and "
                                      "integers, as Gmsh writes on this machine)",
                                      size));
        }
        format_seen_ = true;
        version_ = version;
        msh4_ = !v2;
        binary_ = type == 1;
        if (binary_) {
            int32_t one = 0;
            if (!read_i32(one)) return false;
            if (one != 1) {
                swap_ = true;
                if (__builtin_bswap32(static_cast<uint32_t>(one)) != 1) {
                    fail(line_at, fmt::format("the binary byte-order mark after the format line "
                                              "(byte {}) must be the int 1, got {}",
                                              pos_ - 4, one));
                }
            }
        }
        return true;
    }

    /// $PhysicalNames (ASCII in every format): "count", then lines "dim tag \"name\"" (MSH 2.0:
    /// no dim). Gmsh 4.8's MSH 4 reader indexes an array of 4 iterators by dim: a dimension
    /// outside 0..3 crashed it (SEGV in GModel::setPhysicalName, found by fuzzing).
    bool physical_names(size_t at) {
        long long n = 0;
        if (!line_count(n)) return false;
        const bool has_dim = msh4_ || version_ > 2.0;
        // the names as Gmsh sets them, while every entry is plain (MshPhysicalNames)
        bool plain = names_ != nullptr && ++name_sections_ == 1 && has_dim &&
                     (msh4_ ? version_ == 4.1 : version_ == 2.2);
        std::map<std::pair<int, int>, std::string> names;
        std::set<std::pair<int, std::string>> given;  // (dim, name) already set
        std::string rest;
        for (long long k = 0; k < n; ++k) {
            const size_t entry_at = skip_ws();
            long long dim = 0, tag = 0;
            if (has_dim && !scan_int(dim)) return false;
            if (!scan_int(tag)) return false;
            if (has_dim && (dim < 0 || dim > 3)) {
                fail(entry_at, fmt::format("$PhysicalNames entry {} (tag {}) has dimension {}; "
                                           "expected 0 to 3",
                                           k + 1, tag, dim));
            }
            if (!fgets(rest, 256, false)) return false;
            if (plain) {
                std::string name;
                plain = plain_name(rest, name) && tag >= INT32_MIN && tag <= INT32_MAX;
                const int d = static_cast<int>(dim), t = static_cast<int>(tag);
                if (plain && given.count({d, name}) == 0 &&
                    names.emplace(std::pair{d, t}, name).second) {
                    given.insert({d, name});
                }
            }
        }
        if (names_ == nullptr) return true;
        if (name_sections_ > 1) {
            names_->plain = false;  // a second section: Gmsh's own reading
            return true;
        }
        // the section ends with its "$EndPhysicalNames" line, nothing but blanks before it
        const size_t end_at = skip_ws();
        const std::string end = "$EndPhysicalNames";
        plain = plain && d_.compare(end_at, end.size(), end) == 0 && end_at > 0 &&
                d_[end_at - 1] == '\n';
        if (plain) {
            size_t e = end_at + end.size();
            while (e < d_.size() && d_[e] == '\r')
                ++e;
            plain = e < d_.size() && d_[e] == '\n';
            names_->section_end = e + 1;
        }
        names_->plain = plain;
        names_->section_begin = at;
        names_->entries = static_cast<size_t>(n);
        if (plain) names_->names = std::move(names);
        return true;
    }

    /// The rest of a $PhysicalNames entry line is ` "name"` with 1 to 99 printable characters
    /// other than '"', then only blanks: the name Gmsh's ExtractDoubleQuotedString gives.
    static bool plain_name(const std::string& rest, std::string& name) {
        const size_t q = rest.find('"');
        if (q == std::string::npos) return false;
        for (size_t i = 0; i < q; ++i) {
            if (rest[i] != ' ' && rest[i] != '\t') return false;
        }
        const size_t r = rest.find('"', q + 1);
        if (r == std::string::npos || r == q + 1 || r - q - 1 > 99) return false;
        name = rest.substr(q + 1, r - q - 1);
        for (const char c : name) {
            if (c < 32 || c > 126) return false;
        }
        for (size_t i = r + 1; i < rest.size(); ++i) {
            if (!std::isspace(static_cast<unsigned char>(rest[i]))) return false;
        }
        return rest.back() == '\n';
    }

    /// A count read as "%d" from a whole line (MSH 2 section counts); false if not a number.
    bool line_count(long long& n) {
        std::string line;
        if (!fgets(line)) return false;
        const char* b = line.c_str();
        char* e = nullptr;
        n = std::strtoll(b, &e, 10);
        return e != b;
    }

    /// MSH 2 $Nodes: "count" then id x y z (ASCII) or {int id, 3 doubles} records (binary).
    bool nodes2(size_t at) {
        const size_t count_at = pos_;
        long long n = 0;
        if (!line_count(n)) return false;
        if (n < 0 || n > INT_MAX) {
            fail(count_at, fmt::format("the $Nodes count must be 0 to {}, got {}", INT_MAX, n));
        }
        node_ids_.clear();  // Gmsh keeps the nodes of the last $Nodes section
        ids_sorted_ = false;
        if (!binary_) {
            // fscanf("%d %lf %lf %lf") per node
            for (long long k = 0; k < n; ++k) {
                const size_t id_at = skip_ws();
                long long id = 0;
                if (!scan_int(id)) return false;
                if (id < INT_MIN || id > INT_MAX) {
                    fail(id_at, fmt::format("$Nodes: node id {} is beyond the int range", id));
                }
                node_ids_.push_back(static_cast<int32_t>(id));
                for (int c = 0; c < 3; ++c) {
                    if (!scan_double()) return false;
                }
            }
            return true;
        }
        constexpr uint64_t rec = 4 + 3 * 8;
        if (static_cast<uint64_t>(n) > left() / rec) {
            fail(at, fmt::format("$Nodes (binary) at byte {} declares {} nodes of {} bytes "
                                 "(int tag, 3 doubles), {} bytes; only {} bytes are left in "
                                 "the file",
                                 at, n, rec, static_cast<uint64_t>(n) * rec, left()));
        }
        for (long long k = 0; k < n; ++k) {
            int32_t id = 0;
            read_i32(id);
            node_ids_.push_back(id);
            pos_ += 3 * 8;
        }
        return true;
    }

    /// Whether the last MSH 2 $Nodes section defines node id. Gmsh 4.8 checks an element's node
    /// against its dense node vector with an off-by-one bound: node numVertices + 1 of a 1-based
    /// numbering passed and crashed it (SEGV in _associateEntityWithMeshVertices, fuzzing).
    bool node_defined(int64_t id) {
        if (!ids_sorted_) {
            std::sort(node_ids_.begin(), node_ids_.end());
            ids_sorted_ = true;
        }
        return id >= INT_MIN && id <= INT_MAX &&
               std::binary_search(node_ids_.begin(), node_ids_.end(), static_cast<int32_t>(id));
    }

    /// MSH 2 $Elements: "count", then lines "id type ntags tags... nodes..." (ASCII) or blocks
    /// {int type, count, ntags} + count records of 1 + ntags + nodes ints (binary).
    bool elements2(size_t at) {
        const size_t count_at = pos_;
        long long total = 0;
        const bool counted = line_count(total);
        if (!counted || total < 0 || total > INT_MAX) {
            if (!counted && pos_ >= d_.size()) return false;
            fail(count_at, binary_ ? "the $Elements count must be the number of elements (an "
                                     "integer >= 0)"
                                   : "the $Elements count must be the number of element lines "
                                     "that follow");
        }
        return binary_ ? element_blocks2(at, total) : element_lines2(count_at, total);
    }

    /// Gmsh 4.8 silently drops the first-order triangles of an MSH 2 file whose elementary
    /// entity also holds 6-node triangles (found while adding the composite element), so a file
    /// mixing the two orders is refused here rather than loaded with triangles missing.
    bool mixes_triangle_orders(long long type) {
        if (type == 2) seen_tri3_ = true;
        if (type == 9) seen_tri6_ = true;
        return seen_tri3_ && seen_tri6_;
    }

    bool element_lines2(size_t count_at, long long n) {
        // lines left in the file (a last line without '\n' counts)
        const size_t rest = static_cast<size_t>(std::count(d_.begin() + pos_, d_.end(), '\n')) +
                            (!d_.empty() && d_.back() != '\n' && pos_ < d_.size() ? 1 : 0);
        if (static_cast<size_t>(n) > rest) {
            fail(count_at, "the $Elements count must be the number of element lines that follow");
        }
        std::vector<long> v;
        int line = line_of(pos_);
        for (long long k = 0; k < n; ++k, ++line) {
            const size_t line_at = pos_;
            size_t end = d_.find('\n', pos_);
            if (end == std::string::npos) end = d_.size();
            std::string text = d_.substr(pos_, end - pos_);
            if (!text.empty() && text.back() == '\r') text.pop_back();
            pos_ = std::min(end + 1, d_.size());
            auto fail_line = [&](const std::string& msg) {
                throw InputError({path_, line, 0}, "",
                                 fmt::format("malformed mesh file '{}': {}", path_, msg),
                                 line_text(line_at));
            };
            if (!integers(text, v) || v.size() < 3 || v[2] < 0) {
                fail_line("an $Elements line must be 'id type ntags tags... nodes...' (integers)");
            }
            const int nn = nodes_of_type(v[1]);
            if (nn == 0) {
                fail_line(fmt::format("element {} has unknown element type {}", v[0], v[1]));
            }
            if (mixes_triangle_orders(v[1])) {
                fail_line(
                    fmt::format("element {} is a {}-node triangle, but earlier elements are "
                                "{}-node triangles; a mesh must be entirely first or "
                                "second order (gmsh -order 1 or -order 2)",
                                v[0], v[1] == 2 ? 3 : 6, v[1] == 2 ? 6 : 3));
            }
            const size_t want = 3 + static_cast<size_t>(v[2]) + static_cast<size_t>(nn);
            if (v.size() != want) {
                fail_line(
                    fmt::format("element {} of type {} with {} tags needs {} fields ({} "
                                "node ids), the line has {}",
                                v[0], v[1], v[2], want, nn, v.size()));
            }
            for (size_t f = want - static_cast<size_t>(nn); f < want; ++f) {
                if (!node_defined(v[f])) {
                    fail_line(
                        fmt::format("element {} references node {}, which $Nodes does not "
                                    "define",
                                    v[0], v[f]));
                }
            }
        }
        return true;
    }

    bool element_blocks2(size_t at, long long total) {
        long long done = 0;
        while (done < total) {
            const size_t block_at = pos_;
            int32_t type = 0, n = 0, ntags = 0;
            if (!read_i32(type) || !read_i32(n) || !read_i32(ntags)) return false;
            const std::string where =
                fmt::format("$Elements (binary) block at byte {} (type {}, count {}, tags {})",
                            block_at, type, n, ntags);
            const int nn = nodes_of_type(type);
            if (nn == 0) fail(at, where + ": unknown element type");
            if (n < 1 || n > total - done) {
                fail(at, fmt::format("{}: the element count must be 1 to {} (the $Elements "
                                     "count {} less the {} elements of the blocks before)",
                                     where, total - done, total, done));
            }
            if (ntags < 0) fail(at, where + ": the number of tags must be >= 0");
            if (mixes_triangle_orders(type)) {
                fail(at, where +
                             ": 3-node and 6-node triangles (types 2 and 9) in one file; a "
                             "mesh must be entirely first or second order (gmsh -order 1 or "
                             "-order 2)");
            }
            const uint64_t rec = 4 * (1 + static_cast<uint64_t>(ntags) + nn);
            if (static_cast<uint64_t>(n) > left() / rec) {
                fail(at, fmt::format("{}: {} element records of {} bytes each need {} bytes; "
                                     "only {} bytes are left in the file",
                                     where, n, rec, rec * static_cast<uint64_t>(n), left()));
            }
            for (int32_t e = 0; e < n; ++e) {
                const size_t rec_at = pos_;
                int32_t id = 0;
                read_i32(id);
                pos_ += 4 * static_cast<size_t>(ntags);
                for (int k = 0; k < nn; ++k) {
                    int32_t node = 0;
                    read_i32(node);
                    if (!node_defined(node)) {
                        fail(at, fmt::format("{}: element {} (record at byte {}) references node "
                                             "{}, which $Nodes does not define",
                                             where, id, rec_at, node));
                    }
                }
            }
            done += n;
        }
        return true;
    }

    /// A node or element tag Gmsh can hold (1..INT_MAX).
    void check_tag(uint64_t tag, size_t at, const std::string& what) const {
        if (tag < 1 || tag > kMaxTag) {
            fail(at, fmt::format("{} tag {}; expected 1 to {}", what,
                                 tag > static_cast<uint64_t>(LLONG_MAX)
                                     ? std::to_string(static_cast<long long>(tag))
                                     : std::to_string(tag),
                                 kMaxTag));
        }
    }

    /// A block count against the section total and the bytes left (rec: least bytes per entry).
    void check_block(size_t at, const std::string& where, uint64_t n, uint64_t total, uint64_t done,
                     uint64_t rec, const char* what) const {
        if (n > total - done) {
            fail(at, fmt::format("{} declares {} {}, more than the {} left of the section "
                                 "header's total {}",
                                 where, n, what, total - done, total));
        }
        if (n > left() / rec) {
            fail(at, fmt::format("{} declares {} {} of at least {} bytes each; only {} bytes are "
                                 "left in the file",
                                 where, n, what, rec, left()));
        }
    }

    void check_total(size_t at, const char* section, uint64_t total, uint64_t rec,
                     const char* what) const {
        if (total > left() / rec) {
            fail(at, fmt::format("the {} header declares {} {} of at least {} bytes each; only "
                                 "{} bytes are left in the file",
                                 section, total, what, rec, left()));
        }
    }

    void check_sum(size_t at, const char* section, uint64_t total, uint64_t done,
                   const char* what) const {
        if (done != total) {
            fail(at, fmt::format("the {} header declares {} {}, its blocks hold {}", section, total,
                                 what, done));
        }
    }

    /// MSH 4.1 binary $Entities: 4 counts, then per entity int tag, 3 (points) or 6 doubles,
    /// size_t + ints of physical tags, and for curves and up size_t + ints of bounding entities.
    bool entities4_binary(size_t at) {
        uint64_t count[4] = {0, 0, 0, 0};
        for (uint64_t& c : count) {
            if (!read_u64(c)) return false;
        }
        for (int dim = 0; dim < 4; ++dim) {
            const uint64_t least = 4 + (dim > 0 ? 48 : 24) + 8 + (dim > 0 ? 8 : 0);
            if (count[dim] > left() / least) {
                fail(at, fmt::format("$Entities (binary) at byte {} declares {} entities of "
                                     "dimension {}, at least {} bytes each; only {} bytes are "
                                     "left in the file",
                                     at, count[dim], dim, least, left()));
            }
            for (uint64_t i = 0; i < count[dim]; ++i) {
                const size_t entity_at = pos_;
                int32_t tag = 0;
                if (!read_i32(tag) || left() < (dim > 0 ? 48u : 24u)) return false;
                pos_ += dim > 0 ? 48 : 24;
                const int lists = dim > 0 ? 2 : 1;
                for (int l = 0; l < lists; ++l) {
                    uint64_t n = 0;
                    if (!read_u64(n)) return false;
                    if (n > left() / 4) {
                        fail(at, fmt::format("$Entities (binary): entity {} of dimension {} at "
                                             "byte {} declares {} {} tags (4 bytes each); only "
                                             "{} bytes are left in the file",
                                             tag, dim, entity_at, n,
                                             l == 0 ? "physical" : "bounding-entity", left()));
                    }
                    pos_ += static_cast<size_t>(n) * 4;
                }
            }
        }
        return true;
    }

    /// MSH 4.1 ASCII $Nodes: "blocks total min max", blocks "dim tag parametric n", n tags, then
    /// n lines of 3 (+ dim if parametric) coordinates.
    bool nodes4_ascii(size_t at) {
        uint64_t blocks = 0, total = 0, lo = 0, hi = 0;
        if (!scan_u64(blocks) || !scan_u64(total) || !scan_u64(lo) || !scan_u64(hi)) {
            return false;
        }
        check_total(at, "$Nodes", total, 2, "nodes");
        uint64_t done = 0;
        for (uint64_t b = 0; b < blocks; ++b) {
            const size_t block_at = skip_ws();
            long long dim = 0, tag = 0, parametric = 0;
            uint64_t n = 0;
            if (!scan_int(dim) || !scan_int(tag) || !scan_int(parametric) || !scan_u64(n)) {
                return false;
            }
            if (dim < 0 || dim > 3) {
                fail(block_at, fmt::format("$Nodes block of entity {} has dimension {}; "
                                           "expected 0 to 3",
                                           tag, dim));
            }
            check_block(block_at, fmt::format("the $Nodes block of entity {}", tag), n, total, done,
                        2, "nodes");
            done += n;
            for (uint64_t j = 0; j < n; ++j) {
                const size_t tag_at = skip_ws();
                uint64_t t = 0;
                if (!scan_u64(t)) return false;
                check_tag(t, tag_at, "node");
            }
            const uint64_t coords = n * (3 + (parametric != 0 ? static_cast<uint64_t>(dim) : 0));
            for (uint64_t j = 0; j < coords; ++j) {
                if (!scan_double()) return false;
            }
        }
        check_sum(at, "$Nodes", total, done, "nodes");
        return true;
    }

    /// MSH 4.1 binary $Nodes: 4 size_t, blocks {int dim, tag, parametric; size_t n}, n size_t
    /// tags, n * (3 + dim if parametric) doubles.
    bool nodes4_binary(size_t at) {
        uint64_t head[4];
        for (uint64_t& h : head) {
            if (!read_u64(h)) return false;
        }
        const uint64_t blocks = head[0], total = head[1];
        check_total(at, "$Nodes (binary)", total, 32, "nodes");
        uint64_t done = 0;
        for (uint64_t b = 0; b < blocks; ++b) {
            const size_t block_at = pos_;
            int32_t dim = 0, tag = 0, parametric = 0;
            uint64_t n = 0;
            if (!read_i32(dim) || !read_i32(tag) || !read_i32(parametric) || !read_u64(n)) {
                return false;
            }
            const std::string where =
                fmt::format("the $Nodes (binary) block at byte {} (entity {})", block_at, tag);
            if (dim < 0 || dim > 3) {
                fail(at, fmt::format("{} has dimension {}; expected 0 to 3", where, dim));
            }
            const uint64_t coords = 3 + (parametric != 0 ? static_cast<uint64_t>(dim) : 0);
            check_block(at, where, n, total, done, 8 + 8 * coords, "nodes");
            done += n;
            for (uint64_t j = 0; j < n; ++j) {
                const size_t tag_at = pos_;
                uint64_t t = 0;
                read_u64(t);
                if (t < 1 || t > kMaxTag) {
                    fail(at, fmt::format("{}: node tag {} at byte {}; expected 1 to {}", where, t,
                                         tag_at, kMaxTag));
                }
            }
            pos_ += static_cast<size_t>(n * 8 * coords);
        }
        check_sum(at, "$Nodes (binary)", total, done, "nodes");
        return true;
    }

    /// MSH 4.1 ASCII $Elements: "blocks total min max", blocks "dim tag type n", n lines
    /// "tag node...". Gmsh reads the tag with fscanf, the rest of the line with fgets (10000
    /// bytes) and the nodes from it with sscanf("%lu %[0-9- ]").
    bool elements4_ascii(size_t at) {
        uint64_t blocks = 0, total = 0, lo = 0, hi = 0;
        if (!scan_u64(blocks) || !scan_u64(total) || !scan_u64(lo) || !scan_u64(hi)) {
            return false;
        }
        check_total(at, "$Elements", total, 2, "elements");
        uint64_t done = 0;
        std::string rest;
        for (uint64_t b = 0; b < blocks; ++b) {
            const size_t block_at = skip_ws();
            long long dim = 0, tag = 0, type = 0;
            uint64_t n = 0;
            if (!scan_int(dim) || !scan_int(tag) || !scan_int(type) || !scan_u64(n)) {
                return false;
            }
            const int nn = nodes_of_type(type);
            if (nn == 0) {
                fail(block_at, fmt::format("the $Elements block of entity {} has unknown element "
                                           "type {}",
                                           tag, type));
            }
            check_block(block_at, fmt::format("the $Elements block of entity {}", tag), n, total,
                        done, 2, "elements");
            done += n;
            for (uint64_t j = 0; j < n; ++j) {
                const size_t elem_at = skip_ws();
                uint64_t elem = 0;
                if (!scan_u64(elem)) return false;
                check_tag(elem, elem_at, "element");
                if (!fgets(rest, 10000, false)) return false;
                std::string cur = rest;
                for (int k = 0; k < nn; ++k) {
                    const char* s = cur.c_str();
                    char* e = nullptr;
                    const unsigned long long node = std::strtoull(s, &e, 10);
                    if (e == s) return false;
                    if (node < 1 || node > kMaxTag) {
                        fail(elem_at, fmt::format("element {} references node tag {}; expected "
                                                  "1 to {}",
                                                  elem, node, kMaxTag));
                    }
                    if (k + 1 < nn) {
                        // " %[0-9- ]": skip blanks, then a non-empty run of digits, '-' and ' '
                        while (*e != '\0' && std::isspace(static_cast<unsigned char>(*e)))
                            ++e;
                        const size_t run = std::strspn(e, "0123456789- ");
                        if (run == 0) return false;
                        cur.assign(e, run);
                    }
                }
            }
        }
        check_sum(at, "$Elements", total, done, "elements");
        return true;
    }

    /// MSH 4.1 binary $Elements: 4 size_t, blocks {int dim, tag, type; size_t n}, n records of
    /// size_t tag + node tags.
    bool elements4_binary(size_t at) {
        uint64_t head[4];
        for (uint64_t& h : head) {
            if (!read_u64(h)) return false;
        }
        const uint64_t blocks = head[0], total = head[1];
        check_total(at, "$Elements (binary)", total, 16, "elements");
        uint64_t done = 0;
        for (uint64_t b = 0; b < blocks; ++b) {
            const size_t block_at = pos_;
            int32_t dim = 0, tag = 0, type = 0;
            uint64_t n = 0;
            if (!read_i32(dim) || !read_i32(tag) || !read_i32(type) || !read_u64(n)) {
                return false;
            }
            const std::string where =
                fmt::format("the $Elements (binary) block at byte {} (entity {})", block_at, tag);
            const int nn = nodes_of_type(type);
            if (nn == 0) fail(at, fmt::format("{} has unknown element type {}", where, type));
            check_block(at, where, n, total, done, 8 * (1 + static_cast<uint64_t>(nn)), "elements");
            done += n;
            for (uint64_t j = 0; j < n; ++j) {
                for (int k = 0; k <= nn; ++k) {
                    const size_t tag_at = pos_;
                    uint64_t t = 0;
                    read_u64(t);
                    if (t < 1 || t > kMaxTag) {
                        fail(at, fmt::format("{}: {} tag {} at byte {}; expected 1 to {}", where,
                                             k == 0 ? "element" : "node", t, tag_at, kMaxTag));
                    }
                }
            }
        }
        check_sum(at, "$Elements (binary)", total, done, "elements");
        return true;
    }
};

}  // namespace

void precheck_msh(const std::string& path) {
    precheck_msh(path, nullptr);
}

void precheck_msh(const std::string& path, MshPhysicalNames* names) {
    std::ifstream in(path, std::ios::binary);
    std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (names) *names = MshPhysicalNames{};
    Walker(path, std::move(data), names).run();
}

}  // namespace fdem::io
