// GroupStateMap: OMPL space of a planning group and the state <-> joint value map.
#include "dss/planning/group_state_space.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace ob = ompl::base;

namespace dss {

namespace {

// Value k of an SE(2) state: x, y, yaw.
double se2Get(const ob::State* s, int k) {
  const auto* st = s->as<ob::SE2StateSpace::StateType>();
  return k == 0 ? st->getX() : (k == 1 ? st->getY() : st->getYaw());
}

// Value k of an SE(3) state: x, y, z, then the quaternion x, y, z, w.
double se3Get(const ob::State* s, int k) {
  const auto* st = s->as<ob::SE3StateSpace::StateType>();
  switch (k) {
    case 0:
      return st->getX();
    case 1:
      return st->getY();
    case 2:
      return st->getZ();
    case 3:
      return st->rotation().x;
    case 4:
      return st->rotation().y;
    case 5:
      return st->rotation().z;
    default:
      return st->rotation().w;
  }
}

}  // namespace

GroupStateMap::GroupStateMap(std::shared_ptr<const RobotModel> robot, std::vector<int> group_active,
                             std::vector<double> held)
    : robot_(std::move(robot)), group_(std::move(group_active)), held_(std::move(held)) {
  const RobotModel& m = *robot_;
  if (held_.size() != m.numActiveJoints())
    throw std::invalid_argument(
        "GroupStateMap: held state size differs from the robot's active joints");
  if (group_.empty())
    for (std::size_t i = 0; i < m.numActiveJoints(); ++i) group_.push_back(int(i));
  const std::vector<std::string> names = m.activeJointNames();
  const std::size_t n = group_.size();
  kind_.assign(n, Kind::kReal);
  component_.assign(n, -1);
  index_.assign(n, 0);
  // Multi-DOF joints: the group must hold all their values, in order.
  std::vector<int> multi_first(n, -1);  // for a value of a multi-DOF joint: its first group slot
  for (std::size_t i = 0; i < n; ++i) {
    const int a = group_[i];
    const RobotJoint& j = m.joints[m.active_joints.at(a)];
    names_.push_back(names[a]);
    if (j.multi_dof < 0) continue;
    const MultiDofJoint& md = m.multi_dof_joints[j.multi_dof];
    const int first = m.joints[md.joints.front()].active_index;
    const int count = md.type == MultiDofType::kPlanar ? 3 : 7;
    if (a != first) continue;  // checked from the first value
    for (int k = 0; k < count; ++k)
      if (i + k >= n || group_[i + k] != first + k)
        throw std::runtime_error(m.source + ": the group holds part of the " +
                                 (md.type == MultiDofType::kPlanar ? "planar" : "floating") +
                                 " joint " + md.name + ", not all its values");
    for (int k = 0; k < count; ++k) {
      kind_[i + k] = md.type == MultiDofType::kPlanar ? Kind::kSE2 : Kind::kSE3;
      index_[i + k] = k;
      multi_first[i + k] = int(i);
    }
    // Its translation bounds.
    for (int k = 0; k < (md.type == MultiDofType::kPlanar ? 2 : 3); ++k) {
      const RobotJoint& t = m.joints[m.active_joints[first + k]];
      if (!t.limits.has_position_limits || !std::isfinite(t.limits.lower) ||
          !std::isfinite(t.limits.upper) || !(t.limits.lower <= t.limits.upper))
        throw std::runtime_error(
            m.source + ": the " + (md.type == MultiDofType::kPlanar ? "planar" : "floating") +
            " joint " + md.name + " has no finite bounds for " + names[first + k] +
            ": give them with the request's workspace_parameters or --workspace");
    }
  }
  int num_real = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const RobotJoint& j = m.joints[m.active_joints[group_[i]]];
    if (kind_[i] == Kind::kSE2) {
      const bool yaw = index_[i] == 2;
      lo_.push_back(yaw ? -M_PI : j.limits.lower);
      hi_.push_back(yaw ? M_PI : j.limits.upper);
    } else if (kind_[i] == Kind::kSE3) {
      const bool rot = index_[i] >= 3;
      lo_.push_back(rot ? -1.0 : j.limits.lower);
      hi_.push_back(rot ? 1.0 : j.limits.upper);
    } else if (j.type == JointType::kContinuous || !j.limits.has_position_limits) {
      kind_[i] = Kind::kSO2;
      lo_.push_back(-M_PI);
      hi_.push_back(M_PI);
    } else {
      if (!(j.limits.lower <= j.limits.upper) || !std::isfinite(j.limits.lower) ||
          !std::isfinite(j.limits.upper))
        throw std::runtime_error(m.source + ": joint " + j.name + " has invalid limits");
      lo_.push_back(j.limits.lower);
      hi_.push_back(j.limits.upper);
      index_[i] = num_real++;
    }
  }
  auto rv = num_real > 0 ? std::make_shared<ob::RealVectorStateSpace>(num_real) : nullptr;
  if (rv) {
    ob::RealVectorBounds b(num_real);
    for (std::size_t i = 0; i < n; ++i)
      if (kind_[i] == Kind::kReal) {
        b.setLow(index_[i], lo_[i]);
        b.setHigh(index_[i], hi_[i]);
        rv->setDimensionName(index_[i], names_[i]);
      }
    rv->setBounds(b);
  }
  plain_ = num_real == int(n);
  if (plain_) {
    space_ = rv;
  } else {
    auto compound = std::make_shared<ob::CompoundStateSpace>();
    int comp = 0;
    if (rv) {
      compound->addSubspace(rv, 1.0);
      ++comp;
    }
    for (std::size_t i = 0; i < n; ++i) {
      switch (kind_[i]) {
        case Kind::kReal:
          component_[i] = 0;
          break;
        case Kind::kSO2: {
          component_[i] = comp++;
          auto so2 = std::make_shared<ob::SO2StateSpace>();
          so2->setName(names_[i]);
          compound->addSubspace(so2, 1.0);
          break;
        }
        case Kind::kSE2:
        case Kind::kSE3: {
          if (multi_first[i] != int(i)) {
            component_[i] = component_[multi_first[i]];
            break;
          }
          component_[i] = comp++;
          const RobotJoint& j = m.joints[m.active_joints[group_[i]]];
          const std::string name = m.multi_dof_joints[j.multi_dof].name;
          // The translation's bounds are the first 2 (SE(2)) or 3 (SE(3)) values'.
          auto add = [&](auto space, int dims) {
            ob::RealVectorBounds b(dims);
            for (int k = 0; k < dims; ++k) b.setLow(k, lo_[i + k]), b.setHigh(k, hi_[i + k]);
            space->setBounds(b);
            space->setName(name);
            compound->addSubspace(space, 1.0);
          };
          if (kind_[i] == Kind::kSE2)
            add(std::make_shared<ob::SE2StateSpace>(), 2);
          else
            add(std::make_shared<ob::SE3StateSpace>(), 3);
          break;
        }
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
      throw std::runtime_error(m.source + ": held value of joint " + names[a] + " is not finite");
    if (!in_group[a] && j.limits.has_position_limits &&
        (held_[a] < j.limits.lower || held_[a] > j.limits.upper)) {
      std::ostringstream os;
      os << "joint " << names[a] << " is held at " << held_[a] << ", outside its limits ["
         << j.limits.lower << ", " << j.limits.upper << "]";
      warnings.push_back(os.str());
    }
  }
}

namespace {
// Written so that NaN fails: !(lo <= x <= hi).
inline bool inside(double x, double lo, double hi) { return x >= lo && x <= hi; }
}  // namespace

bool GroupStateMap::toJoints(const ob::State* s, double* q) const {
  std::copy(held_.begin(), held_.end(), q);
  bool ok = true;
  if (plain_) {
    const double* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
    for (std::size_t i = 0; i < group_.size(); ++i) {
      const double x = v[i];
      if (!inside(x, lo_[i], hi_[i])) ok = false;
      q[group_[i]] = x;
    }
    return ok;
  }
  const auto* c = s->as<ob::CompoundStateSpace::StateType>();
  for (std::size_t i = 0; i < group_.size(); ++i) {
    const ob::State* sub = (*c)[component_[i]];
    double x;
    switch (kind_[i]) {
      case Kind::kReal:
        x = sub->as<ob::RealVectorStateSpace::StateType>()->values[index_[i]];
        if (!inside(x, lo_[i], hi_[i])) ok = false;
        break;
      case Kind::kSO2:
        x = sub->as<ob::SO2StateSpace::StateType>()->value;
        if (!std::isfinite(x)) ok = false;
        break;
      case Kind::kSE2:
        x = se2Get(sub, index_[i]);
        if (index_[i] == 2 ? !std::isfinite(x) : !inside(x, lo_[i], hi_[i])) ok = false;
        break;
      case Kind::kSE3:
      default:
        x = se3Get(sub, index_[i]);
        if (!inside(x, lo_[i], hi_[i])) ok = false;
        break;
    }
    q[group_[i]] = x;
  }
  return ok;
}

bool GroupStateMap::finiteValues(const ob::State* s) const {
  thread_local std::vector<double> g;
  if (g.size() < group_.size()) g.resize(group_.size());
  toGroupValues(s, g.data());
  for (std::size_t i = 0; i < group_.size(); ++i)
    if (!std::isfinite(g[i])) return false;
  return true;
}

void GroupStateMap::toGroupValues(const ob::State* s, double* g) const {
  if (plain_) {
    const double* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
    std::copy(v, v + group_.size(), g);
    return;
  }
  const auto* c = s->as<ob::CompoundStateSpace::StateType>();
  for (std::size_t i = 0; i < group_.size(); ++i) {
    const ob::State* sub = (*c)[component_[i]];
    switch (kind_[i]) {
      case Kind::kReal:
        g[i] = sub->as<ob::RealVectorStateSpace::StateType>()->values[index_[i]];
        break;
      case Kind::kSO2:
        g[i] = sub->as<ob::SO2StateSpace::StateType>()->value;
        break;
      case Kind::kSE2:
        g[i] = se2Get(sub, index_[i]);
        break;
      case Kind::kSE3:
        g[i] = se3Get(sub, index_[i]);
        break;
    }
  }
}

void GroupStateMap::fromGroupValues(const double* g, ob::State* s) const {
  if (plain_) {
    double* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
    std::copy(g, g + group_.size(), v);
    return;
  }
  auto* c = s->as<ob::CompoundStateSpace::StateType>();
  for (std::size_t i = 0; i < group_.size(); ++i) {
    ob::State* sub = (*c)[component_[i]];
    switch (kind_[i]) {
      case Kind::kReal:
        sub->as<ob::RealVectorStateSpace::StateType>()->values[index_[i]] = g[i];
        break;
      case Kind::kSO2:  // SO2 values live in [-pi, pi)
        sub->as<ob::SO2StateSpace::StateType>()->value = std::remainder(g[i], 2.0 * M_PI);
        break;
      case Kind::kSE2: {
        if (index_[i] != 0) break;  // the whole state from its first value
        auto* st = sub->as<ob::SE2StateSpace::StateType>();
        st->setXY(g[i], g[i + 1]);
        st->setYaw(std::remainder(g[i + 2], 2.0 * M_PI));
        break;
      }
      case Kind::kSE3: {
        if (index_[i] != 0) break;
        auto* st = sub->as<ob::SE3StateSpace::StateType>();
        st->setXYZ(g[i], g[i + 1], g[i + 2]);
        // OMPL's SO(3) states are unit quaternions: a given one is normalised (a zero one
        // stays zero and is refused by toJoints' caller, the checker, as invalid).
        const double* r = g + i + 3;
        const double norm = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
        const double f = norm > 0.0 && std::isfinite(norm) ? 1.0 / norm : 1.0;
        auto& rot = st->rotation();
        rot.x = r[0] * f, rot.y = r[1] * f, rot.z = r[2] * f, rot.w = r[3] * f;
        break;
      }
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
