// gnuplot runner: writes a script, renders SVG and PNG under temporary names, renames on success, keeps the script.
#include "stiffpath/report/gnuplot.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::report {

bool gnuplot_available() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

Style parse_style(const std::string& text) {
  if (text == "screen") return Style::screen;
  if (text == "paper") return Style::paper;
  throw Error(fmt::format("unknown figure style '{}' (known: screen, paper)", text));
}

namespace {
std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Terminal lines for one output format. The output name can be overridden with -e "svg_out='…'" (render()
// does, to write under temporary names); run by hand the script writes <name>.svg / <name>.png.
std::string terminal(const Figure& f, bool svg) {
  const bool paper = f.style == Style::paper;
  const std::string font = paper ? (svg ? "serif,18" : "serif,16") : (svg ? "sans,12" : "sans,10");
  std::string out = svg ? fmt::format("set terminal svg size {},{} dynamic font '{}' noenhanced{}\n", f.width_px,
                                      f.height_px, font, paper ? " linewidth 1.5" : "")
                        : fmt::format("set terminal pngcairo size {},{} font '{}' noenhanced{}\n", f.width_px,
                                      f.height_px, font, paper ? " mono linewidth 1.5" : "");
  const char* var = svg ? "svg_out" : "png_out";
  out += fmt::format("set output (exists('{0}') ? {0} : {1})\n", var, quote(f.name + (svg ? ".svg" : ".png")));
  return out;
}
}  // namespace

std::string quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string script(const Figure& f) {
  std::string out = fmt::format("# {}: drawn by stiffpath; edit and run `gnuplot {}.gp` in this folder to redraw.\n"
                                "set encoding utf8\n",
                                f.name, f.name);
  if (f.style == Style::paper) {
    // Black and white: dash patterns and point shapes tell the series apart, grey heat maps.
    out += "set monochrome\nset palette gray negative\n";
  }
  out += terminal(f, true) + f.commands + "\n";
  out += "reset\nset encoding utf8\n";
  if (f.style == Style::paper) out += "set monochrome\nset palette gray negative\n";
  // Drawn again rather than replotted: replot would redo only a multiplot's last panel.
  out += terminal(f, false) + f.commands + "\nunset output\n";
  return out;
}

void render(const std::filesystem::path& dir, const Figure& figure) {
  if (!gnuplot_available()) throw Error("gnuplot is not installed (scripts/bootstrap.sh installs gnuplot-nox)");
  const std::string stem = figure.name + ".tmp-" + std::to_string(::getpid());
  const std::filesystem::path script_file = dir / (stem + ".gp"), log = dir / (stem + ".log");
  {
    std::ofstream out(script_file);
    out << script(figure);
  }
  const std::string command = fmt::format("cd {} && gnuplot -e {} {} >{} 2>&1", shell_quote(dir.string()),
                                          shell_quote(fmt::format("svg_out='{0}.svg'; png_out='{0}.png'", stem)),
                                          shell_quote(script_file.filename().string()),
                                          shell_quote(log.filename().string()));
  const int status = std::system(command.c_str());
  std::ostringstream message;
  if (status != 0) message << std::ifstream(log).rdbuf();
  std::error_code ignored;
  std::filesystem::remove(log, ignored);
  const auto svg = dir / (stem + ".svg"), png = dir / (stem + ".png");
  if (status != 0 || !std::filesystem::exists(svg) || !std::filesystem::exists(png)) {
    std::filesystem::remove(script_file, ignored);
    std::filesystem::remove(svg, ignored);
    std::filesystem::remove(png, ignored);
    throw Error(SourceLocation{(dir / figure.name).string()}, "gnuplot failed: " + message.str());
  }
  std::filesystem::rename(svg, dir / (figure.name + ".svg"));
  std::filesystem::rename(png, dir / (figure.name + ".png"));
  std::filesystem::rename(script_file, dir / (figure.name + ".gp"));
}

}  // namespace stiffpath::report
