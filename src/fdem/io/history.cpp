// CSV energy history (docs/output.md). One row per call, flushed at once so a killed run keeps
// every complete row; values in %.17g so they read back bit-exact.
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>

#include "fdem/error.hpp"
#include "fdem/output.hpp"
#include "fracture/sectors.hpp"
#include "io/atomic_file.hpp"

namespace fdem {

namespace {

constexpr const char* kHeader =
    "step,time,kinetic,strain,contact,work_gravity,work_external,dissipated_viscous,"
    "dissipated_contact,total,energy_error,active_contacts\n";
/// Appended when the model has cohesive joints (spec fracture.md §9 output; docs/output.md).
constexpr const char* kFractureColumns =
    ",energy.joint,energy.fracture,joints.softening,joints.broken,crack_length,fragments,"
    "largest_fragment_mass_fraction";

std::string header(bool fracture) {
    std::string h = kHeader;
    if (fracture) {
        h.pop_back();  // '\n'
        h += kFractureColumns;
        h += '\n';
    }
    return h;
}

}  // namespace

HistoryWriter::HistoryWriter(const std::string& path, bool fracture) : path_(path) {
    file_ = std::fopen(path.c_str(), "w");
    if (file_ == nullptr || std::fputs(header(fracture).c_str(), file_) < 0 ||
        std::fflush(file_) != 0) {
        throw SimulationError(0, 0.0, path,
                              std::string("cannot write history file: ") + std::strerror(errno) +
                                  " (check that the output directory exists and is writable)");
    }
}

HistoryWriter::HistoryWriter(const std::string& path, int64_t resume_step, bool fracture)
    : path_(path) {
    // keep the rows up to resume_step (the step column is the first field)
    std::string kept = header(fracture);
    if (std::FILE* in = std::fopen(path.c_str(), "r")) {
        char line[4096];
        bool header = true;
        while (std::fgets(line, sizeof line, in) != nullptr) {
            if (header) {
                header = false;
                continue;
            }
            char* end = nullptr;
            const long long step = std::strtoll(line, &end, 10);
            if (end == line || *end != ',' || step > resume_step) break;
            if (!has_reference_) {
                // total is column 10 (state.hpp order), written with %.17g: reads back exact
                const char* p = line;
                for (int comma = 0; comma < 9 && p != nullptr; ++comma) {
                    p = std::strchr(p, ',');
                    if (p != nullptr) ++p;
                }
                if (p != nullptr) {
                    total0_ = std::strtod(p, nullptr);
                    has_reference_ = true;
                }
            }
            kept += line;
        }
        std::fclose(in);
    }
    // rewrite atomically (a kill now keeps the old file), then append
    try {
        AtomicFile out(path);
        out.write(kept);
        out.commit();
    } catch (const std::runtime_error& e) {
        throw SimulationError(resume_step, 0.0, path,
                              std::string("cannot rewrite history file: ") + e.what());
    }
    file_ = std::fopen(path.c_str(), "a");
    if (file_ == nullptr) {
        throw SimulationError(resume_step, 0.0, path,
                              std::string("cannot write history file: ") + std::strerror(errno) +
                                  " (check that the output directory exists and is writable)");
    }
}

HistoryWriter::~HistoryWriter() {
    if (file_ != nullptr) std::fclose(file_);
}

void HistoryWriter::prepare(const Model& m) {
    if (m.joints.nodes.empty()) return;
    node_frag_.assign(static_cast<size_t>(m.num_nodes()), kNone);
    frag_mass_.assign(static_cast<size_t>(m.num_tris()), 0);
}

void HistoryWriter::write(const Model& m, const State& s) {
    const Energy& e = s.energy;
    const Real total = e.total();

    // energy_error: drift of the balance (state.hpp) from its value at the first row [J/m]
    if (!has_reference_) {
        total0_ = total;
        has_reference_ = true;
    }
    const int n =
        std::fprintf(file_, "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d",
                     static_cast<long long>(s.step), s.time, e.kinetic, e.strain, e.contact,
                     e.work_gravity, e.work_external, e.dissipated_viscous, e.dissipated_contact,
                     total, total - total0_, static_cast<int>(s.contact.active_contacts));
    int nf = 0;
    if (!m.joints.nodes.empty()) {
        // joint counts, crack length (sum of h_0 of the broken joints) and fragments (each is
        // labelled by its smallest triangle, State::tri_fragment)
        int64_t softening = 0, broken = 0;
        Real crack = 0;
        for (size_t j = 0; j < s.joints.status.size(); ++j) {
            if (s.joints.status[j] == JointStatus::Softening) ++softening;
            if (s.joints.status[j] == JointStatus::Broken) {
                ++broken;
                crack += m.joints.length0[j];
            }
        }
        int64_t fragments = 0;
        for (size_t t = 0; t < s.tri_fragment.size(); ++t)
            fragments += s.tri_fragment[t] == static_cast<TriId>(t) ? 1 : 0;
        // largest fragment of the fracture bodies over their mass (computed here, at output
        // times, not in the step; scratch sized by prepare())
        Real largest = 0;
        if (s.tri_fragment.size() == static_cast<size_t>(m.num_tris())) {
            if (node_frag_.size() != static_cast<size_t>(m.num_nodes()) ||
                frag_mass_.size() != static_cast<size_t>(m.num_tris()))
                prepare(m);
            largest = largest_fragment_mass_fraction(m, s.tri_fragment, node_frag_, frag_mass_);
        }
        nf = std::fprintf(file_, ",%.17g,%.17g,%lld,%lld,%.17g,%lld,%.17g", e.joint, e.fracture,
                          static_cast<long long>(softening), static_cast<long long>(broken), crack,
                          static_cast<long long>(fragments), largest);
    }
    if (n < 0 || nf < 0 || std::fputc('\n', file_) == EOF || std::fflush(file_) != 0) {
        throw SimulationError(s.step, s.time, path_,
                              std::string("cannot write history row: ") + std::strerror(errno));
    }
}

}  // namespace fdem
