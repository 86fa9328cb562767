// libFuzzer target: the mesh reader (read_mesh on a .msh file). The input is written to a
// temporary .msh file; read_mesh must return a mesh or raise InputError. Another exception, a
// crash or an exit inside gmsh is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "fdem/error.hpp"
#include "fdem/mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path =
        "/tmp/fdem_mesh_fuzz_" + std::to_string(static_cast<long>(getpid())) + ".msh";
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr) std::abort();
    if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
    std::fclose(f);
    try {
        (void)fdem::read_mesh(path, 0);
    } catch (const fdem::InputError&) {
        // expected for bad input
    } catch (const std::exception& e) {
        std::fprintf(stderr, "unexpected exception (not InputError): %s\n", e.what());
        std::abort();
    }
    return 0;
}
