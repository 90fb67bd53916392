// dss_decompose: convex decompositions of a robot's meshes (or of one mesh file), computed
// ahead of time into the decomposition cache, so that loading the robot with
// `--meshes decomposed` is as fast as with hulls. Prints one JSON line per mesh.
#include <chrono>
#include <ctime>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "cli.h"
#include "dss/mesh/decomposition_cache.h"
#include "dss/robot/urdf_loader.h"

namespace {

using json = nlohmann::json;

const char* const kUsage =
    R"(usage: dss_decompose (--robot R.urdf [--links L1,L2,...] | --mesh FILE [--scale S|SX,SY,SZ])
                     [--tolerance M] [--max-pieces K] [--cache DIR|none]

Cuts every mesh of the robot's collision geometry (or of the links named, or one mesh file)
into convex pieces whose union covers the mesh and, for a closed mesh, its solid, each within
the tolerance of the mesh where the piece cap allows, and stores them in the cache that
`dss_plan`/`dss_check --meshes decomposed` read. One JSON line per mesh: link(s), file,
triangles, closed, hull_concavity_m (the single hull's distance from the mesh), pieces,
max_concavity_m, seconds (CPU), cached (read from the cache).

  --tolerance M    concavity target in metres, in (0, 1] (default 0.008)
  --max-pieces K   pieces per mesh at most, in [1, 64] (default 8)
  --cache DIR      the cache directory (default $DSS_CACHE_DIR, $XDG_CACHE_HOME/dss or
                   ~/.cache/dss); none: compute without storing
Exit codes: 0 success; 1 runtime error (files); 2 usage error.
)";

double cpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

int run(int argc, char** argv) {
  std::string robot, mesh_file, cache = dss::mesh::defaultDecompositionCacheDir();
  std::set<std::string> links;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  dss::mesh::DecompositionOptions options;
  dss::cli::ArgCursor cli(argc, argv, "dss_decompose", kUsage);
  while (cli.next()) {
    if (cli.option("--robot")) {
      robot = cli.value();
    } else if (cli.option("--mesh")) {
      mesh_file = cli.value();
    } else if (cli.option("--links")) {
      std::istringstream in(cli.value());
      std::string l;
      while (std::getline(in, l, ','))
        if (l.empty())
          cli.error("--links: empty link name");
        else
          links.insert(l);
    } else if (cli.option("--scale")) {
      const std::string v = cli.value();
      if (v.find(',') == std::string::npos) {
        const auto s = dss::cli::parseNumber(v.c_str(), -1e6, 1e6);
        if (!s || *s == 0) cli.error("--scale: expected a non-zero number or SX,SY,SZ");
        scale.setConstant(*s);
      } else {
        std::istringstream in(v);
        std::string part;
        int k = 0;
        while (std::getline(in, part, ',')) {
          const auto s = dss::cli::parseNumber(part.c_str(), -1e6, 1e6);
          if (!s || *s == 0 || k == 3) cli.error("--scale: expected SX,SY,SZ, non-zero");
          scale[k++] = *s;
        }
        if (k != 3) cli.error("--scale: expected SX,SY,SZ");
      }
    } else if (cli.option("--tolerance")) {
      options.tolerance = cli.number(1e-6, 1.0);
    } else if (cli.option("--max-pieces")) {
      options.max_pieces = static_cast<int>(cli.integer(1, 64));
    } else if (cli.option("--cache")) {
      const std::string v = cli.value();
      cache = v == "none" ? "" : v;
    } else {
      cli.unknown();
    }
  }
  if (robot.empty() == mesh_file.empty()) cli.error("give --robot or --mesh (one of them)");
  if (!links.empty() && robot.empty()) cli.error("--links needs --robot");

  // The meshes to decompose: (file, scale) -> the links that use it.
  std::map<std::tuple<std::string, double, double, double>, std::vector<std::string>> meshes;
  if (!robot.empty()) {
    const dss::RobotModel model = dss::loadUrdf(robot);  // hulls: only to list the meshes
    for (const auto& l : links)
      if (model.linkIndex(l) < 0)
        throw std::runtime_error(robot + ": --links names link '" + l + "', which robot '" +
                                 model.name + "' does not have");
    for (const auto& link : model.links) {
      if (!links.empty() && !links.count(link.name)) continue;
      for (const auto& c : link.collisions)
        if (!c.mesh_path.empty()) {
          auto& users = meshes[{c.mesh_path, c.mesh_scale.x(), c.mesh_scale.y(), c.mesh_scale.z()}];
          if (users.empty() || users.back() != link.name) users.push_back(link.name);
        }
    }
  } else {
    meshes[{mesh_file, scale.x(), scale.y(), scale.z()}] = {};
  }
  for (const auto& [key, users] : meshes) {
    const auto& [path, sx, sy, sz] = key;
    const dss::mesh::TriangleMesh m = dss::mesh::loadMesh(path, Eigen::Vector3d(sx, sy, sz));
    const double t0 = cpuSeconds();
    bool cached = false;
    const dss::mesh::Decomposition d = dss::mesh::decomposeCached(m, options, path, cache, &cached);
    const double t1 = cpuSeconds();
    json j;
    if (!users.empty()) j["links"] = users;
    j["file"] = path;
    j["scale"] = {sx, sy, sz};
    j["triangles"] = m.triangles.size();
    j["closed"] = d.closed;
    j["hull_concavity_m"] = d.hull_concavity;
    j["pieces"] = d.pieces.size();
    j["max_concavity_m"] = d.max_concavity;
    j["tolerance_m"] = options.tolerance;
    j["max_pieces"] = options.max_pieces;
    j["seconds"] = t1 - t0;
    j["cached"] = cached;
    std::cout << j.dump() << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "dss_decompose: " << e.what() << "\n";
    return 1;
  }
}
