// Formatting of the user-facing error messages (see include/fdem/error.hpp).
#include "fdem/error.hpp"

#include <fmt/format.h>

namespace fdem {

namespace {

std::string format_input_error(const SourceLocation& loc, const std::string& msg,
                               const std::string& line) {
    std::string out;
    if (!loc.file.empty()) {
        out += loc.file;
        if (loc.line > 0) {
            out += fmt::format(":{}", loc.line);
            if (loc.column > 0) out += fmt::format(":{}", loc.column);
        }
        out += ": ";
    }
    out += "error: " + msg;
    // echo the offending line with a caret under the column (LAMMPS-style pointer)
    if (!line.empty() && loc.line > 0) {
        const std::string num = std::to_string(loc.line);
        out += fmt::format("\n {} | {}", num, line);
        if (loc.column > 0) {
            out += fmt::format("\n {} | {}^", std::string(num.size(), ' '),
                               std::string(static_cast<size_t>(loc.column - 1), ' '));
        }
    }
    return out;
}

}  // namespace

InputError::InputError(SourceLocation loc, std::string key, std::string message,
                       std::string source_line)
    : std::runtime_error(format_input_error(loc, message, source_line)),
      loc_(std::move(loc)),
      key_(std::move(key)),
      msg_(std::move(message)),
      line_(std::move(source_line)) {}

SimulationError::SimulationError(int64_t step, double time, std::string entity, std::string message)
    : std::runtime_error(
          fmt::format("step {} (t = {:.6g} s): {}: {}", step, time, entity, message)),
      step_(step),
      time_(time),
      entity_(std::move(entity)),
      msg_(std::move(message)) {}

}  // namespace fdem
