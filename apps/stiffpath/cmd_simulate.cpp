// `stiffpath simulate`: a joint trajectory from `stiffpath run` through the digital twin, measured like the thesis's marks.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <optional>

#include "bounded.hpp"
#include "commands.hpp"
#include "joint_robot.hpp"
#include "progress.hpp"
#include "robot_flags.hpp"
#include "twin_flags.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/job/joint_reader.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/evaluation/path_metrics.hpp"
#include "stiffpath/simulation/cg_lever.hpp"
#include "stiffpath/simulation/run_metrics.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::cli {

namespace {
using simulation::Vec2;

struct SimulateArgs {
  std::string joints;
  std::string robot;  // default: the binary file's robot (a preset), else oc-gu
  int sides = 0;  // 0: inferred per stroke from its commanded corners
  simulation::TrueComplianceOptions truth;
  TwinFlags twin;
  simulation::SimulationOptions sim;
  std::string marks_csv;
  double corner_trim_mm = 1.0;
  bool json = false, quiet = false;
  bool force_robot = false;
};

// The physical line of a joint CSV that holds record `record` (0-based): the reader skips blank and
// '#' lines, and the first line it keeps is the header. 0 when the file is shorter.
int csv_line_of(const std::string& path, std::size_t record) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t kept = 0;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos || line.front() == '#') continue;
    if (kept++ == record + 1) return number;
  }
  return 0;
}

// Where record `record` (0-based) of a joint file is, for an error message.
SourceLocation record_location(const std::string& path, const job::JointReader& reader, std::size_t record) {
  if (reader.binary()) return SourceLocation{path};
  return SourceLocation{path, csv_line_of(path, record), 0};
}

std::string record_name(const job::JointReader& reader, std::size_t record) {
  if (!reader.binary()) return fmt::format("record {}", record + 1);
  const bool v1 = reader.version() == 1;
  const std::uint64_t header = v1 ? job::kBinaryV1HeaderBytes : job::kBinaryHeaderBytes;
  const std::uint64_t bytes = v1 ? job::kBinaryV1RecordBytes : job::kBinaryRecordBytes;
  return fmt::format("record {} (byte {})", record + 1, header + record * bytes);
}

// The first and last record's times and the last record's index, read from the file's ends without
// reading it through (binary: the header's count; CSV: the first and the last data line). nullopt when
// they cannot be read so (the simulation still checks every record as it comes).
struct JobSpan {
  double first_s = 0.0, last_s = 0.0;
  std::size_t last_record = 0;
};
std::optional<JobSpan> job_span(const std::string& path, const job::JointReader& reader) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  JobSpan span;
  if (reader.binary()) {
    const bool v1 = reader.version() == 1;
    const std::uint64_t header = v1 ? job::kBinaryV1HeaderBytes : job::kBinaryHeaderBytes;
    const std::uint64_t bytes = v1 ? job::kBinaryV1RecordBytes : job::kBinaryRecordBytes;
    std::uint64_t count = 0;
    in.seekg(24);
    in.read(reinterpret_cast<char*>(&count), sizeof count);
    if (!in || count == 0) return std::nullopt;
    const auto time_at = [&](std::uint64_t k) -> std::optional<double> {
      double t = 0.0;
      in.seekg(static_cast<std::streamoff>(header + k * bytes));
      in.read(reinterpret_cast<char*>(&t), sizeof t);
      return in && std::isfinite(t) ? std::optional<double>(t) : std::nullopt;
    };
    const auto first = time_at(0), last = time_at(count - 1);
    if (!first || !last) return std::nullopt;
    span = {*first, *last, static_cast<std::size_t>(count - 1)};
    return span;
  }
  const auto time_of = [](const std::string& line) -> std::optional<double> {
    char* end = nullptr;
    const double t = std::strtod(line.c_str(), &end);
    return end != line.c_str() && std::isfinite(t) ? std::optional<double>(t) : std::nullopt;
  };
  std::string line;
  std::optional<double> first;
  bool header = false;
  while (!first && std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos || line.front() == '#') continue;
    if (!header) {
      header = true;
      continue;
    }
    first = time_of(line);
    if (!first) return std::nullopt;
  }
  if (!first) return std::nullopt;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return std::nullopt;
  const std::uint64_t tail = std::min<std::uint64_t>(size, 4096);
  in.clear();
  in.seekg(static_cast<std::streamoff>(size - tail));
  std::string text(tail, '\0');
  in.read(text.data(), static_cast<std::streamsize>(tail));
  text.resize(static_cast<std::size_t>(in.gcount()));
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
  const auto last = time_of(text.substr(text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1));
  if (!last) return std::nullopt;
  span.first_s = *first;
  span.last_s = *last;
  span.last_record = 0;  // counted only when it is named (an error)
  return span;
}

// The work budget, checked before the first step: the file's span at the step rate, with the settling.
void check_budget(const std::string& path, const job::JointReader& reader, const simulation::SimulationOptions& sim) {
  const auto span = job_span(path, reader);
  if (!span) return;
  const double rate = sim.plant.step_rate_hz;
  const double steps = (span->last_s - span->first_s) * rate + std::ceil(sim.settle_s * rate);
  if (!(steps > static_cast<double>(sim.max_steps))) return;
  std::size_t last = span->last_record;
  if (!reader.binary()) {  // count the records only now
    std::ifstream in(path, std::ios::binary);
    std::string line;
    std::size_t kept = 0;
    while (std::getline(in, line)) {
      if (line.find_first_not_of(" \t\r") == std::string::npos || line.front() == '#') continue;
      ++kept;
    }
    last = kept >= 2 ? kept - 2 : 0;
  }
  throw Error(record_location(path, reader, last),
              fmt::format("{} (the last, t = {:g} s): the job is {:.1f} s of motion, about {:.4g} integration steps at {:g} Hz, "
                          "more than the simulation's work budget of {} steps ({:.4g} s of motion; raise it with --max-steps)",
                          record_name(reader, last), span->last_s, span->last_s - span->first_s, steps, rate, sim.max_steps,
                          static_cast<double>(sim.max_steps) / rate));
}

// Records in a joint file, for the progress bar: from the size for the binary format (versions 1 and 2),
// lines for CSV.
double record_count(const std::string& path, const job::JointReader& reader) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec) return 1.0;
  if (reader.binary()) {
    const bool v1 = reader.version() == 1;
    const double header = v1 ? job::kBinaryV1HeaderBytes : job::kBinaryHeaderBytes;
    const double record = v1 ? job::kBinaryV1RecordBytes : job::kBinaryRecordBytes;
    return std::max(1.0, (static_cast<double>(bytes) - header) / record);
  }
  std::ifstream in(path, std::ios::binary);
  double lines = 0;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) lines += static_cast<double>(std::count(buffer, buffer + in.gcount(), '\n'));
  return std::max(1.0, lines - 1);
}

// The laser's mark as x_mm, y_mm in marking order, y flipped to the scan's downward axis, so that
// `stiffpath render-scan --path-csv` draws it as the paper would show it. Written stroke by stroke.
class MarksFile {
 public:
  explicit MarksFile(const std::string& path) : file_(path) { file_.stream() << "x_mm,y_mm\n"; }
  void add(const Vec2& p) { file_.stream() << fmt::format("{:.6f},{:.6f}\n", p.x() * 1e3, -p.y() * 1e3); }
  void commit() { file_.commit(); }

 private:
  core::AtomicFile file_;
};

// What `simulate` does with each stroke while it is marked: the meter measures it, the marks file (if
// any) writes its points, and the points are counted. Nothing of a stroke is kept.
class StrokeTap final : public simulation::StrokeObserver {
 public:
  StrokeTap(simulation::RunMeter& meter, std::optional<MarksFile>& marks) : meter_(meter), marks_(marks) {}
  void begin_stroke(std::size_t index, double t_s) override { meter_.begin_stroke(index, t_s); }
  void command(const Vec2& target_m) override { meter_.command(target_m); }
  void mark(const Vec2& tip_m) override {
    meter_.mark(tip_m);
    ++marked_points;
    if (marks_) marks_->add(tip_m);
  }
  void end_stroke(double t_s) override { meter_.end_stroke(t_s); }
  std::size_t marked_points = 0;

 private:
  simulation::RunMeter& meter_;
  std::optional<MarksFile>& marks_;
};

nlohmann::json mm(double value_m, bool valid = true) { return valid ? nlohmann::json(tidy(value_m * 1e3)) : nlohmann::json(nullptr); }

// The line metrics (null when refused), AT_p and the corner metrics (null without corners) of a job or a stroke.
void put_metrics(nlohmann::json& j, const simulation::RunMetrics& m, bool path_accuracy) {
  const bool line = m.line_strokes > 0;
  j["length_mm"] = mm(m.length_m, line);
  j["commanded_length_mm"] = mm(m.commanded_length_m, line);
  j["length_error_mm"] = mm(m.length_error_m, line);
  j["deviation_area_mm2"] = line ? nlohmann::json(tidy(m.deviation_area_m2 * 1e6)) : nlohmann::json(nullptr);
  j["max_deviation_mm"] = mm(m.max_deviation_m, line);
  j["path_accuracy_mm"] = mm(m.path_accuracy_m, path_accuracy);
  j["corners"] = m.corners;
  j["cornering_round_off_mm"] = mm(m.cornering_round_off_m, m.corners > 0);
  j["cornering_overshoot_mm"] = mm(m.cornering_overshoot_m, m.corners > 0);
}

void simulate(const SimulateArgs& a) {
  job::JointReader reader(a.joints);
  const kinematics::Robot robot = robot_for_joints(a.robot, reader, a.joints, a.force_robot, "simulates");
  core::check_distinct_files(robot_inputs(robot, true, {{"joints", a.joints}}), {{"--marks-csv", a.marks_csv}});
  simulation::TrueComplianceOptions truth_options = a.truth;
  simulation::SimulationOptions sim = a.sim;
  apply_twin_flags(a.twin, sim, truth_options);
  if (!a.twin.no_cg_lever) sim.cg_lever = simulation::make_cg_lever(robot);
  const auto truth = simulation::make_true_compliance(robot, truth_options);
  check_budget(a.joints, reader, sim);
  evaluation::PathMetricsOptions metrics;
  metrics.corner_trim_m = a.corner_trim_mm * 1e-3;
  simulation::RunMeter meter(a.sides, 100000, metrics);
  std::optional<MarksFile> marks;
  if (!a.marks_csv.empty()) marks.emplace(a.marks_csv);
  StrokeTap tap(meter, marks);
  Progress progress("simulate", a.quiet);
  const double total = progress.enabled() ? record_count(a.joints, reader) : 1.0;
  double done = 0;
  simulation::SimulationResult run;
  try {
    run = simulation::simulate(
        [&] {
          if (++done == 1 || static_cast<long>(done) % 2048 == 0) progress.update(done / total);
          return reader.next();
        },
        robot, truth, sim, static_cast<simulation::StrokeObserver&>(tap));
  } catch (const simulation::RecordRefused& e) {
    throw Error(record_location(a.joints, reader, e.record()),
                fmt::format("{}: RANGE: {}", record_name(reader, e.record()), e.message()));
  }
  const std::size_t marked_points = tap.marked_points;
  progress.finish();
  const simulation::RunMetrics m = meter.totals(run);
  if (marks) marks->commit();
  if (a.json) {
    nlohmann::json j{{"joints", a.joints}, {"robot", robot.name}, {"duration_s", tidy(run.duration_s)},
                     {"marked_points", marked_points}};
    put_metrics(j, m, true);
    j["residual_vibration_mm"] = tidy(m.residual_vibration_m * 1e3);
    j["peak_deflection_mm"] = tidy(m.peak_deflection_m * 1e3);
    j["strokes"] = meter.stroke_count();
    j["line_strokes"] = m.line_strokes;
    // The stroke list is written one stroke at a time: a document of a long job's thousands of strokes
    // would cost more memory than the simulation.
    std::string head = j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);  // a file name may not be UTF-8
    head.resize(head.rfind('}'));
    while (!head.empty() && head.back() == '\n') head.pop_back();
    std::cout << head << ",\n  \"stroke_metrics\": [";
    bool first = true;
    for (const auto& s : meter.strokes()) {
      nlohmann::json one{{"stroke", s.index + 1}, {"start_s", tidy(s.start_s)}, {"end_s", tidy(s.end_s)},
                         {"marked_points", s.marked_points}, {"sides", s.sides}};
      put_metrics(one, s.metrics, s.path_accuracy);
      if (!s.refusal.empty()) one["refusal"] = s.refusal;
      std::cout << (first ? "\n    " : ",\n    ") << one.dump();
      first = false;
    }
    std::cout << (first ? "]\n}\n" : "\n  ]\n}\n");
    return;
  }
  fmt::print("{}: simulated {:.4f} s on {} (C_true {} perturbed {:g}, seed {}; {} servo{}), {} laser stroke{}\n",
             a.joints, run.duration_s, robot.name, core::enum_name(truth_options.family), truth_options.perturbation, truth_options.seed,
             a.twin.servo, sim.cg_lever ? ", CG lever" : "", meter.stroke_count(), meter.stroke_count() == 1 ? "" : "s");
  if (m.line_strokes > 0) {
    const std::string over = m.line_strokes == 1 && meter.stroke_count() == 1
                                 ? std::string()
                                 : fmt::format(" (summed over {} of {} strokes)", m.line_strokes, meter.stroke_count());
    fmt::print("  length {:.4f} mm (commanded {:.4f} mm, error {:+.4f} mm){}\n", m.length_m * 1e3,
               m.commanded_length_m * 1e3, m.length_error_m * 1e3, over);
    fmt::print("  deviation area {:.4f} mm^2, max deviation {:.4f} mm\n", m.deviation_area_m2 * 1e6,
               m.max_deviation_m * 1e3);
  }
  for (const auto& s : meter.strokes()) {
    if (!s.refusal.empty()) fmt::print("  stroke {}: no line metrics: {}\n", s.index + 1, s.refusal);
  }
  fmt::print("  path accuracy AT_p {:.4f} mm (largest over the strokes)\n", m.path_accuracy_m * 1e3);
  if (m.corners > 0) {
    fmt::print("  {} corners: round-off CR {:.4f} mm, overshoot CO {:.4f} mm (largest)\n", m.corners,
               m.cornering_round_off_m * 1e3, m.cornering_overshoot_m * 1e3);
  }
  fmt::print("  peak tip deflection {:.4f} mm, residual vibration {:.4f} mm\n", m.peak_deflection_m * 1e3,
             m.residual_vibration_m * 1e3);
}
}  // namespace

void add_simulate_command(CLI::App& app) {
  auto a = std::make_shared<SimulateArgs>();
  auto* cmd = app.add_subcommand("simulate", "Run a joint trajectory (from `run`) on the digital twin and measure the mark");
  cmd->add_option("joints", a->joints, "Joint trajectory file (CSV or binary)")->required();
  add_robot_flag(cmd, a->robot)->description("Robot (preset or file) the joints were made for (default: the preset the file "
                                            "records, else oc-gu); its data give C_true");
  cmd->add_option("--sides", a->sides, "Straight sides of each laser stroke: 1 (line), 3 (triangle); 0 infers "
                                      "them from the stroke's sharp corners")
      ->check(CLI::Range(0, 12))->capture_default_str();
  cmd->add_option("--seed", a->truth.seed, "Seed of the perturbation")->capture_default_str();
  add_twin_flags(cmd, a->twin, a->sim, a->truth);
  cmd->add_option("--marks-csv", a->marks_csv, "Also write the mark (x_mm, y_mm, y down) for `render-scan --path-csv`")->check(output_name());
  cmd->add_option("--corner-trim-mm", a->corner_trim_mm,
                  "Points this close to a corner are left out of the sides' lines and splines (mm), as for scan")
      ->check(within(0.0, 1000.0, "mm"))->capture_default_str();
  cmd->add_option("--max-steps", a->sim.max_steps,
                  "Work budget: the most integration steps the job may take (at the default 20 kHz, 3e8 is 4 h 10 min "
                  "of motion); a longer job is refused before it starts")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{100'000'000'000}))->capture_default_str();
  cmd->add_flag("--force-robot", a->force_robot, "Simulate a joint file written for another robot anyway");
  cmd->add_flag("--json", a->json, "Print the metrics as JSON");
  cmd->add_flag("--quiet", a->quiet, "No progress bar (it is shown only on a terminal anyway)");
  cmd->callback([a] { simulate(*a); });
}

}  // namespace stiffpath::cli
