// Helpers shared by the fuzz targets: a private temporary folder for the readers that take a
// path, and the repository's own robot folders (seeds and models the targets load once).
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace dss_fuzz {

/// A folder of this process, created on first use and never shared with another process
/// (parallel fuzzing jobs each get their own); removed when the process exits normally.
inline const std::string& tempDir() {
  struct Dir {
    std::string path;
    Dir() {
      const char* base = std::getenv("TMPDIR");
      path = std::string(base && *base ? base : "/tmp") + "/dss_fuzz_XXXXXX";
      if (!mkdtemp(path.data())) throw std::runtime_error("fuzz: cannot create " + path);
    }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

/// Writes `size` bytes to tempDir()/name (replacing it) and returns the path.
inline std::string writeTempFile(const std::string& name, const std::uint8_t* data,
                                 std::size_t size) {
  const std::string path = tempDir() + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::runtime_error("fuzz: cannot write " + path);
  if (size && std::fwrite(data, 1, size, f) != size) {
    std::fclose(f);
    throw std::runtime_error("fuzz: short write to " + path);
  }
  std::fclose(f);
  return path;
}

/// Mesh URIs must not depend on the environment of the fuzzing run: package:// lookups through
/// ROS_PACKAGE_PATH and AMENT_PREFIX_PATH are switched off (targets call this once).
inline void isolateEnvironment() {
  unsetenv("ROS_PACKAGE_PATH");
  unsetenv("AMENT_PREFIX_PATH");
}

/// Our own 7-DOF arm (robots/dss_arm7), with its meshes.
inline std::string armDir() { return std::string(DSS_SOURCE_DIR) + "/robots/dss_arm7"; }

/// A violated property: printed, then abort() so that libFuzzer keeps the input as a crash.
[[noreturn]] inline void propertyFailed(const std::string& what) {
  std::fprintf(stderr, "property violated: %s\n", what.c_str());
  std::abort();
}

}  // namespace dss_fuzz
