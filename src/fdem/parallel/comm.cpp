// Collective failure (spec parallel-and-python.md D9): see parallel/comm.hpp.
#include "parallel/comm.hpp"

#include <cstring>
#include <exception>
#include <stdexcept>

#include "fdem/error.hpp"

namespace fdem {

namespace {

// fields as <length>:<bytes>, so any text (newlines, colons) survives
void put_field(std::string& out, const std::string& f) {
    out += std::to_string(f.size());
    out += ':';
    out += f;
}

std::string get_field(const std::string& in, size_t& pos) {
    const size_t colon = in.find(':', pos);
    if (colon == std::string::npos) throw std::runtime_error("corrupt error record");
    const size_t n = std::stoul(in.substr(pos, colon - pos));
    if (colon + 1 + n > in.size()) throw std::runtime_error("corrupt error record");
    std::string f = in.substr(colon + 1, n);
    pos = colon + 1 + n;
    return f;
}

std::string bits_of(double x) {
    uint64_t b = 0;
    std::memcpy(&b, &x, sizeof b);
    return std::to_string(b);
}

double double_of(const std::string& s) {
    const uint64_t b = std::stoull(s);
    double x = 0;
    std::memcpy(&x, &b, sizeof x);
    return x;
}

}  // namespace

std::string encode_error(const std::exception& e) {
    std::string out;
    if (const auto* ie = dynamic_cast<const InputError*>(&e)) {
        put_field(out, "input");
        put_field(out, ie->location().file);
        put_field(out, std::to_string(ie->location().line));
        put_field(out, std::to_string(ie->location().column));
        put_field(out, ie->key());
        put_field(out, ie->message());
        put_field(out, ie->source_line());
    } else if (const auto* se = dynamic_cast<const SimulationError*>(&e)) {
        put_field(out, "simulation");
        put_field(out, std::to_string(se->step()));
        put_field(out, bits_of(se->time()));  // the exact time, so what() prints the same
        put_field(out, se->entity());
        put_field(out, se->message());
    } else {
        put_field(out, "other");
        put_field(out, e.what());
    }
    return out;
}

void throw_decoded_error(const std::string& text) {
    size_t pos = 0;
    const std::string kind = get_field(text, pos);
    if (kind == "input") {
        SourceLocation loc;
        loc.file = get_field(text, pos);
        loc.line = std::stoi(get_field(text, pos));
        loc.column = std::stoi(get_field(text, pos));
        std::string key = get_field(text, pos);
        std::string msg = get_field(text, pos);
        std::string line = get_field(text, pos);
        throw InputError(std::move(loc), std::move(key), std::move(msg), std::move(line));
    }
    if (kind == "simulation") {
        const int64_t step = std::stoll(get_field(text, pos));
        const double time = double_of(get_field(text, pos));
        std::string entity = get_field(text, pos);
        std::string msg = get_field(text, pos);
        throw SimulationError(step, time, std::move(entity), std::move(msg));
    }
    throw std::runtime_error(get_field(text, pos));
}

void run_collectively(const Comm& comm, const std::function<void()>& fn) {
    std::string error;
    std::exception_ptr original;
    try {
        fn();
    } catch (const std::exception& e) {
        original = std::current_exception();
        error = encode_error(e);
    } catch (...) {
        original = std::current_exception();
        error = encode_error(std::runtime_error("unknown exception"));
    }
    const bool failed = original != nullptr;
    if (comm.size() == 1) {
        if (failed) std::rethrow_exception(original);
        return;
    }
    // the lowest failing rank speaks for all (an exact MIN: the same on every process)
    const int root = static_cast<int>(comm.min(failed ? comm.rank() : comm.size()));
    if (root == comm.size()) return;
    comm.broadcast(error, root);
    throw_decoded_error(error);
}

}  // namespace fdem
