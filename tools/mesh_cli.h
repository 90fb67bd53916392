// The command-line options that choose how robot meshes become convex elements (hulls, or the
// pieces of a convex decomposition: dss/robot/urdf_loader.h), shared by dss_check, dss_plan,
// dss_decompose and dss_bench.
#pragma once

#include "cli.h"
#include "dss/robot/urdf_loader.h"

namespace dss::cli {

/// Usage lines for the options below.
extern const char* const kMeshOptionsUsage;

/// Reads the current argument when it is one of
///   --meshes hull|decomposed         every link's meshes (default hull)
///   --decompose-links L1,L2,...      these links' meshes decomposed (others as --meshes)
///   --decompose-tolerance M          concavity target in metres, in (0, 1] (default 0.008)
///   --decompose-max-pieces K         piece cap per mesh, in [1, 64] (default 8)
///   --decomposition-cache DIR|none   where decompositions are cached (default
///                                    $DSS_CACHE_DIR, $XDG_CACHE_HOME/dss or ~/.cache/dss)
/// into `options`; false (nothing read) otherwise. Bad values are usage errors.
bool meshOption(ArgCursor& args, MeshGeometryOptions* options);

}  // namespace dss::cli
