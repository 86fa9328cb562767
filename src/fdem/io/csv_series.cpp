// CSV time series with restart trimming (output.hpp CsvSeries): bodies.csv and probes.csv.
#include <cerrno>
#include <cstdlib>
#include <cstring>

#include <fmt/format.h>

#include "fdem/error.hpp"
#include "fdem/output.hpp"
#include "io/atomic_file.hpp"

namespace fdem {

std::string csv_field(const std::string& text) {
    const bool needs = text.find_first_of(",\"\r\n") != std::string::npos ||
                       (!text.empty() && (text.front() == ' ' || text.back() == ' ' ||
                                          text.front() == '\t' || text.back() == '\t'));
    if (!needs) return text;
    std::string out = "\"";
    for (char c : text) {
        if (c == '"') out += '"';
        out += c;
    }
    out += '"';
    return out;
}

CsvSeries::CsvSeries(std::string path, const std::string& header) : path_(std::move(path)) {
    file_ = std::fopen(path_.c_str(), "w");
    if (file_ == nullptr || std::fputs(header.c_str(), file_) < 0 || std::fputc('\n', file_) < 0 ||
        std::fflush(file_) != 0) {
        throw SimulationError(0, 0.0, path_,
                              std::string("cannot write file: ") + std::strerror(errno) +
                                  " (check that the output directory exists and is writable)");
    }
}

CsvSeries::CsvSeries(std::string path, const std::string& header, int64_t resume_step)
    : path_(std::move(path)) {
    // keep the rows up to resume_step (the step is the first field) under the same header
    std::string kept = header + "\n";
    if (std::FILE* in = std::fopen(path_.c_str(), "r")) {
        std::string line;
        bool first = true;
        int c = 0;
        while (true) {
            line.clear();
            while ((c = std::fgetc(in)) != EOF && c != '\n')
                line += static_cast<char>(c);
            if (c == EOF) break;  // no newline: an incomplete last line, dropped
            if (first) {
                first = false;
                if (line != header) {
                    header_changed_ = true;
                    break;
                }
                continue;
            }
            char* end = nullptr;
            const long long step = std::strtoll(line.c_str(), &end, 10);
            if (end == line.c_str() || *end != ',' || step > resume_step) break;
            kept += line;
            kept += '\n';
        }
        std::fclose(in);
    }
    // rewrite atomically (a kill now keeps the old file), then append
    try {
        AtomicFile out(path_);
        out.write(kept);
        out.commit();
    } catch (const std::runtime_error& e) {
        throw SimulationError(resume_step, 0.0, path_,
                              std::string("cannot rewrite file: ") + e.what());
    }
    open_append(resume_step);
}

void CsvSeries::open_append(int64_t step) {
    file_ = std::fopen(path_.c_str(), "a");
    if (file_ == nullptr) {
        throw SimulationError(step, 0.0, path_,
                              std::string("cannot write file: ") + std::strerror(errno) +
                                  " (check that the output directory exists and is writable)");
    }
}

CsvSeries::~CsvSeries() {
    if (file_ != nullptr) std::fclose(file_);
}

void CsvSeries::write_line(const std::string& line, int64_t step, Real time) {
    if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() ||
        std::fputc('\n', file_) < 0 || std::fflush(file_) != 0) {
        throw SimulationError(step, time, path_,
                              std::string("cannot write row: ") + std::strerror(errno));
    }
}

}  // namespace fdem
