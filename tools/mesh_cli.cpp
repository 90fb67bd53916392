// Mesh-geometry command-line options (see mesh_cli.h).
#include "mesh_cli.h"

#include <sstream>
#include <string>

namespace dss::cli {

const char* const kMeshOptionsUsage =
    "  --meshes hull|decomposed        robot meshes as convex hulls (default) or as convex\n"
    "                                  pieces that cover them (a decomposition, cached on disk)\n"
    "  --decompose-links L1,L2,...     decompose these links' meshes only\n"
    "  --decompose-tolerance M         decomposition: concavity target, metres (0.008)\n"
    "  --decompose-max-pieces K        decomposition: pieces per mesh at most (8)\n"
    "  --decomposition-cache DIR|none  cache of decompositions ($DSS_CACHE_DIR,\n"
    "                                  $XDG_CACHE_HOME/dss or ~/.cache/dss)\n";

bool meshOption(ArgCursor& args, MeshGeometryOptions* o) {
  if (args.option("--meshes")) {
    const std::string v = args.value();
    if (v == "hull")
      o->geometry = MeshGeometry::kHull;
    else if (v == "decomposed")
      o->geometry = MeshGeometry::kDecompose;
    else
      args.error("--meshes: expected hull or decomposed, got '" + v + "'");
    return true;
  }
  if (args.option("--decompose-links")) {
    std::istringstream in(args.value());
    std::string link;
    bool any = false;
    while (std::getline(in, link, ',')) {
      if (link.empty()) args.error("--decompose-links: empty link name");
      o->links[link] = MeshGeometry::kDecompose;
      any = true;
    }
    if (!any) args.error("--decompose-links: no link named");
    return true;
  }
  if (args.option("--decompose-tolerance")) {
    o->decomposition.tolerance = args.number(1e-6, 1.0);
    return true;
  }
  if (args.option("--decompose-max-pieces")) {
    o->decomposition.max_pieces = static_cast<int>(args.integer(1, 64));
    return true;
  }
  if (args.option("--decomposition-cache")) {
    const std::string v = args.value();
    o->cache_dir = v == "none" ? "" : v;
    return true;
  }
  return false;
}

}  // namespace dss::cli
