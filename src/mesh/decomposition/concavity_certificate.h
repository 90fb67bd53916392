// The concavity certificate of a piece P: h(P) = max over x in P of d(x), d the distance to the
// solid (closed meshes) or to the surface (open ones). d is 1-Lipschitz, so over a box of centre c
// and half-diagonal r, d <= d(c) + r; the distance to the surface u(c) bounds d(c). Boxes are
// refined, largest bound first, until the largest open bound meets the stopping rule; that
// bound is the certificate. A box is closed for good when
//  - it misses one of the piece's half-spaces;
//  - it holds no surface (u(c) > r) and its centre is inside the solid;
//  - (face rule) every triangle near it lies on a facet plane of the piece, with the solid on
//    the inner side, or outside a facet plane, and one of the piece's own triangle sections
//    lying on a facet crosses the box: the box's part of the piece's interior is then free of
//    surface, hence on one side of it, and it borders that section from the inside.
#pragma once

#include "cells.h"
#include "geometry.h"
#include "mesh_data.h"
#include "piece_hull.h"

namespace dss::mesh::decomposition {

struct Limits {
  double good_enough = 0.0;  // stop once the bound is at most this
  double give_up = kInf;     // stop once a point of the piece is known to be farther
  double gap_abs = 0.0;      // stop once bound <= lower + max(gap_abs, gap_rel * lower)
  double gap_rel = 0.0;
  // ... but not while the bounds straddle this value: the caller needs to know which side of
  // it h is on (the tolerance).
  double decide = 0.0;
  int max_boxes = 0;
};

struct Certificate {
  double upper = kInf;  // certified bound of h
  double lower = 0.0;   // d(deepest) (a point of the piece, up to the facet rounding)
  Vec3 deepest = Vec3::Zero();
  int boxes = 0;
};

/// The certificate of hull `h`, whose triangle sections are `polys`, within the limits.
Certificate certify(const MeshData& m, const Hull& h, const Polygons& polys, const Limits& lim);

}  // namespace dss::mesh::decomposition
