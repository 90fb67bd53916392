// Named joint values -> a state vector (see dss/robot/joint_state.h).
#include "dss/robot/joint_state.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace dss {

std::vector<double> assembleState(const RobotModel& model,
                                  const std::vector<std::pair<std::string, double>>& named,
                                  const std::string& source, std::vector<std::string>* notes,
                                  std::vector<double> q) {
  if (q.empty()) q = model.defaultState();
  if (q.size() != model.numActiveJoints())
    throw std::runtime_error(source + ": base state has " + std::to_string(q.size()) +
                             " values, robot '" + model.name + "' has " +
                             std::to_string(model.numActiveJoints()) + " active joints");
  auto note = [&](const std::string& s) {
    if (notes) notes->push_back(source + ": " + s);
  };
  std::vector<std::pair<int, double>> mimics;
  for (const auto& [name, value] : named) {
    if (!std::isfinite(value))
      throw std::runtime_error(source + ": joint '" + name + "' has a non-finite value");
    // A quaternion variable of a floating joint (J/rot_x ...) is a value, not a joint.
    if (const int vi = model.variableIndex(name);
        vi >= 0 && model.joints[model.active_joints[vi]].type == JointType::kBall) {
      if (value < -1.0 || value > 1.0)
        note("quaternion variable '" + name + "' value " + std::to_string(value) +
             " is outside [-1, 1]; kept");
      q[vi] = value;
      continue;
    }
    const int ji = model.jointIndex(name);
    if (ji < 0)
      throw std::runtime_error(source + ": joint '" + name + "' is not a joint of robot '" +
                               model.name + "'");
    if (!std::isfinite(value))
      throw std::runtime_error(source + ": joint '" + name + "' has a non-finite value");
    const RobotJoint& j = model.joints[ji];
    if (!j.isMoving()) {
      note("joint '" + name + "' is fixed in the robot; its value is ignored");
      continue;
    }
    if (j.mimic_active >= 0) {
      mimics.emplace_back(ji, value);
      continue;
    }
    if (j.limits.has_position_limits && (value < j.limits.lower || value > j.limits.upper)) {
      std::ostringstream s;
      s << "joint '" << name << "' value " << value << " is outside its limits [" << j.limits.lower
        << ", " << j.limits.upper << "]; kept";
      note(s.str());
    }
    q[j.active_index] = value;
  }
  for (const auto& [ji, value] : mimics) {
    const RobotJoint& j = model.joints[ji];
    const double follows = j.mimic_multiplier * q[j.mimic_active] + j.mimic_offset;
    if (std::abs(follows - value) > 1e-9) {
      std::ostringstream s;
      s << "mimic joint '" << j.name << "' given " << value << " but follows its leader at "
        << follows << "; the given value is ignored";
      note(s.str());
    }
  }
  return q;
}

std::vector<double> heldState(const RobotModel& robot,
                              const std::vector<std::map<std::string, double>>& overrides,
                              std::vector<std::string>* ignored) {
  std::vector<double> q = robot.defaultState();
  for (const auto& m : overrides)
    for (const auto& [name, value] : m) {
      const int v = robot.variableIndex(name);
      if (v < 0) {
        if (ignored) ignored->push_back(name);
        continue;
      }
      q[v] = value;
    }
  return q;
}

}  // namespace dss
