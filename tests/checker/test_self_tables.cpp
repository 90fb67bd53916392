// Self-pair tables (self_pair_table.h): a cell certified free must be free, and a cell
// certified colliding must collide, for every joint value inside it. Checked on the corners,
// edges (and one ulp beyond) and centres of every decided cell against exact DSS and FCL
// (distance, collide), on random states, and by comparing whole checkers with and without
// tables; plus the lookup's handling of wrapping, NaN and out-of-range values.
#include <fcl/fcl.h>

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include "dss/checker/checker_setup.h"
#include "dss/checker/dss_checker.h"
#include "dss/checker/fcl_checker.h"
#include "dss/core/any_shape_query.h"
#include "dss/scene/plan_request.h"
#include "dss/scene/scene_loader.h"
#include "support/shared_data.h"

namespace fs = std::filesystem;

namespace {

const std::string kArm = std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7";
const std::string kPanda = std::string(DSS_SHARED_DIR) + "/robots/panda";
const std::string kMbm = std::string(DSS_SHARED_DIR) + "/scenes/mbm_panda";
constexpr double kInf = std::numeric_limits<double>::infinity();

// Every link pair of the model that has a table is free at q (exact DSS and FCL distance > 0
// on the hull geometry, at the given padding). Returns the number of pairs checked.
std::size_t checkCertified(const dss::CollisionModel& m, const std::vector<double>& q,
                           double padding, const dss::FclChecker& fcl) {
  std::vector<Eigen::Isometry3d> X(m.robot().links.size(), Eigen::Isometry3d::Identity());
  m.kinematics().computeLinkPoses(q.data(), X.data());
  std::size_t checked = 0;
  for (const auto& p : m.selfPairs()) {
    if (p.table < 0) continue;
    const auto cell = m.selfTables().tables()[p.table].cell(q.data());
    if (cell == dss::SelfPairTable::kColliding) {
      // Some element pair intersects (DSS exact and FCL agree).
      const auto& sa = m.slots()[p.a];
      const auto& sb = m.slots()[p.b];
      bool dss_hit = false, fcl_hit = false;
      for (int a = sa.first_element; a < sa.first_element + sa.num_elements; ++a)
        for (int b = sb.first_element; b < sb.first_element + sb.num_elements; ++b) {
          const auto& A = *m.elements()[a].source;
          const auto& B = *m.elements()[b].source;
          const Eigen::Isometry3d XA = X[sa.link] * A.X_LS, XB = X[sb.link] * B.X_LS;
          dss_hit =
              dss_hit || dss::intersect(A.shape, XA, B.shape, XB, dss::Options{}, 0.0).intersect;
          fcl::CollisionRequestd req;
          fcl::CollisionResultd res;
          fcl_hit = fcl_hit || fcl::collide(fcl.elementGeometry(a), XA, fcl.elementGeometry(b), XB,
                                            req, res) > 0;
        }
      BOOST_TEST(dss_hit, "certified colliding cell is free: " << m.robot().links[sa.link].name
                                                               << " / "
                                                               << m.robot().links[sb.link].name);
      BOOST_TEST(fcl_hit, "FCL finds no collision in a certified colliding cell");
      ++checked;
      continue;
    }
    if (cell != dss::SelfPairTable::kFree) continue;
    const auto& sa = m.slots()[p.a];
    const auto& sb = m.slots()[p.b];
    for (int a = sa.first_element; a < sa.first_element + sa.num_elements; ++a)
      for (int b = sb.first_element; b < sb.first_element + sb.num_elements; ++b) {
        const auto& A = *m.elements()[a].source;
        const auto& B = *m.elements()[b].source;
        const Eigen::Isometry3d XA = X[sa.link] * A.X_LS, XB = X[sb.link] * B.X_LS;
        const dss::Result r = dss::intersect(A.shape, XA, B.shape, XB, dss::Options{}, padding);
        BOOST_TEST(!r.intersect, "certified cell collides: " << m.robot().links[sa.link].name
                                                             << " / "
                                                             << m.robot().links[sb.link].name);
        fcl::DistanceRequestd req;
        fcl::DistanceResultd res;
        const double d =
            fcl::distance(fcl.elementGeometry(a), XA, fcl.elementGeometry(b), XB, req, res);
        BOOST_TEST(d > padding, "FCL distance " << d << " in a certified cell");
        ++checked;
      }
  }
  return checked;
}

// Corners, edge values one ulp either side, and the centre of decided cells.
std::size_t checkAllCells(const std::shared_ptr<const dss::CollisionModel>& model, double padding) {
  const dss::CollisionModel& m = *model;
  const dss::FclChecker fcl(model, dss::FclCheckerSettings{dss::FclGeometry::kHull});
  std::size_t checked = 0;
  for (const auto& t : m.selfTables().tables()) {
    const double w0 = (t.hi[0] - t.lo[0]) / t.cells[0];
    const double w1 = t.num_vars > 1 ? (t.hi[1] - t.lo[1]) / t.cells[1] : 0.0;
    std::vector<double> q = m.held();
    for (int i = 0; i < t.cells[0]; ++i)
      for (int j = 0; j < t.cells[1]; ++j) {
        const auto state = t.cell_state[std::size_t(i) * t.cells[1] + j];
        if (state == dss::SelfPairTable::kUnknown) continue;
        // Cells next to a cell in another state (where a wrong bound would show first) in
        // full; one interior cell in 16 at its centre.
        bool edge = false;
        for (int di = -1; di <= 1; ++di)
          for (int dj = -1; dj <= 1; ++dj) {
            const int a = i + di, b = j + dj;
            if (a < 0 || b < 0 || a >= t.cells[0] || b >= t.cells[1]) continue;
            edge = edge || t.cell_state[std::size_t(a) * t.cells[1] + b] != state;
          }
        if (!edge) {
          if ((i * 7 + j) % 16) continue;
          q[t.var[0]] = t.lo[0] + (i + 0.5) * w0;
          if (t.num_vars > 1) q[t.var[1]] = t.lo[1] + (j + 0.5) * w1;
          checked += checkCertified(m, q, padding, fcl);
          continue;
        }
        for (double fi : {0.0, 0.5, 1.0})
          for (double fj : {0.0, 0.5, 1.0})
            for (int nudge : {-1, 0, 1}) {
              double v0 = std::min(t.hi[0], t.lo[0] + (i + fi) * w0);
              if (nudge) v0 = std::nextafter(v0, nudge > 0 ? 1e300 : -1e300);
              q[t.var[0]] = v0;
              if (t.num_vars > 1) {
                double v1 = std::min(t.hi[1], t.lo[1] + (j + fj) * w1);
                if (nudge) v1 = std::nextafter(v1, nudge > 0 ? 1e300 : -1e300);
                q[t.var[1]] = v1;
              }
              checked += checkCertified(m, q, padding, fcl);
            }
      }
  }
  return checked;
}

// SelfPairTables::freeAlong on seeded random straight motions of the group (lengths from 0 to
// a third of the range): a table that certifies a motion must find its cell free at 400
// states along it, ends included; some motions are certified, some not; a motion that leaves
// a table's range is never certified for it.
void checkFreeAlong(const dss::CollisionModel& m, std::uint64_t seed) {
  const dss::SelfPairTables& tables = m.selfTables();
  BOOST_REQUIRE(tables.size() > 0u);
  std::mt19937_64 rng(seed);
  std::vector<double> q0 = m.held(), q1 = m.held(), q = m.held();
  std::vector<unsigned char> flags(tables.size());
  std::size_t certified = 0, refused = 0, samples = 0;
  for (int k = 0; k < 3000; ++k) {
    const double scale = std::uniform_real_distribution<double>(0.0, 1.0 / 3.0)(rng);
    for (int a : m.groupActive()) {
      const auto& j = m.robot().joints[m.robot().active_joints[a]];
      std::uniform_real_distribution<double> v(j.limits.lower, j.limits.upper);
      q0[a] = v(rng);
      q1[a] = q0[a] + scale * (v(rng) - q0[a]);
    }
    tables.freeAlong(q0.data(), q1.data(), 0.0, flags.data());
    for (std::size_t t = 0; t < tables.size(); ++t) {
      if (!flags[t]) {
        ++refused;
        continue;
      }
      ++certified;
      for (int i = 0; i <= 400; ++i) {
        const double s = i / 400.0;
        for (std::size_t a = 0; a < q.size(); ++a) q[a] = q0[a] + s * (q1[a] - q0[a]);
        ++samples;
        BOOST_TEST((tables.tables()[t].cell(q.data()) == dss::SelfPairTable::kFree),
                   "table " << t << ", motion " << k << ", s = " << s);
      }
    }
    // The same motion pushed beyond a table variable's range: refused for that table.
    if (k % 10 == 0) {
      const dss::SelfPairTable& t0 = tables.tables()[0];
      std::vector<double> out = q1;
      out[std::size_t(t0.var[0])] = t0.hi[0] + 0.01;
      tables.freeAlong(q0.data(), out.data(), 0.0, flags.data());
      BOOST_TEST(!flags[0]);
    }
  }
  // A larger self padding than the tables certify: nothing is certified.
  tables.freeAlong(q0.data(), q0.data(), tables.padding() + 0.01, flags.data());
  for (unsigned char f : flags) BOOST_TEST(!f);
  BOOST_TEST(certified > 100u);
  BOOST_TEST(refused > 100u);
  BOOST_TEST_MESSAGE("freeAlong: " << certified << " table-motions certified (" << samples
                                   << " states checked), " << refused << " not");
}

// readLanes on batches of eight seeded random states (at the held values; now and then a value
// beyond its range, NaN, or a table's cell boundary, one ulp below or above it) gives each
// state of the batch what read gives it: the same certified collision, and for the others the
// same free flag per table, at paddings below, at and above the tables', on `path`. Returns
// the free flags compared set.
std::size_t checkReadLanes(const dss::CollisionModel& m, unsigned seed, dss::SimdPath path) {
  const dss::SelfPairTables& tables = m.selfTables();
  const dss::RobotModel& robot = m.robot();
  const std::size_t nq = robot.numActiveJoints();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t flags = 0, colliding = 0;
  std::vector<unsigned char> skip_one(tables.size());
  std::vector<unsigned> skip(tables.size());
  for (double padding : {0.0, tables.padding(), tables.padding() + 0.01}) {
    for (int round = 0; round < 500; ++round) {
      std::vector<std::vector<double>> q(8, m.held());
      std::vector<double> lanes(nq * 8);
      for (int l = 0; l < 8; ++l) {
        for (int a : m.groupActive()) {
          const dss::RobotJoint& j = robot.joints[robot.active_joints[a]];
          const double r = unit(rng);
          q[l][a] = r < 0.02   ? std::numeric_limits<double>::quiet_NaN()
                    : r < 0.05 ? j.limits.upper + 0.5
                               : j.limits.lower + (j.limits.upper - j.limits.lower) * unit(rng);
        }
        if (rng() % 5 == 0) {
          const dss::SelfPairTable& t = tables.tables()[rng() % tables.size()];
          for (int k = 0; k < t.num_vars; ++k) {
            double v = t.lo[k] + double(rng() % std::uint64_t(t.cells[k] + 1)) / t.inv_width[k];
            const unsigned side = unsigned(rng() % 3);
            if (side == 1) v = std::nextafter(v, -kInf);
            if (side == 2) v = std::nextafter(v, kInf);
            q[l][std::size_t(t.var[k])] = v;
          }
        }
        for (std::size_t a = 0; a < nq; ++a) lanes[a * 8 + std::size_t(l)] = q[l][a];
      }
      const unsigned states = unsigned(rng() & 0xFFu);
      std::fill(skip.begin(), skip.end(), 0u);
      const unsigned hit = tables.readLanes(lanes.data(), states, padding, skip.data(), path);
      BOOST_TEST((hit & ~states) == 0u);
      for (int l = 0; l < 8; ++l) {
        if (!((states >> l) & 1u)) {
          for (unsigned s : skip) BOOST_TEST(((s >> l) & 1u) == 0u);
          continue;
        }
        const bool collides = tables.read(q[l].data(), true, padding, skip_one.data());
        BOOST_TEST(((hit >> l) & 1u) == unsigned(collides), "round " << round << " lane " << l);
        colliding += collides;
        if (collides) continue;
        for (std::size_t t = 0; t < tables.size(); ++t) {
          BOOST_TEST(((skip[t] >> l) & 1u) == unsigned(skip_one[t] != 0), "table " << t);
          flags += skip_one[t] != 0;
        }
      }
    }
  }
  BOOST_TEST(colliding > 0u);
  return flags;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(self_pair_tables)

BOOST_AUTO_TEST_CASE(own_arm_tables_read_in_lanes_as_one_by_one) {
  const auto robot = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const auto req = dss::loadPlanRequestYaml(kArm + "/scenes/shelf_request.yaml");
  const dss::ModelSetup p = dss::setupModel(robot, dss::loadScene(kArm + "/scenes/shelf.yaml"),
                                            req.group_name, req.startState());
  BOOST_REQUIRE(p.model->selfTables().size() > 0u);
  for (dss::SimdPath path : {dss::SimdPath::kSse2, dss::SimdPath::kAvx2})
    BOOST_TEST(checkReadLanes(*p.model, 5, path) > 1000u);
}

BOOST_AUTO_TEST_CASE(panda_tables_read_in_lanes_as_one_by_one, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(fs::exists(kPanda + "/panda.urdf"));
  const auto robot = dss::loadRobot(kPanda + "/panda.urdf", kPanda + "/panda.srdf");
  const dss::ModelSetup p =
      dss::setupModel(robot, dss::loadScene(kMbm + "/box/scene0001.yaml"), "", {});
  BOOST_REQUIRE(p.model->selfTables().size() > 0u);
  for (dss::SimdPath path : {dss::SimdPath::kSse2, dss::SimdPath::kAvx2})
    BOOST_TEST(checkReadLanes(*p.model, 6, path) > 1000u);
}

// A continuous joint's table read in lanes: wrapped values (several turns away, at cell
// boundaries and one ulp off them), NaN and infinities get the cell the one-state lookup gives,
// on each path.
BOOST_AUTO_TEST_CASE(wrapped_table_reads_in_lanes_as_one_by_one) {
  dss::SelfPairTable t;
  t.num_vars = 2;
  t.var[0] = 1;
  t.var[1] = 0;
  t.lo[0] = -M_PI, t.hi[0] = M_PI, t.wrap[0] = true;
  t.lo[1] = -1.0, t.hi[1] = 1.0;
  t.cells[0] = 16, t.cells[1] = 8;
  t.inv_width[0] = 16 / (2 * M_PI), t.inv_width[1] = 4.0;
  std::mt19937_64 rng(11);
  t.cell_state.resize(16 * 8);
  for (auto& c : t.cell_state) c = static_cast<unsigned char>(rng() % 3);
  std::vector<int> index;
  const dss::SelfPairTables tables({t}, 0.0, &index);
  int compared = 0, decided = 0;
  for (dss::SimdPath path : {dss::SimdPath::kSse2, dss::SimdPath::kAvx2}) {
    for (int round = 0; round < 2000; ++round) {
      double lanes[2 * 8];
      for (int l = 0; l < 8; ++l) {
        const unsigned pick = unsigned(rng() % 10);
        const double turns = 2 * M_PI * double(int(rng() % 7) - 3);
        double angle = -M_PI + 2 * M_PI * double(rng() % 1000) / 999.0;
        if (pick < 3) angle = -M_PI + double(rng() % 17) / t.inv_width[0];
        double v = angle + turns;
        if (pick == 1) v = std::nextafter(v, -kInf);
        if (pick == 2) v = std::nextafter(v, kInf);
        if (pick == 3) v = rng() % 2 ? std::numeric_limits<double>::quiet_NaN() : kInf;
        lanes[8 + l] = v;
        lanes[l] = pick == 4 ? 1.5 : -1.0 + 2.0 * double(rng() % 1000) / 999.0;
      }
      unsigned skip = 0;
      const unsigned hit = tables.readLanes(lanes, 0xFFu, 0.0, &skip, path);
      for (int l = 0; l < 8; ++l) {
        const double q[2] = {lanes[l], lanes[8 + l]};
        const auto cell = t.cell(q);
        BOOST_TEST(((hit >> l) & 1u) == unsigned(cell == dss::SelfPairTable::kColliding),
                   "round " << round << " lane " << l);
        BOOST_TEST(((skip >> l) & 1u) == unsigned(cell == dss::SelfPairTable::kFree),
                   "round " << round << " lane " << l);
        ++compared;
        decided += cell != dss::SelfPairTable::kUnknown;
      }
    }
  }
  BOOST_TEST(decided > compared / 2);
}

BOOST_AUTO_TEST_CASE(lookup_wraps_and_refuses_nan_inf_and_out_of_range) {
  dss::SelfPairTable t;
  t.num_vars = 2;
  t.var[0] = 0;
  t.var[1] = 1;
  t.lo[0] = -M_PI, t.hi[0] = M_PI, t.wrap[0] = true;
  t.lo[1] = 0.0, t.hi[1] = 1.0;
  t.cells[0] = 4, t.cells[1] = 2;
  t.inv_width[0] = 4 / (2 * M_PI), t.inv_width[1] = 2.0;
  t.cell_state.assign(8, 0);
  t.cell_state[1 * 2 + 1] =
      dss::SelfPairTable::kFree;  // angle in [-pi/2, 0), second value in [0.5, 1]
  t.cell_state[2 * 2 + 0] =
      dss::SelfPairTable::kColliding;  // angle in [0, pi/2), second in [0, 0.5)
  double q[2] = {-0.3, 0.7};
  BOOST_TEST(t.cell(q) == dss::SelfPairTable::kFree);
  q[0] = -0.3 + 4 * M_PI;  // same angle, wrapped
  BOOST_TEST(t.cell(q) == dss::SelfPairTable::kFree);
  q[0] = -0.3 - 6 * M_PI;
  BOOST_TEST(t.cell(q) == dss::SelfPairTable::kFree);
  q[0] = 0.3;
  BOOST_TEST(t.cell(q) != dss::SelfPairTable::kFree);
  BOOST_TEST(t.cell(q) != dss::SelfPairTable::kColliding);
  q[1] = 0.2;
  BOOST_TEST(t.cell(q) == dss::SelfPairTable::kColliding);
  q[0] = 0.3 - 2 * M_PI;
  BOOST_TEST(t.cell(q) == dss::SelfPairTable::kColliding);
  q[1] = 0.7;
  q[0] = -0.3;
  q[1] = 1.0;  // the upper end belongs to the last cell
  BOOST_TEST(t.cell(q) == dss::SelfPairTable::kFree);
  q[1] = std::nextafter(1.0, 2.0);
  BOOST_TEST(t.cell(q) != dss::SelfPairTable::kFree);
  q[1] = 0.49;
  BOOST_TEST(t.cell(q) != dss::SelfPairTable::kFree);
  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()}) {
    q[0] = bad;
    q[1] = 0.7;
    BOOST_TEST(t.cell(q) == dss::SelfPairTable::kUnknown);
    q[0] = -0.3;
    q[1] = bad;
    BOOST_TEST(t.cell(q) == dss::SelfPairTable::kUnknown);
  }
}

// A table built with a joint held outside the group answers only at the held value.
BOOST_AUTO_TEST_CASE(lookup_refuses_other_held_values) {
  dss::SelfPairTable t;
  t.num_vars = 1;
  t.var[0] = 0;
  t.lo[0] = 0.0, t.hi[0] = 1.0;
  t.cells[0] = 2;
  t.inv_width[0] = 2.0;
  t.cell_state = {dss::SelfPairTable::kFree, dss::SelfPairTable::kColliding};
  t.num_fixed = 1;
  t.fixed_var[0] = 2;
  t.fixed_value[0] = 0.04;
  double q[3] = {0.2, 0.0, 0.04};
  BOOST_TEST(t.cell(q) == dss::SelfPairTable::kFree);
  q[0] = 0.7;
  BOOST_TEST(t.cell(q) == dss::SelfPairTable::kColliding);
  for (double other : {0.0, std::nextafter(0.04, 1.0), std::numeric_limits<double>::quiet_NaN()}) {
    q[2] = other;
    BOOST_TEST(t.cell(q) == dss::SelfPairTable::kUnknown, "held value " << other);
  }
}

BOOST_AUTO_TEST_CASE(own_arm_certified_cells_are_free) {
  const auto robot = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const auto req = dss::loadPlanRequestYaml(kArm + "/scenes/shelf_request.yaml");
  const dss::ModelSetup p = dss::setupModel(robot, dss::loadScene(kArm + "/scenes/shelf.yaml"),
                                            req.group_name, req.startState());
  BOOST_TEST_MESSAGE("dss_arm7: " << p.model->summary());
  const std::size_t checked = checkAllCells(p.model, 0.0);
  BOOST_TEST_MESSAGE("dss_arm7: " << checked << " element pairs in certified cells checked");
}

BOOST_AUTO_TEST_CASE(own_arm_tables_certify_motions_only_through_free_cells) {
  const auto robot = dss::loadRobot(kArm + "/dss_arm7.urdf", kArm + "/dss_arm7.srdf");
  const auto req = dss::loadPlanRequestYaml(kArm + "/scenes/shelf_request.yaml");
  const dss::ModelSetup p = dss::setupModel(robot, dss::loadScene(kArm + "/scenes/shelf.yaml"),
                                            req.group_name, req.startState());
  checkFreeAlong(*p.model, 31);
}

BOOST_AUTO_TEST_CASE(panda_tables_certify_motions_only_through_free_cells, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(fs::exists(kPanda + "/panda.urdf"));
  const auto robot = dss::loadRobot(kPanda + "/panda.urdf", kPanda + "/panda.srdf");
  const auto req = dss::loadPlanRequestYaml(kMbm + "/table_pick/request0001.yaml");
  const dss::ModelSetup p = dss::setupModel(
      robot, dss::loadScene(kMbm + "/table_pick/scene0001.yaml"), req.group_name, req.startState());
  checkFreeAlong(*p.model, 32);
}

BOOST_AUTO_TEST_CASE(panda_certified_cells_are_free_and_tables_change_no_answer, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(fs::exists(kPanda + "/panda.urdf"));
  const auto robot = dss::loadRobot(kPanda + "/panda.urdf", kPanda + "/panda.srdf");
  const dss::Scene scene = dss::loadScene(kMbm + "/table_pick/scene0001.yaml");
  const dss::ModelSetup p = dss::setupModel(robot, scene, "", {});
  BOOST_TEST(p.model->selfTables().size() >= 2u, p.model->summary());
  const std::size_t checked = checkAllCells(p.model, 0.0);
  BOOST_TEST(checked > 10000u);
  BOOST_TEST_MESSAGE("panda: " << p.model->summary() << "; " << checked
                               << " element pairs checked");

  // Whole checkers: with and without tables, at zero and at a 1 cm self padding (where only
  // the colliding cells of the zero-padding tables apply), the same answers on seeded
  // random states.
  dss::CollisionModelOptions no_tables;
  no_tables.self_table_cells_1d = no_tables.self_table_cells_2d = 0;
  auto bare =
      std::make_shared<dss::CollisionModel>(robot.model, robot.srdf ? &*robot.srdf : nullptr, scene,
                                            p.model->groupActive(), p.model->held(), no_tables);
  BOOST_TEST(bare->selfTables().size() == 0u);
  std::mt19937_64 rng(11);
  std::vector<double> q = p.model->held();
  for (double pad : {0.0, 0.01}) {
    dss::DssCheckerSettings s;
    s.self_padding = pad;
    const dss::DssChecker with(p.model, s), without(bare, s);
    std::size_t differ = 0, invalid = 0;
    for (int k = 0; k < 20000; ++k) {
      for (int a : p.model->groupActive()) {
        const auto& j = robot.model->joints[robot.model->active_joints[a]];
        q[a] = std::uniform_real_distribution<double>(j.limits.lower, j.limits.upper)(rng);
      }
      const dss::StateVerdict v1 = with.check(q.data()), v2 = without.check(q.data());
      BOOST_TEST_REQUIRE((v1 != dss::StateVerdict::kInvalidInput), "state " << k);
      differ += v1 != v2;
      invalid += v1 != dss::StateVerdict::kFree;
    }
    BOOST_TEST(differ == 0u);
    BOOST_TEST(invalid > 1000u);  // the test sees collisions
    BOOST_TEST_MESSAGE("self padding " << pad << ": " << invalid << " of 20000 invalid, " << differ
                                       << " differ; pair tests with tables "
                                       << with.counters().pair_tests << ", without "
                                       << without.counters().pair_tests);
    BOOST_TEST(with.counters().pair_tests < without.counters().pair_tests);
  }
}

// With the MotionBenchMaker group (the arm; the fingers held), pairs that also depend on a
// finger joint get tables at the held finger value: every decided cell is right there, and a
// checker with tables answers as one without.
BOOST_AUTO_TEST_CASE(panda_arm_group_tables_with_held_fingers, DSS_NEEDS_SHARED) {
  BOOST_REQUIRE(fs::exists(kPanda + "/panda.urdf") &&
                fs::exists(kMbm + "/table_pick/request0001.yaml"));
  const auto robot = dss::loadRobot(kPanda + "/panda.urdf", kPanda + "/panda.srdf");
  const dss::Scene scene = dss::loadScene(kMbm + "/table_pick/scene0001.yaml");
  const auto req = dss::loadPlanRequestYaml(kMbm + "/table_pick/request0001.yaml");
  const dss::ModelSetup p = dss::setupModel(robot, scene, req.group_name, req.startState());
  std::size_t held_tables = 0;
  for (const auto& t : p.model->selfTables().tables()) held_tables += t.num_fixed > 0;
  BOOST_TEST(held_tables >= 2u, p.model->summary());
  const std::size_t checked = checkAllCells(p.model, 0.0);
  BOOST_TEST(checked > 10000u);
  dss::CollisionModelOptions no_tables;
  no_tables.self_table_cells_1d = no_tables.self_table_cells_2d = 0;
  auto bare =
      std::make_shared<dss::CollisionModel>(robot.model, robot.srdf ? &*robot.srdf : nullptr, scene,
                                            p.model->groupActive(), p.model->held(), no_tables);
  std::mt19937_64 rng(12);
  std::vector<double> q = p.model->held();
  const dss::DssChecker with(p.model), without(bare);
  std::size_t differ = 0, invalid = 0;
  for (int k = 0; k < 20000; ++k) {
    for (int a : p.model->groupActive()) {
      const auto& j = robot.model->joints[robot.model->active_joints[a]];
      q[a] = std::uniform_real_distribution<double>(j.limits.lower, j.limits.upper)(rng);
    }
    // One state in four with the fingers elsewhere than held: the tables must not answer.
    if (k % 4 == 0)
      for (std::size_t a = 0; a < q.size(); ++a)
        if (std::find(p.model->groupActive().begin(), p.model->groupActive().end(), int(a)) ==
            p.model->groupActive().end()) {
          const auto& j = robot.model->joints[robot.model->active_joints[a]];
          // The Panda's floating virtual joint stays where it is held (its translation has no
          // bounds to draw from).
          if (j.multi_dof >= 0) continue;
          q[a] = std::uniform_real_distribution<double>(j.limits.lower, j.limits.upper)(rng);
        }
    const dss::StateVerdict v1 = with.check(q.data()), v2 = without.check(q.data());
    BOOST_TEST_REQUIRE((v1 != dss::StateVerdict::kInvalidInput), "state " << k);
    differ += v1 != v2;
    invalid += v1 != dss::StateVerdict::kFree;
    if (k % 4 == 0) q = std::vector<double>(p.model->held());
  }
  BOOST_TEST(differ == 0u);
  BOOST_TEST(invalid > 1000u);
  BOOST_TEST(with.counters().pair_tests < without.counters().pair_tests);
}

BOOST_AUTO_TEST_SUITE_END()
