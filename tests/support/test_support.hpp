// Helpers shared by the tests: a validated Vulkan context that fails the test on any validation
// message, and comparisons that name the first failing element.
#pragma once

#include <catch2/catch.hpp>

#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "carbtf/engine/synthesis/synthesis_block.hpp"
#include "carbtf/engine/vulkan/context.hpp"

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

// The blocks of a grid over `whole` (margin 0): rows of the given heights from whole.row0, columns of the
// given widths from whole.col0.
inline std::vector<SynthesisBlock> grid_blocks(const SynthesisBlock& whole,
                                               std::initializer_list<std::uint32_t> heights,
                                               std::initializer_list<std::uint32_t> widths) {
  std::vector<SynthesisBlock> blocks;
  std::int32_t row = whole.row0;
  for (const std::uint32_t height : heights) {
    std::int32_t col = whole.col0;
    for (const std::uint32_t width : widths) {
      SynthesisBlock block = whole;
      block.row0 = row;
      block.col0 = col;
      block.height = height;
      block.width = width;
      block.margin = 0;
      blocks.push_back(block);
      col += static_cast<std::int32_t>(width);
    }
    row += static_cast<std::int32_t>(height);
  }
  return blocks;
}

// The pixels of `block` within an image synthesized for `whole` (channels interleaved).
inline std::vector<float> crop_block(const std::vector<float>& image, const SynthesisBlock& whole,
                                     const SynthesisBlock& block, std::uint32_t channels) {
  std::vector<float> out;
  for (std::int64_t r = block.row0 - whole.row0; r < block.row0 - whole.row0 + block.height; ++r) {
    const auto first =
        image.begin() + static_cast<std::ptrdiff_t>((r * whole.width + block.col0 - whole.col0) * channels);
    out.insert(out.end(), first, first + static_cast<std::ptrdiff_t>(std::size_t{block.width} * channels));
  }
  return out;
}

}  // namespace carbtf::test
