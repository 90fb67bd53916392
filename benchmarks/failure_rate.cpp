// `dss_bench failure-rate`: the paper's long failure-rate run (Hornus 2017, section 6).
//
// Random tetrahedra as in the narrowphase `tetra` workload (hull of four points on the unit
// sphere containing the origin, shifted along x by U[0, sigma]), their vertices rounded to
// float so that the float shapes and the exact reference describe the same geometry. Every
// pair is decided in float by DSS, GJK and Hybrid with the paper's cap (20 support
// evaluations), and scored against the exact separating-axis reference. A failure is a pair
// that hits the cap (status iteration_limit, answered "intersect"); a wrong answer is a pair
// whose answer differs from the exact one (cap hits included). The pairs come in batches: all
// pairs of `--batch` tetrahedra, each batch from its own seed, the last batch truncated so
// that exactly `--pairs` pairs are decided. Output: a table and one JSON line per spread.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "dss/core/convex_hull.h"
#include "dss/core/dss.h"
#include "dss/core/gjk.h"
#include "narrowphase_reference.h"
#include "narrowphase_workloads.h"
#include "subcommand.h"

namespace dss {
namespace bench {
namespace {

using Clock = std::chrono::steady_clock;

struct FailureConfig {
  long long pairs = 1000000;
  std::uint64_t seed = 20170601;
  std::vector<double> sigmas = {2.0};
  int max_iterations = 20;
  int batch = 1000;
  bool with_double = false;
  int dump = 0;
  std::string json;
  std::string note;
  std::string command;
};

const char* kFailureUsage =
    "usage: dss_bench failure-rate [options]\n"
    "  --pairs N           tetrahedron pairs per spread (default 1e6; the paper's run is 1e8)\n"
    "  --sigma S           spread of the x shifts (default 2: about 72 % density)\n"
    "  --sigmas LIST       comma list of spreads (one result line each)\n"
    "  --max-iterations K  cap of DSS, GJK and Hybrid (default 20, the paper's)\n"
    "  --batch B           tetrahedra per batch, all pairs of a batch (default 1000)\n"
    "  --double            also run DSS and GJK in double on the same (float-rounded) vertices\n"
    "  --seed S            generator seed (batch k uses seed + k)\n"
    "  --json FILE         write the JSON lines to FILE as well as to stdout\n"
    "  --dump N            print the first N pairs of each DSS / Hybrid variant that hit the\n"
    "                      cap or are wrong\n"
    "                      (batch, indices, vertices as hex floats) to stderr\n"
    "  --note TEXT         free text stored in the JSON (build commit, machine load)\n";

FailureConfig parseFailureArgs(int argc, char** argv) {
  FailureConfig c;
  c.command = "dss_bench";
  for (int k = 0; k < argc; ++k) {
    const std::string arg = argv[k];
    c.command += arg.find(' ') == std::string::npos ? " " + arg : " '" + arg + "'";
  }
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    auto value = [&]() -> std::string {
      if (k + 1 >= argc) throw std::runtime_error("failure-rate: option " + a + " needs a value");
      return argv[++k];
    };
    if (a == "--help" || a == "-h") {
      std::fputs(kFailureUsage, stdout);
      std::exit(0);
    } else if (a == "--pairs") {
      c.pairs = static_cast<long long>(std::stod(value()));  // accepts 1e8
    } else if (a == "--sigma") {
      c.sigmas = {std::stod(value())};
    } else if (a == "--sigmas") {
      c.sigmas.clear();
      std::string s = value();
      std::size_t start = 0;
      while (start <= s.size()) {
        const std::size_t end = s.find(',', start);
        c.sigmas.push_back(
            std::stod(s.substr(start, end == std::string::npos ? std::string::npos : end - start)));
        if (end == std::string::npos) break;
        start = end + 1;
      }
    } else if (a == "--max-iterations") {
      c.max_iterations = std::stoi(value());
    } else if (a == "--batch") {
      c.batch = std::stoi(value());
    } else if (a == "--double") {
      c.with_double = true;
    } else if (a == "--seed") {
      c.seed = std::stoull(value());
    } else if (a == "--json") {
      c.json = value();
    } else if (a == "--dump") {
      c.dump = std::stoi(value());
    } else if (a == "--note") {
      c.note = value();
    } else {
      throw std::runtime_error("failure-rate: unknown option '" + a + "'\n" + kFailureUsage);
    }
  }
  if (c.pairs < 1 || c.batch < 2 || c.max_iterations < 1 || c.sigmas.empty())
    throw std::runtime_error("failure-rate: --pairs >= 1, --batch >= 2, --max-iterations >= 1");
  return c;
}

struct Tally {
  std::string name;
  long long cap_hits = 0;
  long long wrong = 0;            // answers differing from the exact reference
  long long wrong_intersect = 0;  // of which "intersect" for a disjoint pair
  long long wrong_decided = 0;    // wrong answers with status decided (not a cap hit)
  long long iterations = 0;
  int max_iterations = 0;
  double seconds = 0;
  int dumped = 0;                    // pairs printed by --dump
  std::vector<long long> histogram;  // pairs by support evaluations, 0..cap

  void add(const Result& r, bool truth) {
    iterations += r.iterations;
    max_iterations = std::max(max_iterations, r.iterations);
    if (r.iterations >= 0 && r.iterations < int(histogram.size())) ++histogram[r.iterations];
    const bool cap = r.status == Status::kIterationLimit;
    cap_hits += cap;
    if (r.intersect != truth) {
      ++wrong;
      wrong_intersect += r.intersect;
      wrong_decided += !cap;
    }
  }
};

int runFailureRate(int argc, char** argv) {
  const FailureConfig cfg = parseFailureArgs(argc, argv);
  std::printf(
      "dss_bench failure-rate: %lld pairs per spread, float, cap %d, batches of %d tetrahedra, "
      "seed %llu\n",
      cfg.pairs, cfg.max_iterations, cfg.batch, (unsigned long long)cfg.seed);
  std::ofstream json_file;
  if (!cfg.json.empty()) {
    json_file.open(cfg.json);
    if (!json_file) throw std::runtime_error("failure-rate: cannot write " + cfg.json);
  }
  for (double sigma : cfg.sigmas) {
    const auto start = Clock::now();
    std::vector<Tally> tallies;
    for (const char* name :
         {"dss-float", "gjk-float", "hybrid-float", "dss-double", "gjk-double"}) {
      if (!cfg.with_double && std::string(name).find("double") != std::string::npos) continue;
      Tally t;
      t.name = name;
      t.dumped = 0;
      t.histogram.assign(cfg.max_iterations + 1, 0);
      tallies.push_back(t);
    }
    long long done = 0, intersecting = 0;
    double reference_seconds = 0;
    for (std::uint64_t batch = 0; done < cfg.pairs; ++batch) {
      WorkloadSet w = makeWorkload(WorkloadKind::kTetrahedra, sigma, cfg.batch, cfg.seed + batch);
      // Round the vertices to float: the float shapes and the exact reference then agree on
      // the geometry (the generator rejects near-flat tetrahedra, so no orientation flips).
      std::vector<ConvexHull> hulls;
      std::vector<ConvexHullT<float>> hulls_f;
      for (auto& p : w.a_polytopes) {
        for (auto& v : p.vertices) v = v.cast<float>().cast<double>();
        p.finishTopology();
        hulls.emplace_back(p.vertices, p.neighbours);
        hulls_f.push_back(hulls.back().cast<float>());
      }
      const long long count = std::min<long long>(cfg.pairs - done, (long long)w.pairs.size());
      std::vector<std::uint8_t> truth(count);
      auto t0 = Clock::now();
      for (long long k = 0; k < count; ++k) {
        const auto [i, j] = w.pairs[k];
        truth[k] = polytopesIntersectExact(w.a_polytopes[i], w.a_polytopes[j]);
        intersecting += truth[k];
      }
      reference_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      for (auto& t : tallies) {
        Options opt;
        opt.max_iterations = cfg.max_iterations;
        opt.mode = t.name.find("float") != std::string::npos ? Mode::kFloat : Mode::kDouble;
        const bool dss = t.name.rfind("dss", 0) == 0, gjk = t.name.rfind("gjk", 0) == 0;
        t0 = Clock::now();
        for (long long k = 0; k < count; ++k) {
          const auto [i, j] = w.pairs[k];
          Result r;
          if (opt.mode == Mode::kFloat) {
            r = dss   ? intersect(hulls_f[i], hulls_f[j], opt)
                : gjk ? intersectGjk(hulls_f[i], hulls_f[j], opt)
                      : intersectHybrid(hulls_f[i], hulls_f[j], opt);
          } else {
            r = dss   ? intersect(hulls[i], hulls[j], opt)
                : gjk ? intersectGjk(hulls[i], hulls[j], opt)
                      : intersectHybrid(hulls[i], hulls[j], opt);
          }
          t.add(r, truth[k]);
          if (t.dumped < cfg.dump && !gjk &&
              (r.status == Status::kIterationLimit || r.intersect != truth[k])) {
            ++t.dumped;
            std::fprintf(stderr,
                         "%s: batch %llu pair (%d, %d) sigma %g: answer %d exact %d status %s "
                         "iterations %d\n",
                         t.name.c_str(), (unsigned long long)batch, i, j, sigma, int(r.intersect),
                         int(truth[k]), toString(r.status), r.iterations);
            for (int side : {i, j}) {
              std::fprintf(stderr, "  tetrahedron %d:", side);
              for (const auto& v : w.a_polytopes[side].vertices)
                std::fprintf(stderr, " (%a, %a, %a)", v.x(), v.y(), v.z());
              std::fprintf(stderr, "\n");
            }
          }
        }
        t.seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      }
      done += count;
    }
    const double total = std::chrono::duration<double>(Clock::now() - start).count();
    const double density = double(intersecting) / double(done);
    std::printf("\nsigma %g: %lld pairs, density %.2f %% (exact), %.1f s (reference %.1f s)\n",
                sigma, done, 100 * density, total, reference_seconds);
    std::printf("  %-13s %12s %12s %10s %10s %10s %8s %8s %9s\n", "algo", "cap_hits", "cap_rate",
                "wrong", "wrong_int", "wrong_dec", "mean_it", "max_it", "ns/pair");
    nlohmann::json line;
    line["benchmark"] = "failure-rate";
    line["command"] = cfg.command;
    line["workload"] = "tetra";
    line["vertices"] = "float-rounded";
    line["sigma"] = sigma;
    line["pairs"] = done;
    line["density"] = density;
    line["max_iterations_cap"] = cfg.max_iterations;
    line["batch"] = cfg.batch;
    line["seed"] = cfg.seed;
    line["reference"] = "exact-sat (all pairs)";
    line["seconds"] = total;
    if (!cfg.note.empty()) line["note"] = cfg.note;
    for (const auto& t : tallies) {
      const double ns = 1e9 * t.seconds / double(done);
      std::printf("  %-13s %12lld %12.3g %10lld %10lld %10lld %8.3f %8d %9.1f\n", t.name.c_str(),
                  t.cap_hits, double(t.cap_hits) / double(done), t.wrong, t.wrong_intersect,
                  t.wrong_decided, double(t.iterations) / double(done), t.max_iterations, ns);
      line["algos"].push_back({{"algo", t.name},
                               {"cap_hits", t.cap_hits},
                               {"cap_rate", double(t.cap_hits) / double(done)},
                               {"wrong", t.wrong},
                               {"wrong_intersect", t.wrong_intersect},
                               {"wrong_decided", t.wrong_decided},
                               {"mean_iterations", double(t.iterations) / double(done)},
                               {"max_iterations", t.max_iterations},
                               {"iteration_histogram", t.histogram},
                               {"ns_per_pair", ns}});
    }
    const std::string text = line.dump();
    std::printf("%s\n", text.c_str());
    std::fflush(stdout);
    if (json_file) json_file << text << '\n' << std::flush;
  }
  return 0;
}

}  // namespace

DSS_BENCH_SUBCOMMAND(
    "failure-rate",
    "long run: cap hits and wrong answers of DSS, GJK, Hybrid in float on random tetrahedra",
    runFailureRate);

}  // namespace bench
}  // namespace dss
