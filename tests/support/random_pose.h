// A random rigid pose for seeded tests: a uniformly random rotation (a normalised Gaussian
// quaternion) and a Gaussian translation of standard deviation `spread` per axis.
#pragma once

#include <Eigen/Geometry>
#include <random>

namespace dss_test {

inline Eigen::Isometry3d randomPose(std::mt19937_64& rng, double spread) {
  std::normal_distribution<double> n;
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
  X.translation() = spread * Eigen::Vector3d(n(rng), n(rng), n(rng));
  return X;
}

}  // namespace dss_test
