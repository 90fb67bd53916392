// The core shapes of a pair file, as closed variants over concrete types: each pair is
// dispatched once (std::visit) into the templated decisions, so the search itself runs on
// concrete shape types with no virtual call.
//
// Primitives become dss::Posed<...> (identity pose when none is given). A convex shape with a
// pose is posed once, vertex by vertex (fl(R v + p)), and kept as a hull of world points:
// the exact mode is then exact for the posed floating-point inputs. Shape A may be padded by
// a radius (dss::Padded), which turns the decision into "distance <= r". Float copies (for
// --mode float) are built from the double shapes once, at load time.
#pragma once

#include <variant>
#include <vector>

#include "dss/core/convex_hull.h"
#include "dss/core/padded.h"
#include "dss/core/posed.h"
#include "dss/core/result.h"
#include "dss/core/shapes.h"
#include "pairs_input.h"

namespace dss {
namespace pairs {

template <class T>
using ShapeVariant =
    std::variant<Posed<SphereT<T>>, Posed<BoxT<T>>, Posed<CapsuleT<T>>, Posed<CylinderT<T>>,
                 Posed<ConeT<T>>, Posed<EllipsoidT<T>>, ConvexHullT<T>>;

/// Side A: a plain shape, or the shape padded by --padding.
template <class T>
using SideAVariant = std::variant<
    Posed<SphereT<T>>, Posed<BoxT<T>>, Posed<CapsuleT<T>>, Posed<CylinderT<T>>,
    Posed<ConeT<T>>, Posed<EllipsoidT<T>>, ConvexHullT<T>, Padded<Posed<SphereT<T>>>,
    Padded<Posed<BoxT<T>>>, Padded<Posed<CapsuleT<T>>>, Padded<Posed<CylinderT<T>>>,
    Padded<Posed<ConeT<T>>>, Padded<Posed<EllipsoidT<T>>>, Padded<ConvexHullT<T>>>;

template <class T>
struct CorePair {
  SideAVariant<T> a;
  ShapeVariant<T> b;
};

/// The double shape of a spec. Throws std::invalid_argument (from the core constructors).
ShapeVariant<double> makeShape(const ShapeSpec& s);

/// Side A of a pair: the shape, padded by `padding` when it is > 0.
SideAVariant<double> makeSideA(const ShapeSpec& s, double padding);

/// Float copies (each number rounded to float once).
ShapeVariant<float> toFloat(const ShapeVariant<double>& s);
SideAVariant<float> toFloat(const SideAVariant<double>& s);

/// The three decisions of the core, over a whole pair list (the loop is inside, so that
/// timing measures the decisions and the per-pair dispatch only).
enum class CoreAlgo { kDss, kGjk, kHybrid };

void decideAll(CoreAlgo algo, const std::vector<CorePair<double>>& pairs, const Options& opt,
               std::vector<Result>& out);
void decideAll(CoreAlgo algo, const std::vector<CorePair<float>>& pairs, const Options& opt,
               std::vector<Result>& out);

// One translation unit per algorithm (compile time; they share pairs_decide_impl.h).
void decideAllDss(const std::vector<CorePair<double>>&, const Options&, std::vector<Result>&);
void decideAllDss(const std::vector<CorePair<float>>&, const Options&, std::vector<Result>&);
void decideAllGjk(const std::vector<CorePair<double>>&, const Options&, std::vector<Result>&);
void decideAllGjk(const std::vector<CorePair<float>>&, const Options&, std::vector<Result>&);
void decideAllHybrid(const std::vector<CorePair<double>>&, const Options&, std::vector<Result>&);
void decideAllHybrid(const std::vector<CorePair<float>>&, const Options&, std::vector<Result>&);

}  // namespace pairs
}  // namespace dss
