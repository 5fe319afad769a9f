// Rendering plots with gnuplot (run as an external program) to SVG and PNG, written atomically.
#pragma once

#include <filesystem>
#include <string>

namespace stiffpath::report {

//! A figure: gnuplot commands that draw it (no `set terminal`/`set output`), and the data files they
//! read, already written into the output directory.
struct Figure {
  std::string name;         //!< base file name: <dir>/<name>.svg and <dir>/<name>.png
  std::string commands;     //!< e.g. "set xlabel 'x (mm)'\nplot 'data.tsv' using 1:2 with lines"
  int width_px = 900;
  int height_px = 650;
};

//! True when a `gnuplot` executable is on the PATH.
bool gnuplot_available();

//! Renders `figure` into `dir` as SVG and PNG. Runs gnuplot with `dir` as working directory, so data
//! files are named relative to it. Throws stiffpath::Error with gnuplot's message if it fails; in that
//! case neither output file is left behind.
void render(const std::filesystem::path& dir, const Figure& figure);

//! Quotes a string for a gnuplot script ('…' with embedded quotes doubled).
std::string quote(const std::string& text);

}  // namespace stiffpath::report
