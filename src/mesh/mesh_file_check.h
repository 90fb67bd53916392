// What a mesh file must pass before assimp reads it. assimp (5.2 in Debian bookworm) trusts a
// file's declared counts and, on some malformed number lists, never stops reading: a few
// hundred bytes can make it allocate gigabytes or loop. The checks here bound what it will do.
#pragma once

#include <string>

namespace dss::mesh {

/// Throws std::runtime_error naming `path` (and the line or element where there is one) when
///  - the file's extension is not one of the formats read: STL, COLLADA (.dae), OBJ
///    (case-insensitive; assimp picks its reader by the extension, so no other reader runs).
///    assimp's other readers are left out: its PLY reader, for one, aborts the process on a
///    binary face list of length zero (an assertion Debian's build keeps);
///  - a COLLADA number list (<p>, <vcount>, <v>, <h>, <float_array>, <int_array>) holds a
///    character that is neither part of a number nor white space, or a count="N" attribute
///    exceeds the file's size in bytes (every counted item takes at least one byte);
///  - a COLLADA file nests deeper than 256 levels, is not UTF-8, or has an array whose count
///    attribute is missing or differs from its number of values, an accessor without a count
///    or reaching past the array it names, or a primitive list without a count.
void checkMeshFile(const std::string& path);

}  // namespace dss::mesh
