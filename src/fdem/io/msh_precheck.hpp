// Structural pre-check of .msh files before they reach Gmsh. Gmsh 4.8.4 trusts the counts and
// tags in a file: fuzzing (tests/fuzz, mesh target) and crafted files made it
//   - crash (SEGV in MElementFactory::create) on an ASCII MSH 2 element line with fewer node ids
//     than its type needs;
//   - allocate tens of GB (binary MSH 2 element block header with a negative tag count; MSH 4.1
//     node/element totals, block sizes, entity physical/bounding counts) before reading the data;
//   - write past its node and element caches when the blocks hold more than the header's total;
//   - crash (SEGV in getMeshVertexByTag(int)) on an MSH 4.1 node tag beyond the int range;
//   - crash (SEGV in GModel::setPhysicalName) on an MSH 4.1 $PhysicalNames dimension beyond 3
//     (fuzzing, tests/fuzz/crashes/mesh/crash-776e4e7...);
//   - crash (SEGV in _associateEntityWithMeshVertices) on an MSH 2 element whose node is one
//     beyond the last of a dense 1-based numbering (an off-by-one bound check; fuzzing).
// The walker below reads the file the way Gmsh does (sections found with fgets(256) lines and
// matched by prefix, ASCII values with scanf semantics, binary blocks with fread) and rejects any
// such value before Gmsh sees it. It does not validate what Gmsh itself reports cleanly (an
// undefined node, a truncated section): those keep Gmsh's message.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <utility>

namespace fdem::io {

/// Throws InputError (file:line, the section and the byte offset for binary data) if the .msh
/// file at path holds a value that would make Gmsh 4.8 crash or allocate without bound:
///  - the file's first section is not $MeshFormat, or a second $MeshFormat follows;
///  - a version other than MSH 2.x or 4.1, a file type other than 0 (ASCII) or 1 (binary), a
///    binary data size other than 8, a binary byte-order mark other than 1;
///  - sections fdem does not read and Gmsh would interpret ($ParametricNodes, $Periodic,
///    $PartitionedEntities, $GhostElements, $Parametrizations, post-processing data);
///  - a count larger than the bytes left in the file can hold (at least 2 bytes per ASCII value,
///    the exact record size for binary data), a negative count, blocks holding more entries than
///    their section header's total (or fewer);
///  - an unknown element type, a node or element tag outside 1..2147483647 (MSH 4.1);
///  - a $PhysicalNames dimension outside 0..3;
///  - an MSH 2 element node that the last $Nodes section does not define;
///  - in ASCII MSH 2, an $Elements line whose field count does not match its type.
/// A file without any section (e.g. empty) passes: Gmsh reads an empty model from it.
void precheck_msh(const std::string& path);

/// The physical names of a .msh file as Gmsh 4.8 sets them from $PhysicalNames, and where that
/// section lies, for reading a file with very many names without Gmsh's quadratic name lookup
/// (GModel::setPhysicalName scans all earlier names; issue #16). Filled by precheck_msh(path,
/// names); `plain` is false unless there is exactly one $PhysicalNames section (MSH 2.2 or 4.1)
/// whose every entry is "dim tag \"name\"" with dim 0..3, a name of 1 to 99 printable characters
/// and nothing after the closing quote, followed by its $EndPhysicalNames line.
struct MshPhysicalNames {
    bool plain = false;
    /// (dim, tag) -> name, as Gmsh keeps them: the first name of a key wins, and a name already
    /// given to a group of the same dimension is not given again
    std::map<std::pair<int, int>, std::string> names;
    size_t section_begin = 0;  ///< byte offset of the "$PhysicalNames" line
    size_t section_end = 0;    ///< byte offset just past the "$EndPhysicalNames" line
    size_t entries = 0;        ///< entries in the section
};

/// precheck_msh(path), also collecting the physical names (names may be nullptr).
void precheck_msh(const std::string& path, MshPhysicalNames* names);

}  // namespace fdem::io
