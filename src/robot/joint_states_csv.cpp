// Robot states as CSV (see joint_states_csv.h).
#include "dss/robot/joint_states_csv.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <stdexcept>

namespace dss {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(
        trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

// Reads one line of at most `max` bytes (without the newline); false at the end of the file.
bool readLine(std::istream& in, std::string& line, std::size_t max, const std::string& where) {
  line.clear();
  char c;
  while (in.get(c)) {
    if (c == '\n') return true;
    if (line.size() == max)
      throw std::runtime_error(where + ": line longer than " + std::to_string(max) +
                               " bytes (CsvLimits::max_line_bytes)");
    line.push_back(c);
  }
  return !line.empty();
}

}  // namespace

JointStatesCsv readJointStatesCsv(const std::string& path, const RobotModel& robot,
                                  const std::vector<double>& base, const CsvLimits& limits) {
  if (base.size() != robot.numActiveJoints())
    throw std::invalid_argument(
        "readJointStatesCsv: base state has " + std::to_string(base.size()) + " values, robot " +
        robot.name + " has " + std::to_string(robot.numActiveJoints()) + " active joints");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  JointStatesCsv csv;
  // Per column: the active joint it sets, or the mimic joint it must agree with.
  struct Column {
    int active = -1;
    int mimic = -1;  // joint index
  };
  std::vector<Column> columns;
  std::string line;
  int lineno = 0;
  for (;;) {
    const std::string where = path + ":" + std::to_string(lineno + 1);
    if (!readLine(in, line, limits.max_line_bytes, where)) break;
    ++lineno;
    if (trim(line).empty()) continue;
    const std::vector<std::string> row = cells(line);
    if (csv.columns.empty()) {
      if (row.size() > limits.max_columns)
        throw std::runtime_error(where + ": " + std::to_string(row.size()) +
                                 " columns, more than " + std::to_string(limits.max_columns) +
                                 " (CsvLimits::max_columns)");
      for (const std::string& name : row) {
        if (name.empty()) throw std::runtime_error(where + ": empty joint name in the header");
        if (std::find(csv.columns.begin(), csv.columns.end(), name) != csv.columns.end())
          throw std::runtime_error(where + ": joint '" + name + "' appears twice in the header");
        Column col;
        // A state value by name (a joint, or a variable of a floating joint's rotation).
        if (const int v = robot.variableIndex(name); v >= 0) {
          col.active = v;
          csv.columns.push_back(name);
          columns.push_back(col);
          continue;
        }
        const int j = robot.jointIndex(name);
        if (j < 0)
          throw std::runtime_error(where + ": '" + name + "' is not a joint of robot " +
                                   robot.name);
        const RobotJoint& joint = robot.joints[j];
        if (joint.active_index >= 0) {
          col.active = joint.active_index;
        } else if (joint.mimic_active >= 0) {
          col.mimic = j;
        } else {
          throw std::runtime_error(where + ": joint '" + name + "' is " + toString(joint.type) +
                                   ": it has no value");
        }
        csv.columns.push_back(name);
        columns.push_back(col);
      }
      continue;
    }
    if (row.size() != columns.size())
      throw std::runtime_error(where + ": " + std::to_string(row.size()) +
                               " values, the header has " + std::to_string(columns.size()));
    if (csv.states.size() == limits.max_rows)
      throw std::runtime_error(where + ": more than " + std::to_string(limits.max_rows) +
                               " rows (CsvLimits::max_rows)");
    std::vector<double> values(row.size());
    for (std::size_t c = 0; c < row.size(); ++c) {
      char* end = nullptr;
      values[c] = std::strtod(row[c].c_str(), &end);
      if (row[c].empty() || *end != '\0')
        throw std::runtime_error(where + ": column '" + csv.columns[c] + "': '" + row[c] +
                                 "' is not a number");
    }
    std::vector<double> q = base;
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c].active >= 0) q[columns[c].active] = values[c];
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (columns[c].mimic < 0) continue;
      const RobotJoint& m = robot.joints[columns[c].mimic];
      const double expected = m.mimic_multiplier * q[m.mimic_active] + m.mimic_offset;
      const double tol = 1e-9 * std::max({1.0, std::abs(expected), std::abs(values[c])});
      // Within rounding when both are finite; otherwise the same infinity (a leader at inf
      // puts its mimic at inf), or NaN for NaN.
      const bool agree =
          std::isfinite(values[c]) && std::isfinite(expected)
              ? std::abs(values[c] - expected) <= tol
              : values[c] == expected || (std::isnan(values[c]) && std::isnan(expected));
      if (!agree)
        throw std::runtime_error(where + ": mimic joint '" + csv.columns[c] + "' is " + row[c] +
                                 ", but its leader '" +
                                 robot.joints[robot.active_joints[m.mimic_active]].name +
                                 "' puts it at " + std::to_string(expected));
    }
    csv.states.push_back(std::move(q));
    csv.lines.push_back(lineno);
  }
  if (csv.columns.empty()) throw std::runtime_error(path + ": no header (a line of joint names)");
  return csv;
}

void writeJointStatesCsv(std::ostream& out, const RobotModel& robot,
                         const std::vector<std::vector<double>>& states) {
  // Columns: every state value (a ball joint's four) and every mimic joint, in model order.
  struct Column {
    std::string name;
    int active;  // the state value; -1: the mimic joint below
    int mimic;
  };
  std::vector<Column> columns;
  const std::vector<std::string> names = robot.activeJointNames();
  for (std::size_t j = 0; j < robot.joints.size(); ++j) {
    const RobotJoint& joint = robot.joints[j];
    for (int k = 0; k < joint.numVariables(); ++k)
      columns.push_back({names[joint.active_index + k], joint.active_index + k, -1});
    if (joint.active_index < 0 && joint.mimic_active >= 0)
      columns.push_back({joint.name, -1, int(j)});
  }
  for (std::size_t k = 0; k < columns.size(); ++k) out << (k ? "," : "") << columns[k].name;
  out << "\n" << std::setprecision(17);
  for (const auto& q : states) {
    for (std::size_t k = 0; k < columns.size(); ++k) {
      double v;
      if (columns[k].active >= 0) {
        v = q[columns[k].active];
      } else {
        const RobotJoint& j = robot.joints[columns[k].mimic];
        v = j.mimic_multiplier * q[j.mimic_active] + j.mimic_offset;
      }
      out << (k ? "," : "") << v;
    }
    out << "\n";
  }
}

}  // namespace dss
