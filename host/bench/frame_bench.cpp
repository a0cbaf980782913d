#include "bench/frame_bench.hpp"

#include <cstdio>
#include <fstream>

#include "cli/cli_support.hpp"

namespace carbtf::cli {

std::string write_frame_bench_report(const std::filesystem::path& out,
                                     const std::vector<FrameRecord>& records, const std::string& heading) {
  std::ofstream csv(out / "bench_frame.csv");
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
  std::ofstream(out / "bench_frame.md") << heading << table;
  return table;
}

}  // namespace carbtf::cli
