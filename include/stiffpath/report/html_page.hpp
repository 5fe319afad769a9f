// One self-contained HTML page (inline SVG figures, no network) assembled from sections.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace stiffpath::report {

//! A part of the page: a heading and its HTML body (built with the helpers below).
struct Section {
  std::string id;     //!< anchor, [a-z0-9-]
  std::string title;
  std::string html;
};

//! Escapes &, <, >, " and ' for HTML text and attribute values.
std::string escape_html(const std::string& text);

//! A table: a header row and rows of cells (escaped).
std::string html_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);

//! Plain text with Markdown tables (the experiment's summary.md) as HTML: each run of lines starting with '|' (a
//! header row, the |---| row, body rows) becomes an html_table, every other non-empty line a paragraph.
std::string markdown_html(const std::string& text);

//! The SVG file `svg` as a <figure> element with the drawing inline (XML prolog and doctype removed,
//! its ids prefixed with `key` so that several figures never share one) and a caption. Throws
//! stiffpath::Error when the file cannot be read or holds no <svg> element.
std::string inline_figure(const std::filesystem::path& svg, const std::string& key, const std::string& caption);

//! The whole page: title, table of contents, sections, and a script that, once the page has loaded,
//! checks every figure's drawing has a size and content, and writes "figures loaded: N/M" into the
//! element #report-status and the document title (read by the browser test, docs/figures.md).
std::string html_page(const std::string& title, const std::string& subtitle, const std::vector<Section>& sections);

}  // namespace stiffpath::report
