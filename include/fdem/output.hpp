// Output: VTU frames (binary appended), PVD series for ParaView, CSV energy history.
// Fields and units: docs/output.md.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "fdem/model.hpp"
#include "fdem/state.hpp"

namespace fdem {

/// Write one VTU frame (UnstructuredGrid, binary appended raw data, written atomically:
/// temporary file then rename). Point data: displacement, velocity, force, contact_force;
/// cell data: stress (Cauchy, 3 comps xx,yy,xy), strain (Green-Lagrange), body, material.
void write_vtu(const std::string& path, const Model& m, const State& s);

/// ParaView time series: collects (time, file) and rewrites the .pvd after each frame.
class PvdSeries {
public:
    explicit PvdSeries(std::string path) : path_(std::move(path)) {}
    void add(Real time, const std::string& relative_file);

private:
    std::string path_;
    std::vector<std::pair<Real, std::string>> frames_;
};

/// CSV history of energies and counters, one row per output interval.
class HistoryWriter {
public:
    explicit HistoryWriter(const std::string& path);
    ~HistoryWriter();
    HistoryWriter(const HistoryWriter&) = delete;
    HistoryWriter& operator=(const HistoryWriter&) = delete;
    void write(const Model& m, const State& s);

private:
    std::FILE* file_ = nullptr;
};

}  // namespace fdem
