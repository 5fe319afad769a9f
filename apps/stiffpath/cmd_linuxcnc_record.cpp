// The recordings of `stiffpath linuxcnc run`: halsampler's lines in, one CSV row per servo period out.
#include "cmd_linuxcnc_record.hpp"

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <numbers>
#include <sstream>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/job/joint_reader.hpp"

namespace stiffpath::cli::linuxcnc {

namespace fs = std::filesystem;

namespace {

constexpr double kRadPerMillidegree = std::numbers::pi / 180.0 * 1e-3;

// The numbers of one halsampler line; an "overrun" line means lost samples.
std::vector<double> fields(const std::string& line, const fs::path& file, int number, std::size_t expected) {
  if (line.find("overrun") != std::string::npos) {
    throw Error(SourceLocation{file.string(), number, 1}, "halsampler lost samples (overrun): the machine was too busy to record");
  }
  std::istringstream in(line);
  std::vector<double> values;
  for (double v = 0.0; in >> v;) values.push_back(v);
  if (values.size() < expected || !in.eof()) {
    throw Error(SourceLocation{file.string(), number, 1}, fmt::format("expected {} numbers, got '{}'", expected, line));
  }
  for (const double v : values) {
    if (!std::isfinite(v)) throw Error(SourceLocation{file.string(), number, 1}, "a value is not finite: '" + line + "'");
  }
  return values;
}

}  // namespace

std::vector<RecordRow> read_machine_record(const fs::path& file, const kinematics::Robot& robot, double period_s) {
  std::ifstream in(file);
  if (!in) throw Error(SourceLocation{file.string()}, "no recording (LinuxCNC did not run the job)");
  const auto five_bar = robot.five_bar();
  std::vector<RecordRow> rows;
  double first = 0.0, last = 0.0;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const auto v = fields(line, file, number, 16);
    if (rows.empty()) first = v[0];
    if (!rows.empty() && v[0] != last + 1) {
      throw Error(SourceLocation{file.string(), number, 1}, fmt::format("sample {} follows {}: the recording skips periods", v[0], last));
    }
    last = v[0];
    RecordRow r;
    r.t_s = (v[0] - first) * period_s;
    const kinematics::Vec2 planned_rad(v[3] * kRadPerMillidegree, v[4] * kRadPerMillidegree);
    for (int j = 0; j < 2; ++j) {
      const double motor_offset_mdeg = v[5 + j] - v[3 + j];
      r.theta_rad[j] = (v[7 + j] - motor_offset_mdeg) * kRadPerMillidegree;
    }
    r.laser = v[14] != 0.0;
    r.power = v[15];
    const kinematics::Vec2 p = five_bar.forward(planned_rad);
    r.x_mm = units::m_to_mm(p.x());
    r.y_mm = units::m_to_mm(p.y());
    rows.push_back(r);
  }
  if (rows.empty()) throw Error(SourceLocation{file.string()}, "the recording is empty");
  return rows;
}

std::vector<RecordRow> read_stream_record(const fs::path& file, const fs::path& joint_file, double period_s) {
  std::vector<compensation::JointCommand> planned;
  job::JointReader reader(joint_file.string());
  while (auto c = reader.next()) planned.push_back(*c);
  std::ifstream in(file);
  if (!in) throw Error(SourceLocation{file.string()}, "no recording (halrun did not play the stream)");
  std::vector<RecordRow> rows;
  double previous_period = 0.0;
  int number = 0;
  for (std::string line; std::getline(in, line) && rows.size() < planned.size();) {
    ++number;
    const auto v = fields(line, file, number, 6);
    const auto sample = static_cast<std::size_t>(v[1]);
    if (sample == 0) continue;  // before the stream's first line
    if (sample != rows.size() + 1 || (!rows.empty() && v[0] != previous_period + 1)) {
      throw Error(SourceLocation{file.string(), number, 1},
                  fmt::format("period {} played sample {} after sample {}: the stream ran dry (an underrun) or lost a line",
                              v[0], sample, rows.size()));
    }
    previous_period = v[0];
    const auto& c = planned[sample - 1];
    RecordRow r;
    r.t_s = static_cast<double>(sample - 1) * period_s;
    r.theta_rad[0] = v[2] * kRadPerMillidegree;
    r.theta_rad[1] = v[3] * kRadPerMillidegree;
    r.laser = v[4] != 0.0;
    r.power = v[5];
    r.x_mm = units::m_to_mm(c.target_m.x());
    r.y_mm = units::m_to_mm(c.target_m.y());
    rows.push_back(r);
  }
  if (rows.size() != planned.size()) {
    throw Error(SourceLocation{file.string()}, fmt::format("{} of the job's {} samples were played", rows.size(), planned.size()));
  }
  return rows;
}

void write_record_csv(const fs::path& file, const std::vector<RecordRow>& rows) {
  core::AtomicFile out(file);
  auto& s = out.stream();
  s << kRecordHeader << '\n';
  for (const auto& r : rows) {
    s << fmt::format("{:.6f},{:.12f},{:.12f},{},{:.9f},{:.9f},{:.9f}\n", r.t_s, r.theta_rad[0], r.theta_rad[1], r.laser ? 1 : 0,
                     r.power, r.x_mm, r.y_mm);
  }
  out.commit();
}

}  // namespace stiffpath::cli::linuxcnc
