// The loop shared by the per-algorithm translation units: one std::visit per pair into the
// templated decision, results written into a pre-sized vector (no allocation in the loop).
#pragma once

#include <variant>
#include <vector>

#include "pairs_shapes.h"

namespace dss {
namespace pairs {

template <class Decide, class T>
void decideLoop(const Decide& decide, const std::vector<CorePair<T>>& pairs, const Options& opt,
                std::vector<Result>& out) {
  out.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    out[i] = std::visit([&](const auto& a, const auto& b) { return decide(a, b, opt); },
                        pairs[i].a, pairs[i].b);
  }
}

}  // namespace pairs
}  // namespace dss
