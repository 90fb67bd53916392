// Pairs of names (robot links, scene objects) that a scene allows to touch, as MoveIt's
// allowed collision matrix says. Only permissions are kept: a pair is allowed when the file
// marks it true, or when one of its names is in the "always allowed" default entries.
#pragma once

#include <set>
#include <string>
#include <utility>

namespace dss {

class AllowedCollisionMatrix {
 public:
  /// Allows the pair (order does not matter).
  void allow(const std::string& a, const std::string& b);
  /// Allows every pair containing `name` (MoveIt's default entries set to true).
  void allowAlways(const std::string& name);
  bool allowed(const std::string& a, const std::string& b) const;

  /// The explicit pairs, each ordered (first < second).
  const std::set<std::pair<std::string, std::string>>& pairs() const { return pairs_; }
  const std::set<std::string>& alwaysAllowed() const { return always_; }
  bool empty() const { return pairs_.empty() && always_.empty(); }

 private:
  std::set<std::pair<std::string, std::string>> pairs_;
  std::set<std::string> always_;
};

}  // namespace dss
