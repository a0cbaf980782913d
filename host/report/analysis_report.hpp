// The pictures and tables of one analysis (`carbtf analyze --report`, `carbtf demo`): index table,
// eigenvalue spectrum, the subspace images as measured, normals, albedo, range map and its enlargement,
// per-stage times and the analysis log.
#pragma once

#include <filesystem>

#include "carbtf/analysis/analyze.hpp"
#include "carbtf/analysis/btf/btf_dataset.hpp"

namespace carbtf::cli {

// Writes index_table.png, eigenvalues.png/.csv, subspaces.csv, subspace_NN.png, normals.png,
// albedo.png, range_map.exr/.png, range_enlarged.png, stages.csv and analysis_log.txt into `folder`.
void write_analysis_report(const std::filesystem::path& folder, const BtfDataset& dataset,
                           const AnalysisResult& result);

}  // namespace carbtf::cli
