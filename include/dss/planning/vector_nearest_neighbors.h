// Nearest neighbours for tree planners on a real vector space: OMPL's NearestNeighbors
// interface over the states' values, kept side by side in memory and scanned four points at a
// time (PointBlocks; the nearest state from PointBlocks::kTreeFrom states on by a k-d tree of
// buckets over the same values, point_tree.h), instead of OMPL's default metric tree (GNAT),
// which reaches every state through the planner's distance function and two pointers. Queries
// can be handed to a GNAT built over the same points with the same distance from a given size
// on (setLinearLimit; never by default).
//
// The distance is OMPL's RealVectorStateSpace::distance, with the same sums in the same order:
// a planner sees the same nearest states as with its default structure, up to exact ties, and
// grows the same trees. The structure does not call the distance function the planner gives
// it; it reads the values of `item->state`, which the items of OMPL's tree planners hold.
//
// The dimension is fixed when the structure is built, which OMPL's planners do with no
// argument: useVectorNearestNeighbors() builds it in a planner for its space's dimension.
#pragma once

// clang-format off
#include <iostream>  // before GNAT's header, which uses std::cout without including it
// clang-format on

#include <ompl/base/Planner.h>
#include <ompl/base/StateSpace.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/datastructures/NearestNeighbors.h>
#include <ompl/datastructures/NearestNeighborsGNATNoThreadSafety.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "dss/planning/point_blocks.h"

namespace dss {

namespace detail {
/// The dimension the next VectorNearestNeighbors takes (set by useVectorNearestNeighbors while
/// a planner builds its structures; 0 otherwise).
unsigned& pendingNearestDimension();
}  // namespace detail

template <class T>
class VectorNearestNeighbors : public ompl::NearestNeighbors<T> {
 public:
  /// The size from which queries go to the GNAT: never (the k-d tree's search beats GNAT's at
  /// every size measured, docs/performance.md#the-nearest-neighbour-search).
  static constexpr std::size_t kDefaultLinearLimit = std::numeric_limits<std::size_t>::max();

  /// Throws std::logic_error outside useVectorNearestNeighbors (the dimension is unknown).
  VectorNearestNeighbors() : VectorNearestNeighbors(detail::pendingNearestDimension()) {}
  /// Throws std::logic_error for dimension 0. Draws one seed from OMPL's seed generator, as the
  /// construction of OMPL's GNAT does (its pivot selection owns a random number generator): the
  /// generators a planner makes later then get the same seeds as with GNAT, and a seeded plan
  /// the same samples.
  explicit VectorNearestNeighbors(unsigned dimension, SimdPath path = activeSimdPath())
      : points_(dimension, path) {
    static_cast<void>(ompl::RNG());
    if (dimension == 0)
      throw std::logic_error(
          "VectorNearestNeighbors: no dimension (build it with dss::useVectorNearestNeighbors)");
  }

  /// Queries go to a GNAT from `n` points on (0: always; SIZE_MAX: never).
  void setLinearLimit(std::size_t n) {
    limit_ = n;
    if (gnat_ && items_.size() < limit_) gnat_.reset();
    syncTree();
  }
  std::size_t linearLimit() const { return limit_; }
  /// Whether queries go to the GNAT now.
  bool usesTree() const { return gnat_ != nullptr; }

  void clear() override {
    items_.clear();
    points_.clear();
    gnat_.reset();
  }
  bool reportsSortedResults() const override { return true; }
  void add(const T& data) override {
    items_.push_back(data);
    points_.push(values(data));
    if (gnat_)
      gnat_->add(data);
    else
      syncTree();
  }
  void add(const std::vector<T>& data) override {
    for (const T& d : data) add(d);
  }
  bool remove(const T& data) override {
    const auto it = std::find(items_.begin(), items_.end(), data);
    if (it == items_.end()) return false;
    const std::size_t i = std::size_t(it - items_.begin());
    items_[i] = items_.back();
    items_.pop_back();
    points_.swapRemove(i);
    if (gnat_) gnat_->remove(data);
    return true;
  }
  T nearest(const T& data) const override {
    if (gnat_) return gnat_->nearest(data);
    const std::size_t i = points_.nearest(values(data));
    if (i == PointBlocks::kNone)
      throw ompl::Exception("No elements found in nearest neighbors data structure");
    return items_[i];
  }
  void nearestK(const T& data, std::size_t k, std::vector<T>& nbh) const override {
    if (gnat_) return gnat_->nearestK(data, k, nbh);
    thread_local std::vector<PointBlocks::Found> found;
    points_.nearestK(values(data), k, found);
    nbh.clear();
    for (const auto& f : found) nbh.push_back(items_[f.second]);
  }
  void nearestR(const T& data, double radius, std::vector<T>& nbh) const override {
    if (gnat_) return gnat_->nearestR(data, radius, nbh);
    thread_local std::vector<PointBlocks::Found> found;
    points_.withinRadius(values(data), radius, found);
    nbh.clear();
    for (const auto& f : found) nbh.push_back(items_[f.second]);
  }
  std::size_t size() const override { return items_.size(); }
  void list(std::vector<T>& data) const override { data = items_; }

  /// OMPL's RealVectorStateSpace::distance on the items' values.
  double distance(const T& a, const T& b) const {
    const double* s1 = values(a);
    const double* s2 = values(b);
    double dist = 0.0;
    for (unsigned i = 0; i < points_.dimension(); ++i) {
      const double diff = s1[i] - s2[i];
      dist += diff * diff;
    }
    return std::sqrt(dist);
  }

 private:
  static const double* values(const T& item) {
    return item->state->template as<ompl::base::RealVectorStateSpace::StateType>()->values;
  }
  // Builds the GNAT once the points reach the limit.
  void syncTree() {
    if (gnat_ || items_.size() < limit_ || items_.empty()) return;
    gnat_ = std::make_unique<ompl::NearestNeighborsGNATNoThreadSafety<T>>();
    gnat_->setDistanceFunction([this](const T& a, const T& b) { return distance(a, b); });
    gnat_->add(items_);
  }

  std::vector<T> items_;
  PointBlocks points_;
  std::size_t limit_ = kDefaultLinearLimit;
  std::unique_ptr<ompl::NearestNeighborsGNATNoThreadSafety<T>> gnat_;
};

/// Builds VectorNearestNeighbors into `planner` (RRTConnect, RRT, RRTstar, LazyRRT or BiTRRT)
/// when its space is a RealVectorStateSpace; the planner is cleared and set up again, so call
/// it once the space information has its validity checker, before planning. Returns false, the
/// planner unchanged, for other planners and spaces.
bool useVectorNearestNeighbors(const ompl::base::PlannerPtr& planner);

}  // namespace dss
