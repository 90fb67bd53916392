// dss_bench nearest: the nearest-neighbour query of a tree planner on a joint-value space, by
// OMPL's default structure (GNAT through the planner's distance function, as RRTConnect uses
// it), by dss::PointBlocks' scan of every point and by its k-d tree (dss::PointTree), each on
// every instruction set, and by dss::VectorNearestNeighbors as planners get it, on the same
// random points and queries. Medians of interleaved repetitions; every structure must return
// the same nearest point.
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "dss/planning/vector_nearest_neighbors.h"
#include "subcommand.h"

namespace ob = ompl::base;

namespace {

struct Item {
  ob::State* state;
};

const char* kUsage =
    "usage: dss_bench nearest [--dim D (7)] [--sizes N,N,... (100,1000,3000,10000,30000,100000)]\n"
    "                         [--queries Q (2000)] [--reps R (7)] [--seed S (1)]\n"
    "  points and queries uniform in [-pi, pi]^D; microseconds per query, median of R\n"
    "  interleaved repetitions\n";

std::vector<std::size_t> parseSizes(const std::string& s) {
  std::vector<std::size_t> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(std::stoul(item));
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

int runNearest(int argc, char** argv) {
  unsigned dim = 7;
  std::vector<std::size_t> sizes = {100, 1000, 3000, 10000, 30000, 100000};
  std::size_t num_queries = 2000;
  int reps = 7;
  unsigned long seed = 1;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(a + ": missing value");
        return argv[++i];
      };
      if (a == "--dim")
        dim = unsigned(std::stoul(value()));
      else if (a == "--sizes")
        sizes = parseSizes(value());
      else if (a == "--queries")
        num_queries = std::stoul(value());
      else if (a == "--reps")
        reps = std::stoi(value());
      else if (a == "--seed")
        seed = std::stoul(value());
      else if (a == "--help" || a == "-h") {
        std::cout << kUsage;
        return 0;
      } else
        throw std::invalid_argument("unknown option " + a);
    }
    if (dim == 0 || dim > 64 || reps < 1 || num_queries == 0 || sizes.empty())
      throw std::invalid_argument("--dim in [1, 64], --reps, --queries and --sizes positive");
  } catch (const std::exception& e) {
    std::cerr << "dss_bench nearest: " << e.what() << "\n" << kUsage;
    return 2;
  }

  auto space = std::make_shared<ob::RealVectorStateSpace>(dim);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-M_PI, M_PI);
  auto make = [&](std::size_t n) {
    std::vector<Item*> v;
    for (std::size_t i = 0; i < n; ++i) {
      auto* it = new Item{space->allocState()};
      for (unsigned d = 0; d < dim; ++d)
        it->state->as<ob::RealVectorStateSpace::StateType>()->values[d] = u(rng);
      v.push_back(it);
    }
    return v;
  };
  auto release = [&](std::vector<Item*>& v) {
    for (Item* it : v) {
      space->freeState(it->state);
      delete it;
    }
    v.clear();
  };
  std::vector<Item*> queries = make(num_queries);

  // The entries: OMPL's GNAT; PointBlocks' scan of every point and its k-d tree (PointTree),
  // each on every instruction set the CPU has; VectorNearestNeighbors as planners get it.
  struct Blocks {
    std::string name;
    dss::SimdPath path;
    std::size_t tree_from;
  };
  std::vector<Blocks> kinds;
  for (const char* kind : {"scan", "tree"})
    for (auto p : {dss::SimdPath::kAvx2, dss::SimdPath::kSse2, dss::SimdPath::kScalar})
      if (dss::simdPathAvailable(p))
        kinds.push_back({std::string(kind) + "-" + dss::simdPathName(p), p,
                         kind[0] == 's' ? std::size_t(-1) : std::size_t(0)});
  std::printf("dim %u, %zu queries, median of %d repetitions; us per query\n", dim, num_queries,
              reps);
  std::printf("%8s %10s", "points", "ompl-gnat");
  for (const auto& k : kinds) std::printf(" %11s", k.name.c_str());
  std::printf(" %10s %8s\n", "vector", "gnat/vec");
  auto values = [](const Item* it) {
    return it->state->as<ob::RealVectorStateSpace::StateType>()->values;
  };
  for (const std::size_t n : sizes) {
    std::vector<Item*> points = make(n);
    ompl::NearestNeighborsGNATNoThreadSafety<Item*> gnat;
    gnat.setDistanceFunction(
        [&](Item* const& a, Item* const& b) { return space->distance(a->state, b->state); });
    gnat.add(points);
    std::vector<dss::PointBlocks> blocks;
    for (const auto& k : kinds) {
      blocks.emplace_back(dim, k.path, k.tree_from);
      for (const Item* it : points) blocks.back().push(values(it));
    }
    dss::VectorNearestNeighbors<Item*> vec(dim);
    vec.add(points);
    std::vector<std::vector<double>> times(blocks.size() + 2);
    std::vector<Item*> expected(queries.size()), got(queries.size());
    using Clock = std::chrono::steady_clock;
    auto check = [&]() {
      if (got == expected) return true;
      std::cerr << "dss_bench nearest: a structure found another nearest point than GNAT (" << n
                << " points)\n";
      return false;
    };
    for (int r = 0; r < reps; ++r) {
      auto t0 = Clock::now();
      for (std::size_t q = 0; q < queries.size(); ++q) expected[q] = gnat.nearest(queries[q]);
      times[0].push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
      for (std::size_t b = 0; b < blocks.size(); ++b) {
        t0 = Clock::now();
        for (std::size_t q = 0; q < queries.size(); ++q)
          got[q] = points[blocks[b].nearest(values(queries[q]))];
        times[b + 1].push_back(
            std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
        if (!check()) return 1;
      }
      t0 = Clock::now();
      for (std::size_t q = 0; q < queries.size(); ++q) got[q] = vec.nearest(queries[q]);
      times.back().push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
      if (!check()) return 1;
    }
    const double per = double(queries.size());
    std::printf("%8zu %10.3f", n, median(times[0]) / per);
    for (std::size_t b = 0; b < blocks.size(); ++b)
      std::printf(" %11.3f", median(times[b + 1]) / per);
    std::printf(" %10.3f %8.2f\n", median(times.back()) / per,
                median(times[0]) / median(times.back()));
    release(points);
  }
  release(queries);
  return 0;
}

}  // namespace

DSS_BENCH_SUBCOMMAND("nearest", "nearest-neighbour queries: OMPL's GNAT against the vector search",
                     runNearest);
