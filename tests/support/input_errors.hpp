// Helpers for the input-error tests (tests/input): the message of the InputError a scenario
// raises, pinned by the tests.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "fdem/error.hpp"
#include "fdem/mesh.hpp"
#include "fdem/scenario.hpp"

namespace fdem::support {

/// The InputError message of scenario `text` loaded as "bad.toml" with meshes resolved in dir;
/// a test failure (and "") if it loads without one.
inline std::string scenario_error(const std::string& text,
                                  const std::string& dir = FDEM_TEST_DATA_DIR) {
    try {
        load_scenario_from_string(text, "bad.toml", dir);
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InputError for:\n" << text;
    return {};
}

/// s with the first occurrence of `from` replaced by `to`; a test failure (and s unchanged) if
/// `from` is not in s.
inline std::string replace_first(std::string s, const std::string& from, const std::string& to) {
    const size_t p = s.find(from);
    EXPECT_NE(p, std::string::npos) << from;
    if (p != std::string::npos) {
        s.replace(p, from.size(), to);
    }
    return s;
}

/// Writes text to the file `name` in the test temp folder; its path, normalized as the scenario
/// reader shows paths (TempDir() ends with a slash).
inline std::string write_temp(const std::string& name, const std::string& text) {
    const std::string path =
        std::filesystem::path(::testing::TempDir() + "/" + name).lexically_normal().string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

/// The InputError message of reading the mesh file at path with mesh_size; a test failure
/// (and "") if it reads without one.
inline std::string mesh_error(const std::string& path, Real mesh_size = 0) {
    try {
        read_mesh(path, mesh_size);
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InputError for " << path;
    return {};
}

}  // namespace fdem::support
