#include "carbtf/analysis/sample/sample_materials.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numbers>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "carbtf/reference/noise.hpp"

namespace carbtf {

namespace fs = std::filesystem;
using json = nlohmann::json;

fs::path asset_directory() {
  if (const char* env = std::getenv("CARBTF_ASSETS"); env && *env) return env;
  std::error_code ec;
  if (fs::is_directory(CARBTF_SOURCE_ASSET_DIR, ec)) return CARBTF_SOURCE_ASSET_DIR;
  return CARBTF_INSTALLED_ASSET_DIR;
}

std::vector<std::string> sample_material_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(asset_directory() / "materials", ec)) {
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

namespace {

// A uniform in [0, 1) for (seed, stream, i, j): the same counter-based generator as the noise.
double uniform(std::uint64_t seed, std::uint32_t stream, std::uint32_t i, std::uint32_t j) {
  const auto words =
      reference::philox4x32_10({i, j, stream, 0x5a4d504cu},
                               {static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)});
  return words[0] * 0x1p-32;
}

double smooth(double t) {
  return t * t * t * (t * (t * 6 - 15) + 10);
}

// Periodic value noise in [-1, 1] with `cells` lattice cells across the tile; u, v in [0, 1).
double value_noise(std::uint64_t seed, std::uint32_t stream, double u, double v, std::uint32_t cells_u,
                   std::uint32_t cells_v) {
  const double x = u * cells_u, y = v * cells_v;
  const double fx = std::floor(x), fy = std::floor(y);
  const auto i0 = static_cast<std::uint32_t>(static_cast<std::int64_t>(fx) % cells_u);
  const auto j0 = static_cast<std::uint32_t>(static_cast<std::int64_t>(fy) % cells_v);
  const std::uint32_t i1 = (i0 + 1) % cells_u, j1 = (j0 + 1) % cells_v;
  const double sx = smooth(x - fx), sy = smooth(y - fy);
  auto at = [&](std::uint32_t i, std::uint32_t j) { return 2 * uniform(seed, stream, i, j) - 1; };
  return (at(i0, j0) * (1 - sx) + at(i1, j0) * sx) * (1 - sy) +
         (at(i0, j1) * (1 - sx) + at(i1, j1) * sx) * sy;
}

double fractal_noise(std::uint64_t seed, std::uint32_t stream, double u, double v, std::uint32_t cells,
                     int octaves) {
  double sum = 0, weight = 1, total = 0;
  for (int o = 0; o < octaves; ++o) {
    const std::uint32_t c = cells << o;
    sum += weight * value_noise(seed, stream + static_cast<std::uint32_t>(o), u, v, c, c);
    total += weight;
    weight *= 0.5;
  }
  return sum / total;
}

// Distances to the nearest and second-nearest jittered cell points (periodic), in cell units.
void cell_distances(std::uint64_t seed, double u, double v, std::uint32_t cells, double& f1, double& f2) {
  const double x = u * cells, y = v * cells;
  const auto cx = static_cast<std::int64_t>(std::floor(x)), cy = static_cast<std::int64_t>(std::floor(y));
  f1 = f2 = 1e9;
  for (std::int64_t dy = -1; dy <= 1; ++dy) {
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      const std::int64_t gx = cx + dx, gy = cy + dy;
      const auto wx = static_cast<std::uint32_t>(((gx % cells) + cells) % cells);
      const auto wy = static_cast<std::uint32_t>(((gy % cells) + cells) % cells);
      const double px = gx + uniform(seed, 900, wx, wy), py = gy + uniform(seed, 901, wx, wy);
      const double d = std::hypot(px - x, py - y);
      if (d < f1) {
        f2 = f1;
        f1 = d;
      } else if (d < f2) {
        f2 = d;
      }
    }
  }
}

std::array<float, 3> color(const json& recipe, const char* key) {
  const auto values = recipe.at(key).get<std::vector<double>>();
  if (values.size() != 3) throw std::invalid_argument(std::string(key) + " needs 3 values");
  return {static_cast<float>(values[0]), static_cast<float>(values[1]), static_cast<float>(values[2])};
}

// Scales heights from [min, max] to [0, amplitude * size] texels.
void normalise_height(Surface& surface, double amplitude) {
  const auto [lo, hi] = std::minmax_element(surface.height.begin(), surface.height.end());
  const double low = *lo, range = std::max(1e-12, double{*hi} - low);
  for (float& h : surface.height) h = static_cast<float>((h - low) / range * amplitude * surface.size);
}

void make_leather(const json& recipe, std::uint64_t seed, Surface& s) {
  const auto cells = recipe.at("cells").get<std::uint32_t>();
  const double crease = recipe.at("crease_width").get<double>();
  const int octaves = recipe.at("noise_octaves").get<int>();
  const auto noise_cells = recipe.at("noise_cells").get<std::uint32_t>();
  const double noise_weight = recipe.at("noise_weight").get<double>();
  const auto base = color(recipe, "base_color");
  const double variation = recipe.at("color_variation").get<double>();
  const double darkening = recipe.at("crease_darkening").get<double>();
  if (cells == 0 || noise_cells == 0 || octaves <= 0)
    throw std::invalid_argument("cells and octaves must be > 0");
  const std::uint32_t n = s.size;
  for (std::uint32_t r = 0; r < n; ++r) {
    for (std::uint32_t c = 0; c < n; ++c) {
      const double u = (c + 0.5) / n, v = (r + 0.5) / n;
      double f1 = 0, f2 = 0;
      cell_distances(seed, u, v, cells, f1, f2);
      const double border = std::clamp((f2 - f1) / crease, 0.0, 1.0);  // 0 on a crease
      const double pillow = 1 - (1 - border) * (1 - border);
      const double grain = fractal_noise(seed, 10, u, v, noise_cells, octaves);
      const std::size_t i = std::size_t{r} * n + c;
      s.height[i] = static_cast<float>((1 - noise_weight) * pillow + noise_weight * 0.5 * (grain + 1));
      const double tint = 1 + variation * fractal_noise(seed, 40, u, v, 3, 3);
      const double shade = 1 - darkening * (1 - pillow);
      for (int k = 0; k < 3; ++k)
        s.albedo[i * 3 + k] = static_cast<float>(std::clamp(base[k] * tint * shade, 0.0, 1.0));
    }
  }
}

void make_weave(const json& recipe, std::uint64_t seed, Surface& s) {
  const auto threads = recipe.at("threads").get<std::uint32_t>();
  const double width = recipe.at("thread_width").get<double>();
  const double undulation = recipe.at("undulation").get<double>();
  const auto warp = color(recipe, "warp_color"), weft = color(recipe, "weft_color");
  const double fiber = recipe.at("fiber_variation").get<double>();
  if (threads == 0 || width <= 0 || width > 1)
    throw std::invalid_argument("threads > 0 and 0 < thread_width <= 1");
  const std::uint32_t n = s.size;
  for (std::uint32_t r = 0; r < n; ++r) {
    for (std::uint32_t c = 0; c < n; ++c) {
      const double u = (c + 0.5) / n, v = (r + 0.5) / n;
      const double x = u * threads, y = v * threads;
      const double i = std::floor(x), j = std::floor(y);
      const double sign_i = std::fmod(i, 2) == 0 ? 1 : -1, sign_j = std::fmod(j, 2) == 0 ? 1 : -1;
      auto profile = [&](double offset) {  // round thread cross-section, offset from its centre line
        const double d = 2 * offset / width;
        return std::abs(d) < 1 ? std::sqrt(1 - d * d) : -1.0;
      };
      // Warp threads run along y, weft along x; at each crossing one is up, the other down.
      const double warp_height = profile(x - i - 0.5) + undulation * std::sin(std::numbers::pi * y) * sign_i;
      const double weft_height = profile(y - j - 0.5) - undulation * std::sin(std::numbers::pi * x) * sign_j;
      const bool warp_on_top = warp_height >= weft_height;
      const std::size_t index = std::size_t{r} * n + c;
      s.height[index] = static_cast<float>(std::max({warp_height, weft_height, -1.0 - undulation}));
      // Fibres: noise stretched along the thread.
      const double streak = warp_on_top ? value_noise(seed, 70, u, v, threads * 8, threads)
                                        : value_noise(seed, 71, u, v, threads, threads * 8);
      const auto& base = warp_on_top ? warp : weft;
      for (int k = 0; k < 3; ++k) {
        s.albedo[index * 3 + k] = static_cast<float>(std::clamp(base[k] * (1 + fiber * streak), 0.0, 1.0));
      }
    }
  }
}

// Area-averages a square 8-bit image down (or nearest-samples it up) to size x size.
std::vector<float> resample_channel_mean(const RgbImage& image, std::uint32_t size, bool srgb_decode,
                                         std::vector<float>* rgb_out) {
  std::vector<float> grey(std::size_t{size} * size);
  if (rgb_out) rgb_out->assign(std::size_t{size} * size * 3, 0.0f);
  const double scale = static_cast<double>(image.width) / size;
  for (std::uint32_t r = 0; r < size; ++r) {
    for (std::uint32_t c = 0; c < size; ++c) {
      const auto r0 = static_cast<std::uint32_t>(r * scale), c0 = static_cast<std::uint32_t>(c * scale);
      const auto r1 = std::max(r0 + 1, static_cast<std::uint32_t>((r + 1) * scale));
      const auto c1 = std::max(c0 + 1, static_cast<std::uint32_t>((c + 1) * scale));
      double sum[3] = {0, 0, 0};
      for (std::uint32_t y = r0; y < r1; ++y) {
        for (std::uint32_t x = c0; x < c1; ++x) {
          for (int k = 0; k < 3; ++k) {
            const float value = image.srgb8[(std::size_t{y} * image.width + x) * 3 + k] / 255.0f;
            sum[k] += srgb_decode ? srgb_to_linear(value) : value;
          }
        }
      }
      const double count = double(r1 - r0) * (c1 - c0);
      const std::size_t i = std::size_t{r} * size + c;
      grey[i] = static_cast<float>((sum[0] + sum[1] + sum[2]) / (3 * count));
      if (rgb_out) {
        for (int k = 0; k < 3; ++k) (*rgb_out)[i * 3 + k] = static_cast<float>(sum[k] / count);
      }
    }
  }
  return grey;
}

void make_scanned(const json& recipe, const fs::path& recipe_folder, Surface& s) {
  auto load = [&](const char* key) {
    const fs::path path = recipe_folder / recipe.at(key).get<std::string>();
    RgbImage image = decode_rgb_image(path.string(), read_file_bytes(path));
    if (image.linear || image.width != image.height) throw InputError(path, "expected a square 8-bit image");
    return image;
  };
  const RgbImage height = load("height_image"), albedo = load("albedo_image");
  // Height maps are data, not colours: no sRGB decoding.
  s.height = resample_channel_mean(height, s.size, false, nullptr);
  resample_channel_mean(albedo, s.size, true, &s.albedo);
}

}  // namespace

Surface make_sample_surface(const std::string& name, std::uint32_t size, std::uint64_t seed) {
  fs::path recipe_path = name;
  if (recipe_path.extension() != ".json") recipe_path = asset_directory() / "materials" / (name + ".json");
  std::error_code ec;
  if (!fs::is_regular_file(recipe_path, ec)) {
    std::string known;
    for (const std::string& n : sample_material_names()) known += (known.empty() ? "" : ", ") + n;
    throw InputError(name,
                     "no such sample material (built in: " + (known.empty() ? "none found" : known) + ")");
  }
  if (size < 8 || size > 4096) throw InputError(name, "size must be between 8 and 4096");
  json recipe;
  try {
    std::ifstream file(recipe_path);
    recipe = json::parse(file);
  } catch (const json::exception& e) {
    throw InputError(recipe_path, std::string("malformed recipe: ") + e.what());
  }
  Surface s;
  s.size = size;
  s.height.assign(std::size_t{size} * size, 0.0f);
  s.albedo.assign(std::size_t{size} * size * 3, 0.0f);
  try {
    const std::string generator = recipe.at("generator").get<std::string>();
    if (generator == "leather") {
      make_leather(recipe, seed, s);
    } else if (generator == "weave") {
      make_weave(recipe, seed, s);
    } else if (generator == "scanned") {
      make_scanned(recipe, recipe_path.parent_path(), s);
    } else {
      throw InputError(recipe_path, "unknown generator '" + generator + "' (leather, weave, scanned)");
    }
    normalise_height(s, recipe.at("height_amplitude").get<double>());
    s.specular = recipe.at("specular").get<float>();
    s.gloss = recipe.at("gloss").get<float>();
  } catch (const json::exception& e) {
    throw InputError(recipe_path, std::string("malformed recipe: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(recipe_path, std::string("bad recipe value: ") + e.what());
  }
  return s;
}

}  // namespace carbtf
