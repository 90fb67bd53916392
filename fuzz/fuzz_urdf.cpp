// Fuzz target: the URDF robot reader (dss::loadUrdfString), with mesh URIs resolved against
// our arm's folder so that meshes/*.stl exist. Any bytes must end in a RobotModel or a
// std::exception naming the source; never a crash, a hang or a sanitizer report. A model that
// loads must be consistent (every index in range, parents before children, active joints
// numbered densely) and its forward kinematics must run on the default state and on a state
// with every joint at 1e6; the self-collision pairs are computed on top.
#include <cmath>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "dss/robot/collision_pairs.h"
#include "dss/robot/kinematics.h"
#include "dss/robot/urdf_loader.h"
#include "fuzz_support.h"

namespace {

void checkModel(const dss::RobotModel& m) {
  const int nl = static_cast<int>(m.links.size()), nj = static_cast<int>(m.joints.size());
  if (nl == 0) dss_fuzz::propertyFailed("a loaded robot without links");
  if (m.root_link < 0 || m.root_link >= nl) dss_fuzz::propertyFailed("root link out of range");
  for (int j = 0; j < nj; ++j) {
    const dss::RobotJoint& joint = m.joints[j];
    if (joint.parent_link < 0 || joint.parent_link >= nl || joint.child_link < 0 ||
        joint.child_link >= nl)
      dss_fuzz::propertyFailed("joint " + joint.name + ": link index out of range");
    if (joint.parent_link >= joint.child_link)
      dss_fuzz::propertyFailed("joint " + joint.name + ": parent after child");
    if (m.links[joint.child_link].parent_joint != j)
      dss_fuzz::propertyFailed("joint " + joint.name + ": child does not point back");
  }
  for (std::size_t a = 0; a < m.active_joints.size(); ++a) {
    // A ball joint (a floating joint's rotation) owns four consecutive values.
    const int j = m.active_joints[a];
    if (j < 0 || j >= nj || m.joints[j].active_index > static_cast<int>(a) ||
        static_cast<int>(a) >= m.joints[j].active_index + m.joints[j].numVariables())
      dss_fuzz::propertyFailed("active joint " + std::to_string(a) + " inconsistent");
  }
  for (const dss::RobotJoint& joint : m.joints)
    if (joint.mimic_active >= static_cast<int>(m.active_joints.size()))
      dss_fuzz::propertyFailed("joint " + joint.name + ": mimic leader out of range");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dss::LoadOptions options;
  options.mesh_paths.use_ros_package_path = false;
  options.mesh_paths.use_ament_prefix_path = false;
  options.limits.max_mesh_vertices = 200'000;
  dss::RobotModel model;
  try {
    model = dss::loadUrdfString(text, "fuzz.urdf", dss_fuzz::armDir(), options);
  } catch (const std::exception&) {
    return 0;
  }
  checkModel(model);
  const dss::Kinematics fk(model, /*all_links=*/true);
  std::vector<Eigen::Isometry3d> X(model.links.size(), Eigen::Isometry3d::Identity());
  fk.computeLinkPoses(model.defaultState().data(), X.data());
  const std::vector<double> far(model.numActiveJoints(), 1e6);
  fk.computeLinkPoses(far.data(), X.data());
  try {
    (void)dss::selfCollisionPairs(model, nullptr);
  } catch (const std::exception&) {
  }
  return 0;
}
