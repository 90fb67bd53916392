// An on-disk cache of convex decompositions (convex_decomposition.h), so that a robot whose
// meshes are decomposed loads as fast the second time as with plain hulls.
//
// One file per decomposition, named by a 64-bit key (FNV-1a) over an algorithm version, the
// mesh's vertex and triangle data (scale applied) and the options. The file repeats the key,
// the counts and the options; a reader trusts nothing in it: every number is parsed with
// bounds, and a file that is malformed, belongs to another mesh, or leaves a mesh vertex
// outside every piece is ignored (and rewritten). Files are written to a temporary name and
// renamed, so concurrent loads never see half a file.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "dss/mesh/convex_decomposition.h"

namespace dss::mesh {

/// Bumped whenever decomposeConvex can give other pieces for the same input.
inline constexpr int kDecompositionVersion = 3;

/// The cache key of (mesh, options).
std::uint64_t decompositionKey(const TriangleMesh& mesh, const DecompositionOptions& options);

/// The default cache directory: $DSS_CACHE_DIR, else $XDG_CACHE_HOME/dss, else
/// $HOME/.cache/dss; empty when none of them is set.
std::string defaultDecompositionCacheDir();

/// The decomposition of `mesh` stored in `dir`, or nullopt when there is none or the file is
/// unusable (see above). Never throws on a bad file.
std::optional<Decomposition> readCachedDecomposition(const std::string& dir,
                                                     const TriangleMesh& mesh,
                                                     const DecompositionOptions& options);

/// Stores `d` in `dir` (created when missing). False when it cannot (never throws).
bool writeCachedDecomposition(const std::string& dir, const TriangleMesh& mesh,
                              const DecompositionOptions& options, const Decomposition& d);

/// The text of a cache file and its parser, exposed for tests and the fuzz target. `parse`
/// returns nullopt for anything but a well-formed file of this key with at most
/// options.max_pieces pieces (no coverage check: readCachedDecomposition adds it).
std::string formatDecomposition(std::uint64_t key, const TriangleMesh& mesh,
                                const DecompositionOptions& options, const Decomposition& d);
std::optional<Decomposition> parseDecomposition(const std::string& text, std::uint64_t key,
                                                const TriangleMesh& mesh,
                                                const DecompositionOptions& options);

/// decomposeConvex through the cache in `dir` (empty: no cache). `from_cache` (optional)
/// tells whether the pieces came from a file.
Decomposition decomposeCached(const TriangleMesh& mesh, const DecompositionOptions& options,
                              const std::string& what, const std::string& dir,
                              bool* from_cache = nullptr);

}  // namespace dss::mesh
