// Benchmarks of the offline job: whole-job throughput of `run` (plan → compensate → write) on a generated
// marking job (targets: ≥ 2 M samples/s with CSV output, ≥ 10 M samples/s with binary output), and its parts.
// Wall-clock time: the job may use more than one thread.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <vector>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compensation/run_filters.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/job/fixed_format.hpp"
#include "stiffpath/job/job.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/job/task_source.hpp"
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
                                                 compliance::load_model("thesis-oc").model.release()),
                                           {.method = compensation::Method::quasi_static});  // the thesis's step
  std::uint64_t samples = 0;
  for (auto _ : state) {
    motion::TrajectoryStream stream(job);
    auto writer = job::make_joint_writer(format, out.string(), 2000.0, {spec.name, spec.geometry_hash()});
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
BENCHMARK_CAPTURE(BM_RunJob, csv, job::OutputFormat::csv)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK_CAPTURE(BM_RunJob, binary, job::OutputFormat::binary)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

// The same job as one plain loop on one thread (plan, compensate, check, write a sample at a time):
// what run_job's two-thread pipeline is measured against.
void BM_PlainLoopJob(benchmark::State& state, job::OutputFormat format) {
  const std::string job = marking_job(static_cast<int>(state.range(0)));
  const auto out = std::filesystem::temp_directory_path() / ("stiffpath_bench_loop_" + std::to_string(::getpid()));
  const auto spec = kinematics::load_robot("oc-gu");
  const compensation::Compensator comp(spec, std::shared_ptr<const compliance::Model>(
                                                 compliance::load_model("thesis-oc").model.release()),
                                           {.method = compensation::Method::quasi_static});  // the thesis's step
  std::uint64_t samples = 0;
  for (auto _ : state) {
    motion::TrajectoryStream stream(job);
    auto writer = job::make_joint_writer(format, out.string(), 2000.0, {spec.name, spec.geometry_hash()});
    double peak = 0.0;
    while (const auto s = stream.next()) {
      const auto c = comp.step(job::to_task_sample(*s));
      if (c.status != compensation::Status::ok) state.SkipWithError("refused");
      peak = std::max(peak, c.deflection_m.squaredNorm());
      writer->write(c);
      ++samples;
    }
    writer->finish();
    benchmark::DoNotOptimize(peak);
    state.PauseTiming();
    std::filesystem::remove(out);
    state.ResumeTiming();
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
  std::filesystem::remove(job);
}
BENCHMARK_CAPTURE(BM_PlainLoopJob, csv, job::OutputFormat::csv)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK_CAPTURE(BM_PlainLoopJob, binary, job::OutputFormat::binary)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

// Where the job's time goes: the same job without output (plan + compensate only) …
void BM_RunJobNoOutput(benchmark::State& state) {
  const std::string job = marking_job(static_cast<int>(state.range(0)));
  const compensation::Compensator comp(kinematics::load_robot("oc-gu"), std::shared_ptr<const compliance::Model>(
                                                 compliance::load_model("thesis-oc").model.release()),
                                           {.method = compensation::Method::quasi_static});  // the thesis's step
  std::uint64_t samples = 0;
  for (auto _ : state) {
    motion::TrajectoryStream stream(job);
    samples += job::run_job(stream, comp, nullptr, job, 2000.0).samples;
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
  std::filesystem::remove(job);
}
BENCHMARK(BM_RunJobNoOutput)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

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
BENCHMARK(BM_PlanJobOnly)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

// `run`'s defaults: the same job, binary output, with the reference smoothed over 8 ms (two moving averages of
// 4 ms) before the compensation, as `stiffpath run JOB --format bin` does.
void BM_RunJobSmoothed(benchmark::State& state) {
  const std::string job = marking_job(static_cast<int>(state.range(0)));
  const auto out = std::filesystem::temp_directory_path() / ("stiffpath_bench_smooth_" + std::to_string(::getpid()));
  const auto spec = kinematics::load_robot("oc-gu");
  const compensation::Compensator comp(spec, std::shared_ptr<const compliance::Model>(
                                                 compliance::load_model("thesis-oc").model.release()));
  std::uint64_t samples = 0;
  for (auto _ : state) {
    motion::TrajectoryStream stream(job);
    compensation::FilterChain filters = compensation::make_run_filters(2000.0, {}, nullptr, spec.moving_mass_kg);
    auto writer = job::make_joint_writer(job::OutputFormat::binary, out.string(), 2000.0, {spec.name, spec.geometry_hash()});
    samples += job::run_job(stream, comp, writer.get(), job, 2000.0, job::AccelerationSource::analytic, {}, &filters).samples;
    state.PauseTiming();
    std::filesystem::remove(out);
    state.ResumeTiming();
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
  std::filesystem::remove(job);
}
BENCHMARK(BM_RunJobSmoothed)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

// The compensation's input alone, on one thread: planning and `run`'s default smoothing (TaskSource), against
// BM_PlanJobOnly (planning without filters).
void BM_PlanAndSmoothJob(benchmark::State& state) {
  const std::string job = marking_job(static_cast<int>(state.range(0)));
  const double mass_kg = kinematics::load_robot("oc-gu").moving_mass_kg;
  std::uint64_t samples = 0;
  for (auto _ : state) {
    motion::TrajectoryStream stream(job);
    compensation::FilterChain filters = compensation::make_run_filters(2000.0, {}, nullptr, mass_kg);
    job::TaskSource tasks(stream, 2000.0, job::AccelerationSource::analytic, &filters);
    compensation::TaskSample s;
    while (tasks.next(s)) {
      benchmark::DoNotOptimize(s);
      ++samples;
    }
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
  std::filesystem::remove(job);
}
BENCHMARK(BM_PlanAndSmoothJob)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

// … and only the writer: 448 000 ready commands (the job's length) encoded and written to a file.
void BM_WriteJoints(benchmark::State& state, job::OutputFormat format) {
  const auto samples = job_samples();
  const compensation::Compensator comp(kinematics::load_robot("oc-gu"), std::shared_ptr<const compliance::Model>(
                                                 compliance::load_model("thesis-oc").model.release()),
                                           {.method = compensation::Method::quasi_static});  // the thesis's step
  std::vector<compensation::JointCommand> commands;
  for (std::size_t k = 0; k < 448000; ++k) commands.push_back(comp.step(samples[k % samples.size()]));
  const auto out = std::filesystem::temp_directory_path() / ("stiffpath_bench_write_" + std::to_string(::getpid()));
  for (auto _ : state) {
    auto writer = job::make_joint_writer(format, out.string(), 2000.0, {"oc-gu", ""});
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

// The yardsticks of `run`'s output: the rows the marking job produces, written by the plainest writer
// (the joint files' number formatter job::write_fixed into a buffer, fwrite; or a memcpy of each record), with no planning or compensation.
// BM_RunJob / BM_PlainWriter is what the job's writer and pipeline cost on top of the bytes themselves.
class Collect final : public job::JointWriter {
 public:
  std::vector<compensation::JointCommand> rows;
  void write(const compensation::JointCommand& c) override { rows.push_back(c); }
  void finish() override {}
};

void BM_PlainWriter(benchmark::State& state, job::OutputFormat format) {
  const std::string job = marking_job(static_cast<int>(state.range(0)));
  const compensation::Compensator comp(kinematics::load_robot("oc-gu"), std::shared_ptr<const compliance::Model>(
                                                 compliance::load_model("thesis-oc").model.release()),
                                           {.method = compensation::Method::quasi_static});  // the thesis's step
  Collect collect;
  motion::TrajectoryStream stream(job);
  job::run_job(stream, comp, &collect, job, 2000.0);
  const auto out = std::filesystem::temp_directory_path() / ("stiffpath_bench_plain_" + std::to_string(::getpid()));
  std::vector<char> buffer((1 << 20) + 4096);
  for (auto _ : state) {
    std::FILE* file = std::fopen(out.c_str(), "wb");
    std::size_t used = 0;
    for (const auto& c : collect.rows) {
      char* p = buffer.data() + used;
      if (format == job::OutputFormat::csv) {
        const auto cell = [&p](double v, int d) {
          p = job::write_fixed(p, v, d);
          *p++ = ',';
        };
        cell(c.t_s, 6);
        for (double v : {c.q_rad.x(), c.q_rad.y(), c.qd_rad_s.x(), c.qd_rad_s.y()}) cell(v, 9);
        for (double v : {c.qdd_rad_s2.x(), c.qdd_rad_s2.y()}) cell(v, 6);
        *p++ = c.laser_on ? '1' : '0';
        *p++ = ',';
        cell(c.power, 6);
        for (double v : {c.target_m.x(), c.target_m.y(), c.command_m.x(), c.command_m.y()}) cell(v * 1e3, 6);
        for (double v : {c.force_N.x(), c.force_N.y()}) cell(v, 4);
        p = std::to_chars(p, p + 12, c.line).ptr;
        *p++ = '\n';
      } else {
        const double v[14] = {c.t_s, c.q_rad.x(), c.q_rad.y(), c.qd_rad_s.x(), c.qd_rad_s.y(), c.qdd_rad_s2.x(),
                              c.qdd_rad_s2.y(), c.target_m.x(), c.target_m.y(), c.command_m.x(), c.command_m.y(),
                              c.force_N.x(), c.force_N.y(), c.power};
        std::memcpy(p, v, sizeof v);
        std::memcpy(p + sizeof v, &c.line, 4);
        p[sizeof v + 4] = c.laser_on ? 1 : 0;
        p += job::kBinaryRecordBytes;
      }
      used = static_cast<std::size_t>(p - buffer.data());
      if (used >= (1 << 20)) {
        std::fwrite(buffer.data(), 1, used, file);
        used = 0;
      }
    }
    std::fwrite(buffer.data(), 1, used, file);
    std::fclose(file);
    state.PauseTiming();
    std::filesystem::remove(out);
    state.ResumeTiming();
  }
  state.counters["samples"] = static_cast<double>(collect.rows.size());
  std::filesystem::remove(job);
}
BENCHMARK_CAPTURE(BM_PlainWriter, csv, job::OutputFormat::csv)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK_CAPTURE(BM_PlainWriter, binary, job::OutputFormat::binary)->Arg(2000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
}  // namespace
