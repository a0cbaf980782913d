// Pictures of an analysis and of benchmarks, as RGB float images ready for write_rgb_image(...,
// srgb_encode = false): values are already display-encoded in [0, 1]. Plots carry axis titles and
// decade labels in a 5x7 bitmap font; the accompanying CSV files carry the exact numbers.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace carbtf {

struct Figure {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<float> rgb;  // width * height * 3, display-encoded
};

// The paper's Fig. 5: the light x view subspace-index table, one `cell`-pixel square per pair (lights
// down, views across), coloured by subspace with a fixed 20-colour palette (repeating beyond 20), and
// a one-pixel grey rule between elevation rings when `ring_starts` lists the first index of each ring.
Figure index_table_figure(std::span<const std::uint8_t> index, std::uint32_t lights, std::uint32_t views,
                          std::uint32_t cell, std::span<const std::uint32_t> ring_starts = {});

// The paper's Fig. 4: log10 of the eigenvalues against their rank, with a light grid line per decade.
Figure eigenvalue_figure(std::span<const double> eigenvalues, std::uint32_t width = 640,
                         std::uint32_t height = 400);

// A point of a scatter plot; `series` picks its colour (subspace_colour(2 * series)) and legend entry.
struct ScatterPoint {
  double x = 0.0;
  double y = 0.0;
  std::uint32_t series = 0;
};

// Log-log scatter plot with a grid line and a label per decade, axis titles, and a legend naming each
// series (legend[i] for series i). Non-positive values are left out. A point that lands on points drawn
// before it is drawn as a ring around them, so that coinciding series stay visible.
Figure scatter_figure(std::span<const ScatterPoint> points, std::string_view x_title,
                      std::string_view y_title, std::span<const std::string_view> legend = {},
                      std::uint32_t width = 720, std::uint32_t height = 480);

// `text` in the 5x7 bitmap font (upper case, digits and . , - + / : ( ) % = _) into an RGB image of
// width x height, from its top-left corner (x, y), each font pixel `scale` pixels; clipped at the edges.
void draw_text(std::span<float> rgb, std::uint32_t width, std::uint32_t height, std::string_view text, int x,
               int y, int scale = 1, std::array<float, 3> colour = {0.0f, 0.0f, 0.0f});

// A display colour of subspace `index` (sRGB-encoded, [0, 1]).
std::array<float, 3> subspace_colour(std::uint32_t index);

}  // namespace carbtf
