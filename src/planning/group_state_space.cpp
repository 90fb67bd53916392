// GroupStateMap: OMPL space of a planning group and the state <-> joint value map.
#include "dss/planning/group_state_space.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>

#include <boost/math/constants/constants.hpp>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace ob = ompl::base;

namespace dss {

GroupStateMap::GroupStateMap(std::shared_ptr<const RobotModel> robot, std::vector<int> group_active,
                             std::vector<double> held)
    : robot_(std::move(robot)), group_(std::move(group_active)), held_(std::move(held)) {
  const RobotModel& m = *robot_;
  if (held_.size() != m.numActiveJoints())
    throw std::invalid_argument(
        "GroupStateMap: held state size differs from the robot's active joints");
  if (group_.empty())
    for (std::size_t i = 0; i < m.numActiveJoints(); ++i) group_.push_back(int(i));
  std::vector<int> bounded;
  int num_continuous = 0;
  for (int a : group_) {
    const RobotJoint& j = m.joints[m.active_joints.at(a)];
    names_.push_back(j.name);
    const bool cont = j.type == JointType::kContinuous || !j.limits.has_position_limits;
    continuous_.push_back(cont);
    if (cont) {
      lo_.push_back(-M_PI);
      hi_.push_back(M_PI);
      ++num_continuous;
    } else {
      if (!(j.limits.lower <= j.limits.upper) || !std::isfinite(j.limits.lower) ||
          !std::isfinite(j.limits.upper))
        throw std::runtime_error(m.source + ": joint " + j.name + " has invalid limits");
      lo_.push_back(j.limits.lower);
      hi_.push_back(j.limits.upper);
    }
  }
  const int num_bounded = int(group_.size()) - num_continuous;
  auto rv = num_bounded > 0 ? std::make_shared<ob::RealVectorStateSpace>(num_bounded) : nullptr;
  if (rv) {
    ob::RealVectorBounds b(num_bounded);
    int k = 0;
    for (std::size_t i = 0; i < group_.size(); ++i)
      if (!continuous_[i]) {
        b.setLow(k, lo_[i]);
        b.setHigh(k, hi_[i]);
        rv->setDimensionName(k, names_[i]);
        ++k;
      }
    rv->setBounds(b);
  }
  plain_ = num_continuous == 0;
  component_.assign(group_.size(), -1);
  index_.assign(group_.size(), 0);
  if (plain_) {
    for (std::size_t i = 0; i < group_.size(); ++i) index_[i] = int(i);
    space_ = rv;
  } else {
    auto compound = std::make_shared<ob::CompoundStateSpace>();
    int comp = 0, k = 0;
    if (rv) {
      compound->addSubspace(rv, 1.0);
      ++comp;
    }
    for (std::size_t i = 0; i < group_.size(); ++i) {
      if (continuous_[i]) {
        component_[i] = comp++;
        auto so2 = std::make_shared<ob::SO2StateSpace>();
        so2->setName(names_[i]);
        compound->addSubspace(so2, 1.0);
      } else {
        component_[i] = 0;
        index_[i] = k++;
      }
    }
    compound->lock();
    space_ = compound;
  }

  // Held joints outside their limits (not an error: MoveIt accepts such start states).
  std::vector<char> in_group(m.numActiveJoints(), 0);
  for (int a : group_) in_group[a] = 1;
  for (std::size_t a = 0; a < m.numActiveJoints(); ++a) {
    const RobotJoint& j = m.joints[m.active_joints[a]];
    if (!std::isfinite(held_[a]))
      throw std::runtime_error(m.source + ": held value of joint " + j.name + " is not finite");
    if (!in_group[a] && j.limits.has_position_limits &&
        (held_[a] < j.limits.lower || held_[a] > j.limits.upper)) {
      std::ostringstream os;
      os << "joint " << j.name << " is held at " << held_[a] << ", outside its limits ["
         << j.limits.lower << ", " << j.limits.upper << "]";
      warnings.push_back(os.str());
    }
  }
}

bool GroupStateMap::toJoints(const ob::State* s, double* q) const {
  std::copy(held_.begin(), held_.end(), q);
  bool ok = true;
  if (plain_) {
    const double* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
    for (std::size_t i = 0; i < group_.size(); ++i) {
      const double x = v[i];
      // Written so that NaN fails: !(lo <= x <= hi).
      if (!(x >= lo_[i] && x <= hi_[i])) ok = false;
      q[group_[i]] = x;
    }
    return ok;
  }
  const auto* c = s->as<ob::CompoundStateSpace::StateType>();
  for (std::size_t i = 0; i < group_.size(); ++i) {
    double x;
    if (continuous_[i]) {
      x = (*c)[component_[i]]->as<ob::SO2StateSpace::StateType>()->value;
      if (!std::isfinite(x)) ok = false;
    } else {
      x = (*c)[component_[i]]->as<ob::RealVectorStateSpace::StateType>()->values[index_[i]];
      if (!(x >= lo_[i] && x <= hi_[i])) ok = false;
    }
    q[group_[i]] = x;
  }
  return ok;
}

void GroupStateMap::toGroupValues(const ob::State* s, double* g) const {
  if (plain_) {
    const double* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
    std::copy(v, v + group_.size(), g);
    return;
  }
  const auto* c = s->as<ob::CompoundStateSpace::StateType>();
  for (std::size_t i = 0; i < group_.size(); ++i)
    g[i] = continuous_[i]
               ? (*c)[component_[i]]->as<ob::SO2StateSpace::StateType>()->value
               : (*c)[component_[i]]->as<ob::RealVectorStateSpace::StateType>()->values[index_[i]];
}

void GroupStateMap::fromGroupValues(const double* g, ob::State* s) const {
  if (plain_) {
    double* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
    std::copy(g, g + group_.size(), v);
    return;
  }
  auto* c = s->as<ob::CompoundStateSpace::StateType>();
  for (std::size_t i = 0; i < group_.size(); ++i) {
    if (continuous_[i]) {
      // SO2 values live in [-pi, pi).
      double x = std::remainder(g[i], 2.0 * M_PI);
      (*c)[component_[i]]->as<ob::SO2StateSpace::StateType>()->value = x;
    } else {
      (*c)[component_[i]]->as<ob::RealVectorStateSpace::StateType>()->values[index_[i]] = g[i];
    }
  }
}

std::vector<double> GroupStateMap::groupValues(const std::map<std::string, double>& by_name) const {
  std::vector<double> g(group_.size());
  for (std::size_t i = 0; i < group_.size(); ++i) {
    auto it = by_name.find(names_[i]);
    g[i] = it != by_name.end() ? it->second : held_[group_[i]];
  }
  return g;
}

}  // namespace dss
