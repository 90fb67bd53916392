// The chains of balls along collision elements (sphere_chain.h): the outer balls together hold
// the shape (its extreme points in random directions, and points between them), a long shape
// gets as many points as it is longer than wide and balls far smaller than its bounding
// sphere, and every inner ball lies inside the shape (the support function in random
// directions); cones and flat hulls get no inner ball, a sphere one point, degenerate shapes no
// NaN.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "dss/checker/element_bounds.h"
#include "dss/checker/sphere_chain.h"

namespace {

Eigen::Vector3d randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
}

Eigen::Vector3d support(const dss::AnyShape& shape, const Eigen::Vector3d& u) {
  return std::visit(
      [&](const auto& s) { return Eigen::Vector3d(s.support(u, Eigen::Vector3d::Zero())); }, shape);
}

struct Named {
  std::string name;
  dss::AnyShape shape;
  int points;        // expected number of chain points (0: not checked)
  double max_outer;  // every outer radius at most this (0: not checked)
  bool inner_balls;  // some point has an inner ball
};

dss::ConvexHull cloud(std::mt19937_64& rng, const Eigen::Vector3d& scale, int n) {
  std::normal_distribution<double> g;
  std::vector<Eigen::Vector3d> pts;
  for (int k = 0; k < n; ++k)
    pts.push_back(Eigen::Vector3d(g(rng), g(rng), g(rng)).cwiseProduct(scale) +
                  Eigen::Vector3d(0.1, -0.2, 0.05));
  return dss::ConvexHull(pts);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(sphere_chain)

BOOST_AUTO_TEST_CASE(outer_balls_hold_the_shape_and_inner_balls_lie_inside) {
  std::mt19937_64 rng(53);
  std::uniform_real_distribution<double> f(0.0, 1.0);
  std::vector<Named> shapes = {
      {"long box", dss::Box{Eigen::Vector3d(0.5, 0.075, 0.075)}, 7, 0.13, true},
      {"cube", dss::Box{Eigen::Vector3d(0.2, 0.2, 0.2)}, 1, 0.35, true},
      {"flat box", dss::Box{Eigen::Vector3d(0.3, 0.0, 0.1)}, 3, 0.1415, false},
      {"point box", dss::Box{Eigen::Vector3d::Zero()}, 1, 1e-6, false},
      {"long cylinder", dss::Cylinder{0.05, 0.4}, 8, 0.0708, true},
      {"disc", dss::Cylinder{0.3, 0.02}, 1, 0.3007, true},
      {"capsule", dss::Capsule{0.04, 0.2}, 6, 0.0694, true},
      {"sphere", dss::Sphere{0.1}, 1, 0.1 + 1e-6, true},
      {"ellipsoid", dss::Ellipsoid{Eigen::Vector3d(0.3, 0.1, 0.05)}, 3, 0.1501, true},
      {"cone", dss::Cone{0.1, 0.3}, 3, 0.1733, false},
      {"long hull", cloud(rng, Eigen::Vector3d(0.4, 0.08, 0.05), 60), 0, 0.0, true},
      {"round hull", cloud(rng, Eigen::Vector3d(0.1, 0.1, 0.1), 40), 0, 0.0, true},
      {"flat hull", cloud(rng, Eigen::Vector3d(0.3, 0.1, 0.0), 30), 0, 0.0, false},
  };
  int covered = 0, inner_checked = 0;
  for (const Named& n : shapes) {
    Eigen::Vector3d box_c, box_h, center;
    double radius;
    dss::localBox(n.shape, &box_c, &box_h);
    dss::elementSphere(n.shape, Eigen::Isometry3d::Identity(), &center, &radius);
    const dss::SphereChain chain = dss::sphereChain(n.shape, box_c, box_h);
    BOOST_TEST_REQUIRE(chain.num_points >= 1, n.name);
    BOOST_TEST_REQUIRE(chain.num_points <= dss::SphereChain::kMaxPoints, n.name);
    if (n.points > 0) BOOST_TEST(chain.num_points == n.points, n.name);
    bool any_inner = false;
    for (int k = 0; k < chain.num_points; ++k) {
      BOOST_TEST(chain.center_S[k].allFinite(), n.name);
      BOOST_TEST(std::isfinite(chain.outer[k]), n.name);
      BOOST_TEST(chain.inner[k] >= 0.0, n.name);
      BOOST_TEST(chain.inner[k] <= chain.outer[k], n.name);
      if (n.max_outer > 0.0) BOOST_TEST(chain.outer[k] <= n.max_outer, n.name << " point " << k);
      // Never looser than the bounding sphere by more than a box's corners can be.
      BOOST_TEST(chain.outer[k] <= std::sqrt(3.0) * radius + 1e-9, n.name);
      any_inner = any_inner || chain.inner[k] > 0.0;
    }
    BOOST_TEST(any_inner == n.inner_balls, n.name);
    // The shape's extreme points, and points between three of them (inside the shape): each
    // within some outer ball.
    std::vector<Eigen::Vector3d> extreme;
    for (int k = 0; k < 1500; ++k) extreme.push_back(support(n.shape, randomUnit(rng)));
    for (int k = 0; k < 3000; ++k) {
      Eigen::Vector3d p = extreme[std::size_t(k) % extreme.size()];
      if (k >= 1500) {
        const double a = f(rng), b = f(rng) * (1.0 - a);
        p = a * p + b * extreme[std::size_t(k * 7) % extreme.size()] +
            (1.0 - a - b) * extreme[std::size_t(k * 13) % extreme.size()];
      }
      bool in = false;
      for (int j = 0; j < chain.num_points && !in; ++j)
        in = (p - chain.center_S[j]).norm() <= chain.outer[j];
      covered += in;
      BOOST_TEST(in, n.name << ": point " << p.transpose() << " in no outer ball");
    }
    // Inner balls inside: h(u) >= u.c + r in every direction.
    for (int j = 0; j < chain.num_points; ++j) {
      if (!(chain.inner[j] > 0.0)) continue;
      for (int k = 0; k < 500; ++k) {
        const Eigen::Vector3d u = randomUnit(rng);
        ++inner_checked;
        BOOST_TEST(support(n.shape, u).dot(u) >= u.dot(chain.center_S[j]) + chain.inner[j],
                   n.name << " inner ball " << j);
      }
    }
  }
  BOOST_TEST(covered == 3000 * int(shapes.size()));
  BOOST_TEST(inner_checked > 5000);
}

// A long shape is covered much more tightly than by its sphere: the long hull's balls are at
// most half its bounding radius, and cut more finely the longer it is.
BOOST_AUTO_TEST_CASE(longer_shapes_get_more_and_smaller_balls) {
  int previous = 0;
  for (const double length : {0.1, 0.3, 0.6, 1.2}) {
    const dss::Box box{Eigen::Vector3d(length, 0.05, 0.04)};
    Eigen::Vector3d box_c, box_h, center;
    double radius;
    dss::localBox(box, &box_c, &box_h);
    dss::elementSphere(box, Eigen::Isometry3d::Identity(), &center, &radius);
    const dss::SphereChain chain = dss::sphereChain(box, box_c, box_h);
    BOOST_TEST(chain.num_points >= previous);
    previous = chain.num_points;
    for (int k = 0; k < chain.num_points; ++k) {
      if (length >= 0.3) BOOST_TEST(chain.outer[k] <= 0.5 * radius);
      BOOST_TEST(std::abs(chain.inner[k] - 0.04) < 1e-6);  // the thinnest half extent
    }
  }
  BOOST_TEST(previous == dss::SphereChain::kMaxPoints);
}

BOOST_AUTO_TEST_SUITE_END()
