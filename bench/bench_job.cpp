// Benchmarks of the offline job: whole-job throughput of `run` (plan → compensate → write) on a generated
// marking job (targets: ≥ 2 M samples/s with CSV output, ≥ 10 M samples/s with binary output), and its parts.
// Wall-clock time: the job may use more than one thread.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <vector>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/job/job.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"
#include "task_samples.hpp"

namespace {
using namespace stiffpath;
using stiffpath::bench::job_samples;
std::string marking_job(int lines) {
  const auto path = std::filesystem::temp_directory_path() / ("stiffpath_bench_job_" + std::to_string(::getpid()) + "_" +
                                                              std::to_string(lines) + ".gcode");
  std::ofstream out(path);
  out << "G21 G90 G64 P0.01\nG0 X180 Y-70\nM3 S500\n";
  for (int i = 0; i < lines; ++i) {
    const double y = -70.0 + (i % 140);
    out << "G1 X" << (i % 2 ? 180 : 265) << " Y" << y << " F60000\n";
  }
  out << "M5\nM2\n";
  return path.string();
}

void BM_RunJob(benchmark::State& state, job::OutputFormat format) {
  const std::string job = marking_job(static_cast<int>(state.range(0)));
  const auto out = std::filesystem::temp_directory_path() / ("stiffpath_bench_out_" + std::to_string(::getpid()));
  const auto spec = kinematics::load_robot("oc-gu");
  const compensation::Compensator comp(spec, std::shared_ptr<const compliance::Model>(
                                                 compliance::load_model("thesis-oc").model.release()));
  std::uint64_t samples = 0;
  for (auto _ : state) {
    motion::TrajectoryStream stream(job);
    auto writer = job::make_joint_writer(format, out.string(), 2000.0, spec.name);
    samples += job::run_job(stream, comp, writer.get(), job, 2000.0).samples;
    // A job writes a new file: deleting the last one (which waits for the disk to take its pages)
    // is not part of it.
    state.PauseTiming();
    std::filesystem::remove(out);
    state.ResumeTiming();
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
  state.counters["samples"] = static_cast<double>(samples) / static_cast<double>(state.iterations());
  std::filesystem::remove(job);
}
BENCHMARK_CAPTURE(BM_RunJob, csv, job::OutputFormat::csv)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_RunJob, binary, job::OutputFormat::binary)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime();

// Where the job's time goes: the same job without output (plan + compensate only) …
void BM_RunJobNoOutput(benchmark::State& state) {
  const std::string job = marking_job(static_cast<int>(state.range(0)));
  const compensation::Compensator comp(kinematics::load_robot("oc-gu"), std::shared_ptr<const compliance::Model>(
                                                 compliance::load_model("thesis-oc").model.release()));
  std::uint64_t samples = 0;
  for (auto _ : state) {
    motion::TrajectoryStream stream(job);
    samples += job::run_job(stream, comp, nullptr, job, 2000.0).samples;
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
  std::filesystem::remove(job);
}
BENCHMARK(BM_RunJobNoOutput)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime();

// … only the planning (G-code → 2 kHz task samples, the part that cannot be shared between threads) …
void BM_PlanJobOnly(benchmark::State& state) {
  const std::string job = marking_job(static_cast<int>(state.range(0)));
  std::uint64_t samples = 0;
  for (auto _ : state) {
    motion::TrajectoryStream stream(job);
    while (const auto s = stream.next()) {
      benchmark::DoNotOptimize(job::to_task_sample(*s));
      ++samples;
    }
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
  std::filesystem::remove(job);
}
BENCHMARK(BM_PlanJobOnly)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime();

// … and only the writer: 448 000 ready commands (the job's length) encoded and written to a file.
void BM_WriteJoints(benchmark::State& state, job::OutputFormat format) {
  const auto samples = job_samples();
  const compensation::Compensator comp(kinematics::load_robot("oc-gu"), std::shared_ptr<const compliance::Model>(
                                                 compliance::load_model("thesis-oc").model.release()));
  std::vector<compensation::JointCommand> commands;
  for (std::size_t k = 0; k < 448000; ++k) commands.push_back(comp.step(samples[k % samples.size()]));
  const auto out = std::filesystem::temp_directory_path() / ("stiffpath_bench_write_" + std::to_string(::getpid()));
  for (auto _ : state) {
    auto writer = job::make_joint_writer(format, out.string(), 2000.0, "oc-gu");
    for (const auto& c : commands) writer->write(c);
    writer->finish();
    state.PauseTiming();
    std::filesystem::remove(out);
    state.ResumeTiming();
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(commands.size() * state.iterations()),
                                                       benchmark::Counter::kIsRate);
  std::filesystem::remove(out);
}
BENCHMARK_CAPTURE(BM_WriteJoints, csv, job::OutputFormat::csv)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_WriteJoints, binary, job::OutputFormat::binary)->Unit(benchmark::kMillisecond)->UseRealTime();
}  // namespace
