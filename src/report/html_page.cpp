// HTML page assembly for `stiffpath report`: escaping, tables, inline SVG figures and the self-check script.
#include "stiffpath/report/html_page.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "stiffpath/core/error.hpp"

namespace stiffpath::report {

std::string escape_html(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string html_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  std::string out = "<table>\n<tr>";
  for (const auto& h : header) out += "<th>" + escape_html(h) + "</th>";
  out += "</tr>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (const auto& cell : row) out += "<td>" + escape_html(cell) + "</td>";
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

namespace {
// The cells of a Markdown table row "| a | b |", trimmed.
std::vector<std::string> markdown_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = line.find('|') + 1;
  for (std::size_t bar = line.find('|', start); bar != std::string::npos; bar = line.find('|', start)) {
    std::string cell = line.substr(start, bar - start);
    const auto first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
    cells.push_back(first == std::string::npos ? std::string() : cell.substr(first, last - first + 1));
    start = bar + 1;
  }
  return cells;
}
}  // namespace

std::string markdown_html(const std::string& text) {
  std::string out;
  std::vector<std::string> lines;
  for (std::size_t at = 0; at <= text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    lines.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  for (std::size_t i = 0; i < lines.size();) {
    if (lines[i].starts_with('|')) {
      const std::vector<std::string> header = markdown_cells(lines[i++]);
      if (i < lines.size() && lines[i].starts_with("|-")) ++i;  // the |---| row
      std::vector<std::vector<std::string>> rows;
      while (i < lines.size() && lines[i].starts_with('|')) rows.push_back(markdown_cells(lines[i++]));
      out += html_table(header, rows);
    } else {
      if (!lines[i].empty()) out += "<p>" + escape_html(lines[i]) + "</p>\n";
      ++i;
    }
  }
  return out;
}

namespace {
void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
}
}  // namespace

std::string inline_figure(const std::filesystem::path& svg, const std::string& key, const std::string& caption) {
  std::ifstream in(svg, std::ios::binary);
  if (!in) throw Error(SourceLocation{svg.string()}, "cannot read the figure");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  const auto start = text.find("<svg");
  if (start == std::string::npos) throw Error(SourceLocation{svg.string()}, "no <svg> element in the figure");
  text.erase(0, start);
  // gnuplot names its markers and canvas with fixed ids (gpPt0, gnuplot_canvas, …): made unique per figure.
  for (const char* quote : {"'", "\""}) {
    replace_all(text, std::string("id=") + quote, std::string("id=") + quote + key + "-");
    replace_all(text, std::string("href=") + quote + "#", std::string("href=") + quote + "#" + key + "-");
  }
  replace_all(text, "url(#", "url(#" + key + "-");
  return fmt::format("<figure data-figure=\"{}\">\n{}\n<figcaption>{}</figcaption>\n</figure>\n", escape_html(key), text,
                     escape_html(caption));
}

std::string html_page(const std::string& title, const std::string& subtitle, const std::vector<Section>& sections) {
  std::string toc, body;
  for (const auto& s : sections) {
    toc += fmt::format("<li><a href=\"#{}\">{}</a></li>", s.id, escape_html(s.title));
    body += fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n{}</section>\n", s.id, escape_html(s.title), s.html);
  }
  return fmt::format(R"(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{title}</title>
<style>
body {{ font-family: sans-serif; max-width: 1150px; margin: 2em auto; padding: 0 1em; color: #222; }}
h1 {{ margin-bottom: 0.2em; }} .subtitle {{ color: #555; margin-top: 0; }}
table {{ border-collapse: collapse; margin: 0.8em 0; font-size: 0.92em; }}
th, td {{ border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: left; }} th {{ background: #eee; }}
code, .hash {{ font-family: monospace; font-size: 0.9em; word-break: break-all; }}
figure {{ margin: 1em 0; border: 1px solid #ddd; padding: 0.5em; }}
figure svg {{ width: 100%; height: auto; display: block; }}
figcaption {{ color: #444; font-size: 0.9em; margin-top: 0.3em; }}
pre {{ background: #f6f6f6; padding: 0.6em; overflow-x: auto; font-size: 0.85em; }}
#report-status {{ color: #555; font-size: 0.85em; }}
</style>
</head>
<body>
<h1>{title}</h1>
<p class="subtitle">{subtitle}</p>
<p id="report-status">figures not checked (scripts disabled)</p>
<nav><ul>{toc}</ul></nav>
{body}<script>
window.addEventListener('load', function () {{
  var figures = document.querySelectorAll('figure[data-figure]'), ok = 0, bad = [];
  figures.forEach(function (f) {{
    var svg = f.querySelector('svg'), box = svg ? svg.getBoundingClientRect() : null, inner = null;
    try {{ inner = svg ? svg.getBBox() : null; }} catch (e) {{ inner = null; }}
    var drawn = svg && box.width > 50 && box.height > 50 && inner && inner.width > 10 && inner.height > 10 &&
                svg.querySelectorAll('path, text').length > 5;
    if (drawn) ok++; else bad.push(f.getAttribute('data-figure'));
  }});
  var status = 'figures loaded: ' + ok + '/' + figures.length + (bad.length ? ' (not drawn: ' + bad.join(', ') + ')' : '');
  var p = document.getElementById('report-status');
  p.textContent = status;
  p.setAttribute('data-loaded', ok);
  p.setAttribute('data-total', figures.length);
  document.title = document.title + ' [' + status + ']';
}});
</script>
</body>
</html>
)",
                     fmt::arg("title", escape_html(title)), fmt::arg("subtitle", escape_html(subtitle)),
                     fmt::arg("toc", toc), fmt::arg("body", body));
}

}  // namespace stiffpath::report
