// Why a state is invalid, in words: a value outside its bounds, or the pairs that collide there
// (exact DSS on the problem's model with the options' paddings; three named).
#pragma once

#include <ompl/base/State.h>

#include <string>

#include "dss/planning/planning_problem.h"
#include "plan_options.h"

namespace dss_plan {

struct Why {
  std::string text;
  bool hull = false;  ///< a mesh checked as its convex hull is involved
  /// The text with a hint when a mesh hull is involved (for a person at the terminal).
  std::string withHint() const {
    return hull ? text +
                      " (meshes are checked as their convex hulls; for a concave link, "
                      "--meshes decomposed follows the mesh more closely)"
                : text;
  }
};

/// For joint values q (one per active joint of the model).
Why whyInvalid(const Args& a, const dss::Problem& p, const double* q);
/// For a state of the problem's space.
Why whyInvalid(const Args& a, const dss::Problem& p, const ompl::base::State* s);

}  // namespace dss_plan
