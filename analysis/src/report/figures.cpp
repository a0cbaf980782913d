#include "carbtf/analysis/report/figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bitmap_font.hpp"

namespace carbtf {

void draw_text(std::span<float> rgb, std::uint32_t width, std::uint32_t height, std::string_view text, int x,
               int y, int scale, std::array<float, 3> colour) {
  detail::rasterize_text(text, x, y, scale, [&](int px, int py) {
    if (px < 0 || py < 0 || static_cast<std::uint32_t>(px) >= width ||
        static_cast<std::uint32_t>(py) >= height)
      return;
    std::copy(colour.begin(), colour.end(),
              rgb.begin() + static_cast<std::ptrdiff_t>(
                                (static_cast<std::size_t>(py) * width + static_cast<std::size_t>(px)) * 3));
  });
}

namespace {

// Tableau 20: distinct, colour-blind-aware hues in light/dark pairs.
constexpr std::array<std::array<int, 3>, 20> kPalette{
    {{31, 119, 180},  {174, 199, 232}, {255, 127, 14},  {255, 187, 120}, {44, 160, 44},
     {152, 223, 138}, {214, 39, 40},   {255, 152, 150}, {148, 103, 189}, {197, 176, 213},
     {140, 86, 75},   {196, 156, 148}, {227, 119, 194}, {247, 182, 210}, {127, 127, 127},
     {199, 199, 199}, {188, 189, 34},  {219, 219, 141}, {23, 190, 207},  {158, 218, 229}}};

void set_pixel(Figure& f, std::int64_t x, std::int64_t y, std::array<float, 3> colour) {
  if (x < 0 || y < 0 || x >= f.width || y >= f.height) return;
  float* p = &f.rgb[(static_cast<std::size_t>(y) * f.width + static_cast<std::size_t>(x)) * 3];
  p[0] = colour[0];
  p[1] = colour[1];
  p[2] = colour[2];
}

void draw_line(Figure& f, double x0, double y0, double x1, double y1, std::array<float, 3> colour) {
  const int steps = static_cast<int>(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    set_pixel(f, std::lround(x0 + t * (x1 - x0)), std::lround(y0 + t * (y1 - y0)), colour);
  }
}

void draw_text(Figure& f, std::string_view text, int x, int y, std::array<float, 3> colour, int scale = 1) {
  carbtf::draw_text(f.rgb, f.width, f.height, text, x, y, scale, colour);
}

// Vertical text, bottom to top (a y-axis title).
void draw_text_up(Figure& f, std::string_view text, int x, int y_bottom, std::array<float, 3> colour) {
  detail::rasterize_text(text, 0, 0, 1, [&](int px, int py) { set_pixel(f, x + py, y_bottom - px, colour); });
}

// "1E-3", "0.1", "1", "10", "1E4": a decade's label, short.
std::string decade_label(int exponent) {
  if (exponent >= 0 && exponent <= 3)
    return std::to_string(static_cast<int>(std::lround(std::pow(10.0, exponent))));
  if (exponent == -1) return "0.1";
  return "1E" + std::to_string(exponent);
}

Figure blank(std::uint32_t width, std::uint32_t height, float grey) {
  Figure f;
  f.width = width;
  f.height = height;
  f.rgb.assign(std::size_t{width} * height * 3, grey);
  return f;
}

}  // namespace

std::array<float, 3> subspace_colour(std::uint32_t index) {
  const auto& c = kPalette[index % kPalette.size()];
  return {c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f};
}

Figure index_table_figure(std::span<const std::uint8_t> index, std::uint32_t lights, std::uint32_t views,
                          std::uint32_t cell, std::span<const std::uint32_t> ring_starts) {
  if (index.size() != std::size_t{lights} * views || cell == 0)
    throw std::invalid_argument("index table figure: size mismatch");
  Figure f = blank(views * cell, lights * cell, 1.0f);
  for (std::uint32_t l = 0; l < lights; ++l) {
    for (std::uint32_t v = 0; v < views; ++v) {
      const auto colour = subspace_colour(index[std::size_t{l} * views + v]);
      for (std::uint32_t y = 0; y < cell; ++y)
        for (std::uint32_t x = 0; x < cell; ++x) set_pixel(f, v * cell + x, l * cell + y, colour);
    }
  }
  const std::array<float, 3> rule{0.25f, 0.25f, 0.25f};
  for (std::uint32_t start : ring_starts) {
    if (start == 0) continue;
    draw_line(f, start * cell, 0, start * cell, f.height - 1.0, rule);
    draw_line(f, 0, start * cell, f.width - 1.0, start * cell, rule);
  }
  return f;
}

Figure eigenvalue_figure(std::span<const double> eigenvalues, std::uint32_t width, std::uint32_t height) {
  Figure f = blank(width, height, 1.0f);
  const double margin = 30.0;
  const double plot_w = width - 2 * margin, plot_h = height - 2 * margin;
  std::vector<double> logs;
  for (double e : eigenvalues) {
    if (e > 0.0) logs.push_back(std::log10(e));
  }
  const std::array<float, 3> axis{0.0f, 0.0f, 0.0f}, grid{0.85f, 0.85f, 0.85f}, curve{0.12f, 0.47f, 0.71f};
  if (!logs.empty()) {
    const double top = std::ceil(*std::max_element(logs.begin(), logs.end()));
    const double bottom = std::min(top - 1.0, std::floor(*std::min_element(logs.begin(), logs.end())));
    auto y_of = [&](double lg) { return margin + (top - lg) / (top - bottom) * plot_h; };
    auto x_of = [&](std::size_t i) {
      return margin + (logs.size() == 1 ? 0.0 : static_cast<double>(i) / (logs.size() - 1) * plot_w);
    };
    for (double decade = bottom; decade <= top; decade += 1.0)
      draw_line(f, margin, y_of(decade), margin + plot_w, y_of(decade), grid);
    for (std::size_t i = 0; i + 1 < logs.size(); ++i)
      draw_line(f, x_of(i), y_of(logs[i]), x_of(i + 1), y_of(logs[i + 1]), curve);
    for (std::size_t i = 0; i < logs.size(); ++i) {
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          set_pixel(f, std::lround(x_of(i)) + dx, std::lround(y_of(logs[i])) + dy, curve);
    }
  }
  draw_line(f, margin, margin, margin, margin + plot_h, axis);
  draw_line(f, margin, margin + plot_h, margin + plot_w, margin + plot_h, axis);
  draw_text(f, "EIGENVALUE (LOG10) AGAINST RANK, " + std::to_string(logs.size()) + " VALUES",
            static_cast<int>(margin), 10, axis);
  return f;
}

Figure scatter_figure(std::span<const ScatterPoint> points, std::string_view x_title,
                      std::string_view y_title, std::span<const std::string_view> legend, std::uint32_t width,
                      std::uint32_t height) {
  Figure f = blank(width, height, 1.0f);
  const std::array<float, 3> axis{0.0f, 0.0f, 0.0f}, grid{0.88f, 0.88f, 0.88f}, label{0.25f, 0.25f, 0.25f};
  const double left = 70.0, right = 20.0, top = 20.0, bottom = 50.0;
  const double plot_w = width - left - right, plot_h = height - top - bottom;
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  for (const ScatterPoint& p : points) {
    if (!(p.x > 0.0) || !(p.y > 0.0)) continue;
    x_lo = std::min(x_lo, std::log10(p.x));
    x_hi = std::max(x_hi, std::log10(p.x));
    y_lo = std::min(y_lo, std::log10(p.y));
    y_hi = std::max(y_hi, std::log10(p.y));
  }
  if (!(x_lo <= x_hi)) x_lo = 0.0, x_hi = 1.0, y_lo = 0.0, y_hi = 1.0;
  x_lo = std::floor(x_lo), x_hi = std::max(std::ceil(x_hi), x_lo + 1.0);
  y_lo = std::floor(y_lo), y_hi = std::max(std::ceil(y_hi), y_lo + 1.0);
  auto x_of = [&](double lg) { return left + (lg - x_lo) / (x_hi - x_lo) * plot_w; };
  auto y_of = [&](double lg) { return top + (y_hi - lg) / (y_hi - y_lo) * plot_h; };
  for (double d = x_lo; d <= x_hi; d += 1.0) {
    draw_line(f, x_of(d), top, x_of(d), top + plot_h, grid);
    const std::string text = decade_label(static_cast<int>(d));
    draw_text(f, text, static_cast<int>(x_of(d)) - detail::text_width(text, 1) / 2,
              static_cast<int>(top + plot_h) + 6, label);
  }
  for (double d = y_lo; d <= y_hi; d += 1.0) {
    draw_line(f, left, y_of(d), left + plot_w, y_of(d), grid);
    const std::string text = decade_label(static_cast<int>(d));
    draw_text(f, text, static_cast<int>(left) - 6 - detail::text_width(text, 1),
              static_cast<int>(y_of(d)) - 3, label);
  }
  draw_line(f, left, top, left, top + plot_h, axis);
  draw_line(f, left, top + plot_h, left + plot_w, top + plot_h, axis);
  draw_text(f, x_title, static_cast<int>(left + plot_w / 2) - detail::text_width(x_title, 1) / 2,
            static_cast<int>(height) - 18, axis);
  draw_text_up(f, y_title, 8, static_cast<int>(top + plot_h / 2) + detail::text_width(y_title, 1) / 2, axis);
  // Two variants that build the same model land on one spot, and a disc drawn over another would hide
  // it: a point within a disc's width of points drawn before it is drawn as a ring around them, one ring
  // wider for each of them, so every series stays visible where they coincide.
  std::vector<std::pair<long, long>> drawn;
  for (const ScatterPoint& p : points) {
    if (!(p.x > 0.0) || !(p.y > 0.0)) continue;
    const auto colour = subspace_colour(2 * p.series);
    const long cx = std::lround(x_of(std::log10(p.x))), cy = std::lround(y_of(std::log10(p.y)));
    const auto beneath = std::count_if(drawn.begin(), drawn.end(), [&](const std::pair<long, long>& d) {
      return std::abs(d.first - cx) <= 6 && std::abs(d.second - cy) <= 6;
    });
    const long outer = 3 + 3 * beneath, inner = outer - 2;
    for (long dy = -outer; dy <= outer; ++dy) {
      for (long dx = -outer; dx <= outer; ++dx) {
        const long r2 = dx * dx + dy * dy;
        if (r2 <= outer * outer && (beneath == 0 || r2 > inner * inner))
          set_pixel(f, cx + dx, cy + dy, colour);
      }
    }
    drawn.emplace_back(cx, cy);
  }
  for (std::size_t i = 0; i < legend.size(); ++i) {
    const int y = static_cast<int>(top) + 8 + static_cast<int>(i) * 14;
    const int x = static_cast<int>(left + plot_w) - 12 - detail::text_width(legend[i], 1);
    const auto colour = subspace_colour(2 * static_cast<std::uint32_t>(i));
    for (int dy = 0; dy < 7; ++dy)
      for (int dx = 0; dx < 7; ++dx) set_pixel(f, x - 12 + dx, y + dy, colour);
    draw_text(f, legend[i], x, y, axis);
  }
  return f;
}

}  // namespace carbtf
