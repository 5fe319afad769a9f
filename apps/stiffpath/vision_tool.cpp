// The subcommands that read or write images (scan, render-scan) run in their own program, stiffpath-vision, so that
// only they load OpenCV: here they are registered by name and hand their arguments over to it unchanged.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <vector>

#include "cli_run.hpp"
#include "commands.hpp"

namespace stiffpath::cli {

// Replaces this process with stiffpath-vision (beside this program, at the same place as in the install tree), so
// its output, exit code and signals are the command's own. Returns only when the program cannot be started.
void run_vision_tool(const std::vector<std::string>& arguments) {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  const std::filesystem::path tool = (error ? std::filesystem::path(".") : self.parent_path()) / STIFFPATH_VISION_TOOL;
  std::vector<std::string> words{"stiffpath"};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  std::cout.flush();
  ::execv(tool.c_str(), argv.data());
  throw std::runtime_error("cannot run " + tool.string() + " (the scan, render-scan and calibrate fit commands): " +
                           std::strerror(errno));
}

void add_vision_commands(CLI::App& app) {
  const std::pair<const char*, const char*> commands[] = {
      {"scan", "Measure a laser-marked path on a scan (thesis 4.6): length, deviation area, width"},
      {"render-scan",
       "Draw a synthetic scan of a laser-marked path (or a plate of marks) and print its ground truth"}};
  for (const auto& [name, description] : commands) {
    auto* cmd = app.add_subcommand(name, description);
    cmd->prefix_command();  // every argument, --help included, belongs to stiffpath-vision
    cmd->set_help_flag();
    const std::string command = name;
    cmd->callback([cmd, command] {
      std::vector<std::string> words{command};
      const auto rest = cmd->remaining();
      words.insert(words.end(), rest.begin(), rest.end());
      run_vision_tool(words);
    });
  }
}

}  // namespace stiffpath::cli
