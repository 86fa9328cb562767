// The two error channels users see (style guide §4.6):
//   InputError      - bad scenario or mesh; the CLI prints it and exits with code 2.
//   SimulationError - the physics failed during a run (NaN, inverted element, blow-up); exit
//   code 1.
// Programming errors are FDEM_ASSERT (fdem/assert.hpp: Debug and sanitizer builds) and never reach
// users as one of these.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace fdem {

/// Where in a user's file something is. line/column are 1-based; 0 = unknown.
struct SourceLocation {
    std::string file;
    int line = 0;
    int column = 0;
};

/// Bad user input. what() is the complete compiler-style message:
///   file:line:column: error: <message>
///      12 | youngs_modulus = -50e9
///         |                  ^
class InputError : public std::runtime_error {
public:
    InputError(SourceLocation loc, std::string key, std::string message,
               std::string source_line = {});
    const SourceLocation& location() const { return loc_; }
    const std::string& key() const { return key_; }      ///< offending key or entity ("" if none)
    const std::string& message() const { return msg_; }  ///< message without location prefix
    const std::string& source_line() const { return line_; }  ///< the echoed line ("" if none)

private:
    SourceLocation loc_;
    std::string key_;
    std::string msg_;
    std::string line_;
};

/// Runtime numerical failure: names the step, the time, the entity and a remedy.
class SimulationError : public std::runtime_error {
public:
    SimulationError(int64_t step, double time, std::string entity, std::string message);
    int64_t step() const { return step_; }
    double time() const { return time_; }
    const std::string& entity() const { return entity_; }
    const std::string& message() const { return msg_; }  ///< the message after the entity

private:
    int64_t step_;
    double time_;
    std::string entity_;
    std::string msg_;
};

}  // namespace fdem
