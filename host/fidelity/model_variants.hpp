// The model options `carbtf bench fidelity` sets beside each other: each a name, what it changes, and
// the change to the default analysis options.
#pragma once

#include <functional>
#include <vector>

#include "carbtf/analysis/analyze.hpp"

namespace carbtf::cli {

struct ModelVariant {
  const char* name;
  const char* description;
  std::function<void(AnalysisOptions&)> apply;
};

// Every variant, the default among them, in the order the bench reports them.
const std::vector<ModelVariant>& model_variants();

}  // namespace carbtf::cli
