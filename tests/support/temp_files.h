// Files a test writes for a reader: one scratch folder per test process (named by the test
// area and the process id), and text written into it.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace dss_test {

/// The scratch folder of this test process for `area` (created on first use).
inline std::filesystem::path scratchDir(const std::string& area) {
  const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                  ("dss_test_" + area + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

/// Writes `text` (bytes as they are) to scratchDir(area)/name, creating folders; returns the path.
inline std::string writeScratch(const std::string& area, const std::string& name,
                                const std::string& text) {
  const std::filesystem::path p = scratchDir(area) / name;
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

}  // namespace dss_test
