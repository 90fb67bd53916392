// Internal helpers for reading URDF and SRDF text with tinyxml: strict number parsing and
// messages that carry the file and line of the element.
#pragma once

#include <tinyxml.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../common/nesting_scan.h"
#include "../common/utf8_scan.h"

namespace dss::xml {

inline std::string where(const std::string& file, const TiXmlElement* e) {
  return file + ":" + std::to_string(e ? e->Row() : 0);
}

[[noreturn]] inline void fail(const std::string& file, const TiXmlElement* e,
                              const std::string& what) {
  throw std::runtime_error(where(file, e) + ": " + what);
}

/// Throws when the element nesting of `text` exceeds `max_depth` (checked on the raw text, so
/// before tinyxml or urdfdom recurse into it); `raise_with` names the setting that raises it.
inline void checkDepth(const std::string& text, const std::string& file, std::size_t max_depth,
                       const std::string& raise_with) {
  const input_scan::NestingExcess e = input_scan::xmlNesting(text, max_depth);
  if (e.exceeded)
    throw std::runtime_error(
        file + ":" + std::to_string(e.line) + ":" + std::to_string(e.column) +
        ": XML element nesting exceeds the limit of " + std::to_string(max_depth) +
        " (RobotInputLimits::max_xml_depth; raise it with " + raise_with + ")");
}

/// Parses a whole document; text that is not UTF-8 (input_scan::firstInvalidUtf8, checked
/// before tinyxml reads it) and malformed XML throw with the line and column.
inline void parse(TiXmlDocument& doc, const std::string& text, const std::string& file) {
  const input_scan::Utf8Error bad = input_scan::firstInvalidUtf8(text);
  if (bad.found) throw std::runtime_error(input_scan::utf8Message(file, bad));
  doc.Parse(text.c_str());
  if (doc.Error())
    throw std::runtime_error(file + ":" + std::to_string(doc.ErrorRow()) + ":" +
                             std::to_string(doc.ErrorCol()) +
                             ": malformed XML: " + doc.ErrorDesc());
}

/// Whitespace-separated finite numbers; `count` < 0 accepts any count.
inline std::vector<double> numbers(const std::string& text, int count, const std::string& file,
                                   const TiXmlElement* e, const std::string& what) {
  std::vector<double> out;
  std::istringstream in(text);
  std::string tok;
  while (in >> tok) {
    char* end = nullptr;
    const double v = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end != '\0' || !std::isfinite(v))
      fail(file, e, what + " '" + text + "': '" + tok + "' is not a finite number");
    out.push_back(v);
  }
  if (count >= 0 && static_cast<int>(out.size()) != count)
    fail(file, e, what + " '" + text + "': expected " + std::to_string(count) + " numbers");
  return out;
}

inline const char* attr(const TiXmlElement* e, const char* name) {
  return e ? e->Attribute(name) : nullptr;
}

/// The URDF rotation of roll-pitch-yaw angles: R = Rz(yaw) Ry(pitch) Rx(roll).
inline Eigen::Matrix3d rpy(double r, double p, double y) {
  return (Eigen::AngleAxisd(y, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(p, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(r, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

/// The pose of an <origin xyz rpy> element (identity when absent).
inline Eigen::Isometry3d origin(const TiXmlElement* o, const std::string& file,
                                const std::string& what) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (!o) return X;
  if (const char* xyz = o->Attribute("xyz")) {
    const auto v = numbers(xyz, 3, file, o, what + " origin xyz");
    X.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  if (const char* r = o->Attribute("rpy")) {
    const auto v = numbers(r, 3, file, o, what + " origin rpy");
    X.linear() = rpy(v[0], v[1], v[2]);
  }
  return X;
}

}  // namespace dss::xml
