// The structure check of a .msh file, made before gmsh reads it.
//
// gmsh parses .msh files in its own code and trusts what they say. An element on a node tag it
// cannot look up crashes it (SIGSEGV): gmsh 4.8 looks nodes up by an int, so a tag past 2^31 or
// a negative one becomes a wild index. Blocks that hold more nodes than their header counts, or
// a physical name of dimension 7, make it write or read past its arrays; a header that claims
// 3e8 nodes makes it reserve gigabytes and read on. A crash cannot be caught in the process
// (a sweep's run dies by signal 11), so the file is checked here first, against everything
// gmsh relies on.
//
// Why a check in this process rather than reading the file in a child process: parsing the four
// sections gmsh reads is cheap (one pass over bytes that gmsh reads again anyway, a few ms for
// a coarse cap) and deterministic, and it names the line and what is wrong, where a child that
// dies says only "signal 11". A child would also have to be a fork of a process that may run
// OpenMP threads and holds gmsh's library-wide state, or an exec of a separate reader program
// that every install must ship and find. The cost is that the check must know the format: it
// reads MSH 4.1 only (ASCII and binary), the format gmsh has written since version 4.1 and the
// one docs/shells.md asks for; older versions (2.x, 3.0, 4.0), which gmsh still reads through
// other parsers, are refused with the command that converts them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace snapjump::mesh {

// Throws MeshError, naming the file, the line (or the byte, in binary data), the section and
// what is wrong, unless the file is an MSH 4.1 file gmsh can read safely: a $MeshFormat of
// version 4.1; $Entities, $Nodes and $Elements in that order, once each, closed by their $End
// lines; every count within what the rest of the file can hold (checked before anything is
// read or reserved for it); node tags from 1 to 2^31 - 1 and unique; every element of a type
// gmsh knows, of its block's dimension, on an entity $Entities declares, its node tags among
// the nodes; $PhysicalNames of dimension 0 to 3 with a quoted name. A section gmsh does not
// know is skipped as gmsh skips it; the sections gmsh reads that snapjump does not use
// ($Periodic, $PartitionedEntities, $NodeData, ...) are refused.
void check_msh_file(const std::filesystem::path& path);

// The same check on a file's bytes; `name` is the file the messages name.
void check_msh_bytes(std::string_view bytes, const std::string& name);

// A gmsh element type the check accepts (1 to 31: points, lines, triangles, quadrangles,
// tetrahedra, hexahedra, prisms and pyramids up to the orders gmsh numbers there): its
// dimension and number of nodes; nothing for another type.
struct MshElementType {
  int dim, nodes;
};
std::optional<MshElementType> msh_element_type(std::int64_t type);

}  // namespace snapjump::mesh
