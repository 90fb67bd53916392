// The colliding pairs of a state (see dss/checker/contacts.h).
#include "dss/checker/contacts.h"

#include "dss/core/any_shape_query.h"

namespace dss {

std::optional<std::vector<Contact>> contactsAt(const DssChecker& checker, const double* q,
                                               std::size_t max_contacts) {
  const CollisionModel& m = checker.model();
  if (!m.withinBounds(q)) return std::nullopt;
  const DssCheckerSettings& set = checker.settings();
  const std::vector<Eigen::Isometry3d> X_WL =
      m.kinematics().linkPoses(std::vector<double>(q, q + m.robot().numActiveJoints()));
  const auto& elements = m.elements();
  auto shapePose = [&](int e) -> Eigen::Isometry3d {
    const CollisionModel::Element& el = elements[std::size_t(e)];
    return X_WL[std::size_t(el.link)] * el.source->X_LS;
  };
  std::vector<Contact> out;
  auto full = [&] { return max_contacts > 0 && out.size() >= max_contacts; };
  for (const CollisionModel::Slot& s : m.slots())
    for (int e = s.first_element; e < s.first_element + s.num_elements && !full(); ++e) {
      const Eigen::Isometry3d X_WS = shapePose(e);
      for (int o : s.obstacles) {
        const Obstacle& ob = m.scene().obstacles[std::size_t(o)];
        const Result r = intersect(elements[std::size_t(e)].source->shape, X_WS, ob.shape, ob.X_WO,
                                   set.options, set.scene_padding);
        if (r.intersect) out.push_back({e, -1, o, r.status == Status::kIterationLimit});
        if (full()) break;
      }
    }
  for (const CollisionModel::SelfPair& p : m.selfPairs()) {
    const CollisionModel::Slot& sa = m.slots()[std::size_t(p.a)];
    const CollisionModel::Slot& sb = m.slots()[std::size_t(p.b)];
    for (int a = sa.first_element; a < sa.first_element + sa.num_elements && !full(); ++a)
      for (int b = sb.first_element; b < sb.first_element + sb.num_elements && !full(); ++b) {
        const Result r = intersect(elements[std::size_t(a)].source->shape, shapePose(a),
                                   elements[std::size_t(b)].source->shape, shapePose(b),
                                   set.options, set.self_padding);
        if (r.intersect) out.push_back({a, b, -1, r.status == Status::kIterationLimit});
      }
  }
  return out;
}

namespace {
std::string elementName(const CollisionModel& m, int e) {
  const CollisionModel::Element& el = m.elements()[std::size_t(e)];
  const RobotLink& link = m.robot().links[std::size_t(el.link)];
  const std::string& d = el.source->description;
  // An object the robot holds (attached_objects.h): its id, its holding link, its part.
  const std::string attached = "attached object '" + link.name + "' on link ";
  if (link.parent_link >= 0 && d.rfind(attached, 0) == 0) {
    std::string s = attached + m.robot().links[std::size_t(link.parent_link)].name;
    if (link.collisions.size() > 1)
      for (std::size_t k = 0; k < link.collisions.size(); ++k)
        if (&link.collisions[k] == el.source) s += " part " + std::to_string(k);
    return s;
  }
  std::string s = "link " + link.name;
  // The file's collision index, from the element's description ("link 'L' collision[i] ...":
  // the pieces of a decomposed mesh share theirs), else its place in the link.
  const std::size_t at = d.find("collision["), end = d.find(']', at);
  if (at != std::string::npos && end != std::string::npos)
    s += " " + d.substr(at, end + 1 - at);
  else
    for (std::size_t k = 0; k < link.collisions.size(); ++k)
      if (&link.collisions[k] == el.source) s += " collision[" + std::to_string(k) + "]";
  if (!el.source->mesh_path.empty())
    s += el.source->piece >= 0 ? " (mesh piece " + std::to_string(el.source->piece + 1) + " of " +
                                     std::to_string(el.source->pieces) + ")"
                               : " (mesh hull)";
  return s;
}
}  // namespace

std::string describeContact(const CollisionModel& m, const Contact& c) {
  std::string s = elementName(m, c.element_a) + " with ";
  if (c.self())
    s += elementName(m, c.element_b);
  else
    s += "scene object '" + m.scene().obstacles[std::size_t(c.obstacle)].name + "'";
  if (c.at_cap) s += " (at the iteration cap)";
  return s;
}

bool involvesMeshHull(const CollisionModel& m, const Contact& c) {
  auto hull = [&](int e) {
    const CollisionElement& src = *m.elements()[std::size_t(e)].source;
    return !src.mesh_path.empty() && src.piece < 0;
  };
  return hull(c.element_a) || (c.self() && hull(c.element_b));
}

}  // namespace dss
