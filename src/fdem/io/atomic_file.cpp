// Write-then-rename helper (see atomic_file.hpp).
#include "io/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace fdem {

namespace {

std::runtime_error io_error(const std::string& what, const std::string& path, int err) {
    return std::runtime_error(what + " '" + path + "': " + std::strerror(err) +
                              " (check that the output directory exists and is writable)");
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), tmp_path_(path_ + ".tmp") {
    file_ = std::fopen(tmp_path_.c_str(), "wb");
    if (file_ == nullptr) {
        throw io_error("cannot open output file", tmp_path_, errno);
    }
}

AtomicFile::~AtomicFile() {
    // not committed: drop the partial temporary file, keep the previous content of path
    if (file_ != nullptr) {
        std::fclose(file_);
        std::remove(tmp_path_.c_str());
    }
}

void AtomicFile::write(const void* data, size_t bytes) {
    if (bytes == 0) return;
    if (std::fwrite(data, 1, bytes, file_) != bytes) {
        throw io_error("short write to", tmp_path_, errno);
    }
}

void AtomicFile::commit() {
    std::FILE* f = file_;
    file_ = nullptr;
    const bool flushed = std::fflush(f) == 0;
    const int flush_err = errno;
    const bool closed = std::fclose(f) == 0;
    if (!flushed || !closed) {
        std::remove(tmp_path_.c_str());
        throw io_error("cannot finish writing", tmp_path_, flushed ? errno : flush_err);
    }
    if (std::rename(tmp_path_.c_str(), path_.c_str()) != 0) {
        const int err = errno;
        std::remove(tmp_path_.c_str());
        throw io_error("cannot rename temporary file to", path_, err);
    }
}

}  // namespace fdem
