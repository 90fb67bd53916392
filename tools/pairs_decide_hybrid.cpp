// dss_pairs: the pair loop for dss::intersectHybrid (its own translation unit: the 14 x 7 shape
// combinations of each scalar type make it the heaviest part of the build).
#include "dss/core/gjk.h"
#include "pairs_decide_impl.h"

namespace dss {
namespace pairs {
namespace {
struct DecideHybrid {
  template <class A, class B>
  Result operator()(const A& a, const B& b, const Options& opt) const {
    return dss::intersectHybrid(a, b, opt);
  }
};
}  // namespace

void decideAllHybrid(const std::vector<CorePair<double>>& pairs, const Options& opt,
                 std::vector<Result>& out) {
  decideLoop(DecideHybrid{}, pairs, opt, out);
}
void decideAllHybrid(const std::vector<CorePair<float>>& pairs, const Options& opt,
                 std::vector<Result>& out) {
  decideLoop(DecideHybrid{}, pairs, opt, out);
}

}  // namespace pairs
}  // namespace dss
