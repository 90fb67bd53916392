// Small URDFs written inline: forward kinematics against hand-computed poses, mimic joints,
// mesh path resolution, self-collision pairs, disabled-pair sampling and bad input.
#include <unistd.h>

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "dss/robot/collision_pairs.h"
#include "dss/robot/kinematics.h"
#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "support/temp_files.h"

namespace fs = std::filesystem;
using Eigen::Isometry3d;
using Eigen::Vector3d;

namespace {

fs::path tempDir() { return dss_test::scratchDir("robot"); }

std::string write(const std::string& name, const std::string& text) {
  return dss_test::writeScratch("robot", name, text);
}

const char* kTetraStl =
    "solid t\n"
    "facet normal 0 0 -1\n outer loop\n vertex 0 0 0\n vertex 0 0.1 0\n vertex 0.1 0 0\n "
    "endloop\nendfacet\n"
    "facet normal 0 -1 0\n outer loop\n vertex 0 0 0\n vertex 0.1 0 0\n vertex 0 0 0.1\n "
    "endloop\nendfacet\n"
    "facet normal -1 0 0\n outer loop\n vertex 0 0 0\n vertex 0 0 0.1\n vertex 0 0.1 0\n "
    "endloop\nendfacet\n"
    "facet normal 1 1 1\n outer loop\n vertex 0.1 0 0\n vertex 0 0.1 0\n vertex 0 0 0.1\n "
    "endloop\nendfacet\n"
    "endsolid t\n";

// base --j1 (revolute z at (0,0,1))--> l1 --f (fixed, xyz 1 0 0, yaw pi/2)--> l2
//      --j2 (prismatic x)--> l3 ; l1 --m (revolute y, mimic j1: 2 q + 0.5)--> l4
const char* kArm = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base"><collision><geometry><box size="1 1 0.2"/></geometry></collision></link>
  <link name="l1"/>
  <link name="l2"><collision><origin xyz="0 0 0.5" rpy="0 0 0"/><geometry><cylinder radius="0.1" length="1"/></geometry></collision></link>
  <link name="l3">
    <collision><geometry><sphere radius="0.1"/></geometry></collision>
    <collision><origin xyz="0.2 0 0"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <link name="l4"><collision><geometry><sphere radius="0.05"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 1"/><axis xyz="0 0 2"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="f" type="fixed"><parent link="l1"/><child link="l2"/><origin xyz="1 0 0" rpy="0 0 1.5707963267948966"/></joint>
  <joint name="j2" type="prismatic"><parent link="l2"/><child link="l3"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
  <joint name="m" type="revolute"><parent link="l1"/><child link="l4"/><origin xyz="0 0 0.3"/><axis xyz="0 1 0"/>
    <limit lower="-10" upper="10" effort="1" velocity="1"/><mimic joint="j1" multiplier="2" offset="0.5"/></joint>
</robot>
)";

Isometry3d pose(const Vector3d& p, const Eigen::Matrix3d& R) {
  Isometry3d X = Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}
Eigen::Matrix3d rot(double a, const Vector3d& axis) {
  return Eigen::AngleAxisd(a, axis.normalized()).toRotationMatrix();
}

std::string errorOf(const std::string& urdf_text, const std::string& name,
                    dss::LoadOptions o = {}) {
  try {
    dss::loadUrdf(write(name, urdf_text), o);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(urdf_inline)

BOOST_AUTO_TEST_CASE(structure_and_fk_against_hand_computed_poses) {
  const auto m = dss::loadUrdf(write("arm.urdf", kArm));
  BOOST_TEST(m.links.size() == 5u);
  BOOST_TEST(m.joints.size() == 4u);
  BOOST_TEST(m.activeJointNames() == (std::vector<std::string>{"j1", "j2"}));
  BOOST_TEST(m.numCollisionElements() == 5u);
  const auto& j1 = m.joints[m.jointIndex("j1")];
  BOOST_TEST((j1.axis - Vector3d::UnitZ()).norm() == 0.0);  // normalised
  const auto& mj = m.joints[m.jointIndex("m")];
  BOOST_TEST(mj.active_index == -1);
  BOOST_TEST(mj.mimic_active == j1.active_index);
  BOOST_TEST(mj.mimic_multiplier == 2.0);
  BOOST_TEST(mj.mimic_offset == 0.5);
  // Cylinder: URDF radius and length along z
  const auto& cyl = std::get<dss::Cylinder>(m.links[m.linkIndex("l2")].collisions[0].shape);
  BOOST_TEST(cyl.radius == 0.1);
  BOOST_TEST(cyl.half_length == 0.5);

  for (const bool all : {false, true}) {
    dss::Kinematics kin(m, all);
    const Isometry3d X_WR = pose(Vector3d(0.1, -0.2, 0.3), rot(0.4, Vector3d(1, 1, 0)));
    kin.setBasePose(X_WR);
    const double q[2] = {0.7, 0.25};
    std::vector<Isometry3d> X(m.links.size(), Isometry3d::Identity());
    kin.computeLinkPoses(q, X.data());
    const Isometry3d l1 = X_WR * pose(Vector3d(0, 0, 1), rot(0.7, Vector3d::UnitZ()));
    const Isometry3d l2 = l1 * pose(Vector3d(1, 0, 0), rot(M_PI / 2, Vector3d::UnitZ()));
    const Isometry3d l3 = l2 * pose(Vector3d(0.25, 0, 0), Eigen::Matrix3d::Identity());
    const Isometry3d l4 = l1 * pose(Vector3d(0, 0, 0.3), rot(2 * 0.7 + 0.5, Vector3d::UnitY()));
    BOOST_TEST((X[m.linkIndex("base")].matrix() - X_WR.matrix()).norm() < 1e-15);
    BOOST_TEST((X[m.linkIndex("l2")].matrix() - l2.matrix()).norm() < 1e-14);
    BOOST_TEST((X[m.linkIndex("l3")].matrix() - l3.matrix()).norm() < 1e-14);
    BOOST_TEST((X[m.linkIndex("l4")].matrix() - l4.matrix()).norm() < 1e-14);
    // l1 has no geometry but its joint moves and leads to geometry: computed in both modes.
    BOOST_TEST((X[m.linkIndex("l1")].matrix() - l1.matrix()).norm() < 1e-14);
    BOOST_TEST(kin.updatedLinks().size() == 5u);
    BOOST_TEST(kin.jointValue(q, m.jointIndex("m")) == 2 * 0.7 + 0.5);
  }
}

BOOST_AUTO_TEST_CASE(general_axes_and_mimic_chains) {
  const std::string urdf = R"(<robot name="g">
  <link name="a"/><link name="b"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="c"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="d"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <joint name="r" type="continuous"><parent link="a"/><child link="b"/><axis xyz="1 2 3"/></joint>
  <joint name="p" type="prismatic"><parent link="b"/><child link="c"/><origin xyz="0 1 0" rpy="0.1 0.2 0.3"/><axis xyz="0 -1 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="r" multiplier="-3" offset="0.25"/></joint>
  <joint name="q" type="prismatic"><parent link="c"/><child link="d"/><axis xyz="0 0 -1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="p" multiplier="0.5" offset="1"/></joint>
</robot>)";
  const auto m = dss::loadUrdf(write("g.urdf", urdf));
  BOOST_TEST(m.numActiveJoints() == 1u);
  BOOST_TEST(!m.joints[m.jointIndex("r")].limits.has_position_limits);
  const dss::Kinematics kin(m);
  const double q = 0.9;
  const auto X = kin.linkPoses({q});
  const double vp = -3 * q + 0.25, vq = 0.5 * vp + 1;
  const Isometry3d b = pose(Vector3d::Zero(), rot(q, Vector3d(1, 2, 3)));
  Isometry3d pj = Isometry3d::Identity();
  pj.translation() = Vector3d(0, 1, 0);
  pj.linear() =
      (Eigen::AngleAxisd(0.3, Vector3d::UnitZ()) * Eigen::AngleAxisd(0.2, Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.1, Vector3d::UnitX()))
          .toRotationMatrix();
  const Isometry3d c =
      b * pj * pose(vp * Vector3d(0, -1, 1).normalized(), Eigen::Matrix3d::Identity());
  const Isometry3d d = c * pose(vq * Vector3d(0, 0, -1), Eigen::Matrix3d::Identity());
  BOOST_TEST((X[m.linkIndex("b")].matrix() - b.matrix()).norm() < 1e-14);
  BOOST_TEST((X[m.linkIndex("c")].matrix() - c.matrix()).norm() < 1e-14);
  BOOST_TEST((X[m.linkIndex("d")].matrix() - d.matrix()).norm() < 1e-14);
}

// Kinematics evaluates the sines and cosines of a state in blocks of 32 joints: a chain longer
// than one block, with axes along +-x, +-y, +-z and angles in every quadrant, against poses
// composed with Eigen's AngleAxis.
BOOST_AUTO_TEST_CASE(long_chain_of_axis_aligned_joints) {
  const int n = 75;
  const char* axes[6] = {"1 0 0", "0 1 0", "0 0 1", "-1 0 0", "0 -1 0", "0 0 -1"};
  const Vector3d axis_v[6] = {Vector3d::UnitX(),  Vector3d::UnitY(),  Vector3d::UnitZ(),
                              -Vector3d::UnitX(), -Vector3d::UnitY(), -Vector3d::UnitZ()};
  std::string urdf = "<robot name=\"chain\"><link name=\"l0\"/>\n";
  for (int i = 1; i <= n; ++i) {
    urdf += "<link name=\"l" + std::to_string(i) +
            "\"><collision><geometry><sphere radius=\"0.01\"/></geometry></collision></link>\n";
    // every fifth joint fixed, so that fixed joints are folded between rotating ones
    const bool fixed = i % 5 == 0;
    urdf += "<joint name=\"j" + std::to_string(i) + "\" type=\"" +
            (fixed ? "fixed" : "continuous") + "\"><parent link=\"l" + std::to_string(i - 1) +
            "\"/><child link=\"l" + std::to_string(i) +
            "\"/><origin xyz=\"0.1 0.02 0.03\" rpy=\"0.3 -0.2 0.1\"/><axis xyz=\"" + axes[i % 6] +
            "\"/></joint>\n";
  }
  urdf += "</robot>";
  const auto m = dss::loadUrdf(write("chain.urdf", urdf));
  const dss::Kinematics kin(m);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-20.0, 20.0);
  Eigen::Matrix3d R_o =
      (Eigen::AngleAxisd(0.1, Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.2, Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.3, Vector3d::UnitX()))
          .toRotationMatrix();
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> q(m.numActiveJoints());
    for (double& v : q) v = angle(rng);
    const auto X = kin.linkPoses(q);
    Isometry3d ref = Isometry3d::Identity();
    for (int i = 1; i <= n; ++i) {
      const auto& joint = m.joints[m.jointIndex("j" + std::to_string(i))];
      ref = ref * pose(Vector3d(0.1, 0.02, 0.03), R_o);
      if (joint.active_index >= 0)
        ref = ref * pose(Vector3d::Zero(), rot(q[joint.active_index], axis_v[i % 6]));
      const double err = (X[m.linkIndex("l" + std::to_string(i))].matrix() - ref.matrix()).norm();
      BOOST_TEST_REQUIRE(err < 1e-12 * (1 + i),
                         "link l" << i << " trial " << trial << " error " << err);
    }
  }
}

// Joint origins turned by multiples of pi/2 (as most real URDFs write them, here all 24
// rotations with their signs, as "1.5707963267948966" and as the Panda's "1.57079632679")
// take a column-selecting path in Kinematics: against poses composed with Eigen.
BOOST_AUTO_TEST_CASE(chain_of_quarter_turn_origins) {
  const int n = 60;
  const char* axes[7] = {"1 0 0", "0 1 0", "0 0 1", "-1 0 0", "0 -1 0", "0 0 -1", "0.6 0 0.8"};
  const Vector3d axis_v[7] = {Vector3d::UnitX(),    Vector3d::UnitY(),  Vector3d::UnitZ(),
                              -Vector3d::UnitX(),   -Vector3d::UnitY(), -Vector3d::UnitZ(),
                              Vector3d(0.6, 0, 0.8)};
  const char* quarter[4] = {"0", "1.5707963267948966", "3.141592653589793", "-1.57079632679"};
  const double quarter_v[4] = {0.0, M_PI / 2, M_PI, -M_PI / 2};
  std::mt19937_64 rng(11);
  std::vector<Eigen::Matrix3d> R_o(n + 1);
  std::string urdf = "<robot name=\"quarters\"><link name=\"l0\"/>\n";
  for (int i = 1; i <= n; ++i) {
    const int r = static_cast<int>(rng() % 4), p = static_cast<int>(rng() % 4),
              y = static_cast<int>(rng() % 4);
    R_o[i] = (Eigen::AngleAxisd(quarter_v[y], Vector3d::UnitZ()) *
              Eigen::AngleAxisd(quarter_v[p], Vector3d::UnitY()) *
              Eigen::AngleAxisd(quarter_v[r], Vector3d::UnitX()))
                 .toRotationMatrix();
    urdf += "<link name=\"l" + std::to_string(i) +
            "\"><collision><geometry><sphere radius=\"0.01\"/></geometry></collision></link>\n";
    const bool fixed = i % 4 == 0;
    urdf += "<joint name=\"j" + std::to_string(i) + "\" type=\"" +
            (fixed ? "fixed" : "continuous") + "\"><parent link=\"l" + std::to_string(i - 1) +
            "\"/><child link=\"l" + std::to_string(i) +
            "\"/><origin xyz=\"0.1 -0.02 0.03\" rpy=\"" + quarter[r] + " " + quarter[p] + " " +
            quarter[y] + "\"/><axis xyz=\"" + axes[i % 7] + "\"/></joint>\n";
  }
  urdf += "</robot>";
  const auto m = dss::loadUrdf(write("quarters.urdf", urdf));
  const dss::Kinematics kin(m);
  std::uniform_real_distribution<double> angle(-4.0, 4.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> q(m.numActiveJoints());
    for (double& v : q) v = angle(rng);
    const auto X = kin.linkPoses(q);
    Isometry3d ref = Isometry3d::Identity();
    for (int i = 1; i <= n; ++i) {
      const auto& joint = m.joints[m.jointIndex("j" + std::to_string(i))];
      ref = ref * pose(Vector3d(0.1, -0.02, 0.03), R_o[i]);
      if (joint.active_index >= 0)
        ref = ref * pose(Vector3d::Zero(), rot(q[joint.active_index], axis_v[i % 7]));
      const double err = (X[m.linkIndex("l" + std::to_string(i))].matrix() - ref.matrix()).norm();
      BOOST_TEST_REQUIRE(err < 1e-10 * (1 + i),
                         "link l" << i << " trial " << trial << " error " << err);
    }
  }
}

BOOST_AUTO_TEST_CASE(fast_sin_cos_matches_libm) {
  for (int i = -200000; i <= 200000; ++i) {
    const double x = i * 1e-4 + 1e-7;
    double s, c;
    dss::sinCosForKinematics(x, &s, &c);
    BOOST_TEST_REQUIRE(std::abs(s - std::sin(x)) <= 4e-16);  // 2 ulp of values <= 1
    BOOST_TEST_REQUIRE(std::abs(c - std::cos(x)) <= 4e-16);
  }
  // Huge angles (joints without limits, URDF limits of 1e300) are right too, and NaN stays NaN.
  for (const double x : {1e5, -3.5e5, 1e9, 123456789.123, 1e16, -1e300, 1.7e308}) {
    double s, c;
    dss::sinCosForKinematics(x, &s, &c);
    BOOST_TEST(s == std::sin(x), x);
    BOOST_TEST(c == std::cos(x), x);
  }
  double s, c;
  dss::sinCosForKinematics(std::nan(""), &s, &c);
  BOOST_TEST((std::isnan(s) && std::isnan(c)));
}

BOOST_AUTO_TEST_CASE(mesh_paths) {
  write("ws/src/my_pkg/meshes/t.stl", kTetraStl);
  write("prefix/share/amnt_pkg/t.stl", kTetraStl);
  write("robotdir/meshes/t.stl", kTetraStl);
  write("explicit_root/m/t.stl", kTetraStl);
  const std::string urdf = R"(<robot name="p">
  <link name="a"><collision><geometry><mesh filename="package://my_pkg/meshes/t.stl"/></geometry></collision>
    <collision><geometry><mesh filename="package://amnt_pkg/t.stl" scale="2 2 2"/></geometry></collision>
    <collision><geometry><mesh filename="package://meshes/t.stl"/></geometry></collision>
    <collision><geometry><mesh filename="meshes/t.stl"/></geometry></collision>
    <collision><geometry><mesh filename="package://xpl/m/t.stl"/></geometry></collision>
    <collision><geometry><mesh filename="file://)" +
                           (tempDir() / "robotdir/meshes/t.stl").string() +
                           R"("/></geometry></collision>
  </link></robot>)";
  const std::string path = write("robotdir/p.urdf", urdf);
  ::setenv("ROS_PACKAGE_PATH", (tempDir() / "ws").c_str(), 1);
  ::setenv("AMENT_PREFIX_PATH", (tempDir() / "prefix").c_str(), 1);
  dss::LoadOptions o;
  o.mesh_paths.package_dirs["xpl"] = (tempDir() / "explicit_root").string();
  const auto m = dss::loadUrdf(path, o);
  BOOST_TEST(m.numCollisionElements() == 6u);
  const auto& scaled = std::get<dss::ConvexHull>(m.links[0].collisions[1].shape);
  // STL stores floats: 0.1f scaled by 2.
  BOOST_TEST(std::abs(scaled.support(Vector3d::UnitX(), Vector3d::Zero()).x() - 0.2) < 1e-7);
  // Without the explicit root, the error names the link and the URI.
  const std::string msg = [&] {
    try {
      dss::loadUrdf(path);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  BOOST_TEST(contains(msg, "link 'a' collision[4]"));
  BOOST_TEST(contains(msg, "package://xpl/m/t.stl"));
  ::unsetenv("ROS_PACKAGE_PATH");
  ::unsetenv("AMENT_PREFIX_PATH");
}

BOOST_AUTO_TEST_CASE(bad_input_names_file_and_element) {
  std::string e = errorOf("<robot name='x'><link name='a'></robot>", "malformed.urdf");
  BOOST_TEST(contains(e, "malformed.urdf:"));
  BOOST_TEST(contains(e, "malformed XML"));

  e = errorOf(
      R"(<robot name="x"><link name="a"><collision><geometry><mesh filename="nowhere.stl"/></geometry></collision></link></robot>)",
      "missing_mesh.urdf");
  BOOST_TEST(contains(e, "missing_mesh.urdf:1"));
  BOOST_TEST(contains(e, "link 'a' collision[0]"));
  BOOST_TEST(contains(e, "nowhere.stl"));

  write("empty.stl", "");
  e = errorOf(
      R"(<robot name="x"><link name="a"><collision><geometry><mesh filename="empty.stl"/></geometry></collision></link></robot>)",
      "empty_mesh.urdf");
  BOOST_TEST(contains(e, "empty_mesh.urdf"));
  BOOST_TEST(contains(e, "link 'a' collision[0]"));
  BOOST_TEST(contains(e, "empty.stl"));

  e = errorOf(
      "<robot name=\"x\">\n<link name=\"a\">\n<collision><geometry><box size=\"1 -1 "
      "1\"/></geometry></collision></link></robot>",
      "negative.urdf");
  BOOST_TEST(contains(e, "negative.urdf:3"));
  BOOST_TEST(contains(e, "link 'a' collision[0]"));
  BOOST_TEST(contains(e, "negative"));

  e = errorOf(
      R"(<robot name="x"><link name="a"><collision><origin xyz="0 nan 0"/><geometry><sphere radius="1"/></geometry></collision></link></robot>)",
      "nan_collision.urdf");
  BOOST_TEST(contains(e, "nan_collision.urdf"));
  BOOST_TEST(contains(e, "link 'a' collision[0] origin xyz"));

  e = errorOf(
      "<robot name=\"x\"><link name=\"a\"/><link name=\"b\"/>\n<joint name=\"j\" "
      "type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/>\n<origin rpy=\"0 0 "
      "NaN\"/></joint></robot>",
      "nan_joint.urdf");
  BOOST_TEST(contains(e, "nan_joint.urdf:3"));
  BOOST_TEST(contains(e, "joint 'j' origin rpy"));

  e = errorOf(
      R"(<robot name="x"><link name="a"/><link name="b"/><link name="c"/><joint name="free" type="planar"><parent link="a"/><child link="b"/></joint><joint name="m" type="prismatic"><parent link="b"/><child link="c"/><limit lower="0" upper="1" effort="1" velocity="1"/><mimic joint="free"/></joint></robot>)",
      "mimic_planar.urdf");
  BOOST_TEST(contains(e, "mimic_planar.urdf"));
  BOOST_TEST(contains(e, "joint 'm' mimics the multi-DOF joint 'free'"));

  e = errorOf(
      R"(<robot name="x"><link name="a"/><link name="b"/><joint name="j" type="revolute"><parent link="a"/><child link="b"/></joint></robot>)",
      "nolimit.urdf");
  BOOST_TEST(contains(e, "nolimit.urdf"));

  e = errorOf(
      R"(<robot name="x"><link name="a"/><link name="b"/><joint name="j" type="revolute"><parent link="a"/><child link="nope"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint></robot>)",
      "badchild.urdf");
  BOOST_TEST(contains(e, "badchild.urdf"));

  BOOST_TEST(contains(errorOf("", "empty.urdf"), "empty.urdf"));
  BOOST_CHECK_THROW(dss::loadUrdf((tempDir() / "does_not_exist.urdf").string()),
                    std::runtime_error);
}

BOOST_AUTO_TEST_CASE(dropped_collisions_are_errors_or_loud_warnings) {
  // urdfdom drops collisions after an unknown geometry; we count every <collision>.
  const std::string urdf = R"(<robot name="x"><link name="a">
    <collision><geometry><sphere radius="1"/></geometry></collision>
    <collision><geometry><torus radius="1"/></geometry></collision>
    <collision><geometry><box size="1 1 1"/></geometry></collision>
    <collision><geometry><capsule radius="0.1" length="0.5"/></geometry></collision>
  </link></robot>)";
  const std::string e = errorOf(urdf, "torus.urdf");
  BOOST_TEST(contains(e, "torus.urdf:3"));
  BOOST_TEST(contains(e, "link 'a' collision[1]"));
  BOOST_TEST(contains(e, "<torus>"));
  dss::LoadOptions o;
  o.allow_dropped_collisions = true;
  const auto m = dss::loadUrdf(write("torus_ok.urdf", urdf), o);
  BOOST_TEST(m.numCollisionElements() == 3u);  // sphere, box, capsule (an extension we read)
  BOOST_TEST(std::count_if(m.warnings.begin(), m.warnings.end(), [](const std::string& w) {
               return contains(w, "dropped collision") && contains(w, "<torus>");
             }) == 1);
  BOOST_TEST(std::holds_alternative<dss::Capsule>(m.links[0].collisions[2].shape));
}

BOOST_AUTO_TEST_CASE(self_collision_pairs_skip_adjacent_across_empty_links) {
  // chain a - e(no geometry) - b - c, and e - d: a, b, d all adjacent through e.
  const std::string urdf = R"(<robot name="x">
  <link name="a"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="e"/>
  <link name="b"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="c"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="d"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="f"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <joint name="ae" type="revolute"><parent link="a"/><child link="e"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="eb" type="revolute"><parent link="e"/><child link="b"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="bc" type="revolute"><parent link="b"/><child link="c"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="ed" type="revolute"><parent link="e"/><child link="d"/><origin xyz="0 1 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="cf" type="fixed"><parent link="c"/><child link="f"/><origin xyz="0 0 3"/></joint>
</robot>)";
  const auto m = dss::loadUrdf(write("pairs.urdf", urdf));
  auto idx = [&](const char* n) { return m.linkIndex(n); };
  auto pr = [&](const char* x, const char* y) {
    return dss::LinkPair{std::min(idx(x), idx(y)), std::max(idx(x), idx(y))};
  };
  const auto adj = dss::adjacentLinkPairs(m);
  std::vector<dss::LinkPair> expected = {pr("a", "b"), pr("a", "d"), pr("b", "d"), pr("b", "c"),
                                         pr("c", "f")};
  std::sort(expected.begin(), expected.end());
  BOOST_TEST(adj == expected);
  // 5 geometry links: 10 pairs; 5 adjacent; c-f is also rigid but counted adjacent.
  const auto srdf = dss::parseSrdf(
      R"(<robot name="x"><disable_collisions link1="d" link2="c" reason="Never"/></robot>)",
      "x.srdf");
  const auto pairs = dss::selfCollisionPairs(m, &srdf, {{"a", "f"}});
  BOOST_TEST(pairs.all_pairs == 10u);
  BOOST_TEST(pairs.adjacent == 5u);
  BOOST_TEST(pairs.disabled == 1u);
  BOOST_TEST(pairs.allowed == 1u);
  BOOST_TEST(pairs.pairs.size() == 3u);  // a-c, b-f, d-f
  BOOST_TEST_MESSAGE(pairs.summary());
  const auto bad = dss::parseSrdf(
      R"(<robot name="x"><disable_collisions link1="zz" link2="c"/></robot>)", "bad.srdf");
  BOOST_CHECK_THROW(dss::selfCollisionPairs(m, &bad), std::runtime_error);
}

BOOST_AUTO_TEST_CASE(disabled_pairs_by_sampling) {
  // A base with two arms: "near" always overlaps the base's post, "far" never reaches anything,
  // "swing" sometimes hits "post".
  const std::string urdf = R"(<robot name="s">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="post"><collision><geometry><box size="0.1 0.1 1"/></geometry></collision></link>
  <link name="near"><collision><geometry><sphere radius="0.3"/></geometry></collision></link>
  <link name="far"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="swing"><collision><origin xyz="0.5 0 0"/><geometry><sphere radius="0.1"/></geometry></collision></link>
  <joint name="bp" type="fixed"><parent link="base"/><child link="post"/><origin xyz="0 0 0.6"/></joint>
  <joint name="bn" type="revolute"><parent link="base"/><child link="near"/><origin xyz="0 0 0.6"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="bf" type="revolute"><parent link="base"/><child link="far"/><origin xyz="5 0 0"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="bs" type="revolute"><parent link="base"/><child link="swing"/><origin xyz="0.5 0 0.6"/><axis xyz="0 0 1"/><limit lower="-3.1" upper="3.1" effort="1" velocity="1"/></joint>
</robot>)";
  const auto m = dss::loadUrdf(write("sampling.urdf", urdf));
  dss::DisabledPairsOptions o;
  o.samples = 300;
  o.seed = 42;
  o.include_default = false;
  const auto r = dss::computeDisabledPairs(m, o);
  std::map<std::pair<std::string, std::string>, std::string> reason;
  for (const auto& p : r.pairs)
    reason[{std::min(p.link1, p.link2), std::max(p.link1, p.link2)}] = p.reason;
  auto why = [&](const std::string& a, const std::string& b) {
    const auto it = reason.find({std::min(a, b), std::max(a, b)});
    return it == reason.end() ? std::string("checked") : it->second;
  };
  BOOST_TEST(why("base", "post") == "Adjacent");
  BOOST_TEST(why("near", "post") == "Always");
  BOOST_TEST(why("far", "post") == "Never");
  BOOST_TEST(why("post", "swing") == "checked");  // sometimes in collision: must stay checked
  BOOST_TEST(contains(r.toSrdf(), "<disable_collisions link1="));
  // Deterministic for a seed.
  BOOST_TEST(dss::computeDisabledPairs(m, o).toSrdf() == r.toSrdf());
}

BOOST_AUTO_TEST_CASE(srdf_bad_input) {
  std::string msg;
  try {
    dss::parseSrdf("<robot name='x'>\n<group name='g'>\n</robot>", "bad.srdf");
  } catch (const std::exception& e) {
    msg = e.what();
  }
  BOOST_TEST(contains(msg, "bad.srdf:"));
  try {
    msg.clear();
    dss::parseSrdf(
        "<robot name='x'>\n<group_state name='s' group='g'>\n<joint name='j' "
        "value='abc'/></group_state></robot>",
        "val.srdf");
  } catch (const std::exception& e) {
    msg = e.what();
  }
  BOOST_TEST(contains(msg, "val.srdf:3"));
  const auto m = dss::loadUrdf(write("arm2.urdf", kArm));
  const auto s = dss::parseSrdf(
      "<robot name='arm'><group name='g'><joint name='j1'/><joint name='zz'/></group>"
      "<group name='c'><chain base_link='base' tip_link='l3'/></group></robot>",
      "g.srdf");
  BOOST_CHECK_THROW(dss::groupActiveJoints(m, s, "g"), std::runtime_error);
  BOOST_TEST(dss::groupActiveJoints(m, s, "c") == (std::vector<int>{0, 1}));
  BOOST_TEST(dss::checkSrdfAgainstModel(m, s).size() == 1u);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(kinematics_folding)

BOOST_AUTO_TEST_CASE(fixed_links_without_geometry_are_folded) {
  // a -j(rev)-> b -f1(fixed)-> c(no geometry) -f2(fixed)-> d(geometry); e hangs off c without
  // geometry.
  const std::string urdf = R"(<robot name="f">
  <link name="a"/><link name="b"/><link name="c"/><link name="e"/>
  <link name="d"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0 1" rpy="0.3 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="f1" type="fixed"><parent link="b"/><child link="c"/><origin xyz="0.5 0 0" rpy="0 0.4 0"/></joint>
  <joint name="f2" type="fixed"><parent link="c"/><child link="d"/><origin xyz="0 0.5 0" rpy="0 0 0.6"/></joint>
  <joint name="ce" type="revolute"><parent link="c"/><child link="e"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>)";
  const auto m = dss::loadUrdf(write("fold.urdf", urdf));
  const dss::Kinematics fast(m), all(m, true);
  BOOST_TEST(fast.updatedLinks().size() == 3u);  // a, b, d (c folded, e leads to no geometry)
  const auto A = fast.linkPoses({0.8, 0.1}), B = all.linkPoses({0.8, 0.1});
  const int d = m.linkIndex("d");
  BOOST_TEST((A[d].matrix() - B[d].matrix()).norm() < 1e-14);
  const Isometry3d b =
      pose(Vector3d(0, 0, 1), rot(0.3, Vector3d::UnitX()) * rot(0.8, Vector3d::UnitY()));
  const Isometry3d expect = b * pose(Vector3d(0.5, 0, 0), rot(0.4, Vector3d::UnitY())) *
                            pose(Vector3d(0, 0.5, 0), rot(0.6, Vector3d::UnitZ()));
  BOOST_TEST((A[d].matrix() - expect.matrix()).norm() < 1e-14);
}

BOOST_AUTO_TEST_SUITE_END()

#include "dss/robot/joint_state.h"

BOOST_AUTO_TEST_SUITE(joint_state)

BOOST_AUTO_TEST_CASE(assemble_state_from_named_values) {
  const auto m = dss::loadUrdf(write("arm3.urdf", kArm));
  std::vector<std::string> notes;
  // j2 above its limit (kept, noted), m is a mimic (ignored, disagreement noted), f is fixed.
  const auto q = dss::assembleState(m, {{"j1", 0.5}, {"j2", 0.65}, {"m", 0.0}, {"f", 1.0}},
                                    "req.yaml", &notes);
  BOOST_TEST(q == (std::vector<double>{0.5, 0.65}));
  BOOST_TEST(notes.size() == 3u);
  for (const auto& n : notes) BOOST_TEST(contains(n, "req.yaml: "));
  // Unnamed joints keep the base state.
  BOOST_TEST(dss::assembleState(m, {{"j2", 0.1}}, "s", nullptr, {2.0, 0.0}) ==
             (std::vector<double>{2.0, 0.1}));
  try {
    dss::assembleState(m, {{"elbow", 0.1}}, "req.yaml");
    BOOST_FAIL("expected an exception");
  } catch (const std::runtime_error& e) {
    BOOST_TEST(contains(e.what(), "req.yaml: joint 'elbow'"));
  }
  BOOST_CHECK_THROW(dss::assembleState(m, {{"j1", NAN}}, "s"), std::runtime_error);
}

BOOST_AUTO_TEST_SUITE_END()
