// Uses the installed core: two unit boxes, touching, then apart.
#include <dss/core/dss.h>

#include <cstdio>

int main() {
  const dss::Mat3d I = dss::Mat3d::Identity();
  const auto a = dss::posed(dss::Box::fromSize({1, 1, 1}), I, dss::Vec3d(0, 0, 0));
  const auto b = dss::posed(dss::Box::fromSize({1, 1, 1}), I, dss::Vec3d(1, 0, 0));
  const auto c = dss::posed(dss::Box::fromSize({1, 1, 1}), I, dss::Vec3d(1.5, 0, 0));
  const bool ok = dss::intersect(a, b).intersect && !dss::intersect(a, c).intersect;
  std::printf("downstream: %s\n", ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
