// Test helper: a job's joint commands kept in memory (a JointWriter that keeps), and a program run into them.
#pragma once

#include <string>
#include <vector>

#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/job/prepared_job.hpp"

namespace stiffpath::test {

//! Keeps every command written to it.
class Keep final : public job::JointWriter {
 public:
  void write(const compensation::JointCommand& c) override { commands.push_back(c); }
  void finish() override {}
  std::vector<compensation::JointCommand> commands;
};

//! The joint commands `spec` makes of the G-code `text` (named `name` in messages).
inline std::vector<compensation::JointCommand> commands_of(const job::JobSpec& spec, const std::string& text,
                                                           const std::string& name = "job.gcode") {
  Keep keep;
  job::run(job::prepare(spec, job::Program::text(text, name)), &keep);
  return keep.commands;
}

}  // namespace stiffpath::test
