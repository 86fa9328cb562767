// probes.csv: position, velocity and stress of the [[probe]] entries (output.hpp ProbesWriter,
// docs/output.md).
#include <iterator>

#include <fmt/format.h>

#include "fdem/output.hpp"

namespace fdem {

std::string ProbesWriter::header(const std::vector<ProbeSpec>& probes) {
    std::string h = "step,time";
    for (const ProbeSpec& p : probes) {
        for (const char* c : {"x", "y", "vx", "vy", "sxx", "syy", "sxy"}) {
            // appended piecewise: "," + std::string trips GCC 12's false -Wrestrict
            std::string name = p.name;
            name += '.';
            name += c;
            h += ',';
            h += csv_field(name);
        }
    }
    return h;
}

ProbesWriter::ProbesWriter(const std::string& path, const std::vector<ProbeSpec>& probes,
                           int64_t resume_step)
    : probes_(probes),
      csv_(resume_step < 0 ? CsvSeries(path, header(probes))
                           : CsvSeries(path, header(probes), resume_step)) {}

void ProbesWriter::write(const Model& m, const State& s) {
    line_.clear();
    auto out = std::back_inserter(line_);
    fmt::format_to(out, "{},{:.17g}", s.step, s.time);
    for (const ProbeSpec& p : probes_) {
        const ProbeValues v = evaluate_probe(m, s, p);
        fmt::format_to(out, ",{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}", v.x.x,
                       v.x.y, v.v.x, v.v.y, v.stress.xx, v.stress.yy, v.stress.xy);
    }
    csv_.write_line(line_, s.step, s.time);
}

}  // namespace fdem
