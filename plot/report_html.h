// The HTML of `evas report` (plot/report_page.h): one HTML5 document with its
// style and script inline (no external resource), figures as relative links.
// The script, on the window's load, counts the <img> elements that displayed
// (complete, with a natural width) and writes the counts on <body>
// (data-images, data-images-loaded, data-images-failed: the failed sources),
// so a headless browser's DOM shows whether every figure loaded
// (tests/test_report.cpp).
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace evas::report {

/// Text with &, <, >, " and ' escaped for HTML text and attribute values.
std::string escape(const std::string& s);

/// An HTML page under construction.
class Page {
 public:
  explicit Page(const std::string& title);
  void heading(int level, const std::string& text, const std::string& id = "");
  /// A paragraph of `html` (already escaped where it must be).
  void paragraph(const std::string& html, const std::string& css_class = "");
  /// A table: the header cells and the rows, all plain text (escaped here).
  void table(const std::vector<std::string>& head,
             const std::vector<std::vector<std::string>>& rows, const std::string& caption = "");
  /// A numbered figure: the image `file` (a name in the page's folder), linked
  /// to itself, its script and data named in the caption.
  void figure(const std::string& file, const std::string& alt, const std::string& caption);
  /// Figures side by side from here to end_row().
  void begin_row() { body_ << "<div class=\"row\">\n"; }
  void end_row() { body_ << "</div>\n"; }
  /// The table of contents (from the level-2 headings with ids) and the page.
  std::string html() const;
  int figures() const { return figures_; }

 private:
  std::string title_;
  std::ostringstream body_;
  std::vector<std::pair<std::string, std::string>> toc_;  // id, text
  int figures_ = 0;
};

}  // namespace evas::report
