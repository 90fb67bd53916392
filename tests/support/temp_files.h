// Files a test writes for a reader: one scratch folder per test process and area (named by
// the area and the process id), and text written into it. The folders are removed when the
// test process exits, so that repeated test runs leave nothing behind in the temporary folder.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <string>
#include <system_error>

namespace dss_test {

namespace detail {
/// The scratch folders this process made, removed (with what is in them) at exit.
class ScratchFolders {
 public:
  ~ScratchFolders() {
    for (const auto& [area, dir] : dirs_) {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  }
  std::filesystem::path get(const std::string& area) {
    const std::lock_guard<std::mutex> lock(mutex_);
    auto it = dirs_.find(area);
    if (it == dirs_.end()) {
      const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                      ("dss_test_" + area + "_" + std::to_string(::getpid()));
      std::filesystem::create_directories(d);
      it = dirs_.emplace(area, d).first;
    }
    return it->second;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, std::filesystem::path> dirs_;
};

inline ScratchFolders& scratchFolders() {
  static ScratchFolders folders;
  return folders;
}
}  // namespace detail

/// The scratch folder of this test process for `area` (created on first use, removed at exit).
inline std::filesystem::path scratchDir(const std::string& area) {
  return detail::scratchFolders().get(area);
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
