// bodies.csv: resultants, reactions and mean motion of body entries and boundary groups
// (output.hpp BodiesWriter, docs/output.md).
#include <iterator>

#include <fmt/format.h>

#include "fdem/output.hpp"

namespace fdem {

namespace {

constexpr const char* kColumns[] = {"ux",        "uy",        "vx",
                                    "vy",        "contact_x", "contact_y",
                                    "contact_avg_x", "contact_avg_y", "reaction_x",
                                    "reaction_y", "reaction_avg_x", "reaction_avg_y"};

}  // namespace

std::string BodiesWriter::header(const Resultants& r) {
    std::string h = "step,time";
    for (int32_t k = 0; k < r.num_sets(); ++k) {
        for (const char* c : kColumns) {
            // appended piecewise: "," + std::string trips GCC 12's false -Wrestrict
            std::string name = r.name(k);
            name += '.';
            name += c;
            h += ',';
            h += csv_field(name);
        }
    }
    return h;
}

BodiesWriter::BodiesWriter(const std::string& path, const Resultants& r, int64_t resume_step)
    : r_(r),
      csv_(resume_step < 0 ? CsvSeries(path, header(r)) : CsvSeries(path, header(r), resume_step)),
      values_(static_cast<size_t>(r.num_sets())) {}

void BodiesWriter::write(const Model& m, const State& s, const IntervalImpulses& acc) {
    r_.evaluate(m, s, acc, values_.data());
    line_.clear();
    auto out = std::back_inserter(line_);
    fmt::format_to(out, "{},{:.17g}", s.step, s.time);
    for (const SetValues& v : values_) {
        for (const Vec2 q : {v.u, v.v, v.contact, v.contact_avg, v.reaction, v.reaction_avg})
            fmt::format_to(out, ",{:.17g},{:.17g}", q.x, q.y);
    }
    csv_.write_line(line_, s.step, s.time);
}

}  // namespace fdem
