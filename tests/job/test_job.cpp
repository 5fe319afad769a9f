// Tests of run_job's two-thread pipeline against the plain loop: same file, summary, refusals, errors, progress.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include "cli_runner.hpp"
#include "stiffpath/job/job.hpp"
#include "stiffpath/compensation/numeric_acceleration.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::job {
using namespace stiffpath::compensation;  // NOLINT: the step is what the job runs
namespace {

// A hatching job of `lines` moves (about 220 samples each at 5 g), optionally with one extra line
// inserted after move `at`.
std::string hatch(int lines, int at = -1, const std::string& extra = "") {
  std::ostringstream out;
  out << "G21 G90 G64 P0.01\nG0 X180 Y-70\nM3 S500\n";
  for (int i = 0; i < lines; ++i) {
    out << "G1 X" << (i % 2 ? 180 : 265) << " Y" << -70 + (i % 140) << " F60000\n";
    if (i == at) out << extra << "\n";
  }
  out << "M5\nM2\n";
  return out.str();
}

Compensator compensator() {
  CompensatorOptions quasi;
  quasi.method = Method::quasi_static;
  return Compensator(kinematics::load_robot("oc-gu"),
                     std::shared_ptr<const compliance::Model>(compliance::load_model("thesis-oc").model.release()), quasi);
}

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The job as one loop, one sample at a time (what run_job did before it used two threads).
// Returns the summary, or throws what the loop met first.
JobSummary sequential(const std::string& gcode, const Compensator& comp, JointWriter* writer,
                      AccelerationSource acceleration) {
  std::istringstream in(gcode);
  motion::TrajectoryStream stream(in, "job.gcode");
  JobSummary s;
  const auto use = [&](const TaskSample& task) {
    const JointCommand c = comp.step(task);
    if (c.status != Status::ok) throw Error(SourceLocation{"job.gcode", c.line}, std::string("refused: ") + describe(c.status));
    s.duration_s = c.t_s;
    s.peak_deflection_m = std::max(s.peak_deflection_m, c.deflection_m.norm());
    s.peak_correction_m = std::max(s.peak_correction_m, (c.command_m - c.target_m).norm());
    s.peak_force_N = std::max(s.peak_force_N, c.force_N.norm());
    s.peak_joint_velocity_rad_s = std::max(s.peak_joint_velocity_rad_s, c.qd_rad_s.cwiseAbs().maxCoeff());
    s.peak_joint_acceleration_rad_s2 = std::max(s.peak_joint_acceleration_rad_s2, c.qdd_rad_s2.cwiseAbs().maxCoeff());
    s.samples_outside_grid += c.outside_grid ? 1 : 0;
    ++s.samples;
    if (writer) writer->write(c);
  };
  NumericDifferentiator numeric(2000.0);
  while (const auto sample = stream.next()) {
    if (acceleration == AccelerationSource::analytic) {
      use(to_task_sample(*sample));
    } else if (const auto ready = numeric.push(to_task_sample(*sample))) {
      use(*ready);
    }
  }
  while (const auto rest = numeric.drain()) use(*rest);
  if (writer) writer->finish();
  return s;
}

JobSummary pipelined(const std::string& gcode, const Compensator& comp, JointWriter* writer,
                     AccelerationSource acceleration, const Progress& progress = {}) {
  std::istringstream in(gcode);
  motion::TrajectoryStream stream(in, "job.gcode");
  return run_job(stream, comp, writer, "job.gcode", 2000.0, acceleration, progress);
}

// The error message of `job`, or "" when it succeeds.
template <typename Job>
std::string error_of(Job&& job) {
  try {
    job();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(RunJob, WritesTheSameFileAndSummaryAsOneSampleAtATime) {
  const Compensator comp = compensator();
  const std::string job = hatch(120);  // ≈ 26 000 samples: many blocks of the pipeline
  test::TempDir dir;
  for (AccelerationSource acceleration : {AccelerationSource::analytic, AccelerationSource::numeric}) {
    for (OutputFormat format : {OutputFormat::binary, OutputFormat::csv}) {
      auto a = make_joint_writer(format, (dir / "a").string(), 2000.0, {"oc-gu", ""});
      auto b = make_joint_writer(format, (dir / "b").string(), 2000.0, {"oc-gu", ""});
      const JobSummary x = sequential(job, comp, a.get(), acceleration);
      const JobSummary y = pipelined(job, comp, b.get(), acceleration);
      EXPECT_GT(y.samples, 20000u);
      EXPECT_EQ(read_bytes(dir / "a"), read_bytes(dir / "b"));
      EXPECT_EQ(x.samples, y.samples);
      EXPECT_EQ(x.duration_s, y.duration_s);
      EXPECT_EQ(x.peak_deflection_m, y.peak_deflection_m);
      EXPECT_EQ(x.peak_correction_m, y.peak_correction_m);
      EXPECT_EQ(x.peak_force_N, y.peak_force_N);
      EXPECT_EQ(x.peak_joint_velocity_rad_s, y.peak_joint_velocity_rad_s);
      EXPECT_EQ(x.peak_joint_acceleration_rad_s2, y.peak_joint_acceleration_rad_s2);
      EXPECT_EQ(x.samples_outside_grid, y.samples_outside_grid);
    }
  }
  EXPECT_EQ(pipelined(job, comp, nullptr, AccelerationSource::analytic).samples,
            sequential(job, comp, nullptr, AccelerationSource::analytic).samples);
}

TEST(RunJob, TheFirstProblemInTimeIsReportedAndNoFileIsLeft) {
  // A move out of reach late in the job, followed by a bad G-code line soon after it or much later:
  // the error must be the one the plain loop meets first, and nothing may be written.
  const Compensator comp = compensator();
  test::TempDir dir;
  for (int gap : {-1, 3, 4, 60}) {  // −1: the bad line comes first; the reader runs up to three blocks ahead (the line
                                    // merger holds one more than the blender)
    std::string job = hatch(200, 100, "G1 X296 Y0");
    const std::string marker = "G1 X296 Y0\n";
    std::size_t at = job.find(marker) + (gap < 0 ? 0 : marker.size());
    for (int k = 0; k < gap; ++k) at = job.find('\n', at) + 1;
    job.insert(at, "G1 X200 Q7\n");
    const std::string expected = error_of([&] { sequential(job, comp, nullptr, AccelerationSource::analytic); });
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(expected.find("Q7") != std::string::npos, gap < 0) << expected;
    auto writer = make_joint_writer(OutputFormat::binary, (dir / "j.bin").string(), 2000.0, {"oc-gu", ""});
    const std::string got = error_of([&] { pipelined(job, comp, writer.get(), AccelerationSource::analytic); });
    writer.reset();
    // The same place: the refusal's line (the message words differ) or the same G-code error.
    EXPECT_EQ(got.substr(0, got.find(": t = ")), expected.substr(0, expected.find(": refused"))) << got << "\n" << expected;
    EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << gap;
  }
}

// A writer that fails like a full disk after `limit` commands, and remembers its thread.
class FailingWriter final : public JointWriter {
 public:
  explicit FailingWriter(std::size_t limit) : limit_(limit) {}
  void write(const JointCommand&) override {
    thread_ = std::this_thread::get_id();
    if (++written_ > limit_) throw Error(SourceLocation{"out.bin"}, "write failed (disk full?)");
  }
  void finish() override { finished_ = true; }
  std::size_t written_ = 0;
  std::size_t limit_;
  bool finished_ = false;
  std::thread::id thread_;
};

TEST(RunJob, AWriterErrorStopsTheJob) {
  const Compensator comp = compensator();
  FailingWriter writer(5000);
  const std::string got = error_of([&] { pipelined(hatch(120), comp, &writer, AccelerationSource::analytic); });
  EXPECT_EQ(got, "out.bin: write failed (disk full?)");
  EXPECT_FALSE(writer.finished_);
  EXPECT_EQ(writer.written_, 5001u);  // nothing after the failed write
}

TEST(RunJob, ProgressComesFromTheCallingThreadAndTheWriterFromOneOther) {
  const Compensator comp = compensator();
  FailingWriter writer(1u << 30);
  std::vector<std::uint64_t> calls;
  std::vector<std::thread::id> threads;
  const JobSummary s = pipelined(hatch(320), comp, &writer, AccelerationSource::analytic,
                                 [&](std::uint64_t samples, int line) {
                                   calls.push_back(samples);
                                   threads.push_back(std::this_thread::get_id());
                                   EXPECT_GT(line, 3);
                                 });
  ASSERT_GT(s.samples, 65536u);
  ASSERT_EQ(calls.size(), s.samples / 65536);
  EXPECT_EQ(calls.front(), 65536u);
  for (const auto& id : threads) EXPECT_EQ(id, std::this_thread::get_id());
  EXPECT_TRUE(writer.finished_);
  EXPECT_EQ(writer.written_, s.samples);
  EXPECT_NE(writer.thread_, std::this_thread::get_id());
}

}  // namespace
}  // namespace stiffpath::job
