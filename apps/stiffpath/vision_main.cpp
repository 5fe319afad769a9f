// stiffpath-vision: the image subcommands (scan, render-scan, calibrate fit) in a program of their own, the one that links OpenCV;
// `stiffpath scan …` and `stiffpath render-scan …` run it with their arguments.
#include "cli_run.hpp"
#include "commands.hpp"
#include "stiffpath/core/signal_cleanup.hpp"

int main(int argc, char** argv) {
  stiffpath::core::install_signal_cleanup();  // an interrupted render leaves no temporary file
  CLI::App app{"stiffpath: compliance compensation for high-acceleration planar parallel robots", "stiffpath"};
  app.require_subcommand(1);
  stiffpath::cli::add_scan_command(app);
  stiffpath::cli::add_render_scan_command(app);
  stiffpath::cli::add_calibrate_fit_command(app);  // calibrate fit: reads the plate's scan
  return stiffpath::cli::run(app, argc, argv);
}
