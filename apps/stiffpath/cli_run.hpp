// What the two CLI programs share besides the subcommands: the runner and the hand-over of the image commands.
#pragma once

#include <CLI/CLI.hpp>

namespace stiffpath::cli {

//! scan and render-scan in the stiffpath program: they run stiffpath-vision (the only program that loads OpenCV)
//! with their arguments.
void add_vision_commands(CLI::App& app);

//! Parses the command line and runs the subcommand; returns the exit code (0, 2 for bad input, 1 for an internal
//! error), printing errors as "error: …" lines or, for --json commands, as one JSON document on stderr.
int run(CLI::App& app, int argc, char** argv);

}  // namespace stiffpath::cli
