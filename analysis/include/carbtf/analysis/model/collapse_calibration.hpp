// Keeping the measured contrast through the pyramid collapse (issue 13, item 3d).
//
// Each band's CAR model keeps its own band's variance (the synthesized band's variance is within a few
// per cent of the measured one), yet the collapsed subspace image lost 30-45% of the measured variance
// on the leather sample. The loss is in the collapse: expand() passes a smooth measured Laplacian level
// almost whole but a CAR field's high frequencies on the coarse grid hardly at all, and the measured
// levels are correlated with one another where the synthesized ones are independent. So, per channel:
//   M_l = var(expand^l(measured level l)),  V = var(measured band),  target_l = M_l V / sum_k M_k
//   S_l = var(expand^l(CAR field of level l)), synthesized with the fitted model
//   sigma_l *= sqrt(target_l / S_l)
// which makes every level's expanded contribution, and the collapsed variance, the measurement's.
// Deterministic: the CAR fields use a fixed seed. Constant and zero-sigma bands are left alone.
#pragma once

#include <vector>

#include "carbtf/analysis/model/plane.hpp"
#include "carbtf/engine/material/material.hpp"

namespace carbtf {

// `pyramids[channel][level]` are the measured levels the bands of `model` were fitted to, and
// `bands[channel]` the measured bands they were built from. Returns the factor applied to each band's
// sigma (model.bands order).
std::vector<double> calibrate_collapse_variance(SubspaceModel& model, const std::vector<Plane>& bands,
                                                const std::vector<std::vector<Plane>>& pyramids);

}  // namespace carbtf
