// stiffpath-halstream: a joint file of `stiffpath run` (CSV or binary) as lines for LinuxCNC's halstreamer.
//
// One line per sample: the sample number (from 1), θ1 and θ2 in degrees (or radians), the laser bit and the
// laser power (0..1), numbers with 17 significant digits so that halstreamer's strtod gets back the file's
// doubles; the last line is repeated once with the laser off (a LinuxCNC 2.9 streamer quirk, below). The matching streamer is
// `loadrt streamer cfg=uffbf` (`uff` with --joints-only). The file's sample rate must be the servo thread's
// (--period-ns), since streamer puts out one line per period.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "stiffpath/job/joint_reader.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"

namespace {

using namespace stiffpath;

struct Options {
  std::string input;
  std::string output;           // empty: standard output
  long long period_ns = 500000;
  std::string units = "deg";
  bool joints_only = false;
};

// One line: sample number, the joints (scaled to the stream's units), and unless joints_only the laser bit and power.
void write_line(std::ostream& out, std::uint64_t n, const compensation::JointCommand& c, double scale, bool joints_only,
                bool laser) {
  char line[160];
  const int length = joints_only ? std::snprintf(line, sizeof line, "%llu %.17g %.17g\n", static_cast<unsigned long long>(n),
                                                 c.q_rad.x() * scale, c.q_rad.y() * scale)
                                 : std::snprintf(line, sizeof line, "%llu %.17g %.17g %d %.17g\n", static_cast<unsigned long long>(n),
                                                 c.q_rad.x() * scale, c.q_rad.y() * scale, laser ? 1 : 0, laser ? c.power : 0.0);
  out.write(line, length);
}

// Converts and writes; throws stiffpath::Error for a bad file or a rate that does not match the period.
void convert(const Options& o, std::ostream& out) {
  if (o.units != "deg" && o.units != "rad") throw Error(fmt::format("--units {}: must be deg or rad", o.units));
  if (o.period_ns <= 0) throw Error(fmt::format("--period-ns {}: must be positive", o.period_ns));
  const double scale = o.units == "deg" ? 180.0 / M_PI : 1.0;
  const double period_s = static_cast<double>(o.period_ns) * 1e-9;
  job::JointReader reader(o.input);
  std::uint64_t n = 0;
  double first_t = 0.0;
  compensation::JointCommand last;
  out << fmt::format("# {} as halstreamer input: one line per {} ns servo period; columns: sample, theta1_{}, theta2_{}{}\n",
                     o.input, o.period_ns, o.units, o.units, o.joints_only ? "" : ", laser, power");
  while (const auto record = reader.next()) {
    if (n == 0) first_t = record->t_s;
    // The samples must fall on the servo period's grid: half a period off means another rate.
    const double expected_t = first_t + static_cast<double>(n) * period_s;
    if (std::abs(record->t_s - expected_t) > 0.25 * period_s) {
      throw Error(fmt::format("{}: sample {} at t = {:.6f} s, expected {:.6f} s: the file's rate is not one "
                              "sample per {} ns (plan it with `stiffpath run --rate {}`)",
                              o.input, n + 1, record->t_s, expected_t, o.period_ns, 1e9 / static_cast<double>(o.period_ns)));
    }
    ++n;
    last = *record;
    write_line(out, n, last, scale, o.joints_only, last.laser_on);
    if (n >= 0xFFFFFFFFull) throw Error(fmt::format("{}: more than 2^32 - 1 samples, more than a u32 pin counts", o.input));
  }
  if (n == 0) throw Error(fmt::format("{}: no samples", o.input));
  // LinuxCNC 2.9's streamer counts the FIFO one short when its indices have wrapped, and so never plays
  // a stream's last line if that line sits in the FIFO's last slot. Repeating it costs one period of
  // standing still and makes sure the real last command is played. The repeat has the laser off: the
  // streamer holds its last line's values after the stream, and the laser must not stay on.
  out << "# the last sample again with the laser off, so that streamer plays the one before and the laser ends off "
         "(see docs/linuxcnc.md)\n";
  write_line(out, n, last, scale, o.joints_only, false);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"stiffpath-halstream: a stiffpath joint file as halstreamer input (see docs/linuxcnc.md)"};
  Options o;
  app.add_option("joint_file", o.input, "Joint file written by `stiffpath run -o` (CSV or binary)")->required();
  app.add_option("-o,--output", o.output, "Output file (written atomically); default: standard output");
  app.add_option("--period-ns", o.period_ns, "Servo period the stream is played at (ns)")->capture_default_str();
  app.add_option("--units", o.units, "Joint units of the machine: deg or rad")->capture_default_str();
  app.add_flag("--joints-only", o.joints_only,
               "Only the sample number and the joints (streamer cfg=uff); default: with the laser bit and power (cfg=uffbf)");
  CLI11_PARSE(app, argc, argv);
  try {
    if (o.output.empty()) {
      std::ios::sync_with_stdio(false);
      convert(o, std::cout);
      std::cout.flush();
      if (!std::cout) throw Error("writing to standard output failed");
    } else {
      core::AtomicFile file(o.output);
      convert(o, file.stream());
      file.commit();
    }
  } catch (const Error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
