// Benchmarks of compensation: Compensator::step() latency distribution (median, p99.9, max) against 500 µs at 2 kHz.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compliance/model_factory.hpp"

namespace {
using namespace stiffpath;

// One hour would be 7.2 M samples; 400 000 samples (200 s at 2 kHz) keep the run short.
std::vector<compensation::TaskSample> job_samples() {
  std::vector<compensation::TaskSample> out;
  const double w = 2 * M_PI * 2.0;
  for (int k = 0; k < 400000; ++k) {
    const double t = k / 2000.0;
    compensation::TaskSample s;
    s.t_s = t;
    s.position_m = {0.222 + 0.045 * std::sin(w * t), 0.07 * std::sin(2 * w * t)};
    s.velocity_m_s = {0.045 * w * std::cos(w * t), 0.14 * w * std::cos(2 * w * t)};
    s.acceleration_m_s2 = {-0.045 * w * w * std::sin(w * t), -0.28 * w * w * std::sin(2 * w * t)};
    s.jerk_m_s3 = {-0.045 * w * w * w * std::cos(w * t), -0.56 * w * w * w * std::cos(2 * w * t)};
    out.push_back(s);
  }
  return out;
}

void BM_StepLatency(benchmark::State& state, const char* model_name) {
  const auto samples = job_samples();
  const compensation::Compensator comp(kinematics::load_robot("oc-gu"),
                                       std::shared_ptr<const compliance::Model>(compliance::load_model(model_name).model.release()));
  std::vector<double> ns(samples.size());
  using clock = std::chrono::steady_clock;
  // The clock's own cost, subtracted from every reading.
  auto t0 = clock::now();
  for (int i = 0; i < 100000; ++i) benchmark::DoNotOptimize(clock::now());
  const double clock_ns = std::chrono::duration<double, std::nano>(clock::now() - t0).count() / 100000.0;
  for (auto _ : state) {
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const auto a = clock::now();
      benchmark::DoNotOptimize(comp.step(samples[k]));
      const auto b = clock::now();
      ns[k] = std::chrono::duration<double, std::nano>(b - a).count() - clock_ns;
    }
  }
  std::sort(ns.begin(), ns.end());
  state.counters["median_ns"] = ns[ns.size() / 2];
  state.counters["p99_ns"] = ns[ns.size() * 99 / 100];
  state.counters["p99.9_ns"] = ns[ns.size() * 999 / 1000];
  state.counters["max_ns"] = ns.back();
  state.counters["samples"] = static_cast<double>(ns.size());
}
BENCHMARK_CAPTURE(BM_StepLatency, bilinear, "thesis-oc")->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StepLatency, physical, "thesis-oc-physical")->Iterations(1)->Unit(benchmark::kMillisecond);

void BM_StepThroughput(benchmark::State& state) {
  const auto samples = job_samples();
  const compensation::Compensator comp(kinematics::load_robot("oc-gu"),
                                       std::shared_ptr<const compliance::Model>(compliance::load_model("thesis-oc").model.release()));
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(comp.step(samples[k]));
    if (++k == samples.size()) k = 0;
  }
}
BENCHMARK(BM_StepThroughput);
}  // namespace

// Whole-job throughput of `run`: plan → compensate → write, on a generated marking job (targets:
// ≥ 2 M samples/s with CSV output, ≥ 10 M samples/s with binary output). Wall-clock time: the job
// may use more than one thread.
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "stiffpath/job/job.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace {
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
