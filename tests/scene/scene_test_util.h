// Helpers for the scene tests: the shared scene folder (its tests carry DSS_NEEDS_SHARED),
// file listing, and checks on exception messages.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/temp_files.h"
#include "support/thrown_message.h"

namespace dss_test {

/// A folder of this test process for the files the tests write, removed at exit.
inline std::filesystem::path scratchDir() { return scratchDir("scene"); }

/// Writes `text` to `name` in scratchDir() (folders created); returns the path.
inline std::string writeScratch(const std::string& name, const std::string& text) {
  return writeScratch("scene", name, text);
}

inline std::string scenesDir() { return std::string(DSS_SHARED_DIR) + "/scenes"; }

/// The shared scenes are there (tests that need them carry DSS_NEEDS_SHARED).
inline void requireShared() {
  BOOST_REQUIRE_MESSAGE(std::filesystem::is_directory(scenesDir()), scenesDir() << " not found");
}

/// Files under dir (recursive) whose name matches `pattern`, sorted.
inline std::vector<std::string> filesMatching(const std::string& dir, const std::string& pattern) {
  std::vector<std::string> out;
  const std::regex re(pattern);
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file() && std::regex_match(e.path().filename().string(), re))
      out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

inline std::string readAll(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

}  // namespace dss_test
