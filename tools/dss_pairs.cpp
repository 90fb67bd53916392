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
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "pairs_fcl.h"
#include "pairs_input.h"
#include "pairs_shapes.h"

namespace {

using namespace dss::pairs;

constexpr int kExitUsage = 2;

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

Options:
  --algo A           dss (default), gjk, hybrid or fcl (FCL 0.7, fcl::collide with a
                     default CollisionRequest: GJK solver libccd). A comma list (dss,gjk,fcl)
                     needs --time; stdout then has the answers of the first one.
  --mode M           exact (default), double or float (fcl always computes in double)
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

[[noreturn]] void usageError(const std::string& what) {
  std::fprintf(stderr, "dss_pairs: %s\n(dss_pairs --help for usage)\n", what.c_str());
  std::exit(kExitUsage);
}

double parseDouble(const std::string& opt, const std::string& v) {
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0' || !std::isfinite(x))
    usageError(opt + ": expected a finite number, got '" + v + "'");
  return x;
}

int parseInt(const std::string& opt, const std::string& v, int min) {
  char* end = nullptr;
  const long x = std::strtol(v.c_str(), &end, 10);
  if (v.empty() || *end != '\0' || x < min || x > 1000000000)
    usageError(opt + ": expected an integer >= " + std::to_string(min) + ", got '" + v + "'");
  return static_cast<int>(x);
}

Args parseArgs(int argc, char** argv) {
  Args args;
  std::string algo_list = "dss";
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    std::string value;
    bool has_value = false;
    if (a.size() > 2 && a.compare(0, 2, "--") == 0) {
      const auto eq = a.find('=');
      if (eq != std::string::npos) {
        value = a.substr(eq + 1);
        a = a.substr(0, eq);
        has_value = true;
      }
    }
    auto need = [&]() -> std::string {
      if (has_value) return value;
      if (i + 1 >= argc) usageError(a + " needs a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (a == "--algo") {
      algo_list = need();
    } else if (a == "--mode") {
      const std::string m = need();
      if (m == "exact") args.mode = dss::Mode::kExact;
      else if (m == "double") args.mode = dss::Mode::kDouble;
      else if (m == "float") args.mode = dss::Mode::kFloat;
      else usageError("--mode: expected exact, double or float, got '" + m + "'");
    } else if (a == "--max-iterations") {
      args.max_iterations = parseInt(a, need(), 1);
    } else if (a == "--padding") {
      args.padding = parseDouble(a, need());
      if (args.padding < 0) usageError("--padding: must not be negative");
    } else if (a == "--time") {
      if (has_value) usageError("--time takes no value");
      args.time = true;
    } else if (a == "--repeat") {
      args.repeat = parseInt(a, need(), 1);
    } else if (a == "-" || a.empty() || a[0] != '-') {
      if (!args.file.empty()) usageError("more than one input file");
      args.file = a;
    } else {
      usageError("unknown option " + a);
    }
  }
  if (args.file.empty()) usageError("no input file (use - for stdin)");
  std::stringstream ss(algo_list);
  std::string name;
  while (std::getline(ss, name, ',')) {
    Algo algo;
    if (name == "dss") algo = Algo::kDss;
    else if (name == "gjk") algo = Algo::kGjk;
    else if (name == "hybrid") algo = Algo::kHybrid;
    else if (name == "fcl") algo = Algo::kFcl;
    else usageError("--algo: expected dss, gjk, hybrid or fcl, got '" + name + "'");
    if (std::find(args.algos.begin(), args.algos.end(), algo) != args.algos.end())
      usageError("--algo: '" + name + "' given twice");
    args.algos.push_back(algo);
    args.algo_names.push_back(name);
  }
  if (args.algos.empty()) usageError("--algo: empty list");
  if (args.algos.size() > 1 && !args.time) usageError("--algo: a list needs --time");
  return args;
}

CoreAlgo coreAlgo(Algo a) {
  return a == Algo::kGjk ? CoreAlgo::kGjk : a == Algo::kHybrid ? CoreAlgo::kHybrid : CoreAlgo::kDss;
}

/// Everything one run needs, built once from the file.
struct Workload {
  std::vector<std::string> ids;
  std::vector<CorePair<double>> core_double;
  std::vector<CorePair<float>> core_float;
  std::vector<FclPair> fcl;
};

/// Decisions of one algorithm over the whole file, in input order.
struct Answers {
  std::vector<dss::Result> results;  // core algorithms
  std::vector<char> fcl;             // fcl: intersect per pair
};

void decide(Algo algo, const Args& args, const dss::Options& opt, const Workload& w,
            Answers& out) {
  if (algo == Algo::kFcl) {
    out.fcl.resize(w.fcl.size());
    for (std::size_t i = 0; i < w.fcl.size(); ++i)
      out.fcl[i] = fclIntersect(w.fcl[i], args.padding) ? 1 : 0;
    return;
  }
  if (args.mode == dss::Mode::kFloat)
    decideAll(coreAlgo(algo), w.core_float, opt, out.results);
  else
    decideAll(coreAlgo(algo), w.core_double, opt, out.results);
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
    const double median = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
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
        if (need_core) {
          CorePair<double> c{makeSideA(p.a, args.padding), makeShape(p.b)};
          if (args.mode == dss::Mode::kFloat)
            w.core_float.push_back(CorePair<float>{toFloat(c.a), toFloat(c.b)});
          else
            w.core_double.push_back(std::move(c));
        }
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
