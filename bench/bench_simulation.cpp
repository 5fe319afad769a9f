// Benchmarks of the digital twin: one simulated second of motion (target ≤ 10 ms) and the 120-run matrix (≤ 30 s).
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/simulation/experiment.hpp"

namespace {
using namespace stiffpath;

// One second of a 2 kHz joint stream: a 2 Hz Lissajous figure over the workspace (no compensation needed:
// the plant's cost does not depend on what the joints do).
std::vector<compensation::JointCommand> one_second() {
  const auto robot = kinematics::load_robot("oc-gu").five_bar();
  std::vector<compensation::JointCommand> out;
  const double w = 2 * std::numbers::pi * 2.0;
  for (int k = 0; k <= 2000; ++k) {
    const double t = k / 2000.0;
    const kinematics::Vec2 p(0.222 + 0.045 * std::sin(w * t), 0.07 * std::sin(2 * w * t));
    const kinematics::Vec2 v(0.045 * w * std::cos(w * t), 0.14 * w * std::cos(2 * w * t));
    compensation::JointCommand r;
    r.t_s = t;
    r.q_rad = robot.inverse(p);
    r.qd_rad_s = robot.jacobian(r.q_rad).inverse() * v;
    r.target_m = p;
    r.laser_on = true;
    out.push_back(r);
  }
  return out;
}

void BM_SimulatedSecond(benchmark::State& state) {
  const auto records = one_second();
  const auto spec = kinematics::load_robot("oc-gu");
  const auto truth = simulation::make_true_compliance(spec);
  simulation::SimulationOptions options;
  options.settle_s = 0.0;
  for (auto _ : state) {
    std::size_t i = 0;
    const auto result = simulation::simulate(
        [&]() -> std::optional<compensation::JointCommand> {
          if (i == records.size()) return std::nullopt;
          return records[i++];
        },
        spec, truth, options);
    benchmark::DoNotOptimize(result.marked.data());
  }
  state.counters["steps_per_s"] = benchmark::Counter(20000.0 * static_cast<double>(state.iterations()),
                                                     benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulatedSecond)->Unit(benchmark::kMillisecond);

// The whole thesis matrix: 4 mechanisms × 2 × 3 motions × 5 accelerations = 120 runs, models included.
void BM_ExperimentMatrix(benchmark::State& state) {
  for (auto _ : state) {
    const auto results = simulation::run_experiment();
    benchmark::DoNotOptimize(results.data());
  }
}
BENCHMARK(BM_ExperimentMatrix)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
