// The concavity certificate (see concavity_certificate.h).
#include "concavity_certificate.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <queue>
#include <utility>
#include <vector>

namespace dss::mesh::decomposition {
namespace {

class Certifier {
 public:
  Certifier(const MeshData& m, const Hull& h, const Polygons& polys)
      : m_(m), h_(h), polys_(polys), cls_(m.elements.size(), kUnknown) {}

  Certificate run(const Limits& lim) {
    Certificate cert;
    cert.deepest = 0.5 * (h_.box.lo + h_.box.hi);
    if (h_.points.empty()) {
      cert.upper = 0.0;
      return cert;
    }
    good_enough_ = lim.good_enough;
    // The face rule accepts triangles within on_eps of a facet plane; the plane tests keep a
    // margin of their own. Every bound carries both.
    slack_ = 2.0 * m_.on_eps + 4.0 * m_.margin;
    std::vector<int> all(h_.planes.size());
    std::iota(all.begin(), all.end(), 0);
    const Vec3 grow = Vec3::Constant(m_.margin);
    double floor = 0.0;  // bounds of boxes too small to refine
    bool found = false;
    std::priority_queue<Item> heap;
    auto process = [&](const Vec3& lo, const Vec3& hi, bool outside, std::vector<int> active) {
      ++cert.boxes;
      Item item;
      if (!evaluate(lo, hi, outside, active, item, cert, found)) return;
      item.lo = lo;
      item.hi = hi;
      item.active = std::move(active);
      heap.push(std::move(item));
    };
    process(h_.box.lo - grow, h_.box.hi + grow, false, all);
    const double r_min = 1e-7 * m_.size + m_.on_eps;
    while (!heap.empty()) {
      const Item& top = heap.top();
      const double bound = top.ub + slack_;
      const double lower = found ? cert.lower : 0.0;
      const bool straddles = lower < lim.decide && bound > lim.decide;
      if (bound <= lim.good_enough || lower > lim.give_up ||
          (!straddles && bound <= lower + std::max(lim.gap_abs, lim.gap_rel * lower)) ||
          cert.boxes >= lim.max_boxes)
        break;
      Item box = top;
      heap.pop();
      const Vec3 ext = box.hi - box.lo;
      if (0.5 * ext.norm() <= r_min) {
        floor = std::max(floor, box.ub);
        continue;
      }
      // Halve every side longer than half the longest: boxes stay near cubes.
      const double longest = ext.maxCoeff();
      int split[3], ns = 0;
      for (int k = 0; k < 3; ++k)
        if (ext[k] >= 0.5 * longest) split[ns++] = k;
      for (int code = 0; code < (1 << ns); ++code) {
        Vec3 lo = box.lo, hi = box.hi;
        for (int j = 0; j < ns; ++j) {
          const int k = split[j];
          const double mid = 0.5 * (box.lo[k] + box.hi[k]);
          if (code & (1 << j))
            lo[k] = mid;
          else
            hi[k] = mid;
        }
        process(lo, hi, box.outside, box.active);
      }
    }
    cert.upper = std::max(floor, heap.empty() ? 0.0 : heap.top().ub) + slack_;
    if (!found) cert.lower = 0.0;
    if (!found && !heap.empty()) cert.deepest = 0.5 * (heap.top().lo + heap.top().hi);
    return cert;
  }

 private:
  enum : std::int8_t { kUnknown, kOnFacet, kApart, kBlocking };

  struct Item {
    double ub = 0.0;
    Vec3 lo, hi;
    bool outside = false;  // free of surface and outside the solid (inherited)
    std::vector<int> active;
    bool operator<(const Item& o) const { return ub < o.ub; }
  };

  // Fills item.ub; false when the box is closed for good.
  bool evaluate(const Vec3& lo, const Vec3& hi, bool outside, std::vector<int>& active, Item& item,
                Certificate& cert, bool& found) {
    const Vec3 c = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    const double r = half.norm();
    // Half-spaces: a box wholly inside one is done with it; wholly outside one, done for good.
    bool centre_in = true;
    std::size_t keep = 0;
    for (int i : active) {
      const Plane& p = h_.planes[i];
      const double mid = p.n.dot(c) - p.o;
      const double spread = p.n.cwiseAbs().dot(half);
      if (mid - spread > m_.margin) return false;
      if (mid > 0.0) centre_in = false;
      if (mid + spread > 0.0) active[keep++] = i;
    }
    active.resize(keep);
    const double u = m_.tree.nearest(c);
    item.outside = outside;
    // A box whose plain bound already meets the stopping level is never refined: the tests
    // below could only lower a bound that no longer matters.
    const double settled = std::max(good_enough_ - slack_, found ? cert.lower : 0.0);
    if (u + r <= settled) {
      item.ub = u + r;
      return true;
    }
    // d(c): u(c) outside the solid (and for open meshes), 0 inside, at most u(c) when unsure.
    bool known_out = outside || !m_.closed;
    double d = u;
    if (!known_out && u > m_.near_eps) {
      const bool in = m_.inside(c);
      if (u > r + m_.near_eps) {
        // No surface in the box: all of it is on the centre's side.
        if (in) return false;
        item.outside = true;
      }
      known_out = !in;
      if (in) d = 0.0;
    }
    // The face rule would close a box holding a point of the piece known to be outside the
    // solid only through the on_eps slack: such a box stays open.
    const bool witnessed_out = known_out && centre_in && u > 2.0 * m_.on_eps;
    if (!item.outside && !witnessed_out && m_.closed && faceRule(lo, hi)) return false;
    item.ub = d + r;
    if (centre_in && known_out && (!found || u > cert.lower)) {
      found = true;
      cert.lower = u;
      cert.deepest = c;
    }
    return true;
  }

  bool faceRule(const Vec3& lo, const Vec3& hi) {
    if (!m_.face_rule || !h_.full) return false;
    Box box{lo - Vec3::Constant(m_.on_eps), hi + Vec3::Constant(m_.on_eps)};
    bool witness = false;
    const bool clear = m_.tree.visit(box, [&](int e) {
      const std::int8_t k = classify(e);
      if (k == kBlocking) return false;
      if (k == kOnFacet && !witness) witness = crosses(e, lo, hi);
      return true;
    });
    return clear && witness;
  }

  std::int8_t classify(int e) {
    std::int8_t& k = cls_[e];
    if (k != kUnknown) return k;
    const auto& t = m_.elements[e];
    const Vec3 &a = m_.v[t[0]], &b = m_.v[t[1]], &c = m_.v[t[2]];
    const Vec3& n = m_.normal[e];
    k = kBlocking;
    for (const Plane& p : h_.planes) {
      const double sa = p.n.dot(a) - p.o, sb = p.n.dot(b) - p.o, sc = p.n.dot(c) - p.o;
      if (std::min({sa, sb, sc}) > m_.margin) {
        k = kApart;
        break;
      }
      if (std::max({std::abs(sa), std::abs(sb), std::abs(sc)}) <= m_.on_eps && n.dot(p.n) > 0.0)
        k = kOnFacet;
    }
    return k;
  }

  // Whether the piece's section of element e has area inside the box (shrunk by a margin).
  bool crosses(int e, const Vec3& lo, const Vec3& hi) {
    auto it = std::lower_bound(polys_.element.begin(), polys_.element.end(), e);
    for (; it != polys_.element.end() && *it == e; ++it) {
      const std::size_t i = static_cast<std::size_t>(it - polys_.element.begin());
      std::vector<Vec3> poly(polys_.pts.begin() + polys_.start[i],
                             polys_.pts.begin() + polys_.start[i + 1]);
      std::vector<Vec3> next;
      for (int k = 0; k < 3 && poly.size() >= 3; ++k) {
        const Vec3 axis = Vec3::Unit(k);
        clipPolygon(poly.data(), poly.data() + poly.size(), {axis, hi[k] - m_.margin}, next);
        poly.swap(next);
        if (poly.size() < 3) break;
        clipPolygon(poly.data(), poly.data() + poly.size(), {-axis, -lo[k] - m_.margin}, next);
        poly.swap(next);
      }
      if (poly.size() < 3) continue;
      Vec3 area = Vec3::Zero();
      for (std::size_t j = 1; j + 1 < poly.size(); ++j)
        area += (poly[j] - poly[0]).cross(poly[j + 1] - poly[0]);
      if (area.norm() > 1e-18 * m_.size * m_.size) return true;
    }
    return false;
  }

  const MeshData& m_;
  const Hull& h_;
  const Polygons& polys_;
  std::vector<std::int8_t> cls_;
  double good_enough_ = 0.0;
  double slack_ = 0.0;
};

}  // namespace

Certificate certify(const MeshData& m, const Hull& h, const Polygons& polys, const Limits& lim) {
  return Certifier(m, h, polys).run(lim);
}

}  // namespace dss::mesh::decomposition
