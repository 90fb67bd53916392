// The message of the exception a call must throw (a failed check when it throws nothing).
#pragma once

#include <boost/test/unit_test.hpp>
#include <functional>
#include <stdexcept>
#include <string>

namespace dss_test {

/// Runs f, which must throw E; returns the message (empty and a failed check otherwise).
template <class E = std::runtime_error>
std::string thrownMessage(const std::function<void()>& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  BOOST_ERROR("expected an exception");
  return std::string();
}

}  // namespace dss_test
