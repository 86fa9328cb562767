// Helpers for the input-error tests (tests/input): the message of the InputError a scenario
// raises, pinned by the tests.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "fdem/error.hpp"
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

}  // namespace fdem::support
