// A robot placed in the world by a fixed joint, the reference the planning tests compare a
// planar or floating base against: the same states must answer alike when the base stands where
// the fixed joint puts it.
#pragma once

#include <Eigen/Core>
#include <boost/test/unit_test.hpp>
#include <map>
#include <memory>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "dss/checker/checker_setup.h"
#include "dss/planning/planning_problem.h"
#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"

namespace dss_test {

/// The robot of the URDF text `urdf` (mesh paths resolved against `mesh_dir`) with a new root
/// link "world" and a fixed joint from it to its root link `root` at origin xyz, rpy (URDF
/// conventions), and the SRDF text `srdf`.
inline dss::LoadedRobot placedByFixedJoint(const std::string& urdf, const std::string& root,
                                           const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy,
                                           const std::string& srdf, const std::string& mesh_dir) {
  std::ostringstream fixed;
  fixed.precision(17);
  fixed << "<link name=\"world\"/><joint name=\"place\" type=\"fixed\"><parent link=\"world\"/>"
        << "<child link=\"" << root << "\"/><origin xyz=\"" << xyz.x() << " " << xyz.y() << " "
        << xyz.z() << "\" rpy=\"" << rpy.x() << " " << rpy.y() << " " << rpy.z() << "\"/></joint>";
  const std::regex robot_tag("(<robot[^>]*>)");
  BOOST_REQUIRE(std::regex_search(urdf, robot_tag));
  const std::string placed = std::regex_replace(urdf, robot_tag, "$1" + fixed.str(),
                                                std::regex_constants::format_first_only);
  dss::LoadedRobot r;
  r.model =
      std::make_shared<const dss::RobotModel>(dss::loadUrdfString(placed, "placed.urdf", mesh_dir));
  r.srdf = dss::parseSrdf(srdf, "placed.srdf");
  return r;
}

/// The values of `start` that name joints of `robot`.
inline std::map<std::string, double> startOf(const dss::RobotModel& robot,
                                             const std::map<std::string, double>& start) {
  std::map<std::string, double> out;
  for (const auto& [n, v] : start)
    if (robot.variableIndex(n) >= 0) out[n] = v;
  return out;
}

/// The group joints of `fixed` drawn uniformly within their limits: into `qf` (held values
/// elsewhere) and, by name, into `q`, a state of the robot `m` with the moving base.
inline void drawGroupJoints(const dss::Problem& fixed, const dss::RobotModel& m,
                            std::mt19937_64& rng, std::vector<double>& qf, std::vector<double>& q) {
  const dss::RobotModel& fm = fixed.model->robot();
  qf = fixed.model->held();
  for (int a : fixed.model->groupActive()) {
    const auto& j = fm.joints[fm.active_joints[a]];
    const double v = std::uniform_real_distribution<double>(j.limits.lower, j.limits.upper)(rng);
    qf[a] = v;
    q[m.variableIndex(fm.activeJointNames()[a])] = v;
  }
}

}  // namespace dss_test
