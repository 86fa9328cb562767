// fdem_validate: reproduces the paper's examples (spec §5, checks of spec §8 T13-T18, T20) and
// writes, into --out DIR, checks.csv (one row per check: measured, expected, tolerance, pass)
// plus one CSV per plotted series. scripts/validate runs it and turns DIR into
// docs/validation/README.md and its figures. Exit code 0 = every check passed, 1 = a check
// failed, 2 = bad command line.
//
//   fdem_validate [--quick] [--out DIR] [--only NAME[,NAME...]]
//
// --quick uses the reduced resolutions of the CTest suite (label `validation`); the default is
// the full resolution of the spec (label `full`). NAME: block, disk, slide, field.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "validation/cases/block_impact.hpp"
#include "validation/cases/composite_field_maps.hpp"
#include "validation/cases/disk_impact.hpp"
#include "validation/cases/field_maps.hpp"
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
            std::fprintf(
                stderr,
                "usage: fdem_validate [--quick] [--out DIR] [--only block,disk,slide,field]\n");
            return 2;
        }
    }
    std::filesystem::create_directories(out);
    auto want = [&](const char* n) { return only.empty() || only.count(n) > 0; };
    auto path = [&](const std::string& f) { return (std::filesystem::path(out) / f).string(); };
    std::vector<Check> all;
    auto add = [&](const std::vector<Check>& c) {
        for (const Check& k : c) {
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
        add(block_impact_suite(quick ? 10 : 20, &runs));
        for (size_t i = 0; i < runs.size(); ++i)
            runs[i].series.write(path("block_impact_" + std::to_string(i) + ".csv"));
    }
    if (want("disk"))
        add(disk_impact_suite(quick ? DiskImpactOptions::quick() : DiskImpactOptions{}, out));
    if (want("slide"))
        add(sliding_block_suite(quick ? SlidingOptions::quick() : SlidingOptions{}, out));
    if (want("field")) add(field_maps_suite(out));
    // paper Figs. 15-18: the 6-node composite element, options (b) and (a) of paper §2.4
    if (want("field")) add(composite_field_maps_suite(out));

    FILE* f = std::fopen(path("checks.csv").c_str(), "w");
    if (!f) {
        std::fprintf(stderr, "cannot write %s\n", path("checks.csv").c_str());
        return 1;
    }
    std::fprintf(f, "id,name,measured,expected,relation,tolerance,tolerance_text,unit,pass,why\n");
    int failed = 0;
    for (const Check& k : all) {
        const bool ok = k.pass();
        if (!ok) ++failed;
        std::fprintf(f, "%s,%s,%.8g,%.8g,%s,%.8g,%s,%s,%s,%s\n", k.id.c_str(),
                     csv_escape(k.name).c_str(), k.measured, k.expected, rel_name(k.rel), k.tol,
                     csv_escape(k.tolerance_text()).c_str(), csv_escape(k.unit).c_str(),
                     k.rel == Rel::Report ? "report"
                     : ok                 ? "pass"
                                          : "FAIL",
                     csv_escape(k.why).c_str());
    }
    std::fclose(f);
    std::printf("%zu checks, %d failed; results in %s\n", all.size(), failed, out.c_str());
    return failed ? 1 : 0;
}
