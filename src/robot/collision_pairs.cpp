// Self-collision pair selection and disabled-pair sampling (see dss/robot/collision_pairs.h).
#include "dss/robot/collision_pairs.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "dss/core/any_shape_query.h"
#include "dss/robot/kinematics.h"

namespace dss {
namespace {

LinkPair ordered(int a, int b) { return a < b ? LinkPair{a, b} : LinkPair{b, a}; }

}  // namespace

std::vector<LinkPair> adjacentLinkPairs(const RobotModel& model) {
  const int n = static_cast<int>(model.links.size());
  std::set<LinkPair> adj;
  // Tree edges between links with geometry.
  for (int l = 0; l < n; ++l) {
    const int p = model.links[l].parent_link;
    if (p >= 0 && model.links[l].hasGeometry() && model.links[p].hasGeometry())
      adj.insert(ordered(p, l));
  }
  // Components of geometry-less links joined by tree edges: all geometry links touching one
  // component are pairwise adjacent.
  std::vector<int> comp(n, -1);
  int ncomp = 0;
  for (int l = 0; l < n; ++l) {
    if (model.links[l].hasGeometry() || comp[l] >= 0) continue;
    std::vector<int> stack{l};
    comp[l] = ncomp;
    std::set<int> touching;
    while (!stack.empty()) {
      const int k = stack.back();
      stack.pop_back();
      std::vector<int> nb;
      if (model.links[k].parent_link >= 0) nb.push_back(model.links[k].parent_link);
      for (int j : model.links[k].child_joints) nb.push_back(model.joints[j].child_link);
      for (int m : nb) {
        if (model.links[m].hasGeometry())
          touching.insert(m);
        else if (comp[m] < 0) {
          comp[m] = ncomp;
          stack.push_back(m);
        }
      }
    }
    for (int a : touching)
      for (int b : touching)
        if (a < b) adj.insert({a, b});
    ++ncomp;
  }
  return {adj.begin(), adj.end()};
}

std::string SelfCollisionPairs::summary() const {
  std::ostringstream s;
  s << "check " << pairs.size() << " of " << all_pairs << " link pairs (" << geometry_links
    << " links with geometry; removed: adjacent " << adjacent << ", rigidly attached " << rigid
    << ", SRDF disabled " << disabled << ", allowed " << allowed << ")";
  return s.str();
}

SelfCollisionPairs selfCollisionPairs(
    const RobotModel& model, const Srdf* srdf,
    const std::vector<std::pair<std::string, std::string>>& allowed, bool exclude_rigid) {
  SelfCollisionPairs out;
  std::vector<int> geo;
  for (int l = 0; l < static_cast<int>(model.links.size()); ++l)
    if (model.links[l].hasGeometry()) geo.push_back(l);
  out.geometry_links = geo.size();
  const auto adjacent = adjacentLinkPairs(model);
  const std::set<LinkPair> adj(adjacent.begin(), adjacent.end());
  std::set<LinkPair> disabled, extra;
  if (srdf)
    for (const auto& p : srdf->disabled_collisions) {
      const int a = model.linkIndex(p.link1), b = model.linkIndex(p.link2);
      if (a < 0 || b < 0)
        throw std::runtime_error(srdf->source + ": disable_collisions names link '" +
                                 (a < 0 ? p.link1 : p.link2) + "' that robot '" + model.name +
                                 "' lacks");
      disabled.insert(ordered(a, b));
    }
  for (const auto& [n1, n2] : allowed) {
    const int a = model.linkIndex(n1), b = model.linkIndex(n2);
    if (a < 0 || b < 0)
      throw std::runtime_error("allowed collision list names link '" + (a < 0 ? n1 : n2) +
                               "' that robot '" + model.name + "' lacks");
    extra.insert(ordered(a, b));
  }
  for (std::size_t i = 0; i < geo.size(); ++i)
    for (std::size_t k = i + 1; k < geo.size(); ++k) {
      const LinkPair p{geo[i], geo[k]};
      ++out.all_pairs;
      if (adj.count(p))
        ++out.adjacent;
      else if (exclude_rigid && model.rigidAncestor(p.first) == model.rigidAncestor(p.second))
        ++out.rigid;
      else if (disabled.count(p))
        ++out.disabled;
      else if (extra.count(p))
        ++out.allowed;
      else
        out.pairs.push_back(p);
    }
  return out;
}

bool linksIntersect(const RobotModel& model, const Eigen::Isometry3d* X_WL, int a, int b) {
  Options opt;
  opt.mode = Mode::kExact;
  for (const auto& ca : model.links[a].collisions) {
    const Eigen::Isometry3d X_WA = X_WL[a] * ca.X_LS;
    const double ra = shapeMagnitude(ca.shape);
    for (const auto& cb : model.links[b].collisions) {
      const Eigen::Isometry3d X_WB = X_WL[b] * cb.X_LS;
      const double rb = shapeMagnitude(cb.shape);
      if ((X_WA.translation() - X_WB.translation()).norm() > ra + rb) continue;
      if (intersect(ca.shape, X_WA, cb.shape, X_WB, opt).intersect) return true;
    }
  }
  return false;
}

std::string DisabledPairsResult::toSrdf() const {
  std::ostringstream s;
  for (const auto& p : pairs)
    s << "  <disable_collisions link1=\"" << p.link1 << "\" link2=\"" << p.link2 << "\" reason=\""
      << p.reason << "\"/>\n";
  return s.str();
}

DisabledPairsResult computeDisabledPairs(const RobotModel& model,
                                         const DisabledPairsOptions& options) {
  DisabledPairsResult out;
  out.samples = options.samples;
  const Kinematics kin(model);
  std::vector<Eigen::Isometry3d> X(model.links.size(), Eigen::Isometry3d::Identity());
  std::vector<int> geo;
  for (int l = 0; l < static_cast<int>(model.links.size()); ++l)
    if (model.links[l].hasGeometry()) geo.push_back(l);
  const auto adjacent = adjacentLinkPairs(model);
  const std::set<LinkPair> adj(adjacent.begin(), adjacent.end());
  auto name = [&](int l) { return model.links[l].name; };
  for (const auto& p : adjacent) out.pairs.push_back({name(p.first), name(p.second), "Adjacent"});

  std::vector<double> q = model.defaultState();
  kin.computeLinkPoses(q.data(), X.data());
  std::vector<LinkPair> candidates;
  for (std::size_t i = 0; i < geo.size(); ++i)
    for (std::size_t k = i + 1; k < geo.size(); ++k) {
      const LinkPair p{geo[i], geo[k]};
      if (adj.count(p)) continue;
      if (options.include_default && linksIntersect(model, X.data(), p.first, p.second)) {
        out.pairs.push_back({name(p.first), name(p.second), "Default"});
        continue;
      }
      candidates.push_back(p);
    }
  out.checked_pairs = candidates.size();
  std::vector<int> hits(candidates.size(), 0);
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int s = 0; s < options.samples; ++s) {
    for (std::size_t i = 0; i < q.size(); ++i) {
      const JointLimits& l = model.joints[model.active_joints[i]].limits;
      const double lo = l.has_position_limits ? l.lower : -M_PI,
                   hi = l.has_position_limits ? l.upper : M_PI;
      q[i] = lo + (hi - lo) * unit(rng);
    }
    kin.computeLinkPoses(q.data(), X.data());
    for (std::size_t c = 0; c < candidates.size(); ++c)
      if (linksIntersect(model, X.data(), candidates[c].first, candidates[c].second)) ++hits[c];
  }
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const auto& p = candidates[c];
    if (hits[c] == 0)
      out.pairs.push_back({name(p.first), name(p.second), "Never"});
    else if (hits[c] == options.samples)
      out.pairs.push_back({name(p.first), name(p.second), "Always"});
  }
  return out;
}

}  // namespace dss
