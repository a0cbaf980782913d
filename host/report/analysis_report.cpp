#include "report/analysis_report.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/report/figures.hpp"
#include "carbtf/engine/material/range_tiles.hpp"
#include "cli/cli_support.hpp"

namespace carbtf::cli {

namespace fs = std::filesystem;

namespace {

// The first index of each elevation ring of a direction set ordered by elevation (for figure rules).
std::vector<std::uint32_t> ring_starts(const std::vector<Direction>& directions) {
  std::vector<std::uint32_t> starts;
  for (std::uint32_t i = 0; i < directions.size(); ++i) {
    if (i == 0 || std::abs(directions[i].theta - directions[i - 1].theta) > 1e-6) starts.push_back(i);
  }
  return starts;
}

}  // namespace

void write_analysis_report(const fs::path& folder, const BtfDataset& dataset, const AnalysisResult& result) {
  create_folder(folder);
  const Segmentation& seg = result.segmentation;
  const auto light_rings = ring_starts(dataset.lights());
  const Figure table = index_table_figure(seg.index, seg.lights, seg.views, 6, light_rings);
  write_rgb_image(folder / "index_table.png", table.rgb, table.width, table.height, false);
  const Figure spectrum = eigenvalue_figure(seg.eigenvalues);
  write_rgb_image(folder / "eigenvalues.png", spectrum.rgb, spectrum.width, spectrum.height, false);
  {
    std::ostringstream csv;
    csv << "rank,eigenvalue\n";
    for (std::size_t i = 0; i < seg.eigenvalues.size(); ++i)
      csv << i + 1 << ',' << seg.eigenvalues[i] << '\n';
    write_output_file(folder / "eigenvalues.csv", csv.str());
  }
  {
    std::ostringstream csv;
    csv << "subspace,light,view,light_theta_deg,light_phi_deg,view_theta_deg,view_phi_deg,images\n";
    for (std::size_t s = 0; s < seg.representatives.size(); ++s) {
      const LightView p = seg.representatives[s];
      csv << s << ',' << p.light << ',' << p.view << ',' << dataset.lights()[p.light].theta_degrees() << ','
          << dataset.lights()[p.light].phi_degrees() << ',' << dataset.views()[p.view].theta_degrees() << ','
          << dataset.views()[p.view].phi_degrees() << ',' << seg.sizes[s] << '\n';
    }
    write_output_file(folder / "subspaces.csv", csv.str());
  }
  std::vector<float> rgb(dataset.pixel_count() * 3);
  for (std::size_t s = 0; s < seg.representatives.size(); ++s) {
    dataset.linear_rgb(seg.representatives[s], rgb);
    char name[48];
    std::snprintf(name, sizeof name, "subspace_%02zu.png", s);
    write_rgb_image(folder / name, rgb, dataset.width(), dataset.height());
  }
  const NormalMap& n = result.normals;
  std::vector<float> encoded(n.normals.size());
  for (std::size_t i = 0; i < encoded.size(); ++i) encoded[i] = 0.5f * n.normals[i] + 0.5f;
  write_rgb_image(folder / "normals.png", encoded, n.width, n.height, false);
  write_rgb_image(folder / "albedo.png", n.albedo, n.width, n.height);
  std::vector<float> range(result.range_map.data(), result.range_map.data() + result.range_map.size());
  const auto [low, high] = std::minmax_element(range.begin(), range.end());
  write_field_image(folder / "range_map.exr", range, n.width, n.height);
  write_field_image(folder / "range_map.png", range, n.width, n.height,
                    {*low, std::max(*high, *low + 1e-6f)});
  const std::uint32_t enlarged_size = 512;
  std::vector<float> enlarged(std::size_t{enlarged_size} * enlarged_size);
  enlarge_range_map(result.material.range, {1, 0, 0, enlarged_size, enlarged_size}, enlarged);
  write_field_image(folder / "range_enlarged.png", enlarged, enlarged_size, enlarged_size,
                    {*low, std::max(*high, *low + 1e-6f)});
  {
    std::ostringstream csv;
    csv << "stage,seconds,peak_rss_mib\n";
    for (const StageReport& s : result.stages)
      csv << s.name << ',' << s.seconds << ',' << s.peak_rss_bytes / 1048576.0 << '\n';
    write_output_file(folder / "stages.csv", csv.str());
  }
  std::string log;
  for (const std::string& line : result.log) log += line + '\n';
  write_output_file(folder / "analysis_log.txt", log);
}

}  // namespace carbtf::cli
