// `evas report`'s HTML (report_html.h).
#include "plot/report_html.h"

#include <filesystem>
#include <regex>

namespace evas::report {

namespace {

const char* kStyle =
    R"(body { font-family: sans-serif; max-width: 1400px; margin: 1em auto; padding: 0 1em; color: #222; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; margin-top: 1.6em; }
table { border-collapse: collapse; margin: 0.6em 0; font-size: 0.92em; }
th, td { border: 1px solid #bbb; padding: 0.2em 0.6em; text-align: left; }
td.n { text-align: right; }
caption { caption-side: top; text-align: left; font-style: italic; padding-bottom: 0.3em; }
figure { margin: 0.8em 0; }
figure img { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 0.92em; color: #333; max-width: 60em; }
.row { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
.row figure { flex: 1 1 30em; max-width: 48%; }
.note { background: #fff6d6; border-left: 4px solid #e0b000; padding: 0.4em 0.8em; }
code { background: #f2f2f2; padding: 0 0.2em; }
nav ul { columns: 2; })";

// Counts the figures that displayed, on the window's load (report_html.h).
const char* kScript = R"(window.addEventListener('load', function () {
  var imgs = document.images, loaded = 0, failed = [];
  for (var i = 0; i < imgs.length; i++) {
    if (imgs[i].complete && imgs[i].naturalWidth > 0) loaded++;
    else failed.push(imgs[i].getAttribute('src'));
  }
  document.body.setAttribute('data-images', String(imgs.length));
  document.body.setAttribute('data-images-loaded', String(loaded));
  document.body.setAttribute('data-images-failed', failed.join(' '));
});)";

// A number, or an order and its amplitude ("2: 12.3"): right-aligned.
bool numeric(const std::string& c) {
  static const std::regex re("[-+]?[0-9][0-9.eE+-]*(: [0-9][0-9.eE+-]*)?");
  return std::regex_match(c, re);
}

}  // namespace

std::string escape(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (char c : s) switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      case '\'':
        o += "&#39;";
        break;
      default:
        o += c;
    }
  return o;
}

Page::Page(const std::string& title) : title_(title) {}

void Page::heading(int level, const std::string& text, const std::string& id) {
  const std::string h = "h" + std::to_string(level);
  body_ << "<" << h << (id.empty() ? "" : " id=\"" + escape(id) + "\"") << ">" << escape(text)
        << "</" << h << ">\n";
  if (level == 2 && !id.empty()) toc_.emplace_back(id, text);
}

void Page::paragraph(const std::string& html, const std::string& css_class) {
  body_ << "<p" << (css_class.empty() ? "" : " class=\"" + css_class + "\"") << ">" << html
        << "</p>\n";
}

void Page::table(const std::vector<std::string>& head,
                 const std::vector<std::vector<std::string>>& rows, const std::string& caption) {
  body_ << "<table>\n";
  if (!caption.empty()) body_ << "<caption>" << escape(caption) << "</caption>\n";
  body_ << "<thead><tr>";
  for (const auto& h : head) body_ << "<th>" << escape(h) << "</th>";
  body_ << "</tr></thead>\n<tbody>\n";
  for (const auto& r : rows) {
    body_ << "<tr>";
    for (const auto& c : r)
      body_ << (numeric(c) ? "<td class=\"n\">" : "<td>") << escape(c) << "</td>";
    body_ << "</tr>\n";
  }
  body_ << "</tbody>\n</table>\n";
}

void Page::figure(const std::string& file, const std::string& alt, const std::string& caption) {
  ++figures_;
  const std::filesystem::path p(file);
  const std::string gp = std::filesystem::path(p).replace_extension(".gp").string();
  const std::string dat = std::filesystem::path(p).replace_extension(".dat").string();
  body_ << "<figure id=\"fig" << figures_ << "\">\n<a href=\"" << escape(file) << "\"><img src=\""
        << escape(file) << "\" alt=\"" << escape(alt) << "\"></a>\n"
        << "<figcaption>Figure " << figures_ << ": " << escape(caption) << " (gnuplot <a href=\""
        << escape(gp) << "\">script</a> and <a href=\"" << escape(dat)
        << "\">data</a>)</figcaption>\n</figure>\n";
}

std::string Page::html() const {
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
    << "<meta name=\"generator\" content=\"evas report\">\n"
    << "<title>" << escape(title_) << "</title>\n<style>\n"
    << kStyle << "\n</style>\n<script>\n"
    << kScript << "\n</script>\n</head>\n<body>\n<h1>" << escape(title_) << "</h1>\n";
  if (!toc_.empty()) {
    o << "<nav>\n<ul>\n";
    for (const auto& [id, text] : toc_)
      o << "<li><a href=\"#" << escape(id) << "\">" << escape(text) << "</a></li>\n";
    o << "</ul>\n</nav>\n";
  }
  o << "<main>\n" << body_.str() << "</main>\n</body>\n</html>\n";
  return o.str();
}

}  // namespace evas::report
