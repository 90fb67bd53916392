// OMPL's console silenced for a scope: for calls whose own log lines dss_plan replaces with
// its messages or expects (a reseed, a parameter OMPL rejects).
#pragma once

#include <ompl/util/Console.h>

namespace dss_plan {

/// Sets OMPL's log level to LOG_NONE, and back to what it was on scope exit.
class QuietOmpl {
 public:
  QuietOmpl() : level_(ompl::msg::getLogLevel()) { ompl::msg::setLogLevel(ompl::msg::LOG_NONE); }
  ~QuietOmpl() { ompl::msg::setLogLevel(level_); }
  QuietOmpl(const QuietOmpl&) = delete;
  QuietOmpl& operator=(const QuietOmpl&) = delete;

 private:
  ompl::msg::LogLevel level_;
};

}  // namespace dss_plan
