// Fuzz target: the dss_pairs input reader (tools/pairs_input.h: JSON Lines through
// nlohmann::json, one pair per line, read with dss::pairs::readPairs) and the shapes built from
// it (tools/pairs_shapes.h), each pair then decided by DSS in the three modes, GJK and the
// Hybrid. Any bytes must end in pairs or a PairsInputError with a line number within the
// input; every decision must return a defined status, a finite certificate when disjoint, and,
// in exact mode for two convex shapes (world vertices), the same answer with the arguments
// swapped.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <sstream>
#include <string>

#include "dss/comparisons/any_shape_comparisons.h"
#include "dss/core/any_shape_query.h"
#include "fuzz_support.h"
#include "pairs_input.h"
#include "pairs_shapes.h"

namespace {

void checkResult(const dss::Result& r, const char* what) {
  if (r.status != dss::Status::kDecided && r.status != dss::Status::kIterationLimit &&
      r.status != dss::Status::kInvalidInput)
    dss_fuzz::propertyFailed(std::string(what) + ": undefined status");
  if (!r.intersect && (r.status != dss::Status::kDecided || !r.separating_direction.allFinite() ||
                       r.separating_direction.isZero(0)))
    dss_fuzz::propertyFailed(std::string(what) + ": disjoint without a finite certificate");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const int lines = 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  std::istringstream in(text);
  std::vector<dss::pairs::PairSpec> pairs;
  try {
    pairs = dss::pairs::readPairs(in);
  } catch (const dss::pairs::PairsInputError& e) {
    if (e.line() < 1 || e.line() > lines) dss_fuzz::propertyFailed("error line out of range");
    return 0;
  }
  for (const auto& spec : pairs) {
    dss::pairs::CorePair p;
    try {
      p = dss::pairs::makeCorePair(spec.a, spec.b);
    } catch (const std::invalid_argument&) {
      continue;
    }
    dss::Options opt;
    for (dss::Mode mode : {dss::Mode::kExact, dss::Mode::kDouble, dss::Mode::kFloat}) {
      opt.mode = mode;
      checkResult(dss::intersect(p.a, p.X_WA, p.b, p.X_WB, opt), "dss");
    }
    opt.mode = dss::Mode::kExact;
    checkResult(dss::intersectGjk(p.a, p.X_WA, p.b, p.X_WB, opt, 0.0), "gjk");
    checkResult(dss::intersectHybrid(p.a, p.X_WA, p.b, p.X_WB, opt, 0.0), "hybrid");
    if (spec.a.kind == dss::pairs::ShapeKind::kConvex &&
        spec.b.kind == dss::pairs::ShapeKind::kConvex) {
      const dss::Result ab = dss::intersect(p.a, p.X_WA, p.b, p.X_WB, opt);
      const dss::Result ba = dss::intersect(p.b, p.X_WB, p.a, p.X_WA, opt);
      if (ab.status == dss::Status::kDecided && ba.status == dss::Status::kDecided &&
          ab.intersect != ba.intersect)
        dss_fuzz::propertyFailed("exact answer of two convex shapes changes under swap");
    }
  }
  return 0;
}
