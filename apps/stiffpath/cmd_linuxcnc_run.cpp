// `stiffpath linuxcnc run`: one G-code job through a configuration of `linuxcnc config`, headless, recorded each period.
#include <fmt/format.h>
#include <memory>

#include "cmd_linuxcnc.hpp"
#include "cmd_linuxcnc_compare.hpp"
#include "cmd_linuxcnc_record.hpp"
#include "cmd_linuxcnc_routes.hpp"
#include "cmd_linuxcnc_session.hpp"
#include "commands.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"

namespace stiffpath::cli::linuxcnc {

namespace {

constexpr std::uintmax_t kMaxJobBytes = 64u << 20;  // LinuxCNC reads the program itself; a bound for the copy
constexpr double kMaxTimeout_s = 3600.0;

struct RunArgs {
  std::string config;  // the folder of `linuxcnc config`, or its INI file
  std::string job;
  std::string route = "linuxcnc";
  std::string record;
  std::string compare;
  std::string user;
  std::string work_dir;
  double timeout_s = 300.0;
  std::vector<std::string> run_options;  // after --: for `stiffpath run`
};

void print_summary(const char* route, const std::vector<RecordRow>& rows, double period_s) {
  std::size_t on = 0;
  for (const auto& r : rows) on += r.laser;
  fmt::print("  {}: {} servo periods ({:.4f} s), laser on for {} ({:.4f} s)\n", route, rows.size(),
             static_cast<double>(rows.size()) * period_s, on, static_cast<double>(on) * period_s);
}

void run(const RunArgs& a) {
  const Machine m = read_machine(a.config);
  if (!(a.timeout_s > 0.0 && a.timeout_s <= kMaxTimeout_s)) throw Error(fmt::format("--timeout: must be within (0, {:g}] s, got {}", kMaxTimeout_s, a.timeout_s));
  std::error_code ec;
  const auto job_size = fs::file_size(a.job, ec);
  if (ec) throw Error(SourceLocation{a.job}, "cannot read the job: " + ec.message());
  if (job_size > kMaxJobBytes) throw Error(SourceLocation{a.job}, fmt::format("{} bytes: a job is at most 64 MiB here", job_size));
  const bool both = !a.compare.empty();
  if (both && !a.record.empty()) throw Error("--record and --compare: --compare writes both routes' records into its folder");
  if (!a.run_options.empty() && a.route == "linuxcnc" && !both) {
    throw Error("options after -- are for `stiffpath run`, which only the streamed route (--route stiffpath) or --compare uses");
  }
  if (!a.record.empty()) core::check_output_directory(fs::absolute(a.record).parent_path());
  std::unique_ptr<AtomicDirectory> compare_dir;
  if (both) compare_dir = std::make_unique<AtomicDirectory>(a.compare);
  check_linuxcnc_installed();
  const RunUser user = choose_user(a.user);
  WorkDir work(a.work_dir);
  const fs::path job = work.path / "job.ngc";
  fs::copy_file(a.job, job);
  const double period_s = static_cast<double>(m.period_ns) * 1e-9;

  fmt::print("{} in {} ({}):\n", a.job, m.ini.string(), m.robot.name);
  std::vector<RecordRow> linuxcnc_rows, stiffpath_rows;
  if (both || a.route == "linuxcnc") {
    linuxcnc_rows = run_linuxcnc_route(m, job, user, work, a.timeout_s);
    print_summary("LinuxCNC plans (stiffpathkins, stiffpathcomp, stiffpathlaser)", linuxcnc_rows, period_s);
  }
  if (both || a.route == "stiffpath") {
    stiffpath_rows = run_stiffpath_route(m, job, a.run_options, user, work);
    print_summary("stiffpath plans (stiffpath run, streamer)", stiffpath_rows, period_s);
  }
  if (!a.record.empty()) {
    write_record_csv(a.record, a.route == "linuxcnc" ? linuxcnc_rows : stiffpath_rows);
    fmt::print("  wrote {}\n", a.record);
  }
  if (both) {
    const fs::path dir = compare_dir->path();
    write_record_csv(dir / "linuxcnc.csv", linuxcnc_rows);
    write_record_csv(dir / "stiffpath.csv", stiffpath_rows);
    bool figure = false;
    const Comparison c = compare_routes(linuxcnc_rows, stiffpath_rows, m.robot, period_s, dir, figure);
    const nlohmann::json summary{
        {"job", a.job},
        {"robot", m.robot.name},
        {"comparable", c.comparable},
        {"largest_difference_um", c.comparable ? nlohmann::json(tidy(c.largest_difference_um)) : nlohmann::json(nullptr)},
        {"at_stretch", c.at_interval + 1},
        {"at_stretch_mm", tidy(c.at_path_mm)},
        {"laser_stretches", c.routes[0].intervals},
        {"routes",
         {{"linuxcnc",
           {{"duration_s", tidy(c.routes[0].duration_s)}, {"laser_s", tidy(c.routes[0].laser_s)},
            {"laser_path_mm", tidy(c.routes[0].laser_path_mm)}, {"largest_correction_um", tidy(c.routes[0].largest_correction_um)}}},
          {"stiffpath",
           {{"duration_s", tidy(c.routes[1].duration_s)}, {"laser_s", tidy(c.routes[1].laser_s)},
            {"laser_path_mm", tidy(c.routes[1].laser_path_mm)}, {"largest_correction_um", tidy(c.routes[1].largest_correction_um)}}}}}};
    core::write_file_atomically(dir / "compare.json", summary.dump(2) + "\n");
    compare_dir->commit();
    if (!c.comparable) {
      fmt::print(stderr, "warning: the routes switch the laser on {} and {} times: their laser paths cannot be paired, "
                         "so there is no difference and no figure\n", c.routes[0].intervals, c.routes[1].intervals);
    } else {
      fmt::print("  the two routes' commanded tool paths lie up to {:.1f} um apart (laser-on stretch {}, {:.1f} mm from its start); "
               "laser on over {:.1f} / {:.1f} mm for {:.4f} / {:.4f} s\n",
               c.largest_difference_um, c.at_interval + 1, c.at_path_mm, c.routes[0].laser_path_mm, c.routes[1].laser_path_mm,
               c.routes[0].laser_s, c.routes[1].laser_s);
    }
    fmt::print("  wrote {}/ (linuxcnc.csv, stiffpath.csv, compare.json{})\n", a.compare, figure ? ", compare.svg, compare.png" : "");
  }
  if (work.keep) fmt::print("  kept the work folder {}\n", work.path.string());
}

}  // namespace

void add_run_command(CLI::App& linuxcnc) {
  auto a = std::make_shared<RunArgs>();
  auto* cmd = linuxcnc.add_subcommand("run", "Run a G-code job in LinuxCNC headless (as root too) and record every servo period");
  cmd->add_option("config", a->config, "The folder written by `stiffpath linuxcnc config` (or its INI file)")->required();
  cmd->add_option("job", a->job, "G-code program")->required();
  cmd->add_option("run_options", a->run_options, "After --: options for `stiffpath run` (the streamed route)");
  cmd->add_option("--route", a->route,
                  "linuxcnc: LinuxCNC interprets and plans, stiffpathcomp corrects; stiffpath: `stiffpath run` plans and "
                  "compensates, streamer plays it")
      ->check(CLI::IsMember({"linuxcnc", "stiffpath"}))
      ->capture_default_str();
  cmd->add_option("--record", a->record, "CSV of every servo period: t_s,theta1_rad,theta2_rad,laser,power,x_mm,y_mm");
  cmd->add_option("--compare", a->compare,
                  "Run both routes and write their records, the difference and a figure into this new folder");
  cmd->add_option("--user", a->user, "As root: the unprivileged user LinuxCNC runs as (default: SUDO_USER, else 'stiffpath')");
  cmd->add_option("--work-dir", a->work_dir, "Keep LinuxCNC's files, logs and raw recordings in this new folder");
  cmd->add_option("--timeout", a->timeout_s, "Longest time the job may take in LinuxCNC (s)")->capture_default_str();
  cmd->callback([a] { run(*a); });
}

}  // namespace stiffpath::cli::linuxcnc

