// Write-then-rename helper: a file that either keeps its previous content or holds the complete
// new content, so a run killed mid-write never leaves a truncated frame or series file.
#pragma once

#include <cstdio>
#include <string>

namespace fdem {

/// Opens "<path>.tmp" for binary writing; commit() closes it and renames it over path
/// (rename(2) is atomic within one directory on POSIX file systems). If the object is destroyed
/// without commit() (an exception while writing), the temporary file is removed and path is left
/// untouched. No fsync: this protects against a killed process, not against a power loss.
///
/// Errors (cannot open, short write, rename failure) throw std::runtime_error whose message
/// names the file and the system error; callers add step/time context (SimulationError).
class AtomicFile {
public:
    explicit AtomicFile(std::string path);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::FILE* get() const { return file_; }
    const std::string& path() const { return path_; }

    /// fwrite that throws on a short write.
    void write(const void* data, size_t bytes);
    void write(const std::string& text) { write(text.data(), text.size()); }

    /// Close the temporary file and rename it to path. Throws on failure.
    void commit();

private:
    std::string path_;
    std::string tmp_path_;
    std::FILE* file_ = nullptr;
};

}  // namespace fdem
