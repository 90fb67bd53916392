// Which pairs collide: for a state the DSS checker calls colliding, every pair of its model
// (robot element against kept obstacle, element against element of a checked self pair) that
// exact DSS finds within the checker's padding, named for a person to read. A diagnostic, off
// the query path: it decides every pair without the sweep's stages, so it takes a few
// microseconds per pair, and it allocates.
//
// The stages of the sweep and the tables only skip pairs proved apart and report collisions
// proved, so for a state within the model's bounds the list is empty exactly when check(q)
// says free (answers at the iteration cap count as collisions in both).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "dss/checker/dss_checker.h"

namespace dss {

struct Contact {
  int element_a = -1;   ///< CollisionModel::elements() index
  int element_b = -1;   ///< the other element of a self pair, else -1
  int obstacle = -1;    ///< a kept obstacle (CollisionModel::scene().obstacles), else -1
  bool at_cap = false;  ///< decided by the iteration cap (answered colliding)
  bool self() const { return element_b >= 0; }
};

/// The colliding pairs at state q (active joint values), robot-scene pairs first, then self
/// pairs, each in the model's order; at most `max_contacts` (0: all). nullopt when q is
/// outside the model's bounds (invalid input: no pair is decided).
std::optional<std::vector<Contact>> contactsAt(const DssChecker& checker, const double* q,
                                               std::size_t max_contacts = 0);

/// "link panda_hand collision[0] (mesh hull) with scene object 'shelf_top'" or
/// "link panda_link7 collision[0] (mesh hull) with link panda_link5 collision[0] (mesh hull)".
std::string describeContact(const CollisionModel& model, const Contact& contact);

/// True when a contact involves a mesh checked as its convex hull (a concave link's hull may
/// touch what the mesh does not: --meshes decomposed follows it more closely).
bool involvesMeshHull(const CollisionModel& model, const Contact& contact);

}  // namespace dss
