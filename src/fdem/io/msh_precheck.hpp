// Structural pre-check of ASCII MSH 2 files before they reach Gmsh: Gmsh 4.8 crashes (SEGV in
// MElementFactory::create, found by tests/fuzz mesh target) on an $Elements line with fewer node
// tags than its element type needs. MSH 4 and binary files are not pre-checked.
#pragma once

#include <string>

namespace fdem::io {

/// Throws InputError (file:line) if the $Elements section of an ASCII MSH 2 file is malformed:
/// its count, non-integer fields, an unknown element type or a field count that does not match
/// the type (undefined node ids are left to Gmsh, which reports them). Other files pass.
void precheck_msh(const std::string& path);

}  // namespace fdem::io
