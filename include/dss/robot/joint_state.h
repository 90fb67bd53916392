// A full robot state (one value per active joint) from named joint values, as requests and
// SRDF group states give them.
//
// Real files are loose: MotionBenchMaker starts the Panda fingers at 0.065, above the URDF's
// 0.04 limit (kept, with a warning: refusing would reject every MBM problem), and the UR5
// requests name Robotiq joints that are fixed in the URDF (ignored, with a note). A joint the
// robot lacks is an error naming the source and the joint. Mimic joints named explicitly are
// ignored (they follow their leader); a value that disagrees with the leader is noted.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "dss/robot/robot_model.h"

namespace dss {

/// Starts from `base` (defaultState() when empty) and sets every named active joint.
/// `notes` (optional) receives one line per warning (out-of-limit value, fixed or mimic joint
/// ignored). Throws std::runtime_error "<source>: joint 'x' ..." for an unknown joint or a
/// non-finite value.
std::vector<double> assembleState(const RobotModel& model,
                                  const std::vector<std::pair<std::string, double>>& named,
                                  const std::string& source,
                                  std::vector<std::string>* notes = nullptr,
                                  std::vector<double> base = {});

/// Held values of every active joint: the model's default state, then `overrides` by name
/// (scene robot state, request start). Unknown names are skipped (returned in `ignored`).
std::vector<double> heldState(const RobotModel& robot,
                              const std::vector<std::map<std::string, double>>& overrides,
                              std::vector<std::string>* ignored = nullptr);

}  // namespace dss
