// Measures how long loading a URDF (with meshes and hulls) takes and what forward kinematics
// costs per state. Usage: dss_robot_timing [robot.urdf] [states]
#include <chrono>
#include <cstdio>
#include <ctime>
#include <limits>
#include <random>
#include <string>

#include "cli.h"
#include "dss/robot/kinematics.h"
#include "dss/robot/urdf_loader.h"

namespace {

const char* const kUsage = R"(usage: dss_robot_timing [robot.urdf] [states]

Loads the URDF five times (best load time reported), then times forward kinematics over
`states` random states, alone and with world bounding spheres per link.

  robot.urdf   default: the Panda of the shared robots directory
  states       forward-kinematics states to time, an integer >= 1 (default 1000000)
  --help       this text

Exit codes: 0 success; 1 the robot cannot be loaded; 2 usage error.
)";

}  // namespace

int main(int argc, char** argv) {
  std::string path = std::string(DSS_SHARED_DIR_DEFAULT) + "/robots/panda/panda.urdf";
  int states = 1000000;
  int positional = 0;
  dss::cli::ArgCursor cli(argc, argv, "dss_robot_timing", kUsage);
  while (cli.next()) {
    if (positional == 0 && cli.positional("robot.urdf")) {
      path = cli.value();
      ++positional;
    } else if (positional == 1 && cli.positional("states")) {
      states = static_cast<int>(cli.integer(1, std::numeric_limits<int>::max()));
      ++positional;
    } else {
      cli.unknown();
    }
  }
  using Clock = std::chrono::steady_clock;
  try {
    // First load warms the file cache and assimp's importer registry; report the best of 5.
    double best_ms = 1e30;
    dss::RobotModel model;
    for (int i = 0; i < 5; ++i) {
      const auto t0 = Clock::now();
      model = dss::loadUrdf(path);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      std::printf("load %d: %.2f ms\n", i, ms);
      best_ms = std::min(best_ms, ms);
    }
    std::printf(
        "%s: %zu links, %zu joints, %zu active, %zu collision elements; load best %.2f ms\n",
        path.c_str(), model.links.size(), model.joints.size(), model.numActiveJoints(),
        model.numCollisionElements(), best_ms);
    const dss::Kinematics kin(model);
    std::vector<Eigen::Isometry3d> X(model.links.size(), Eigen::Isometry3d::Identity());
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    const int pool = 1024;
    std::vector<double> qs(pool * model.numActiveJoints());
    for (auto& v : qs) v = u(rng);
    double sink = 0;
    // CPU time as well as wall time: the machine may be shared.
    const std::clock_t c0 = std::clock();
    const auto t0 = Clock::now();
    for (int s = 0; s < states; ++s) {
      kin.computeLinkPoses(&qs[(s % pool) * model.numActiveJoints()], X.data());
      sink += X[kin.updatedLinks().back()].translation().x();
    }
    const double us = std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / states;
    const double cpu_us = 1e6 * double(std::clock() - c0) / CLOCKS_PER_SEC / states;
    std::printf(
        "FK: %zu links updated per state, %.4f us wall, %.4f us CPU per state (%d states, checksum "
        "%.3f)\n",
        kin.updatedLinks().size(), us, cpu_us, states, sink);
    // FK plus world-space bounding volumes: one sphere per link with geometry, enclosing its
    // elements (centre in the link frame, radius from the elements' magnitudes), moved to world.
    std::vector<int> geo_links;
    std::vector<Eigen::Vector3d> c_L;
    std::vector<double> r_L;
    for (std::size_t l = 0; l < model.links.size(); ++l) {
      const auto& els = model.links[l].collisions;
      if (els.empty()) continue;
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (const auto& e : els) c += e.X_LS.translation();
      c /= double(els.size());
      double r = 0;
      for (const auto& e : els)
        r = std::max(r, (e.X_LS.translation() - c).norm() + dss::shapeMagnitude(e.shape));
      geo_links.push_back(int(l));
      c_L.push_back(c);
      r_L.push_back(r);
    }
    std::vector<Eigen::Vector3d> c_W(geo_links.size());
    const std::clock_t c1 = std::clock();
    for (int s = 0; s < states; ++s) {
      kin.computeLinkPoses(&qs[(s % pool) * model.numActiveJoints()], X.data());
      for (std::size_t k = 0; k < geo_links.size(); ++k) c_W[k] = X[geo_links[k]] * c_L[k];
      sink += c_W.back().x();
    }
    const double bv_us = 1e6 * double(std::clock() - c1) / CLOCKS_PER_SEC / states;
    std::printf("FK + world bounding spheres of %zu links: %.4f us CPU per state (checksum %.3f)\n",
                geo_links.size(), bv_us, sink);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
