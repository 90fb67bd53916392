// dss_pairs: decide every pair of a JSON Lines pair file with DSS, GJK, Hybrid or FCL, so that
// anyone can check the library against their own cases (format: see pairs_input.h, or
// `dss_pairs --help`).
//
// The whole file is read and validated first (a bad line stops the run before any output,
// with `FILE:N: <what is wrong>` on stderr and exit code 2), the shapes are built once, then
// every pair is decided and one JSON line per input line is written to stdout. With --time,
// the whole file is decided again and again (after one warm-up pass; the algorithms of a
// comma list interleaved in each repetition) and one JSON summary per algorithm goes to
// stderr with the median time per pair.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "cli.h"
#include "pairs_fcl.h"
#include "pairs_input.h"
#include "pairs_shapes.h"

namespace {

using namespace dss::pairs;

constexpr int kExitUsage = dss::cli::kExitUsage;

const char* const kUsage = R"(usage: dss_pairs [options] FILE        (FILE = - reads stdin)

Decides for each pair of convex shapes in FILE (JSON Lines) whether they intersect
(touching counts as intersecting) and prints one JSON line per input line on stdout:
  {"id":"p1","intersect":true,"status":"decided","iterations":3}
status is "decided" or "iteration_limit" (a cap hit answers "intersect").

Input line: {"id": "p1", "a": SHAPE, "b": SHAPE}, SHAPE one of
  {"type":"sphere","radius":r}
  {"type":"box","size":[x,y,z]}                 full edge lengths
  {"type":"cylinder","radius":r,"length":l}     axis local z, centred
  {"type":"capsule","radius":r,"length":l}      segment of length l along z, plus r
  {"type":"cone","radius":r,"length":l}         base at z=-l/2, apex at z=+l/2 (as fcl::Cone)
  {"type":"ellipsoid","radii":[a,b,c]}
  {"type":"convex","vertices":[[x,y,z],...]}    convex hull of the points
each with an optional "pose":{"position":[x,y,z],"orientation":[qx,qy,qz,qw]}
(world = R(q) local + position; q normalised; identity when absent). A posed convex shape
is posed vertex by vertex once, and decided as the hull of those world points.
A field the object does not have (e.g. "radius" on a box), a key given twice in one object
and arrays or objects nested more than 64 deep are errors.

Options:
  --algo A           dss (default), gjk, hybrid or fcl (FCL 0.7, fcl::collide with a
                     default CollisionRequest: GJK solver libccd). A comma list (dss,gjk,fcl)
                     needs --time; stdout then has the answers of the first one.
  --mode M           exact (default), double or float: the search in float arithmetic, on
                     supports rounded to float (fcl always computes in double)
  --max-iterations N cap on support evaluations (default: the core's, 64)
  --padding r        grow shape A by a ball of radius r: the answer is then "distance <= r"
                     (fcl: collide, then fcl::distance <= r for pairs that do not collide)
  --time             also time the whole file per algorithm; one JSON summary per
                     algorithm on stderr: algo, mode, pairs, ns_per_pair (median), ...
  --repeat K         repetitions for --time (default 21), after one warm-up pass
  --help             this text

Exit codes: 0 success; 2 usage error, unreadable file or malformed line
(stderr: FILE:N: what is wrong).
)";

enum class Algo { kDss, kGjk, kHybrid, kFcl };

struct Args {
  std::vector<Algo> algos;
  std::vector<std::string> algo_names;
  dss::Mode mode = dss::Mode::kExact;
  int max_iterations = -1;
  double padding = 0;
  bool time = false;
  int repeat = 21;
  std::string file;
};

Args parseArgs(int argc, char** argv) {
  Args args;
  std::string algo_list = "dss";
  dss::cli::ArgCursor cli(argc, argv, "dss_pairs", kUsage);
  while (cli.next()) {
    if (cli.option("--algo")) {
      algo_list = cli.value();
    } else if (cli.option("--mode")) {
      const std::string m = cli.value();
      if (m == "exact")
        args.mode = dss::Mode::kExact;
      else if (m == "double")
        args.mode = dss::Mode::kDouble;
      else if (m == "float")
        args.mode = dss::Mode::kFloat;
      else
        cli.error("--mode: expected exact, double or float, got '" + m + "'");
    } else if (cli.option("--max-iterations")) {
      args.max_iterations = static_cast<int>(cli.integer(1, 1000000000));
    } else if (cli.option("--padding")) {
      args.padding = cli.number(0, std::numeric_limits<double>::max());
    } else if (cli.flag("--time")) {
      args.time = true;
    } else if (cli.option("--repeat")) {
      args.repeat = static_cast<int>(cli.integer(1, 1000000000));
    } else if (cli.positional("FILE")) {
      if (!args.file.empty()) cli.error("more than one input file");
      args.file = cli.value();
    } else {
      cli.unknown();
    }
  }
  if (args.file.empty()) cli.error("no input file (use - for stdin)");
  std::stringstream ss(algo_list);
  std::string name;
  while (std::getline(ss, name, ',')) {
    Algo algo;
    if (name == "dss")
      algo = Algo::kDss;
    else if (name == "gjk")
      algo = Algo::kGjk;
    else if (name == "hybrid")
      algo = Algo::kHybrid;
    else if (name == "fcl")
      algo = Algo::kFcl;
    else
      cli.error("--algo: expected dss, gjk, hybrid or fcl, got '" + name + "'");
    if (std::find(args.algos.begin(), args.algos.end(), algo) != args.algos.end())
      cli.error("--algo: '" + name + "' given twice");
    args.algos.push_back(algo);
    args.algo_names.push_back(name);
  }
  if (args.algos.empty()) cli.error("--algo: empty list");
  if (args.algos.size() > 1 && !args.time) cli.error("--algo: a list needs --time");
  return args;
}

CoreAlgo coreAlgo(Algo a) {
  return a == Algo::kGjk ? CoreAlgo::kGjk : a == Algo::kHybrid ? CoreAlgo::kHybrid : CoreAlgo::kDss;
}

/// Everything one run needs, built once from the file.
struct Workload {
  std::vector<std::string> ids;
  std::vector<CorePair> core;
  std::vector<FclPair> fcl;
};

/// Decisions of one algorithm over the whole file, in input order.
struct Answers {
  std::vector<dss::Result> results;  // core algorithms
  std::vector<char> fcl;             // fcl: intersect per pair
};

void decide(Algo algo, const Args& args, const dss::Options& opt, const Workload& w, Answers& out) {
  if (algo == Algo::kFcl) {
    out.fcl.resize(w.fcl.size());
    for (std::size_t i = 0; i < w.fcl.size(); ++i)
      out.fcl[i] = fclIntersect(w.fcl[i], args.padding) ? 1 : 0;
    return;
  }
  decideAll(coreAlgo(algo), w.core, opt, args.padding, out.results);
}

void printAnswers(Algo algo, const Workload& w, const Answers& ans) {
  std::string line;
  for (std::size_t i = 0; i < w.ids.size(); ++i) {
    line.assign("{\"id\":").append(w.ids[i]);
    if (algo == Algo::kFcl) {
      line.append(ans.fcl[i] ? ",\"intersect\":true" : ",\"intersect\":false");
      line.append(",\"status\":\"decided\"}\n");
    } else {
      const dss::Result& r = ans.results[i];
      line.append(r.intersect ? ",\"intersect\":true" : ",\"intersect\":false");
      line.append(",\"status\":\"").append(dss::toString(r.status)).append("\"");
      line.append(",\"iterations\":").append(std::to_string(r.iterations)).append("}\n");
    }
    std::fwrite(line.data(), 1, line.size(), stdout);
  }
}

std::size_t countIntersecting(Algo algo, const Answers& ans) {
  if (algo == Algo::kFcl) return std::count(ans.fcl.begin(), ans.fcl.end(), 1);
  return std::count_if(ans.results.begin(), ans.results.end(),
                       [](const dss::Result& r) { return r.intersect; });
}

void timeRuns(const Args& args, const dss::Options& opt, const Workload& w) {
  const std::size_t n_algos = args.algos.size();
  std::vector<Answers> scratch(n_algos);
  std::vector<std::vector<double>> ns_per_pair(n_algos);
  const double pairs = static_cast<double>(w.ids.size());
  std::size_t sink = 0;  // keeps the decisions observable
  for (std::size_t k = 0; k < n_algos; ++k) decide(args.algos[k], args, opt, w, scratch[k]);
  for (int rep = 0; rep < args.repeat; ++rep) {
    for (std::size_t k = 0; k < n_algos; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      decide(args.algos[k], args, opt, w, scratch[k]);
      const auto t1 = std::chrono::steady_clock::now();
      sink += countIntersecting(args.algos[k], scratch[k]);
      ns_per_pair[k].push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / pairs);
    }
  }
  for (std::size_t k = 0; k < n_algos; ++k) {
    std::vector<double> v = ns_per_pair[k];
    std::sort(v.begin(), v.end());
    const double median =
        v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    const Algo algo = args.algos[k];
    std::size_t cap_hits = 0;
    double mean_iterations = 0;
    if (algo != Algo::kFcl) {
      for (const dss::Result& r : scratch[k].results) {
        cap_hits += r.status == dss::Status::kIterationLimit;
        mean_iterations += r.iterations;
      }
      mean_iterations /= pairs;
    }
    std::fprintf(stderr,
                 "{\"algo\":\"%s\",\"mode\":\"%s\",\"pairs\":%zu,\"ns_per_pair\":%.1f,"
                 "\"min_ns_per_pair\":%.1f,\"repetitions\":%d,\"intersecting\":%zu",
                 args.algo_names[k].c_str(),
                 algo == Algo::kFcl ? "double" : dss::toString(args.mode), w.ids.size(), median,
                 v.front(), args.repeat, countIntersecting(algo, scratch[k]));
    if (algo == Algo::kFcl)
      std::fprintf(stderr, ",\"solver\":\"fcl::collide GST_LIBCCD\"}\n");
    else
      std::fprintf(stderr, ",\"mean_iterations\":%.2f,\"cap_hits\":%zu}\n", mean_iterations,
                   cap_hits);
  }
  if (sink == static_cast<std::size_t>(-1)) std::fputc('\n', stderr);
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parseArgs(argc, argv);
  const std::string file_label = args.file == "-" ? "<stdin>" : args.file;

  std::vector<PairSpec> specs;
  Workload w;
  {
    std::ifstream file;
    std::istream* in = &std::cin;
    if (args.file != "-") {
      file.open(args.file);
      if (!file) {
        std::fprintf(stderr, "%s: cannot open file\n", file_label.c_str());
        return kExitUsage;
      }
      in = &file;
    }
    const bool need_core =
        std::any_of(args.algos.begin(), args.algos.end(), [](Algo a) { return a != Algo::kFcl; });
    const bool need_fcl =
        std::find(args.algos.begin(), args.algos.end(), Algo::kFcl) != args.algos.end();
    int line = 0;
    try {
      specs = readPairs(*in);
      for (const PairSpec& p : specs) {
        line = p.line;
        w.ids.push_back(p.id_json);
        if (need_core) w.core.push_back(makeCorePair(p.a, p.b));
        if (need_fcl) w.fcl.push_back(FclPair{makeFclShape(p.a), makeFclShape(p.b)});
      }
    } catch (const PairsInputError& e) {
      std::fprintf(stderr, "%s:%d: %s\n", file_label.c_str(), e.line(), e.what());
      return kExitUsage;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s:%d: %s\n", file_label.c_str(), line, e.what());
      return kExitUsage;
    }
  }

  dss::Options opt;
  opt.mode = args.mode;
  if (args.max_iterations > 0) opt.max_iterations = args.max_iterations;

  Answers answers;
  decide(args.algos.front(), args, opt, w, answers);
  printAnswers(args.algos.front(), w, answers);
  std::fflush(stdout);
  if (args.time) {
    if (w.ids.empty()) {
      std::fprintf(stderr, "%s: no pairs to time\n", file_label.c_str());
      return kExitUsage;
    }
    timeRuns(args, opt, w);
  }
  return 0;
}
