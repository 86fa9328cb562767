// libFuzzer target: the scenario reader (load_scenario_from_string). Any input must either load
// or raise InputError; another exception type or a crash is a finding. Meshes resolve against
// tests/data (the seeds use its small pre-meshed .msh files; .geo meshing is avoided because
// gmsh is slow and a fuzzed mesh_size could ask for billions of elements).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "fdem/error.hpp"
#include "fdem/scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    // skip inputs that would make gmsh mesh a .geo file (slow, global), see above
    if (text.find(".geo") != std::string::npos) return 0;
    try {
        (void)fdem::load_scenario_from_string(text, "fuzz.toml", FDEM_TEST_DATA_DIR);
    } catch (const fdem::InputError&) {
        // expected for bad input
    } catch (const std::exception& e) {
        std::fprintf(stderr, "unexpected exception (not InputError): %s\n", e.what());
        std::abort();
    }
    return 0;
}
