// CsvSeries and csv_field (src/fdem/io/csv_series.cpp): header, flushed rows, restart trimming,
// a changed header, RFC 4180 quoting read back by a minimal parser.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fdem/error.hpp"
#include "fdem/output.hpp"
#include "support/csv.hpp"

namespace fdem {
namespace {

namespace fs = std::filesystem;

fs::path test_file(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path dir = fs::path(::testing::TempDir()) / (std::string("fdem_csv_") + info->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir / name;
}

std::vector<std::string> read_lines(const fs::path& p) {
    std::ifstream in(p);
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);)
        out.push_back(line);
    return out;
}

using testing::parse_csv_line;

TEST(CsvSeries, QuotesOnlyWhatNeedsIt) {
    EXPECT_EQ(csv_field("block"), "block");
    EXPECT_EQ(csv_field("slab/base.ux"), "slab/base.ux");
    EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
    EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
    EXPECT_EQ(csv_field(" pad"), "\" pad\"");
    const std::string header = "step," + csv_field("a,b") + "," + csv_field("q\"x");
    EXPECT_EQ(parse_csv_line(header), (std::vector<std::string>{"step", "a,b", "q\"x"}));
}

TEST(CsvSeries, RestartKeepsRowsUpToTheStepAndAppends) {
    const fs::path p = test_file("t.csv");
    {
        CsvSeries c(p.string(), "step,x");
        for (int k = 1; k <= 5; ++k)
            c.write_line(std::to_string(10 * k) + ",0." + std::to_string(k), 10 * k, 0.0);
        EXPECT_EQ(read_lines(p).size(), 6u);  // flushed per row
    }
    {
        CsvSeries c(p.string(), "step,x", 30);
        EXPECT_FALSE(c.header_changed());
        c.write_line("40,9", 40, 0.0);
    }
    EXPECT_EQ(read_lines(p),
              (std::vector<std::string>{"step,x", "10,0.1", "20,0.2", "30,0.3", "40,9"}));
}

TEST(CsvSeries, RestartUnderAnotherHeaderStartsAfresh) {
    const fs::path p = test_file("t.csv");
    {
        CsvSeries c(p.string(), "step,x");
        c.write_line("10,1", 10, 0.0);
    }
    {
        CsvSeries c(p.string(), "step,x,y", 10);
        EXPECT_TRUE(c.header_changed());
        c.write_line("20,1,2", 20, 0.0);
    }
    EXPECT_EQ(read_lines(p), (std::vector<std::string>{"step,x,y", "20,1,2"}));
}

TEST(CsvSeries, RestartDropsAnIncompleteLastLine) {
    const fs::path p = test_file("t.csv");
    {
        std::ofstream o(p);
        o << "step,x\n10,1\n20,2\n30,3";  // killed in the middle of row 30
    }
    {
        CsvSeries c(p.string(), "step,x", 100);
        c.write_line("30,3", 30, 0.0);
    }
    EXPECT_EQ(read_lines(p), (std::vector<std::string>{"step,x", "10,1", "20,2", "30,3"}));
}

TEST(CsvSeries, UnwritableFileIsASimulationError) {
    EXPECT_THROW(CsvSeries("/nonexistent_dir_fdem/x.csv", "step"), SimulationError);
}

}  // namespace
}  // namespace fdem
