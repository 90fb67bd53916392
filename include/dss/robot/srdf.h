// The semantic robot description (SRDF, as MoveIt writes it): planning groups, pairs of links
// whose collisions are never checked, and named group states.
//
// A planning group is built from joints, links (their parent joint), chains (the joints from
// the tip up to, not including, the base link's parent joint) and subgroups, as MoveIt does.
// Its state is the ordered list of its active joints (model order); every other joint keeps
// the value given by the caller (e.g. a request's start state).
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

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

  const SrdfGroup* group(const std::string& name) const;  ///< nullptr when absent
  const SrdfGroupState* groupState(const std::string& group, const std::string& name) const;
};

/// Throws std::runtime_error naming the file and line (malformed XML, an element lacking a
/// required attribute, a non-numeric joint value).
Srdf loadSrdf(const std::string& path);
Srdf parseSrdf(const std::string& text, const std::string& source);

/// The active joints (indices into a state vector, increasing) of a planning group.
/// Throws std::runtime_error naming the SRDF and the group when the group, or a joint, link
/// or subgroup it names, is missing from the model, or a chain's base is not an ancestor of
/// its tip. Joints named in the group that are fixed (or mimic) are skipped.
std::vector<int> groupActiveJoints(const RobotModel& model, const Srdf& srdf,
                                   const std::string& group);

/// Every link or joint the SRDF names that the model lacks, one line each (empty: consistent).
std::vector<std::string> checkSrdfAgainstModel(const RobotModel& model, const Srdf& srdf);

}  // namespace dss
