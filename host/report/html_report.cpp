#include "report/html_report.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "carbtf/engine/file_output.hpp"

namespace carbtf::cli {

std::string html_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

HtmlReport::HtmlReport(std::string title) : title_(std::move(title)) {}

void HtmlReport::heading(const std::string& text) {
  body_ += "<h2>" + html_escape(text) + "</h2>\n";
}

void HtmlReport::paragraph(const std::string& text) {
  body_ += "<p>" + html_escape(text) + "</p>\n";
}

void HtmlReport::table(const std::vector<std::vector<std::string>>& rows) {
  body_ += "<table>\n";
  for (std::size_t r = 0; r < rows.size(); ++r) {
    body_ += "<tr>";
    for (const std::string& cell : rows[r]) {
      body_ += (r == 0 ? "<th>" : "<td>") + html_escape(cell) + (r == 0 ? "</th>" : "</td>");
    }
    body_ += "</tr>\n";
  }
  body_ += "</table>\n";
}

namespace {

std::string figure_html(const std::string& file, const std::string& caption, int display_width) {
  return "<figure><img src=\"" + html_escape(file) + "\" width=\"" + std::to_string(display_width) +
         "\" style=\"image-rendering:pixelated\"><figcaption>" + html_escape(caption) +
         "</figcaption></figure>\n";
}

}  // namespace

void HtmlReport::image(const std::string& file, const std::string& caption, int display_width) {
  body_ += figure_html(file, caption, display_width);
}

void HtmlReport::image_row(const std::vector<std::pair<std::string, std::string>>& images,
                           int display_width) {
  body_ += "<div style=\"display:flex;flex-wrap:wrap;gap:12px\">\n";
  for (const auto& [file, caption] : images) body_ += figure_html(file, caption, display_width);
  body_ += "</div>\n";
}

void HtmlReport::histogram_chart(const std::vector<double>& centres, const std::vector<double>& heights,
                                 const std::vector<std::pair<double, double>>& curve,
                                 const std::string& caption) {
  if (centres.empty() || centres.size() != heights.size()) return;
  const double width = 520, height = 260, margin = 30;
  const double x0 = centres.front(), x1 = centres.back();
  double y1 = *std::max_element(heights.begin(), heights.end());
  for (const auto& point : curve) y1 = std::max(y1, point.second);
  y1 *= 1.05;
  auto sx = [&](double x) { return margin + (x - x0) / (x1 - x0) * (width - 2 * margin); };
  auto sy = [&](double y) { return height - margin - y / y1 * (height - 2 * margin); };
  char buffer[256];
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(int(width)) +
                    "\" height=\"" + std::to_string(int(height)) + "\" style=\"background:#fff\">\n";
  const double bar = (width - 2 * margin) / static_cast<double>(centres.size());
  for (std::size_t i = 0; i < centres.size(); ++i) {
    std::snprintf(buffer, sizeof buffer,
                  "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#8ab\"/>\n",
                  sx(centres[i]) - bar / 2, sy(heights[i]), bar, sy(0) - sy(heights[i]));
    svg += buffer;
  }
  svg += "<polyline fill=\"none\" stroke=\"#c33\" stroke-width=\"2\" points=\"";
  for (const auto& [x, y] : curve) {
    std::snprintf(buffer, sizeof buffer, "%.1f,%.1f ", sx(x), sy(y));
    svg += buffer;
  }
  svg += "\"/>\n";
  std::snprintf(buffer, sizeof buffer,
                "<line x1=\"%.0f\" y1=\"%.1f\" x2=\"%.0f\" y2=\"%.1f\" stroke=\"#333\"/>\n", margin, sy(0),
                width - margin, sy(0));
  svg += buffer;
  for (int tick = static_cast<int>(x0); tick <= static_cast<int>(x1); ++tick) {
    std::snprintf(buffer, sizeof buffer,
                  "<text x=\"%.1f\" y=\"%.1f\" font-size=\"11\" text-anchor=\"middle\">%d</text>\n", sx(tick),
                  height - margin + 14, tick);
    svg += buffer;
  }
  svg += "</svg>";
  body_ += "<figure>" + svg + "<figcaption>" + html_escape(caption) + "</figcaption></figure>\n";
}

bool HtmlReport::write(const std::filesystem::path& folder, std::string& error) const {
  const std::filesystem::path file = folder / "index.html";
  std::ostringstream out;
  out << "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>" << html_escape(title_)
      << "</title>\n<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}"
         "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:4px 10px;text-align:left}"
         "figure{display:inline-block;margin:1em}figcaption{font-size:90%;color:#555}</style></"
         "head>\n<body>\n<h1>"
      << html_escape(title_) << "</h1>\n"
      << body_ << "</body></html>\n";
  if (const Status s = write_file_whole(file.string(), out.str()); !s.ok()) {
    error = s.message();
    return false;
  }
  return true;
}

}  // namespace carbtf::cli
