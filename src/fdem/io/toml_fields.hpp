// Typed readers for TOML tables that turn every problem into an InputError pointing at the
// offending key or value (file:line:column, the source line and a caret), in one format:
//   <context>: <key> must be <expectation>, got <value>
// Used by the scenario reader (scenario_reader.cpp); style guide §4.6.
#pragma once

#include <toml++/toml.h>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fdem/error.hpp"
#include "fdem/math.hpp"

namespace fdem::io {

/// The text of a scenario, kept so messages can echo the offending line.
struct SourceText {
    std::string name;                ///< file name (or virtual name) used in messages
    std::vector<std::string> lines;  ///< without line terminators

    SourceText(std::string name_, const std::string& text);
    std::string line(int n) const;  ///< 1-based; "" when out of range
};

/// Levenshtein distance (case-insensitive), for "did you mean" suggestions.
int edit_distance(std::string_view a, std::string_view b);

/// The closest candidate to word if it is close enough to be a plausible typo, else "".
std::string closest(std::string_view word, const std::vector<std::string>& candidates);

/// `"a", "b", "c"`, for listing the valid choices in a message.
std::string quoted_list(const std::vector<std::string>& items);

/// Short description of a TOML value for messages: 5e+10, "text", true, [1, 2], a table.
std::string describe_value(const toml::node& n);

/// Name of the type of a node: "a number", "a string", "a boolean", "an array", "a table".
std::string describe_type(const toml::node& n);

/// Inclusive or exclusive bounds of a real value; rendered as "> 0", ">= 0", "in [0, 0.5)".
struct Bounds {
    std::optional<Real> lo, hi;
    bool lo_open = false, hi_open = false;

    static Bounds any() { return {}; }
    static Bounds positive() { return {0.0, std::nullopt, true, false}; }
    static Bounds non_negative() { return {0.0, std::nullopt, false, false}; }
    static Bounds at_least(Real v) { return {v, std::nullopt, false, false}; }
    bool contains(Real v) const;
    std::string text() const;  ///< e.g. "> 0", "in [0, 0.5)"
};

/// Reader for one TOML table. Rejects unknown keys on construction (with a suggestion), then
/// hands out typed values; every failure throws InputError located at the node concerned.
class Fields {
public:
    /// context: how messages name the table, e.g. `[simulation]` or `[[material]] "steel"`.
    /// path: dotted key prefix for InputError::key(), e.g. "material[0]".
    Fields(const SourceText& src, const toml::table& table, std::string context, std::string path,
           std::vector<std::string> allowed);

    const toml::table& table() const { return table_; }
    const std::string& context() const { return context_; }
    void set_context(std::string c) { context_ = std::move(c); }
    bool has(std::string_view key) const { return table_.contains(key); }
    const toml::node* node(std::string_view key) const { return table_.get(key); }

    /// Throw at node n (its begin line/column), naming key.
    [[noreturn]] void fail(const toml::node& n, std::string_view key, const std::string& msg) const;
    /// Throw at the table header: a required key is missing. what = unit and range hint.
    [[noreturn]] void fail_missing(std::string_view key, const std::string& what) const;
    /// Throw at the table header without a key.
    [[noreturn]] void fail_table(const std::string& msg) const;

    /// Real value within bounds; def = nullopt makes the key required. unit goes in messages.
    Real real(std::string_view key, std::optional<Real> def, const char* unit, Bounds b) const;
    bool boolean(std::string_view key, std::optional<bool> def) const;
    /// Non-empty string; def = nullopt makes the key required.
    std::string string(std::string_view key, std::optional<std::string> def) const;
    /// One of choices (exact match); suggests the closest on a typo.
    std::string choice(std::string_view key, std::optional<std::string> def,
                       const std::vector<std::string>& choices) const;
    /// [x, y] with two finite numbers.
    Vec2 vec2(std::string_view key, std::optional<Vec2> def, const char* unit) const;
    /// Component list like ["x", "y"]: non-empty, each "x" or "y", no repeats.
    void components(std::string_view key, std::optional<std::pair<bool, bool>> def, bool& has_x,
                    bool& has_y) const;

    /// Location of a key's value (or of the table when absent), for later checks.
    SourceLocation location(std::string_view key) const;
    std::string full_key(std::string_view key) const;

private:
    const toml::node& required(std::string_view key, const std::string& what) const;

    const SourceText& src_;
    const toml::table& table_;
    std::string context_;
    std::string path_;
};

/// Throw an InputError at node n (file:line:column from the node, line echoed from src).
[[noreturn]] void fail_at(const SourceText& src, const toml::node& n, const std::string& key,
                          const std::string& msg);

}  // namespace fdem::io
