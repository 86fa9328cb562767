// Typed TOML field readers with located error messages (see toml_fields.hpp).
#include "io/toml_fields.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <fmt/format.h>

namespace fdem::io {

SourceText::SourceText(std::string name_, const std::string& text) : name(std::move(name_)) {
    size_t start = 0;
    while (start <= text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) {
            end = text.size();
        }
        std::string l = text.substr(start, end - start);
        if (!l.empty() && l.back() == '\r') {
            l.pop_back();
        }
        lines.push_back(std::move(l));
        start = end + 1;
    }
}

std::string SourceText::line(int n) const {
    if (n < 1 || n > static_cast<int>(lines.size())) {
        return {};
    }
    return lines[static_cast<size_t>(n - 1)];
}

int edit_distance(std::string_view a, std::string_view b) {
    std::vector<int> prev(b.size() + 1), cur(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) {
        prev[j] = static_cast<int>(j);
    }
    for (size_t i = 1; i <= a.size(); ++i) {
        cur[0] = static_cast<int>(i);
        for (size_t j = 1; j <= b.size(); ++j) {
            const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                              std::tolower(static_cast<unsigned char>(b[j - 1]));
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (same ? 0 : 1)});
        }
        std::swap(prev, cur);
    }
    return prev[b.size()];
}

std::string closest(std::string_view word, const std::vector<std::string>& candidates) {
    std::string best;
    int best_d = 1 << 30;
    for (const std::string& c : candidates) {
        const int d = edit_distance(word, c);
        if (d < best_d) {
            best_d = d;
            best = c;
        }
    }
    // a typo: at most 2 edits, or a third of the word for long names
    const int limit = std::max(2, static_cast<int>(word.size()) / 3);
    return best_d <= limit ? best : std::string{};
}

std::string quoted_list(const std::vector<std::string>& items) {
    std::string out;
    for (size_t i = 0; i < items.size(); ++i) {
        out += (i ? ", \"" : "\"") + items[i] + "\"";
    }
    return out;
}

std::string describe_value(const toml::node& n) {
    if (const auto* s = n.as_string()) {
        return fmt::format("\"{}\"", s->get());
    }
    if (const auto* i = n.as_integer()) {
        return fmt::format("{}", i->get());
    }
    if (const auto* f = n.as_floating_point()) {
        return fmt::format("{}", f->get());
    }
    if (const auto* b = n.as_boolean()) {
        return b->get() ? "true" : "false";
    }
    if (const auto* a = n.as_array()) {
        std::string out = "[";
        for (size_t i = 0; i < a->size(); ++i) {
            out += (i ? ", " : "") + describe_value(*a->get(i));
        }
        return out + "]";
    }
    if (n.is_table()) {
        return "a table";
    }
    return "a date/time";
}

std::string describe_type(const toml::node& n) {
    switch (n.type()) {
        case toml::node_type::string:
            return "a string";
        case toml::node_type::integer:
        case toml::node_type::floating_point:
            return "a number";
        case toml::node_type::boolean:
            return "a boolean";
        case toml::node_type::array:
            return "an array";
        case toml::node_type::table:
            return "a table";
        default:
            return "a date/time";
    }
}

bool Bounds::contains(Real v) const {
    if (lo && (lo_open ? !(v > *lo) : !(v >= *lo))) {
        return false;
    }
    if (hi && (hi_open ? !(v < *hi) : !(v <= *hi))) {
        return false;
    }
    return true;
}

std::string Bounds::text() const {
    if (lo && hi) {
        return fmt::format("in {}{}, {}{}", lo_open ? "(" : "[", *lo, *hi, hi_open ? ")" : "]");
    }
    if (lo) {
        return fmt::format("{} {}", lo_open ? ">" : ">=", *lo);
    }
    if (hi) {
        return fmt::format("{} {}", hi_open ? "<" : "<=", *hi);
    }
    return "finite";
}

[[noreturn]] void fail_at(const SourceText& src, const toml::node& n, const std::string& key,
                          const std::string& msg) {
    const auto& b = n.source().begin;
    const int line = static_cast<int>(b.line), col = static_cast<int>(b.column);
    throw InputError({src.name, line, col}, key, msg, src.line(line));
}

Fields::Fields(const SourceText& src, const toml::table& table, std::string context,
               std::string path, std::vector<std::string> allowed)
    : src_(src), table_(table), context_(std::move(context)), path_(std::move(path)) {
    // unknown keys first, in file order, so a typo is reported as a typo and not as a
    // missing required key
    std::vector<std::pair<toml::source_position, std::string>> unknown;
    for (const auto& [k, v] : table_) {
        if (std::find(allowed.begin(), allowed.end(), k.str()) == allowed.end()) {
            unknown.push_back({k.source().begin, std::string(k.str())});
        }
    }
    if (unknown.empty()) {
        return;
    }
    std::sort(unknown.begin(), unknown.end(), [](const auto& a, const auto& b) {
        return a.first.line < b.first.line ||
               (a.first.line == b.first.line && a.first.column < b.first.column);
    });
    const auto& [pos, key] = unknown.front();
    const std::string guess = closest(key, allowed);
    const std::string hint = guess.empty()
                                 ? fmt::format("; valid keys are {}", quoted_list(allowed))
                                 : fmt::format("; did you mean '{}'?", guess);
    const int line = static_cast<int>(pos.line), col = static_cast<int>(pos.column);
    throw InputError({src_.name, line, col}, full_key(key),
                     fmt::format("{}: unknown key '{}'{}", context_, key, hint), src_.line(line));
}

std::string Fields::full_key(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void Fields::fail(const toml::node& n, std::string_view key, const std::string& msg) const {
    fail_at(src_, n, full_key(key), fmt::format("{}: {}", context_, msg));
}

void Fields::fail_missing(std::string_view key, const std::string& what) const {
    const auto& b = table_.source().begin;
    const int line = static_cast<int>(b.line), col = static_cast<int>(b.column);
    throw InputError({src_.name, line, col}, full_key(key),
                     fmt::format("{}: missing required key '{}' ({})", context_, key, what),
                     src_.line(line));
}

void Fields::fail_table(const std::string& msg) const {
    const auto& b = table_.source().begin;
    const int line = static_cast<int>(b.line), col = static_cast<int>(b.column);
    throw InputError({src_.name, line, col}, path_, fmt::format("{}: {}", context_, msg),
                     src_.line(line));
}

SourceLocation Fields::location(std::string_view key) const {
    const toml::node* n = table_.get(key);
    const auto& b = n ? n->source().begin : table_.source().begin;
    return {src_.name, static_cast<int>(b.line), static_cast<int>(b.column)};
}

const toml::node& Fields::required(std::string_view key, const std::string& what) const {
    const toml::node* n = table_.get(key);
    if (!n) {
        fail_missing(key, what);
    }
    return *n;
}

Real Fields::real(std::string_view key, std::optional<Real> def, const char* unit, Bounds b) const {
    const std::string what = fmt::format("a number{}{}, {}", *unit ? " in " : "", unit, b.text());
    const toml::node* n = table_.get(key);
    if (!n) {
        if (!def) {
            fail_missing(key, what);
        }
        return *def;
    }
    if (!n->is_number()) {
        fail(*n, key,
             fmt::format("{} must be {}, got {} {}", key, what, describe_type(*n),
                         describe_value(*n)));
    }
    const Real v = n->value<double>().value_or(0.0);
    if (!std::isfinite(v)) {
        fail(*n, key, fmt::format("{} must be a finite number, got {}", key, describe_value(*n)));
    }
    if (!b.contains(v)) {
        fail(*n, key, fmt::format("{} must be {}, got {}", key, b.text(), describe_value(*n)));
    }
    return v;
}

bool Fields::boolean(std::string_view key, std::optional<bool> def) const {
    const toml::node* n = table_.get(key);
    if (!n) {
        if (!def) {
            fail_missing(key, "true or false");
        }
        return *def;
    }
    if (!n->is_boolean()) {
        fail(*n, key,
             fmt::format("{} must be true or false, got {} {}", key, describe_type(*n),
                         describe_value(*n)));
    }
    return n->as_boolean()->get();
}

std::string Fields::string(std::string_view key, std::optional<std::string> def) const {
    const toml::node* n = table_.get(key);
    if (!n) {
        if (!def) {
            fail_missing(key, "a string");
        }
        return *def;
    }
    if (!n->is_string()) {
        fail(*n, key,
             fmt::format("{} must be a string, got {} {}", key, describe_type(*n),
                         describe_value(*n)));
    }
    std::string s = n->as_string()->get();
    if (s.empty()) {
        fail(*n, key, fmt::format("{} must not be empty", key));
    }
    return s;
}

std::string Fields::choice(std::string_view key, std::optional<std::string> def,
                           const std::vector<std::string>& choices) const {
    const std::string what = "one of " + quoted_list(choices);
    const toml::node* n = table_.get(key);
    if (!n) {
        if (!def) {
            fail_missing(key, what);
        }
        return *def;
    }
    if (!n->is_string()) {
        fail(*n, key,
             fmt::format("{} must be {}, got {} {}", key, what, describe_type(*n),
                         describe_value(*n)));
    }
    const std::string s = n->as_string()->get();
    if (std::find(choices.begin(), choices.end(), s) == choices.end()) {
        const std::string guess = closest(s, choices);
        fail(*n, key,
             fmt::format("{} must be {}, got \"{}\"{}", key, what, s,
                         guess.empty() ? "" : fmt::format("; did you mean \"{}\"?", guess)));
    }
    return s;
}

Vec2 Fields::vec2(std::string_view key, std::optional<Vec2> def, const char* unit) const {
    const std::string what = fmt::format("[x, y], two numbers in {}", unit);
    const toml::node* n = table_.get(key);
    if (!n) {
        if (!def) {
            fail_missing(key, what);
        }
        return *def;
    }
    const toml::array* a = n->as_array();
    if (!a || a->size() != 2 || !a->get(0)->is_number() || !a->get(1)->is_number()) {
        fail(*n, key,
             fmt::format("{} must be {}, got {}", key, what,
                         a ? describe_value(*n) : describe_type(*n) + " " + describe_value(*n)));
    }
    const Vec2 v{a->get(0)->value<double>().value_or(0.0),
                 a->get(1)->value<double>().value_or(0.0)};
    if (!std::isfinite(v.x) || !std::isfinite(v.y)) {
        fail(*n, key, fmt::format("{} must be finite, got {}", key, describe_value(*n)));
    }
    return v;
}

void Fields::components(std::string_view key, std::optional<std::pair<bool, bool>> def, bool& has_x,
                        bool& has_y) const {
    const std::string what = R"(a list of components, e.g. ["x"], ["y"] or ["x", "y"])";
    const toml::node* n = table_.get(key);
    if (!n) {
        if (!def) {
            fail_missing(key, what);
        }
        has_x = def->first;
        has_y = def->second;
        return;
    }
    const toml::array* a = n->as_array();
    if (!a || a->empty()) {
        fail(*n, key, fmt::format("{} must be {}, got {}", key, what, describe_value(*n)));
    }
    has_x = has_y = false;
    for (const toml::node& c : *a) {
        const auto s = c.value<std::string>();
        if (!s || (*s != "x" && *s != "y")) {
            fail(c, key,
                 fmt::format("{} entries must be \"x\" or \"y\", got {}", key, describe_value(c)));
        }
        bool& flag = *s == "x" ? has_x : has_y;
        if (flag) {
            fail(c, key, fmt::format("{} lists \"{}\" twice", key, *s));
        }
        flag = true;
    }
}

}  // namespace fdem::io
