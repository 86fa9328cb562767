// fdem_validate: reproduces the paper's examples (spec §5, checks of spec §8 T13-T18, T20) and
// writes, into --out DIR, checks_<case>.csv (one row per check: measured, expected, tolerance,
// pass) plus one CSV per plotted series. --only refreshes the named cases and leaves the other
// cases' files in DIR, so the report (built from every checks_*.csv present) stays complete.
// scripts/validate runs it and turns DIR into docs/validation/README.md and its figures. Exit code
// 0 = every check passed, 1 = a check failed, 2 = bad command line.
//
//   fdem_validate [--quick] [--out DIR] [--only NAME[,NAME...]]
//
// --quick uses the reduced resolutions of the CTest suite (label `validation`); the default is
// the full resolution of the spec (label `full`). NAME: block, disk, slide, field, hertz,
// sensitivity, legacy, composite, pull_apart, shear, penalty, refinement. sensitivity and legacy
// run at the reduced resolution in both modes (docs/validation/NOTES.md).
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "validation/cases/block_impact.hpp"
#include "validation/cases/composite_dynamics.hpp"
#include "validation/cases/composite_field_maps.hpp"
#include "validation/cases/disk_impact.hpp"
#include "validation/cases/field_maps.hpp"
#include "validation/cases/hertz.hpp"
#include "validation/cases/legacy_sliding.hpp"
#include "validation/cases/penalty.hpp"
#include "validation/cases/pull_apart.hpp"
#include "validation/cases/refinement.hpp"
#include "validation/cases/sensitivity.hpp"
#include "validation/cases/shear.hpp"
#include "validation/cases/sliding_block.hpp"

using namespace fdem::validation;

namespace {

std::string csv_escape(const std::string& s) {
    std::string o = "\"";
    for (char ch : s)
        o += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return o + "\"";
}

const char* rel_name(Rel r) {
    switch (r) {
        case Rel::Abs:
            return "abs";
        case Rel::RelTol:
            return "rel";
        case Rel::AtMost:
            return "at_most";
        case Rel::AtLeast:
            return "at_least";
        case Rel::Report:
            return "report";
    }
    return "?";
}

/// checks.csv format: one row per check (scripts/validate_report.py reads every checks_*.csv).
bool write_checks(const std::string& file, const std::vector<Check>& checks) {
    FILE* f = std::fopen(file.c_str(), "w");
    if (!f) return false;
    std::fprintf(f, "id,name,measured,expected,relation,tolerance,tolerance_text,unit,pass,why\n");
    for (const Check& k : checks) {
        const bool ok = k.pass();
        std::fprintf(f, "%s,%s,%.8g,%.8g,%s,%.8g,%s,%s,%s,%s\n", k.id.c_str(),
                     csv_escape(k.name).c_str(), k.measured, k.expected, rel_name(k.rel), k.tol,
                     csv_escape(k.tolerance_text()).c_str(), csv_escape(k.unit).c_str(),
                     k.rel == Rel::Report ? "report"
                     : ok                 ? "pass"
                                          : "FAIL",
                     csv_escape(k.why).c_str());
    }
    return std::fclose(f) == 0;
}

}  // namespace

int main(int argc, char** argv) {
    bool quick = false;
    std::string out = "validation_out";
    std::set<std::string> only;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--quick") {
            quick = true;
        } else if (a == "--out" && i + 1 < argc) {
            out = argv[++i];
        } else if (a == "--only" && i + 1 < argc) {
            std::stringstream ss(argv[++i]);
            std::string item;
            while (std::getline(ss, item, ','))
                only.insert(item);
        } else {
            std::fprintf(stderr,
                         "usage: fdem_validate [--quick] [--out DIR] [--only "
                         "block,disk,slide,field,hertz,sensitivity,legacy,composite,pull_apart,"
                         "shear,penalty,refinement,...]\n");
            return 2;
        }
    }
    std::filesystem::create_directories(out);
    std::filesystem::remove(std::filesystem::path(out) / "checks.csv");  // old single-file format
    auto want = [&](const char* n) { return only.empty() || only.count(n) > 0; };
    auto path = [&](const std::string& f) { return (std::filesystem::path(out) / f).string(); };
    std::vector<Check> all;
    std::set<std::string> ran;
    int failed = 0;
    // every case writes its own checks_<case>.csv, so `--only <case>` refreshes that case in the
    // same data dir and the report merges all checks_*.csv present (scripts/validate_report.py)
    auto add_case = [&](const std::string& name, const std::vector<Check>& c) {
        ran.insert(name);
        if (!write_checks(path("checks_" + name + ".csv"), c)) {
            std::fprintf(stderr, "cannot write %s\n", path("checks_" + name + ".csv").c_str());
            ++failed;
        }
        for (const Check& k : c) {
            if (!k.pass()) ++failed;
            std::printf("%-4s %-62s %14.6g  %s\n", k.id.c_str(), k.name.c_str(), k.measured,
                        k.rel == Rel::Report ? "(reported)"
                        : k.pass()           ? "pass"
                                             : "FAIL");
            all.push_back(k);
        }
        std::fflush(stdout);
    };

    if (want("block")) {
        std::vector<BlockImpactResult> runs;
        add_case("block", block_impact_suite(quick ? 10 : 20, &runs));
        for (size_t i = 0; i < runs.size(); ++i)
            runs[i].series.write(path("block_impact_" + std::to_string(i) + ".csv"));
    }
    if (want("disk"))
        add_case("disk",
                 disk_impact_suite(quick ? DiskImpactOptions::quick() : DiskImpactOptions{}, out));
    if (want("slide"))
        add_case("slide",
                 sliding_block_suite(quick ? SlidingOptions::quick() : SlidingOptions{}, out));
    if (want("field")) add_case("field", field_maps_suite(out));
    // paper Figs. 15-18: the 6-node composite element, options (b) and (a) of paper §2.4
    if (want("field")) add_case("field_composite", composite_field_maps_suite(out));
    if (want("hertz"))
        add_case("hertz",
                 hertz_suite(quick ? HertzOptions::quick() : HertzOptions::full(), out, true));
    // T20 is centred on the reduced resolution in both modes (sensitivity.hpp, NOTES.md)
    if (want("sensitivity")) add_case("sensitivity", sensitivity_suite(SensitivityOptions{}, out));
    if (want("legacy")) {
        // reduced resolution in both modes: baselines A and B on the perturbed platform cost
        // ~4 min CPU at h = 0.1 m (their stable dt shrinks with the distorted elements)
        std::vector<Check> c = legacy_block_suite(10, true, out);
        SlidingOptions lo = SlidingOptions::quick();
        for (const Check& k : legacy_sliding_suite(lo, true, out))
            c.push_back(k);
        add_case("legacy", c);
    }
    if (want("composite"))
        add_case("composite", composite_dynamics_suite(quick ? CompositeDynamicsOptions::quick()
                                                             : CompositeDynamicsOptions::full(),
                                                       out));

    // spec fracture.md §11 V1 (examples/07_pull_apart): the same run in both modes (60 triangles)
    if (want("pull_apart")) add_case("pull_apart", pull_apart_suite(out));
    // V2: mode II of the same line, sigma_n = 0, -5, -10 MPa (the same runs in both modes)
    if (want("shear")) add_case("shear", shear_suite(out));
    // V3, V3b: penalty sensitivity (structured mesh; + 3 unstructured meshes in full mode), time
    // step
    if (want("penalty"))
        add_case("penalty", penalty_suite(quick ? PenaltyOptions::quick() : PenaltyOptions{}, out));
    // V7 on V1: the inclined jointed line at h, h/2, h/4 x 3 meshes (quick: h only)
    if (want("refinement"))
        add_case("refinement",
                 refinement_suite(quick ? RefinementOptions::quick() : RefinementOptions{}, out));

    for (const std::string& n : only) {
        if (ran.count(n) == 0) {
            std::fprintf(stderr, "fdem_validate: unknown case '%s' in --only\n", n.c_str());
            return 2;
        }
    }
    std::printf("%zu checks, %d failed; results in %s\n", all.size(), failed, out.c_str());
    return failed ? 1 : 0;
}
