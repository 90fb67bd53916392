// dss_pairs: the pair loop for dss::intersect (its own translation unit: the 14 x 7 shape
// combinations of each scalar type make it the heaviest part of the build).
#include "dss/core/dss.h"
#include "pairs_decide_impl.h"

namespace dss {
namespace pairs {
namespace {
struct DecideDss {
  template <class A, class B>
  Result operator()(const A& a, const B& b, const Options& opt) const {
    return dss::intersect(a, b, opt);
  }
};
}  // namespace

void decideAllDss(const std::vector<CorePair<double>>& pairs, const Options& opt,
                 std::vector<Result>& out) {
  decideLoop(DecideDss{}, pairs, opt, out);
}
void decideAllDss(const std::vector<CorePair<float>>& pairs, const Options& opt,
                 std::vector<Result>& out) {
  decideLoop(DecideDss{}, pairs, opt, out);
}

}  // namespace pairs
}  // namespace dss
