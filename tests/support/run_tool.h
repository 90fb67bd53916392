// Running the project's executables from a test: the exit code and what they printed.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace dss_test {

struct ToolRun {
  int exit_code = -1;
  std::string out, err;
};

/// The path of executable `name` in the build tree.
inline std::string toolPath(const std::string& name) {
  return std::string(DSS_BINARY_DIR) + (name == "dss_plan" ? "/planners_demo/" : "/tools/") + name;
}

/// Runs tool `name` with `args` (each shell-quoted), stdin from /dev/null, at most two minutes.
inline ToolRun runTool(const std::string& name, const std::vector<std::string>& args) {
  namespace fs = std::filesystem;
  auto quote = [](const std::string& s) { return "'" + s + "'"; };
  static int counter = 0;
  const fs::path dir = fs::temp_directory_path() / ("dss_tool_run_" + std::to_string(::getpid()) +
                                                    "_" + std::to_string(counter++));
  fs::create_directories(dir);
  const fs::path out = dir / "out.txt", err = dir / "err.txt";
  std::string cmd = "timeout 120 " + quote(toolPath(name));
  for (const std::string& a : args) cmd += " " + quote(a);
  cmd += " < /dev/null > " + quote(out.string()) + " 2> " + quote(err.string());
  const int status = std::system(cmd.c_str());
  ToolRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  auto read = [](const fs::path& p) {
    std::ifstream in(p);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  r.out = read(out);
  r.err = read(err);
  fs::remove_all(dir);
  return r;
}

/// The lines of a tool's output, without their line ends.
inline std::vector<std::string> outputLines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

}  // namespace dss_test
