// Robot states as CSV (see joint_states_csv.h).
#include "dss/robot/joint_states_csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <stdexcept>

namespace dss {

namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// The cells of a line as [begin, end) offsets, blanks at both ends left out.
void cellBounds(const std::string& line, std::vector<std::pair<std::size_t, std::size_t>>& out) {
  out.clear();
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    std::size_t b = start, e = comma == std::string::npos ? line.size() : comma;
    while (b < e && isBlank(line[b])) ++b;
    while (e > b && isBlank(line[e - 1])) --e;
    out.emplace_back(b, e);
    if (comma == std::string::npos) return;
    start = comma + 1;
  }
}

// The lines of a file, each at most `max` bytes (without the newline), read in blocks and
// counted from 1.
class LineReader {
 public:
  LineReader(std::istream& in, const std::string& path, std::size_t max)
      : in_(in), path_(path), max_(max), block_(1 << 16) {}

  // The next line into `line`; false at the end of the file.
  bool next(std::string& line) {
    line.clear();
    bool any = false;
    for (;;) {
      if (pos_ == size_ && !fill()) {
        if (any) ++number_;  // a last line without a newline
        return any;
      }
      any = true;
      const char* const b = block_.data() + pos_;
      const char* const nl = static_cast<const char*>(std::memchr(b, '\n', size_ - pos_));
      const std::size_t n = nl ? std::size_t(nl - b) : size_ - pos_;
      if (n > max_ - line.size())
        throw std::runtime_error(path_ + ":" + std::to_string(number_ + 1) + ": line longer than " +
                                 std::to_string(max_) + " bytes (CsvLimits::max_line_bytes)");
      line.append(b, n);
      pos_ += n;
      if (nl) {
        ++pos_;
        ++number_;
        return true;
      }
    }
  }
  // The number of the line next() read last.
  int number() const { return number_; }

 private:
  bool fill() {
    in_.read(block_.data(), std::streamsize(block_.size()));
    size_ = std::size_t(in_.gcount());
    pos_ = 0;
    return size_ > 0;
  }
  std::istream& in_;
  const std::string& path_;
  std::size_t max_;
  std::vector<char> block_;
  std::size_t pos_ = 0, size_ = 0;
  int number_ = 0;
};

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
  std::vector<double> values;
  std::string line;
  std::vector<std::pair<std::size_t, std::size_t>> bounds;
  LineReader lines(in, path, limits.max_line_bytes);
  // "path:line", built only for an error message.
  const auto where = [&] { return path + ":" + std::to_string(lines.number()); };
  while (lines.next(line)) {
    cellBounds(line, bounds);
    if (bounds.size() == 1 && bounds[0].first == bounds[0].second) continue;  // a blank line
    const auto cell = [&](std::size_t c) {
      return line.substr(bounds[c].first, bounds[c].second - bounds[c].first);
    };
    if (csv.columns.empty()) {
      std::vector<std::string> row;
      for (std::size_t c = 0; c < bounds.size(); ++c) row.push_back(cell(c));
      if (row.size() > limits.max_columns)
        throw std::runtime_error(where() + ": " + std::to_string(row.size()) +
                                 " columns, more than " + std::to_string(limits.max_columns) +
                                 " (CsvLimits::max_columns)");
      for (const std::string& name : row) {
        if (name.empty()) throw std::runtime_error(where() + ": empty joint name in the header");
        if (std::find(csv.columns.begin(), csv.columns.end(), name) != csv.columns.end())
          throw std::runtime_error(where() + ": joint '" + name + "' appears twice in the header");
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
          throw std::runtime_error(where() + ": '" + name + "' is not a joint of robot " +
                                   robot.name);
        const RobotJoint& joint = robot.joints[j];
        if (joint.active_index >= 0) {
          col.active = joint.active_index;
        } else if (joint.mimic_active >= 0) {
          col.mimic = j;
        } else {
          throw std::runtime_error(where() + ": joint '" + name + "' is " + toString(joint.type) +
                                   ": it has no value");
        }
        csv.columns.push_back(name);
        columns.push_back(col);
      }
      continue;
    }
    if (bounds.size() != columns.size())
      throw std::runtime_error(where() + ": " + std::to_string(bounds.size()) +
                               " values, the header has " + std::to_string(columns.size()));
    if (csv.states.size() == limits.max_rows)
      throw std::runtime_error(where() + ": more than " + std::to_string(limits.max_rows) +
                               " rows (CsvLimits::max_rows)");
    values.resize(bounds.size());
    for (std::size_t c = 0; c < bounds.size(); ++c) {
      // In place: a number must take the whole cell. std::from_chars reads the usual decimal
      // forms (correctly rounded, as strtod); what it refuses or cannot hold (a leading '+',
      // hexadecimal, a value beyond a double's range) goes to strtod, which ends before the
      // comma or the end of the line (the string is NUL-terminated).
      const char* const b = line.c_str() + bounds[c].first;
      const char* const e = line.c_str() + bounds[c].second;
      const std::from_chars_result fast = std::from_chars(b, e, values[c]);
      const char* end = fast.ptr;
      if (fast.ec != std::errc() || end != e) {
        char* slow = nullptr;
        values[c] = std::strtod(b, &slow);
        end = slow;
      }
      if (b == e || end != e)
        throw std::runtime_error(where() + ": column '" + csv.columns[c] + "': '" + cell(c) +
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
        throw std::runtime_error(where() + ": mimic joint '" + csv.columns[c] + "' is " + cell(c) +
                                 ", but its leader '" +
                                 robot.joints[robot.active_joints[m.mimic_active]].name +
                                 "' puts it at " + std::to_string(expected));
    }
    csv.states.push_back(std::move(q));
    csv.lines.push_back(lines.number());
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
