// Benchmarks of compensation: Compensator::step() latency distribution (median, p99.9, max) against 500 µs at 2 kHz.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compensation/reference_filter.hpp"
#include "task_samples.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/physical_model.hpp"

namespace {
using namespace stiffpath;
using stiffpath::bench::job_samples;

void BM_StepLatency(benchmark::State& state, const char* model_name, compensation::Method method) {
  const auto samples = job_samples();
  compensation::CompensatorOptions options;
  options.method = method;
  const compensation::Compensator comp(kinematics::load_robot("oc-gu"),
                                       std::shared_ptr<const compliance::Model>(compliance::load_model(model_name).model.release()),
                                       options);
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
BENCHMARK_CAPTURE(BM_StepLatency, bilinear, "thesis-oc", compensation::Method::quasi_static)
    ->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StepLatency, physical, "thesis-oc-physical", compensation::Method::quasi_static)
    ->Iterations(1)->Unit(benchmark::kMillisecond);
// Dynamic inversion (tip time constant T = 2ζ√m·C^{1/2}, the T-terms of δ and its rates): target median ≤ 300 ns.
BENCHMARK_CAPTURE(BM_StepLatency, bilinear_dynamic, "thesis-oc", compensation::Method::dynamic)
    ->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StepLatency, physical_dynamic, "thesis-oc-physical", compensation::Method::dynamic)
    ->Iterations(1)->Unit(benchmark::kMillisecond);
// The model cross-validation favours on the thesis's tables (physical + residual spline, read from its lattice).
BENCHMARK_CAPTURE(BM_StepLatency, physical_spline_dynamic, "thesis-oc-physical-spline", compensation::Method::dynamic)
    ->Iterations(1)->Unit(benchmark::kMillisecond);

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

void BM_StepThroughputDynamic(benchmark::State& state, const char* model_name) {
  const auto samples = job_samples();
  compensation::CompensatorOptions options;
  options.method = compensation::Method::dynamic;
  const compensation::Compensator comp(kinematics::load_robot("oc-gu"),
                                       std::shared_ptr<const compliance::Model>(compliance::load_model(model_name).model.release()),
                                       options);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(comp.step(samples[k]));
    if (++k == samples.size()) k = 0;
  }
}
BENCHMARK_CAPTURE(BM_StepThroughputDynamic, bilinear, "thesis-oc");
BENCHMARK_CAPTURE(BM_StepThroughputDynamic, physical, "thesis-oc-physical");
BENCHMARK_CAPTURE(BM_StepThroughputDynamic, physical_spline, "thesis-oc-physical-spline");

// The step on a general five-bar (the asymmetric robot of examples/robots/): general inverse
// kinematics and J̇, and the physical model with U from the robot's own geometry.
void BM_StepThroughputGeneralRobot(benchmark::State& state) {
  kinematics::Robot robot = kinematics::load_robot("oc-gu");
  robot.geometry.actuator_m = {kinematics::Vec2(-0.04, 0.0), kinematics::Vec2(0.04, 0.0)};
  robot.geometry.proximal_m = {0.120, 0.130};
  robot.geometry.distal_m = {0.180, 0.170};
  robot.joints[0].min_rad = -3.0;
  robot.joints[0].max_rad = 3.0;
  robot.joints[1].min_rad = -3.0;
  robot.joints[1].max_rad = 3.0;
  auto model = std::make_shared<compliance::PhysicalModel>(
      robot.geometry, compliance::GridBounds{-0.06, 0.06, 0.17, 0.25}, 1,
      std::vector<std::array<double, 3>>{{1.0e-6, 0.1e-6, 1.2e-6}, {0.2e-6, 0.0, -0.1e-6}, {0.0, 0.05e-6, 0.1e-6}},
      nlohmann::json::object());
  const compensation::Compensator comp(robot, model, {1.0, true, false});
  // The thesis samples moved into this robot's workspace (centre (0, 210) mm).
  auto samples = job_samples();
  for (auto& s : samples) s.position_m += kinematics::Vec2(-0.222, 0.210);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(comp.step(samples[k]));
    if (++k == samples.size()) k = 0;
  }
}
BENCHMARK(BM_StepThroughputGeneralRobot);

// The reference filters alone: `run`'s default smoothing (two moving averages of 4 ms) on the Lissajous samples,
// pushed one at a time as the job does (filtering the planned point itself, as for samples without a path).
void BM_FilterChainSmooth(benchmark::State& state) {
  const auto samples = job_samples();
  compensation::FilterChain chain(compensation::smoothing_filters(2000.0, compensation::kDefaultSmoothing_s));
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(chain.push(samples[k]));
    if (++k == samples.size()) k = 0;
  }
}
BENCHMARK(BM_FilterChainSmooth);
}  // namespace
