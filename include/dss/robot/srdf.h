// The semantic robot description (SRDF, as MoveIt writes it): planning groups, pairs of links
// whose collisions are never checked, and named group states.
//
// A planning group is built from joints, links (their parent joint), chains (the joints from
// the tip up to, not including, the base link's parent joint) and subgroups, as MoveIt does.
// Its state is the ordered list of its active joints (model order); every other joint keeps
// the value given by the caller (e.g. a request's start state). Subgroups are expanded once
// each (shared subgroups are not expanded again), a group that includes itself is an error
// naming the groups, and subgroup nesting is bounded by RobotInputLimits::max_group_depth.
// Elements and attributes that the SRDF format has but we do not use (end effectors, passive
// joints, ...) are skipped, as MoveIt's srdfdom skips unknown ones; things read but not used
// (a group_state joint without a value) are listed in Srdf::warnings.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "dss/robot/input_limits.h"
#include "dss/robot/robot_model.h"

namespace dss {

struct SrdfChain {
  std::string base_link;
  std::string tip_link;
};

struct SrdfGroup {
  std::string name;
  std::vector<std::string> joints;
  std::vector<std::string> links;
  std::vector<SrdfChain> chains;
  std::vector<std::string> subgroups;
};

struct SrdfDisabledPair {
  std::string link1;
  std::string link2;
  std::string reason;
};

struct SrdfGroupState {
  std::string name;
  std::string group;
  std::vector<std::pair<std::string, double>> values;  ///< joint name -> value, as written
};

struct SrdfVirtualJoint {
  std::string name;
  std::string type;
  std::string parent_frame;
  std::string child_link;
};

struct Srdf {
  std::string name;
  std::string source;
  std::vector<SrdfGroup> groups;
  std::vector<SrdfDisabledPair> disabled_collisions;
  std::vector<SrdfGroupState> group_states;
  std::vector<SrdfVirtualJoint> virtual_joints;
  /// Non-fatal findings of the reader, one line each ("file:line: ...").
  std::vector<std::string> warnings;
  /// Subgroup nesting allowed when groups are expanded (from the limits given to the reader).
  std::size_t max_group_depth = RobotInputLimits::kDefaultMaxGroupDepth;

  const SrdfGroup* group(const std::string& name) const;  ///< nullptr when absent
  const SrdfGroupState* groupState(const std::string& group, const std::string& name) const;
};

/// Throws std::runtime_error naming the file and line (malformed XML, nesting deeper than
/// limits.max_xml_depth, an element lacking a required attribute, a non-numeric joint value).
Srdf loadSrdf(const std::string& path, const RobotInputLimits& limits = {});
Srdf parseSrdf(const std::string& text, const std::string& source,
               const RobotInputLimits& limits = {});

/// The active joints (indices into a state vector, increasing) of a planning group.
/// Throws std::runtime_error naming the SRDF and the group when the group, or a joint, link
/// or subgroup it names, is missing from the model, a chain's base is not an ancestor of its
/// tip, the group includes itself through subgroups, or subgroups nest deeper than
/// srdf.max_group_depth. Joints named in the group that are fixed (or mimic) are skipped.
std::vector<int> groupActiveJoints(const RobotModel& model, const Srdf& srdf,
                                   const std::string& group);

/// Every link or joint the SRDF names that the model lacks, one line each (empty: consistent).
std::vector<std::string> checkSrdfAgainstModel(const RobotModel& model, const Srdf& srdf);

}  // namespace dss
