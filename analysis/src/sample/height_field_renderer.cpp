#include "carbtf/analysis/sample/height_field_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "carbtf/analysis/progress.hpp"
#include "carbtf/reference/parallel_for.hpp"

namespace carbtf {

std::vector<float> surface_normals(const Surface& surface) {
  const std::uint32_t n = surface.size;
  std::vector<float> normals(std::size_t{n} * n * 3);
  auto h = [&](std::int64_t c, std::int64_t r) {
    return surface.height[static_cast<std::size_t>(((r % n + n) % n) * n + ((c % n + n) % n))];
  };
  for (std::uint32_t r = 0; r < n; ++r) {
    for (std::uint32_t c = 0; c < n; ++c) {
      const double dx = 0.5 * (h(c + 1, r) - h(c - 1, r));
      const double dy = 0.5 * (h(c, std::int64_t{r} - 1) - h(c, r + 1));  // +y is towards row 0
      const double length = std::sqrt(dx * dx + dy * dy + 1.0);
      float* out = &normals[(std::size_t{r} * n + c) * 3];
      out[0] = static_cast<float>(-dx / length);
      out[1] = static_cast<float>(-dy / length);
      out[2] = static_cast<float>(1.0 / length);
    }
  }
  return normals;
}

namespace {

// Bilinear lookup with wrap-around of `channels` interleaved values at continuous texel coordinates
// (texel centres at integers).
struct PeriodicGrid {
  const float* data;
  std::uint32_t size;
  int channels;

  void sample(double col, double row, float* out) const {
    const double fc = std::floor(col), fr = std::floor(row);
    const double tc = col - fc, tr = row - fr;
    const auto wrap = [&](double v) {
      const std::int64_t i = static_cast<std::int64_t>(v) % static_cast<std::int64_t>(size);
      return static_cast<std::size_t>(i < 0 ? i + size : i);
    };
    const std::size_t c0 = wrap(fc), c1 = wrap(fc + 1), r0 = wrap(fr), r1 = wrap(fr + 1);
    for (int k = 0; k < channels; ++k) {
      const double top =
          data[(r0 * size + c0) * channels + k] * (1 - tc) + data[(r0 * size + c1) * channels + k] * tc;
      const double bottom =
          data[(r1 * size + c0) * channels + k] * (1 - tc) + data[(r1 * size + c1) * channels + k] * tc;
      out[k] = static_cast<float>(top * (1 - tr) + bottom * tr);
    }
  }
  double at(double col, double row) const {
    float value = 0;
    sample(col, row, &value);
    return value;
  }
};

struct TexelDirection {
  double col, row, z;  // direction in texel space: +col right, +row down, +z out
  double horizontal;   // length of (col, row)
};

TexelDirection texel_direction(const Direction& d) {
  const auto v = d.vector();
  return {v[0], -v[1], v[2], std::hypot(v[0], v[1])};
}

// Where the camera ray through plane point (col, row) first meets the surface, found by marching down
// from above the highest point and refining by bisection.
void view_hit(const PeriodicGrid& height, double h_min, double h_max, const TexelDirection& v, double col,
              double row, double& hit_col, double& hit_row) {
  if (v.horizontal < 1e-9) {
    hit_col = col;
    hit_row = row;
    return;
  }
  auto above = [&](double t) { return t * v.z - height.at(col + t * v.col, row + t * v.row); };
  const double step = 0.5 / std::max(v.horizontal, v.z);
  const double t_low = h_min / v.z;
  double t = h_max / v.z + step;
  double previous = t;
  while (t > t_low && above(t) > 0) {
    previous = t;
    t -= step;
  }
  if (t <= t_low) {
    t = t_low;
  } else {
    double lo = t, hi = previous;  // above(lo) <= 0 < above(hi)
    for (int i = 0; i < 8; ++i) {
      const double mid = 0.5 * (lo + hi);
      (above(mid) > 0 ? hi : lo) = mid;
    }
    t = hi;
  }
  hit_col = col + t * v.col;
  hit_row = row + t * v.row;
}

// 1 where texel (col, row) sees the light, 0 where the height field casts a shadow on it.
std::vector<float> shadow_map(const Surface& surface, const PeriodicGrid& height, double h_max,
                              const TexelDirection& l) {
  const std::uint32_t n = surface.size;
  std::vector<float> lit(std::size_t{n} * n, 1.0f);
  if (l.horizontal < 1e-9) return lit;
  const double step = 0.5 / l.horizontal;
  for (std::uint32_t r = 0; r < n; ++r) {
    for (std::uint32_t c = 0; c < n; ++c) {
      const double h0 = surface.height[std::size_t{r} * n + c];
      for (double t = step; h0 + t * l.z < h_max; t += step) {
        if (height.at(c + t * l.col, r + t * l.row) > h0 + t * l.z + 1e-3) {
          lit[std::size_t{r} * n + c] = 0.0f;
          break;
        }
      }
    }
  }
  return lit;
}

}  // namespace

std::vector<float> light_visibility(const Surface& surface, const Direction& light) {
  const std::uint32_t n = surface.size;
  if (n == 0 || surface.height.size() != std::size_t{n} * n)
    throw std::invalid_argument("light_visibility: height map does not match the size");
  const PeriodicGrid height{surface.height.data(), n, 1};
  const double h_max = *std::max_element(surface.height.begin(), surface.height.end());
  return shadow_map(surface, height, h_max, texel_direction(light));
}

void render_btf(const Surface& surface, const std::vector<Direction>& lights,
                const std::vector<Direction>& views, const RenderOptions& options,
                const std::function<void(std::uint32_t, std::uint32_t, std::span<const float>)>& emit) {
  const std::uint32_t n = surface.size;
  if (n == 0 || surface.height.size() != std::size_t{n} * n ||
      surface.albedo.size() != std::size_t{n} * n * 3) {
    throw std::invalid_argument("render_btf: surface maps do not match its size");
  }
  const std::size_t texels = std::size_t{n} * n;
  const auto [min_it, max_it] = std::minmax_element(surface.height.begin(), surface.height.end());
  const double h_min = *min_it, h_max = *max_it;
  const std::vector<float> normals = surface_normals(surface);
  const PeriodicGrid height{surface.height.data(), n, 1};
  const PeriodicGrid normal_grid{normals.data(), n, 3};
  const PeriodicGrid albedo_grid{surface.albedo.data(), n, 3};

  // Shadow maps depend on the light only: computed once each, in parallel.
  std::vector<std::vector<float>> shadows(lights.size());
  Progress progress("rendering " + std::to_string(lights.size() * views.size()) + " images",
                    lights.size() + lights.size() * views.size(), options.progress);
  detail::parallel_for(lights.size(), options.threads, [&](std::size_t l) {
    shadows[l] = shadow_map(surface, height, h_max, texel_direction(lights[l]));
    progress.advance();
  });

  const double diffuse_scale = 1.0 / std::numbers::pi;
  const double lobe_scale = surface.specular * (surface.gloss + 8.0) / (8.0 * std::numbers::pi);
  detail::parallel_for(views.size(), options.threads, [&](std::size_t v) {
    const TexelDirection view = texel_direction(views[v]);
    const auto view_vector = views[v].vector();
    // What each output pixel sees under this view: position, normal and albedo of the visible point.
    std::vector<float> hit(texels * 2), hit_normal(texels * 3), hit_albedo(texels * 3);
    for (std::uint32_t r = 0; r < n; ++r) {
      for (std::uint32_t c = 0; c < n; ++c) {
        const std::size_t i = std::size_t{r} * n + c;
        double hc = 0, hr = 0;
        view_hit(height, h_min, h_max, view, c, r, hc, hr);
        hit[i * 2] = static_cast<float>(hc);
        hit[i * 2 + 1] = static_cast<float>(hr);
        normal_grid.sample(hc, hr, &hit_normal[i * 3]);
        albedo_grid.sample(hc, hr, &hit_albedo[i * 3]);
      }
    }
    std::vector<float> image(texels * 3);
    for (std::uint32_t l = 0; l < lights.size(); ++l) {
      const auto light_vector = lights[l].vector();
      double half[3] = {light_vector[0] + view_vector[0], light_vector[1] + view_vector[1],
                        light_vector[2] + view_vector[2]};
      const double half_length = std::sqrt(half[0] * half[0] + half[1] * half[1] + half[2] * half[2]);
      for (double& h : half) h /= half_length;
      const PeriodicGrid shadow{shadows[l].data(), n, 1};
      for (std::size_t i = 0; i < texels; ++i) {
        const float* nrm = &hit_normal[i * 3];
        const double length =
            std::sqrt(double{nrm[0]} * nrm[0] + double{nrm[1]} * nrm[1] + double{nrm[2]} * nrm[2]);
        const double n_dot_l =
            (nrm[0] * light_vector[0] + nrm[1] * light_vector[1] + nrm[2] * light_vector[2]) / length;
        const double n_dot_h =
            std::max(0.0, (nrm[0] * half[0] + nrm[1] * half[1] + nrm[2] * half[2]) / length);
        const double direct =
            n_dot_l > 0 ? options.irradiance * n_dot_l * shadow.at(hit[i * 2], hit[i * 2 + 1]) : 0.0;
        const double lobe = lobe_scale * std::pow(n_dot_h, surface.gloss);
        for (int k = 0; k < 3; ++k) {
          const double a = hit_albedo[i * 3 + k];
          image[i * 3 + k] = static_cast<float>(direct * (a * diffuse_scale + lobe) + options.ambient * a);
        }
      }
      emit(l, static_cast<std::uint32_t>(v), image);
      progress.advance();
    }
  });
}

}  // namespace carbtf
