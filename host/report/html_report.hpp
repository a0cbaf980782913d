// A self-contained HTML report (one file, images beside it) for people who would rather look than
// read: figures in tables, pictures, and inline SVG charts.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace carbtf::cli {

class HtmlReport {
 public:
  explicit HtmlReport(std::string title);

  void heading(const std::string& text);
  void paragraph(const std::string& text);
  // rows[0] is the header row.
  void table(const std::vector<std::vector<std::string>>& rows);
  // `file` is relative to the report folder.
  void image(const std::string& file, const std::string& caption, int display_width = 512);
  // Pictures side by side (file, caption), each shown display_width pixels wide.
  void image_row(const std::vector<std::pair<std::string, std::string>>& images, int display_width = 256);
  // Bars of a histogram (bin centres and heights) with a reference curve over them, as inline SVG.
  void histogram_chart(const std::vector<double>& centres, const std::vector<double>& heights,
                       const std::vector<std::pair<double, double>>& curve, const std::string& caption);

  // Writes index.html into `folder`; false with `error` set when the file cannot be written.
  bool write(const std::filesystem::path& folder, std::string& error) const;

 private:
  std::string title_;
  std::string body_;
};

std::string html_escape(const std::string& text);

}  // namespace carbtf::cli
