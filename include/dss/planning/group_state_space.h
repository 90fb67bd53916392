// The OMPL state space of a planning group, and the map between its states and the robot's
// joint values.
//
// A group's bounded joints (revolute, prismatic) become one RealVectorStateSpace with the
// URDF limits, in group order. When the group has continuous joints or multi-DOF joints, the
// space is a CompoundStateSpace: the real-vector part first (if any), then one SO2StateSpace
// per continuous joint, one SE2StateSpace per planar joint and one SE3StateSpace per floating
// joint (multi_dof.h), in group order. The translation of a planar or floating joint needs
// bounds (setMultiDofTranslationBounds, e.g. from a request's workspace_parameters): the
// constructor refuses a group with an unbounded one. Joints outside the group are held at fixed
// values (typically a request's start state; a warning is recorded when such a value lies outside
// its limits, e.g. Panda fingers at 0.065 against an upper limit of 0.04). toJoints() also
// validates: non-finite values and values outside the bounds make it return false, so NaN/Inf
// states are invalid.
#pragma once

#include <ompl/base/StateSpace.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "dss/robot/multi_dof.h"
#include "dss/robot/robot_model.h"

namespace dss {

class GroupStateMap {
 public:
  /// `group_active`: active joint indices (empty: all). `held`: one value per active joint.
  GroupStateMap(std::shared_ptr<const RobotModel> robot, std::vector<int> group_active,
                std::vector<double> held);

  const ompl::base::StateSpacePtr& space() const { return space_; }
  /// The number of group values (a planar joint has three, a floating joint seven).
  std::size_t dimension() const { return group_.size(); }
  const std::vector<int>& groupActive() const { return group_; }
  const std::vector<std::string>& jointNames() const { return names_; }
  const std::vector<double>& held() const { return held_; }
  const RobotModel& robot() const { return *robot_; }
  /// Lower/upper bound of group value i (continuous and planar theta: -pi, pi; quaternion
  /// values: -1, 1).
  double lower(std::size_t i) const { return lo_[i]; }
  double upper(std::size_t i) const { return hi_[i]; }
  /// True when the space is one RealVectorStateSpace holding every group value in group order
  /// (no continuous or multi-DOF joints in the group).
  bool plain() const { return plain_; }

  /// Writes every active joint value of the robot (held values, then the state's group values).
  /// Returns false (q partially written) when a value is non-finite or out of bounds.
  bool toJoints(const ompl::base::State* s, double* q) const;
  /// Group values (group order) <-> state.
  void toGroupValues(const ompl::base::State* s, double* g) const;
  /// True when every group value of the state is finite (no NaN, no infinity).
  bool finiteValues(const ompl::base::State* s) const;
  void fromGroupValues(const double* g, ompl::base::State* s) const;
  /// Group values from a joint-name map; missing names take the held value.
  std::vector<double> groupValues(const std::map<std::string, double>& by_name) const;

  std::vector<std::string> warnings;

 private:
  std::shared_ptr<const RobotModel> robot_;
  std::vector<int> group_;
  std::vector<double> held_;
  std::vector<std::string> names_;
  std::vector<double> lo_, hi_;
  // Where group value i lives: its kind, component (-1: the state is a plain RealVector) and
  // index within the component.
  enum class Kind : unsigned char { kReal, kSO2, kSE2, kSE3 };
  std::vector<Kind> kind_;
  std::vector<int> component_, index_;
  bool plain_ = true;
  ompl::base::StateSpacePtr space_;
};

}  // namespace dss
