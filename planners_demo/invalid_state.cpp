// Why a state is invalid (see invalid_state.h).
#include "invalid_state.h"

#include <vector>

#include "dss/checker/contacts.h"

namespace dss_plan {

Why whyInvalid(const Args& a, const dss::Problem& p, const double* q) {
  dss::DssCheckerSettings set;
  set.scene_padding = a.padding;
  set.self_padding = a.self_padding;
  const dss::DssChecker dss_checker(p.model, set);
  const auto contacts = dss::contactsAt(dss_checker, q);
  if (!contacts) return {"a value is outside the model's bounds"};
  if (contacts->empty()) return {"no pair collides under exact DSS"};
  Why why;
  for (std::size_t k = 0; k < contacts->size(); ++k) {
    why.hull |= dss::involvesMeshHull(*p.model, (*contacts)[k]);
    if (k < 3) why.text += (k ? "; " : "") + dss::describeContact(*p.model, (*contacts)[k]);
  }
  if (contacts->size() > 3) why.text += "; and " + std::to_string(contacts->size() - 3) + " more";
  return why;
}

Why whyInvalid(const Args& a, const dss::Problem& p, const ompl::base::State* s) {
  std::vector<double> q(p.model->robot().numActiveJoints());
  if (!p.map->toJoints(s, q.data())) return {"a value is not finite or outside its bounds"};
  return whyInvalid(a, p, q.data());
}

}  // namespace dss_plan
