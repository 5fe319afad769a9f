// gnuplot runner: writes a script, renders SVG and PNG under temporary names, renames on success.
#include "stiffpath/report/gnuplot.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::report {

bool gnuplot_available() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

namespace {
std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}
}  // namespace

std::string quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

void render(const std::filesystem::path& dir, const Figure& figure) {
  if (!gnuplot_available()) throw Error("gnuplot is not installed (scripts/bootstrap.sh installs gnuplot-nox)");
  const std::string stem = figure.name + ".tmp-" + std::to_string(::getpid());
  const std::filesystem::path script = dir / (stem + ".gp"), log = dir / (stem + ".log");
  {
    std::ofstream out(script);
    out << "set encoding utf8\n"
        << "set terminal svg size " << figure.width_px << "," << figure.height_px << " dynamic font 'sans,12'\n"
        << "set output " << quote(stem + ".svg") << "\n"
        << figure.commands << "\n"
        << "set terminal pngcairo size " << figure.width_px << "," << figure.height_px << " font 'sans,10'\n"
        << "set output " << quote(stem + ".png") << "\n"
        << figure.commands << "\nunset output\n";  // drawn again: replot would redo only a multiplot's last panel
  }
  const std::string command = "cd " + shell_quote(dir.string()) + " && gnuplot " +
                              shell_quote(script.filename().string()) + " >" + shell_quote(log.filename().string()) +
                              " 2>&1";
  const int status = std::system(command.c_str());
  std::ostringstream message;
  if (status != 0) message << std::ifstream(log).rdbuf();
  std::error_code ignored;
  std::filesystem::remove(script, ignored);
  std::filesystem::remove(log, ignored);
  const auto svg = dir / (stem + ".svg"), png = dir / (stem + ".png");
  if (status != 0 || !std::filesystem::exists(svg) || !std::filesystem::exists(png)) {
    std::filesystem::remove(svg, ignored);
    std::filesystem::remove(png, ignored);
    throw Error(SourceLocation{(dir / figure.name).string()}, "gnuplot failed: " + message.str());
  }
  std::filesystem::rename(svg, dir / (figure.name + ".svg"));
  std::filesystem::rename(png, dir / (figure.name + ".png"));
}

}  // namespace stiffpath::report
