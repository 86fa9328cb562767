// A minimal RFC 4180 CSV reader for the tests of bodies.csv and probes.csv: the files must open
// as CSV (quoted fields with doubled quotes, one record per line).
#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace fdem::testing {

/// Fields of one CSV line.
inline std::vector<std::string> parse_csv_line(const std::string& line) {
    std::vector<std::string> out(1);
    bool quoted = false;
    for (size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
                out.back() += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                out.back() += c;
            }
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            out.emplace_back();
        } else {
            out.back() += c;
        }
    }
    return out;
}

/// Every line of a CSV file, split into fields.
inline std::vector<std::vector<std::string>> read_csv(const std::string& path) {
    std::ifstream in(path);
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(in, line);)
        rows.push_back(parse_csv_line(line));
    return rows;
}

}  // namespace fdem::testing
