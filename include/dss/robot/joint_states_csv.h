// Robot states as CSV, the way MoveIt tools and MotionBenchMaker data write them: a header of
// joint names, then one state per row.
//
// Reading: every column names a joint of the robot. An active joint's column sets its value;
// a mimic joint's column must agree with its leader (multiplier x leader + offset, within
// 1e-9 of the larger magnitude) or the row is refused; a fixed joint has no value and its
// column is refused. Joints without a column keep the base values (typically the held state).
// NaN and Inf values are kept: such states are invalid, which is the checker's answer, not a
// file error. The file is hostile until parsed: line length, columns and rows are bounded
// (CsvLimits), and every error names the file and the line.
//
// Writing: every active joint and every mimic joint, by name, at full precision, so that a
// written file reads back into the same states.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include "dss/robot/robot_model.h"

namespace dss {

struct CsvLimits {
  std::size_t max_line_bytes = std::size_t(1) << 20;  ///< one header or row
  std::size_t max_columns = 4096;
  std::size_t max_rows = 50'000'000;
};

struct JointStatesCsv {
  std::vector<std::string> columns;         ///< the header's joint names
  std::vector<std::vector<double>> states;  ///< one value per active joint, per row
  std::vector<int> lines;                   ///< the file line of each row
};

/// Reads `path` (see above). `base`: one value per active joint, for joints without a column.
/// Throws std::runtime_error "PATH:LINE: what is wrong" (or "PATH: ..." for the whole file).
JointStatesCsv readJointStatesCsv(const std::string& path, const RobotModel& robot,
                                  const std::vector<double>& base, const CsvLimits& limits = {});

/// The header and the rows of `states` (one value per active joint each), every active and
/// mimic joint, in model order.
void writeJointStatesCsv(std::ostream& out, const RobotModel& robot,
                         const std::vector<std::vector<double>>& states);

}  // namespace dss
