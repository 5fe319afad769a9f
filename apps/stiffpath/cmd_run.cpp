// `stiffpath run`: the main job — G-code to compensated joint commands (thesis fig. 4.3); flags onto job::JobSpec.
#include <iostream>
#include <memory>

#include "bounded.hpp"
#include "commands.hpp"
#include "job_flags.hpp"
#include "job_summary.hpp"
#include "progress.hpp"
#include "robot_flags.hpp"
#include "stiffpath/core/distinct_files.hpp"

namespace stiffpath::cli {

namespace {
struct RunArgs {
  std::string job, output;
  bool json = false, quiet = false;
  JobFlags flags;
};

void run(const RunArgs& a) {
  job::JobSpec spec = job_spec(a.flags);
  core::check_distinct_files(robot_inputs(spec.robot, true, {{"gcode", a.job}, {"--model", a.flags.model.model}}),
                             {{"-o", a.output}});
  const job::PreparedJob prepared = job::prepare(std::move(spec), job::Program::file(a.job));
  std::unique_ptr<job::JointWriter> writer;
  if (!a.output.empty()) {
    job::check_output(prepared, a.output);
    const auto& robot = prepared.spec.robot;
    writer = job::make_joint_writer(prepared.spec.format, a.output, prepared.spec.plan.rate_hz,
                                    {robot.name, robot.geometry_hash()});
  }
  Progress bar("run", a.quiet);
  const job::JobSummary summary = job::run(prepared, writer.get(), job_progress(a.job, bar));
  bar.finish();
  if (a.json) {  // with -o - the joint records own standard output, so the summary goes to standard error
    (a.output == "-" ? std::cerr : std::cout) << dump_json(job_summary_json(prepared, summary, a.output)) << '\n';
  } else {
    print_job_summary(a.output == "-" ? stderr : stdout, prepared, summary, a.output);
  }
}
}  // namespace

void add_run_command(CLI::App& app) {
  auto a = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand("run", "The main job: G-code -> compliance-compensated joint commands (fig. 4.3)");
  cmd->add_option("job", a->job, "G-code program")->required();
  add_job_flags(cmd, a->flags);
  cmd->add_option("-o,--output", a->output, "Joint trajectory file (written atomically; - for standard output)")->check(output_name());
  cmd->add_flag("--json", a->json, "Print the summary as JSON");
  cmd->add_flag("--quiet", a->quiet, "No progress bar (it is shown only on a terminal anyway)");
  cmd->callback([a] { run(*a); });
}

}  // namespace stiffpath::cli
