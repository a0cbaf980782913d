#include "bench/frame_bench.hpp"

#include <cstdio>
#include <sstream>

#include "carbtf/analysis/image_io.hpp"

#include "cli/cli_support.hpp"

namespace carbtf::cli {

std::string write_frame_bench_report(const std::filesystem::path& out,
                                     const std::vector<FrameRecord>& records, const std::string& heading) {
  std::ostringstream csv;
  csv << "frame,synthesized_subspaces,resident_subspaces,synthesis_gpu_ms,render_gpu_ms,frame_wall_ms\n";
  for (const FrameRecord& r : records) {
    csv << r.frame << ',' << r.synthesized << ',' << r.resident << ',' << r.synthesis_gpu_ms << ','
        << r.render_gpu_ms << ',' << r.wall_ms << '\n';
  }
  std::vector<double> render_gpu, render_wall, synthesis_gpu, synthesis_wall;
  for (const FrameRecord& r : records) {
    render_gpu.push_back(r.render_gpu_ms);
    (r.synthesized > 0 ? synthesis_wall : render_wall).push_back(r.wall_ms);
    if (r.synthesized > 0) synthesis_gpu.push_back(r.synthesis_gpu_ms);
  }
  char line[256];
  std::string table = "| what | frames | median ms | p95 ms |\n|---|---|---|---|\n";
  auto row = [&](const char* what, const std::vector<double>& v) {
    if (v.empty()) return;
    std::snprintf(line, sizeof line, "| %s | %zu | %.2f | %.2f |\n", what, v.size(), median(v),
                  percentile(v, 0.95));
    table += line;
  };
  row("render pass, GPU timestamps", render_gpu);
  row("frame wall time, render only", render_wall);
  row("synthesis, GPU timestamps (frames that synthesize)", synthesis_gpu);
  row("frame wall time, with synthesis", synthesis_wall);
  write_output_file(out / "bench_frame.csv", csv.str());
  write_output_file(out / "bench_frame.md", heading + table);
  return table;
}

std::string write_frame_parts_report(const std::filesystem::path& out,
                                     const std::vector<FramePartTimes>& parts, const std::string& heading) {
  std::ostringstream csv;
  csv << "part,frame,render_gpu_ms\n";
  for (const FramePartTimes& p : parts) {
    // Quoted: a part's name may hold commas.
    for (std::size_t i = 0; i < p.render_gpu_ms.size(); ++i)
      csv << '"' << p.part << "\"," << i << ',' << p.render_gpu_ms[i] << '\n';
  }
  const double full = parts.empty() ? 0.0 : median(parts[0].render_gpu_ms);
  std::string table =
      "| replaced (by a constant, or as the row says) | frames | render pass median ms | the part costs ms "
      "|\n"
      "|---|---|---|---|\n";
  char line[256];
  for (const FramePartTimes& p : parts) {
    const double m = median(p.render_gpu_ms);
    std::snprintf(line, sizeof line, "| %s | %zu | %.2f | %.2f |\n", p.part.c_str(), p.render_gpu_ms.size(),
                  m, full - m);
    table += line;
  }
  write_output_file(out / "bench_frame_parts.csv", csv.str());
  write_output_file(out / "bench_frame_parts.md", heading + table);
  return table;
}

}  // namespace carbtf::cli
