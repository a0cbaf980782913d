// Helpers shared by the tests: a validated Vulkan context that fails the test on any validation
// message, and comparisons that name the first failing element.
#pragma once

#include <catch2/catch.hpp>

#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "carbtf/engine/context.hpp"

namespace carbtf::test {

// A context with validation (and synchronization validation) on. Tests call require_clean() at the
// end; the destructor also checks, so a message raised during teardown still fails the test.
class ValidatedContext {
 public:
  ValidatedContext() {
    ContextCreateInfo info;
    info.enable_validation = true;
    info.application_name = "carbtf tests";
    const Status status = Context::create(info, context_);
    INFO(status.message());
    REQUIRE(status.ok());
  }
  ~ValidatedContext() {
    if (context_) {
      const ValidationReport report = context_->validation_report();
      CHECK(report.clean());
    }
  }
  Context& operator*() { return *context_; }
  Context* operator->() { return context_.get(); }

  void require_clean() const {
    const ValidationReport report = context_->validation_report();
    std::string all;
    for (const std::string& m : report.messages) all += m + "\n";
    INFO("validation messages:\n" << all);
    REQUIRE(report.errors == 0);
    REQUIRE(report.warnings == 0);
  }

 private:
  std::unique_ptr<Context> context_;
};

// Requires `actual` to equal `expected` bit for bit, naming the first differing element.
inline void require_bitwise_equal(const std::vector<float>& actual, const std::vector<float>& expected,
                                  std::size_t row_pitch = 0) {
  REQUIRE(actual.size() == expected.size());
  std::size_t differing = 0, first = actual.size();
  for (std::size_t i = 0; i < actual.size(); ++i) {
    if (std::memcmp(&actual[i], &expected[i], sizeof(float)) != 0) {
      if (differing++ == 0) first = i;
    }
  }
  if (differing > 0) {
    std::ostringstream where;
    where << "element " << first;
    if (row_pitch) where << " (row " << first / row_pitch << ", col " << first % row_pitch << ")";
    where.precision(9);
    where << ": " << actual[first] << " != " << expected[first] << "; " << differing << " elements differ";
    FAIL(where.str());
  }
}

}  // namespace carbtf::test
