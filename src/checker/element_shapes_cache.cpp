// The process-wide cache of element bounds (see dss/checker/element_shapes_cache.h).
#include "dss/checker/element_shapes_cache.h"

#include <cmath>
#include <deque>
#include <mutex>

#include "dss/checker/element_bounds.h"
#include "dss/checker/inner_shapes.h"

namespace dss {

CachedElementShapes computeElementShapes(const CollisionElement& ce) {
  CachedElementShapes e;
  elementSphere(ce.shape, ce.X_LS, &e.center_L, &e.radius);
  localBox(ce.shape, &e.box_center_S, &e.box_half);
  e.num_inner = innerBalls(ce.shape, e.box_center_S, e.box_half, e.inner_S, e.kMaxInner);
  // The box only where it holds more than the balls: on rounded links it would be small and
  // cost a test whenever a pair reaches the inner stage.
  double balls_volume = 0.0;
  for (int b = 0; b < e.num_inner; ++b)
    balls_volume += 4.18879020478639 * std::pow(e.inner_S[b].w(), 3);  // 4/3 pi r^3
  e.has_inner_box =
      innerBox(ce.shape, e.box_center_S, e.box_half, &e.inner_box_c, &e.inner_box_h) &&
      8.0 * e.inner_box_h.prod() >= balls_volume;
  e.chain = sphereChain(ce.shape, e.box_center_S, e.box_half);
  return e;
}

namespace {

constexpr std::size_t kMaxRobots = 16;

struct Entry {
  std::weak_ptr<const RobotModel> robot;
  const RobotModel* robot_ptr = nullptr;
  std::shared_ptr<const std::vector<CachedElementShapes>> shapes;
};

struct Cache {
  std::mutex mutex;
  std::deque<Entry> entries;  // oldest first
};

Cache& cache() {
  static Cache c;
  return c;
}

}  // namespace

std::shared_ptr<const std::vector<CachedElementShapes>> cachedElementShapes(
    const std::shared_ptr<const RobotModel>& robot) {
  Cache& c = cache();
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    for (const Entry& e : c.entries) {
      // The same address may hold another robot once the first is gone: an entry counts only
      // while its robot lives.
      if (e.robot_ptr != robot.get()) continue;
      const std::shared_ptr<const RobotModel> alive = e.robot.lock();
      if (alive && alive.get() == robot.get()) return e.shapes;
    }
  }
  auto shapes = std::make_shared<std::vector<CachedElementShapes>>();
  for (const RobotLink& link : robot->links)
    for (const CollisionElement& ce : link.collisions) shapes->push_back(computeElementShapes(ce));
  std::lock_guard<std::mutex> lock(c.mutex);
  for (auto it = c.entries.begin(); it != c.entries.end();)  // the dead and this robot's
    it = it->robot.expired() || it->robot_ptr == robot.get() ? c.entries.erase(it) : it + 1;
  c.entries.push_back({robot, robot.get(), shapes});
  while (c.entries.size() > kMaxRobots) c.entries.pop_front();
  return shapes;
}

}  // namespace dss
