// Planar and floating joints (URDF and SRDF virtual): their expansion into one-variable
// joints, forward kinematics against poses composed by hand, state values by name, CSV round
// trips, values from transforms, and bad input.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <random>
#include <sstream>

#include "dss/robot/joint_state.h"
#include "dss/robot/joint_states_csv.h"
#include "dss/robot/kinematics.h"
#include "dss/robot/multi_dof.h"
#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "support/temp_files.h"
#include "support/thrown_message.h"

using Eigen::Isometry3d;
using Eigen::Vector3d;

namespace {

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// A body on a planar or floating joint whose origin is turned and moved, with an arm link on
// a revolute joint below it.
std::string robotWith(const std::string& type) {
  return R"(<robot name="r"><link name="world"/>
<link name="body"><collision><geometry><box size="0.4 0.2 0.1"/></geometry></collision></link>
<link name="arm"><collision><origin xyz="0.3 0 0"/><geometry><sphere radius="0.05"/></geometry></collision></link>
<joint name="base" type=")" +
         type + R"("><parent link="world"/><child link="body"/>
  <origin xyz="1 2 0.5" rpy="0.1 -0.2 0.3"/></joint>
<joint name="elbow" type="revolute"><parent link="body"/><child link="arm"/>
  <origin xyz="0.2 0 0"/><axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
</robot>)";
}

Isometry3d originOfBase() {
  Isometry3d X = Isometry3d::Identity();
  X.translation() = Vector3d(1, 2, 0.5);
  X.linear() =
      (Eigen::AngleAxisd(0.3, Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.2, Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.1, Vector3d::UnitX()))
          .toRotationMatrix();
  return X;
}

Isometry3d elbowPose(double elbow) {
  Isometry3d X = Isometry3d::Identity();
  X.translation() = Vector3d(0.2, 0, 0);
  X.linear() = Eigen::AngleAxisd(elbow, Vector3d::UnitZ()).toRotationMatrix();
  return X;
}

// The kinematics of the links with geometry only (the default) folds the multi-DOF joint's
// translation links into the body's step: those links are not written, and the body and arm
// poses are exactly those of the kinematics of every link.
void samePosesWithFoldedSteps(const dss::RobotModel& m, const dss::Kinematics& all,
                              const std::vector<double>& q) {
  const dss::Kinematics geometry(m);
  BOOST_TEST(geometry.updatedLinks().size() < all.updatedLinks().size());
  for (int l : geometry.updatedLinks()) BOOST_TEST(m.links[l].name.find('/') == std::string::npos);
  const Isometry3d unset = Isometry3d(Eigen::Matrix4d::Constant(-7.0));
  std::vector<Isometry3d> X(m.links.size(), unset);
  geometry.computeLinkPoses(q.data(), X.data());
  const auto Y = all.linkPoses(q);
  for (const char* name : {"body", "arm"}) {
    const int l = m.linkIndexOrThrow(name);
    BOOST_TEST((X[l].matrix() == Y[l].matrix()), name);
  }
  BOOST_TEST(
      (X[m.linkIndexOrThrow("base/" + std::string(q.size() == 4 ? "x" : "trans_x"))].matrix() ==
       unset.matrix()));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(multi_dof)

BOOST_AUTO_TEST_CASE(urdf_planar_joint_is_x_y_theta_in_its_joint_frame) {
  const dss::RobotModel m = dss::loadUrdfString(robotWith("planar"), "planar.urdf", ".");
  const std::vector<std::string> names = m.activeJointNames();
  BOOST_TEST(names == (std::vector<std::string>{"base/x", "base/y", "base/theta", "elbow"}),
             boost::test_tools::per_element());
  BOOST_REQUIRE(m.multi_dof_joints.size() == 1u);
  BOOST_TEST(m.multi_dof_joints[0].name == "base");
  BOOST_TEST(m.multiDofIndex("base") == 0);
  BOOST_TEST(m.variableIndex("base/theta") == 2);
  BOOST_TEST(m.variableIndex("elbow") == 3);
  BOOST_TEST(m.variableIndex("base") == -1);
  // Parents before children, the synthetic links without geometry.
  for (std::size_t l = 1; l < m.links.size(); ++l) BOOST_TEST(m.links[l].parent_link < int(l));
  BOOST_TEST(!m.links[m.linkIndexOrThrow("base/x")].hasGeometry());

  const dss::Kinematics kin(m, true);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  for (int k = 0; k < 200; ++k) {
    const std::vector<double> q = {u(rng), u(rng), u(rng), 0.5 * u(rng)};
    const auto X = kin.linkPoses(q);
    Isometry3d motion = Isometry3d::Identity();
    motion.translation() = Vector3d(q[0], q[1], 0);
    motion.linear() = Eigen::AngleAxisd(q[2], Vector3d::UnitZ()).toRotationMatrix();
    const Isometry3d body = originOfBase() * motion;
    BOOST_TEST((X[m.linkIndexOrThrow("body")].matrix() - body.matrix()).norm() < 1e-12);
    const Isometry3d arm = body * elbowPose(q[3]);
    BOOST_TEST((X[m.linkIndexOrThrow("arm")].matrix() - arm.matrix()).norm() < 1e-12);
    samePosesWithFoldedSteps(m, kin, q);
  }
}

BOOST_AUTO_TEST_CASE(urdf_floating_joint_is_translation_then_quaternion) {
  const dss::RobotModel m = dss::loadUrdfString(robotWith("floating"), "floating.urdf", ".");
  BOOST_TEST(
      m.activeJointNames() ==
          (std::vector<std::string>{"base/trans_x", "base/trans_y", "base/trans_z", "base/rot_x",
                                    "base/rot_y", "base/rot_z", "base/rot_w", "elbow"}),
      boost::test_tools::per_element());
  BOOST_TEST(m.variableIndex("base/rot_w") == 6);
  BOOST_TEST(m.variableIndex("base/rot_q") == -1);
  BOOST_TEST(m.variableIndex("base/rot") == -1);
  // The identity rotation by default.
  const std::vector<double> d = m.defaultState();
  BOOST_TEST(d[3] == 0.0);
  BOOST_TEST(d[6] == 1.0);

  const dss::Kinematics kin(m, true);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    std::vector<double> q(8);
    for (double& v : q) v = u(rng);
    // Any scale of the quaternion: the kinematics normalises it.
    const double scale = std::ldexp(1.0, int(std::floor(8 * u(rng))));
    for (int i = 3; i < 7; ++i) q[i] *= scale;
    const auto X = kin.linkPoses(q);
    Isometry3d motion = Isometry3d::Identity();
    motion.translation() = Vector3d(q[0], q[1], q[2]);
    motion.linear() = Eigen::Quaterniond(q[6], q[3], q[4], q[5]).normalized().toRotationMatrix();
    const Isometry3d body = originOfBase() * motion;
    BOOST_TEST((X[m.linkIndexOrThrow("body")].matrix() - body.matrix()).norm() < 1e-12);
    const Isometry3d arm = body * elbowPose(q[7]);
    BOOST_TEST((X[m.linkIndexOrThrow("arm")].matrix() - arm.matrix()).norm() < 1e-12);
    samePosesWithFoldedSteps(m, kin, q);
  }
  // A zero quaternion has no rotation: the poses below it are NaN, never a made-up pose.
  std::vector<double> q = d;
  for (int i = 3; i < 7; ++i) q[i] = 0.0;
  BOOST_TEST(!kin.linkPoses(q)[m.linkIndexOrThrow("arm")].matrix().allFinite());
  q[6] = std::nan("");
  BOOST_TEST(!kin.linkPoses(q)[m.linkIndexOrThrow("arm")].matrix().allFinite());
}

BOOST_AUTO_TEST_CASE(srdf_virtual_joints_connect_the_root_to_the_world) {
  const std::string urdf = R"(<robot name="r">
<link name="body"><collision><geometry><box size="0.4 0.2 0.1"/></geometry></collision></link>
<link name="arm"><collision><geometry><sphere radius="0.05"/></geometry></collision></link>
<joint name="elbow" type="continuous"><parent link="body"/><child link="arm"/><axis xyz="0 0 1"/></joint>
</robot>)";
  for (const std::string type : {"planar", "floating"}) {
    dss::RobotModel m = dss::loadUrdfString(urdf, "r.urdf", ".");
    dss::applyVirtualJoint(m, "base", type, "world", "body", "r.srdf");
    BOOST_TEST(m.links[m.root_link].name == "world");
    BOOST_TEST(m.numActiveJoints() == (type == "planar" ? 4u : 8u));
    BOOST_TEST(m.activeJointNames().back() == "elbow");
    BOOST_TEST(m.multi_dof_joints.at(0).from_srdf);
    // The group names the virtual joint: all its values.
    const dss::Srdf srdf =
        dss::parseSrdf(R"(<robot name="r"><group name="g"><joint name="base"/></group>
<group name="arm"><link name="arm"/></group><group name="body"><link name="body"/></group>
<virtual_joint name="base" type=")" +
                           type + R"(" parent_frame="world" child_link="body"/></robot>)",
                       "r.srdf");
    const std::vector<int> g = dss::groupActiveJoints(m, srdf, "g");
    BOOST_TEST(g.size() == (type == "planar" ? 3u : 7u));
    BOOST_TEST(dss::groupActiveJoints(m, srdf, "arm").size() == 1u);
    // A link on a multi-DOF joint brings the whole joint.
    BOOST_TEST(dss::groupActiveJoints(m, srdf, "body").size() == g.size());
  }
  dss::RobotModel m = dss::loadUrdfString(urdf, "r.urdf", ".");
  dss::applyVirtualJoint(m, "fixed_base", "fixed", "world", "body", "r.srdf");
  BOOST_TEST(m.numActiveJoints() == 1u);
  BOOST_TEST(contains(dss_test::thrownMessage([&] {
                        dss::applyVirtualJoint(m, "v", "planar", "world", "arm", "r.srdf");
                      }),
                      "r.srdf: virtual joint 'v' connects link 'arm', which is not the root link "
                      "'body'"));
  BOOST_TEST(contains(dss_test::thrownMessage([&] {
                        dss::applyVirtualJoint(m, "v", "spherical", "world", "body", "r.srdf");
                      }),
                      "has type 'spherical'"));
  BOOST_TEST(contains(dss_test::thrownMessage([&] {
                        dss::applyVirtualJoint(m, "v", "planar", "arm", "body", "r.srdf");
                      }),
                      "parent frame 'arm' is a link of the robot"));
  BOOST_TEST(contains(dss_test::thrownMessage([&] {
                        dss::applyVirtualJoint(m, "elbow", "planar", "world", "body", "r.srdf");
                      }),
                      "already has a joint of that name"));
}

BOOST_AUTO_TEST_CASE(a_name_clash_with_a_generated_joint_is_an_error) {
  const std::string urdf = R"(<robot name="r"><link name="w"/><link name="b"/><link name="c"/>
<joint name="base" type="planar"><parent link="w"/><child link="b"/></joint>
<joint name="base/x" type="fixed"><parent link="b"/><child link="c"/></joint></robot>)";
  BOOST_TEST(
      contains(dss_test::thrownMessage([&] { dss::loadUrdfString(urdf, "clash.urdf", "."); }),
               "clash.urdf: planar joint 'base' becomes joint 'base/x', but the robot "
               "already has a joint of that name"));
}

BOOST_AUTO_TEST_CASE(values_from_transforms_and_by_name) {
  const dss::RobotModel planar = dss::loadUrdfString(robotWith("planar"), "p.urdf", ".");
  const dss::RobotModel floating = dss::loadUrdfString(robotWith("floating"), "f.urdf", ".");
  Isometry3d X = Isometry3d::Identity();
  X.translation() = Vector3d(0.5, -1.5, 0.25);
  X.linear() = Eigen::AngleAxisd(2.5, Vector3d::UnitZ()).toRotationMatrix();
  std::vector<std::string> notes;
  const auto p = dss::multiDofStateValues(
      planar, {{"base", X}, {"virtual_joint", Isometry3d::Identity()}}, &notes);
  BOOST_TEST(notes.empty());
  BOOST_TEST(p.at("base/x") == 0.5);
  BOOST_TEST(p.at("base/y") == -1.5);
  BOOST_TEST(std::abs(p.at("base/theta") - 2.5) < 1e-12);
  // The floating joint's quaternion with w >= 0 (the same rotation as -q).
  X.linear() = Eigen::AngleAxisd(3.0, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const auto f = dss::multiDofStateValues(floating, {{"base", X}, {"other", X}}, &notes);
  BOOST_REQUIRE(notes.size() == 1u);
  BOOST_TEST(contains(notes[0], "'other' is not a planar or floating joint"));
  BOOST_TEST(f.at("base/trans_z") == 0.25);
  BOOST_TEST(f.at("base/rot_w") >= 0.0);
  const Eigen::Quaterniond q(f.at("base/rot_w"), f.at("base/rot_x"), f.at("base/rot_y"),
                             f.at("base/rot_z"));
  BOOST_TEST((q.toRotationMatrix() - X.linear()).norm() < 1e-12);
  // assembleState takes the variable names.
  std::vector<std::pair<std::string, double>> named(f.begin(), f.end());
  const std::vector<double> s = dss::assembleState(floating, named, "test");
  BOOST_TEST(s[floating.variableIndex("base/rot_y")] == f.at("base/rot_y"));
}

BOOST_AUTO_TEST_CASE(csv_states_of_a_floating_joint_round_trip) {
  const dss::RobotModel m = dss::loadUrdfString(robotWith("floating"), "f.urdf", ".");
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::vector<double>> states(20, std::vector<double>(m.numActiveJoints()));
  for (auto& q : states)
    for (double& v : q) v = u(rng);
  std::ostringstream out;
  dss::writeJointStatesCsv(out, m, states);
  BOOST_TEST(out.str().rfind("base/trans_x,base/trans_y,base/trans_z,base/rot_x,base/rot_y,"
                             "base/rot_z,base/rot_w,elbow\n",
                             0) == 0u);
  const std::string path = dss_test::writeScratch("robot", "floating_states.csv", out.str());
  const dss::JointStatesCsv csv = dss::readJointStatesCsv(path, m, m.defaultState());
  BOOST_TEST(csv.states == states);
}

BOOST_AUTO_TEST_SUITE_END()
