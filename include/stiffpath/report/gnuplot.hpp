// Rendering plots with gnuplot (run as an external program) to SVG and PNG, written atomically, script kept.
#pragma once

#include <filesystem>
#include <string>

namespace stiffpath::report {

//! How figures look: `screen` (colour, 12 pt sans) or `paper` (black and white with dash patterns
//! and point shapes, 18 pt serif), for the printed page.
enum class Style { screen, paper };
//! "screen" | "paper"; throws stiffpath::Error naming the known styles otherwise.
Style parse_style(const std::string& text);

//! A figure: gnuplot commands that draw it (no `set terminal`/`set output`), and the data files they
//! read, already written into the output directory.
struct Figure {
  std::string name;         //!< base file name: <dir>/<name>.svg, <dir>/<name>.png and the script <dir>/<name>.gp
  std::string commands;     //!< e.g. "set xlabel 'x (mm)'\nplot 'data.tsv' using 1:2 with lines"
  int width_px = 900;
  int height_px = 650;
  Style style = Style::screen;
};

//! True when a `gnuplot` executable is on the PATH.
bool gnuplot_available();

//! The whole gnuplot script of `figure`: terminal settings of its style, text taken literally (no
//! enhanced-text markup, so `a_b` stays `a_b`), the commands drawn once to <name>.svg and once to
//! <name>.png. Run in the figure's directory with `gnuplot <name>.gp` it redraws both files.
std::string script(const Figure& figure);

//! Renders `figure` into `dir` as SVG and PNG and keeps its script as <name>.gp beside them, for
//! restyling. Runs gnuplot with `dir` as working directory, so data files are named relative to it.
//! Throws stiffpath::Error with gnuplot's message if it fails; in that case no output file is left behind.
void render(const std::filesystem::path& dir, const Figure& figure);

//! Quotes a string for a gnuplot script ('…' with embedded quotes doubled).
std::string quote(const std::string& text);

}  // namespace stiffpath::report
