#include "fidelity/fidelity_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <sstream>

#include "carbtf/analysis/report/figures.hpp"
#include "carbtf/engine/material/mip_levels.hpp"
#include "carbtf/engine/render/material_binding.hpp"
#include "carbtf/engine/render/mesh.hpp"
#include "carbtf/engine/render/mesh_renderer.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "cli/cli_support.hpp"
#include "scene/material_render.hpp"
#include "scene/measured_render.hpp"
#include "scene/orbit.hpp"

namespace carbtf::cli {
namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;

std::uint32_t nearest(const std::vector<MaterialDirection>& set, double theta_degrees, double phi_degrees) {
  const auto wanted = unit_vector_degrees(theta_degrees, phi_degrees);
  std::uint32_t best = 0;
  double best_dot = -2.0;
  for (std::uint32_t i = 0; i < set.size(); ++i) {
    const auto v = unit_vector_degrees(set[i].theta * kDegrees, set[i].phi * kDegrees);
    const double dot = double{v[0]} * wanted[0] + double{v[1]} * wanted[1] + double{v[2]} * wanted[2];
    if (dot > best_dot) best_dot = dot, best = i;
  }
  return best;
}

std::string degrees_text(const MaterialDirection& d) {
  char text[48];
  std::snprintf(text, sizeof text, "(%.0f, %.0f)", d.theta * kDegrees, d.phi * kDegrees);
  return text;
}

// The largest centred axis-aligned rectangle where the plane covers every pixel (alpha 1): an
// orthographic view of the plane from an azimuth that is a multiple of 90 degrees is a rectangle, and
// any other a parallelogram whose inner rectangle this finds.
struct Rectangle {
  std::uint32_t row0 = 0, col0 = 0, width = 0, height = 0;
};

Rectangle covered_rectangle(const std::vector<float>& rgba, std::uint32_t width, std::uint32_t height) {
  auto covered = [&](std::uint32_t r, std::uint32_t c) {
    return rgba[(std::size_t{r} * width + c) * 4 + 3] > 0.999f;
  };
  Rectangle best;
  const std::uint32_t cr = height / 2, cc = width / 2;
  // Grow rows outwards from the centre; for each row span, the common column span.
  std::uint32_t left = 0, right = width;  // [left, right)
  for (std::uint32_t half = 0; cr >= half && cr + half < height; ++half) {
    for (const std::uint32_t r : {cr - half, cr + half}) {
      if (!covered(r, cc)) return best;
      std::uint32_t l = cc, rr = cc + 1;
      while (l > 0 && covered(r, l - 1)) --l;
      while (rr < width && covered(r, rr)) ++rr;
      left = std::max(left, l);
      right = std::min(right, rr);
    }
    const Rectangle candidate{cr - half, left, right - left, 2 * half + 1};
    if (std::uint64_t{candidate.width} * candidate.height >= std::uint64_t{best.width} * best.height)
      best = candidate;
  }
  return best;
}

RgbField crop_rgba(const std::vector<float>& rgba, std::uint32_t width, const Rectangle& rect) {
  RgbField out{std::vector<float>(std::size_t{rect.width} * rect.height * 3), rect.width, rect.height};
  for (std::uint32_t r = 0; r < rect.height; ++r) {
    for (std::uint32_t c = 0; c < rect.width; ++c) {
      for (int k = 0; k < 3; ++k) {
        out.rgb[(std::size_t{r} * rect.width + c) * 3 + k] =
            rgba[((std::size_t{rect.row0 + r}) * width + rect.col0 + c) * 4 + k];
      }
    }
  }
  return out;
}

std::vector<float> rgba_floats(const RenderedImage& frame) {
  std::vector<float> values(frame.bytes.size() / sizeof(float));
  std::memcpy(values.data(), frame.bytes.data(), values.size() * sizeof(float));
  return values;
}

// A photograph's pixel integrates the light over its footprint on the sample: 1 / cos(view theta) texels
// along the tilt, 2 at 60 degrees. The render pass samples the model's factors at one point per pixel,
// which at such a view skips every other texel of the full-resolution relief and smooth texture and
// folds their finest octave into grain the rectified measurement does not have (its pixels were
// integrated by the camera). So the frames of an oblique pair are rendered at this many samples per pixel
// side and averaged, model and measurement alike; the top view and views up to 37 degrees, whose
// footprint is under 1.25 texels, keep one sample (more would only blur both by a fraction of a texel).
// A power of two: the average is mip-level halving (next_mip_level()).
constexpr double kSupersampledFootprint = 1.25;
constexpr std::uint32_t kMaxSamplesPerSide = 4;

// `frame` (RGBA floats, `factor` * width x `factor` * height) averaged over factor x factor blocks.
std::vector<float> pixel_averages(std::vector<float> frame, std::uint32_t width, std::uint32_t height,
                                  std::uint32_t factor) {
  for (std::uint32_t f = factor; f > 1; f /= 2) frame = next_mip_level(frame, width * f, height * f, 4);
  return frame;
}

// The smallest side of the plane's image the measure scores (distribution_statistics() wants 16 x 16).
constexpr std::uint32_t kMinCoveredSide = 16;

}  // namespace

std::uint32_t camera_samples_per_side(double view_theta) {
  const double footprint = 1.0 / std::max(std::cos(view_theta), 1e-6);
  if (!(footprint >= kSupersampledFootprint)) return 1;
  std::uint32_t samples = 2;
  // A measured 60 degrees, stored as a float, is 2.0000001 texels: a twentieth of a texel is slack.
  while (samples + 0.05 < footprint && samples < kMaxSamplesPerSide) samples *= 2;
  return samples;
}

std::vector<FidelityPair> default_fidelity_pairs(const Material& material) {
  struct Wanted {
    double light_theta, light_phi, view_theta, view_phi;
  };
  const Wanted wanted[] = {{15, 0, 0, 0}, {45, 0, 0, 0}, {75, 90, 0, 0}, {45, 180, 45, 0}, {45, 0, 60, 90}};
  std::vector<FidelityPair> pairs;
  for (const Wanted& w : wanted) {
    FidelityPair p;
    p.light = nearest(material.lights, w.light_theta, w.light_phi);
    p.view = nearest(material.views, w.view_theta, w.view_phi);
    p.label =
        "light " + degrees_text(material.lights[p.light]) + " view " + degrees_text(material.views[p.view]);
    const bool duplicate = std::any_of(pairs.begin(), pairs.end(), [&](const FidelityPair& q) {
      return q.light == p.light && q.view == p.view;
    });
    if (!duplicate) pairs.push_back(p);
  }
  return pairs;
}

std::vector<FidelityPair> spread_fidelity_pairs(const Material& material, const BtfDataset& dataset,
                                                std::size_t count) {
  // R2 (Roberts 2018): the plastic number's inverse powers as the two steps.
  const double plastic = 1.32471795724474602596;
  const double step_light = 1.0 / plastic, step_view = 1.0 / (plastic * plastic);
  const std::size_t lights = std::min(material.lights.size(), dataset.lights().size());
  const std::size_t views = std::min(material.views.size(), dataset.views().size());
  std::vector<FidelityPair> pairs;
  std::vector<bool> taken(lights * views, false);
  for (std::size_t i = 0; pairs.size() < count && i < 4 * lights * views; ++i) {
    const double x = 0.5 + step_light * static_cast<double>(i), y = 0.5 + step_view * static_cast<double>(i);
    const auto light = static_cast<std::uint32_t>((x - std::floor(x)) * static_cast<double>(lights));
    const auto view = static_cast<std::uint32_t>((y - std::floor(y)) * static_cast<double>(views));
    if (light >= lights || view >= views || taken[light * views + view] || !dataset.has_image({light, view}))
      continue;
    // A view so oblique that the plane's image is too thin to score well: its side shrinks by cos theta,
    // and at an azimuth between the axes the rectangle inside the slanted plane shrinks further (at 75
    // degrees, 256^2 images gave halves of 22 x 45 pixels, where two crops of one image differ by as
    // much as a model does). Views covering under a third of the frame's side are skipped.
    const double side = std::min(dataset.width(), dataset.height());
    if (std::cos(static_cast<double>(material.views[view].theta)) * side <
        std::max(side / 3.0, kMinCoveredSide + 2.0))
      continue;
    taken[light * views + view] = true;
    pairs.push_back(
        {light, view,
         "light " + degrees_text(material.lights[light]) + " view " + degrees_text(material.views[view])});
  }
  return pairs;
}

std::vector<PairFidelity> run_fidelity(Context& context, const Material& material, const BtfDataset& dataset,
                                       const std::vector<FidelityPair>& pairs,
                                       const FidelityRunOptions& options) {
  for (const FidelityPair& p : pairs) {
    if (p.light >= material.lights.size() || p.view >= material.views.size() ||
        !dataset.has_image({p.light, p.view})) {
      throw CommandError("fidelity: the measurement has no image of " + p.label);
    }
  }
  // The model at the measurement's scale: one texel per measured pixel, the 2 x 2 plane filling the
  // frame when seen from the top.
  const std::uint32_t width = dataset.width(), height = dataset.height();
  std::unique_ptr<SubspaceSynthesizer> synthesizer;
  check(SubspaceSynthesizer::create(context, synthesizer), "cannot build the synthesis pipelines");
  SynthesisRequest request;
  request.seed = options.seed;
  request.width = width;
  request.height = height;
  // Level 0 alone, for the model and the measurement: the measure judges the model's texture at its
  // own scale. Mip levels would low-pass both images of an oblique pair alike but filter the model's
  // factors (relit relief, tone, smooth texture) apart, a render-pass effect, not the model's
  // (measured: leather 45/45 0.255 -> 0.458, coast_sand_rocks 45/60 0.271 -> 0.108).
  check(synthesizer->prepare(material, request), "cannot plan the synthesis");
  check(context.submit_and_wait([&](VkCommandBuffer cb) { return synthesizer->record(cb); }),
        "synthesis failed");
  const Mesh plane = make_plane();
  const MaterialRender model = prepare_material_render(context, material, *synthesizer, options.seed,
                                                       options.parallax_scale, width, height, plane, false);
  // The model's renderer per samples per pixel side (camera_samples_per_side()), on the one binding.
  std::vector<std::unique_ptr<MeshRenderer>> supersampled(kMaxSamplesPerSide + 1);
  const auto model_renderer = [&](std::uint32_t samples) -> MeshRenderer& {
    if (samples == 1) return *model.renderer;
    if (!supersampled[samples]) {
      RenderTargetInfo target;
      target.width = samples * width;
      target.height = samples * height;
      target.colour_format = VK_FORMAT_R32G32B32A32_SFLOAT;
      check(MeshRenderer::create(context, *model.binding, target, supersampled[samples]),
            "cannot build the supersampled render pass");
      check(supersampled[samples]->set_mesh(plane), "cannot upload the mesh");
    }
    return *supersampled[samples];
  };

  std::vector<PairFidelity> results;
  for (const FidelityPair& p : pairs) {
    const MaterialDirection& light = material.lights[p.light];
    const MaterialDirection& view = material.views[p.view];
    RenderScene scene;
    scene.camera.eye = unit_vector_degrees(view.theta * kDegrees, view.phi * kDegrees);
    for (float& x : scene.camera.eye) x *= 3.0f;
    scene.camera.up = {0, 1, 0};
    scene.camera.fov_y_degrees = 0.0f;
    scene.camera.ortho_height = 2.0f;  // the plane's height: one texel per pixel from the top
    scene.lights = {{false, unit_vector_degrees(light.theta * kDegrees, light.phi * kDegrees), {1, 1, 1}}};
    const std::uint32_t samples = camera_samples_per_side(view.theta);
    RenderedImage model_frame;
    check(model_renderer(samples).render(scene, model_frame), "rendering the model failed");
    RenderTargetInfo target;  // the measurement's render, alike
    target.width = samples * width;
    target.height = samples * height;
    target.colour_format = VK_FORMAT_R32G32B32A32_SFLOAT;
    const RenderedImage measured_frame =
        render_measured(context, material, dataset, {{p.light, p.view}}, plane, scene, target, 1);
    const std::vector<float> model_rgba = pixel_averages(rgba_floats(model_frame), width, height, samples),
                             measured_rgba =
                                 pixel_averages(rgba_floats(measured_frame), width, height, samples);
    const Rectangle rect = covered_rectangle(measured_rgba, width, height);
    if (std::min(rect.width, rect.height) < kMinCoveredSide ||
        std::max(rect.width, rect.height) < 2 * kMinCoveredSide)
      throw CommandError("fidelity: the plane covers too little of the frame at " + p.label);
    PairFidelity result;
    result.pair = p;
    result.model = crop_rgba(model_rgba, width, rect);
    result.measured = crop_rgba(measured_rgba, width, rect);
    require_finite(result.model.rgb, "fidelity: the rendered model at " + p.label);
    result.result = calibrated_fidelity(result.model, result.measured, options.seed);
    result.gaussian = phase_randomised(result.measured, options.seed);
    if (options.progress) {
      std::printf("  %-40s s %6.3f   rel %6.3f (Gaussian reference %6.3f)   %s\n", p.label.c_str(),
                  result.result.structure, result.result.rel, result.result.gaussian_rel,
                  verdict(result.result));
      std::fflush(stdout);
    }
    results.push_back(std::move(result));
  }
  return results;
}

const char* verdict(const CalibratedFidelity& f) {
  return f.beats_gaussian() ? "beats the Gaussian reference" : "does not beat the Gaussian reference";
}

FidelitySummaryLine summarize(const std::vector<PairFidelity>& results) {
  FidelitySummaryLine s;
  for (const PairFidelity& r : results) {
    s.mean_structure += r.result.structure;
    s.worst_structure = s.pairs == 0 ? r.result.structure : std::max(s.worst_structure, r.result.structure);
    s.mean_rel += r.result.rel;
    s.mean_gaussian_rel += r.result.gaussian_rel;
    s.worst_rel = s.pairs == 0 ? r.result.rel : std::max(s.worst_rel, r.result.rel);
    s.beats_gaussian += r.result.beats_gaussian();
    ++s.pairs;
  }
  if (s.pairs) {
    s.mean_structure /= static_cast<double>(s.pairs);
    s.mean_rel /= static_cast<double>(s.pairs);
    s.mean_gaussian_rel /= static_cast<double>(s.pairs);
  }
  return s;
}

std::string summary_text(const FidelitySummaryLine& s) {
  char text[400];
  std::snprintf(text, sizeof text,
                "s mean %.3f, worst %.3f (0: the measurement itself, 1: no better than a Gaussian field); "
                "rel mean %.3f, worst %.3f "
                "(1: white noise), the Gaussian reference's %.3f; the model beats the Gaussian reference on "
                "%zu of %zu pairs",
                s.mean_structure, s.worst_structure, s.mean_rel, s.worst_rel, s.mean_gaussian_rel,
                s.beats_gaussian, s.pairs);
  return text;
}

std::string fidelity_markdown(const std::vector<PairFidelity>& results) {
  const FidelitySummaryLine summary = summarize(results);
  std::ostringstream md;
  md << "| pair | s | rel | Gaussian reference rel | the model beats it |\n|---|---|---|---|---|\n";
  for (const PairFidelity& r : results) {
    md << "| " << r.pair.label << " | " << r.result.structure << " | " << r.result.rel << " | "
       << r.result.gaussian_rel << " | " << (r.result.beats_gaussian() ? "yes" : "no") << " |\n";
  }
  md << "| mean | " << summary.mean_structure << " | " << summary.mean_rel << " | "
     << summary.mean_gaussian_rel << " | " << summary.beats_gaussian << " of " << summary.pairs
     << " |\n| worst | " << summary.worst_structure << " | " << summary.worst_rel << " | | |\n";
  return md.str();
}

RgbField fidelity_grid(const std::vector<PairFidelity>& results) {
  std::uint32_t cell_w = 0, cell_h = 0;
  for (const PairFidelity& r : results) {
    cell_w = std::max(cell_w, r.measured.width);
    cell_h = std::max(cell_h, r.measured.height);
  }
  // Drawn on the picture, so that a reader checks the verdict by eye: the columns' titles on top, and
  // above each row its pair, s and verdict.
  // Two caption lines of the 5x7 font fit a row of 64-pixel cells (33 characters).
  constexpr std::uint32_t gap = 4, caption = 12, row_caption = 21, scale = 1;
  constexpr const char* kTitles[3] = {"MEASURED", "MODEL", "GAUSSIAN"};
  RgbField grid;
  grid.width = 3 * cell_w + 2 * gap;
  grid.height = caption + static_cast<std::uint32_t>(results.size()) * (row_caption + cell_h + gap);
  grid.rgb.assign(std::size_t{grid.width} * grid.height * 3, 1.0f);
  for (std::uint32_t column = 0; column < 3; ++column)
    draw_text(grid.rgb, grid.width, grid.height, kTitles[column], static_cast<int>(column * (cell_w + gap)),
              2, scale);
  for (std::size_t row = 0; row < results.size(); ++row) {
    const PairFidelity& r = results[row];
    const std::uint32_t top = caption + static_cast<std::uint32_t>(row) * (row_caption + cell_h + gap);
    char verdict_line[64];
    std::snprintf(verdict_line, sizeof verdict_line, "S %.2f: %s", r.result.structure,
                  r.result.beats_gaussian() ? "THE MODEL BEATS IT" : "THE GAUSSIAN IS NEARER");
    draw_text(grid.rgb, grid.width, grid.height, r.pair.label, 0, static_cast<int>(top + 2), scale);
    draw_text(grid.rgb, grid.width, grid.height, verdict_line, 0, static_cast<int>(top + 11), scale);
    const RgbField* cells[3] = {&r.measured, &r.model, &r.gaussian};
    for (std::uint32_t column = 0; column < 3; ++column) {
      const RgbField& cell = *cells[column];
      for (std::uint32_t y = 0; y < cell.height; ++y) {
        const std::size_t to =
            (std::size_t(top + row_caption + y) * grid.width + column * (cell_w + gap)) * 3;
        std::copy_n(cell.rgb.begin() + static_cast<std::ptrdiff_t>(std::size_t{y} * cell.width * 3),
                    std::size_t{cell.width} * 3, grid.rgb.begin() + static_cast<std::ptrdiff_t>(to));
      }
    }
  }
  return grid;
}

std::string fidelity_csv(const std::vector<PairFidelity>& results, const Material& material) {
  std::ostringstream csv;
  csv << "light,view,light_theta,light_phi,view_theta,view_phi,rel,structure,gaussian_rel,floor,ceiling,"
         "gaussian_distance,model_distance";
  for (const char* name : DistributionDistance::kGroupNames) csv << ',' << name;
  for (const char* name : DistributionDistance::kGroupNames) csv << ",gaussian_" << name;
  csv << '\n';
  for (const PairFidelity& r : results) {
    const MaterialDirection& l = material.lights[r.pair.light];
    const MaterialDirection& v = material.views[r.pair.view];
    csv << r.pair.light << ',' << r.pair.view << ',' << l.theta * kDegrees << ',' << l.phi * kDegrees << ','
        << v.theta * kDegrees << ',' << v.phi * kDegrees << ',' << r.result.rel << ',' << r.result.structure
        << ',' << r.result.gaussian_rel << ',' << r.result.floor << ',' << r.result.ceiling << ','
        << r.result.gaussian << ',' << r.result.model;
    for (double g : r.result.parts.groups) csv << ',' << g;
    for (double g : r.result.gaussian_parts.groups) csv << ',' << g;
    csv << '\n';
  }
  return csv.str();
}

std::string fidelity_octaves_csv(const std::vector<PairFidelity>& results) {
  std::ostringstream csv;
  csv << "light,view,octave,period_px";
  for (const char* image : {"model", "measured"}) {
    csv << ',' << image << "_energy_db," << image << "_a_energy_db," << image << "_b_energy_db";
    for (const char* vector : {"skewness", "dark_side", "bright_side"})
      csv << ',' << image << '_' << vector << "_x," << image << '_' << vector << "_y";
  }
  csv << '\n';
  for (const PairFidelity& r : results) {
    const DistributionStatistics model = distribution_statistics(r.model.rgb, r.model.width, r.model.height);
    const DistributionStatistics measured =
        distribution_statistics(r.measured.rgb, r.measured.width, r.measured.height);
    for (std::size_t o = 0; o < std::min(model.octaves, measured.octaves); ++o) {
      csv << r.pair.light << ',' << r.pair.view << ',' << o << ',' << (4u << o);
      for (const DistributionStatistics* s : {&model, &measured}) {
        const OctaveProfile p = octave_profile(*s, o);
        csv << ',' << p.energy_db << ',' << p.chroma_energy_db[0] << ',' << p.chroma_energy_db[1];
        for (const auto& v : {p.skewness, p.dark_side, p.bright_side}) csv << ',' << v[0] << ',' << v[1];
      }
      csv << '\n';
    }
  }
  return csv.str();
}

}  // namespace carbtf::cli
