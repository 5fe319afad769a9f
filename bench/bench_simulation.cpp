// Benchmarks of the digital twin: one simulated second (≤ 10 ms), the 120-run matrix (≤ 30 s), and a hatch marked
// as one stroke (3000 lines: ≤ 12× the time and ≤ 1.3× the peak heap of 300 lines).
#include <benchmark/benchmark.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <malloc.h>
#include <new>
#include <numbers>
#include <sstream>
#include <vector>

#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/motion/limits.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"
#include "stiffpath/simulation/experiment.hpp"
#include "stiffpath/simulation/run_metrics.hpp"

// Heap in use and its peak, counted by this program's operator new/delete (what the library allocates).
namespace heap {
std::atomic<std::size_t> in_use{0}, peak{0};
void note(void* p) {
  if (!p) return;
  const std::size_t now = in_use.fetch_add(malloc_usable_size(p)) + malloc_usable_size(p);
  std::size_t seen = peak.load();
  while (now > seen && !peak.compare_exchange_weak(seen, now)) {
  }
}
}  // namespace heap

void* operator new(std::size_t n) {
  void* p = std::malloc(n == 0 ? 1 : n);
  if (!p) throw std::bad_alloc();
  heap::note(p);
  return p;
}
void operator delete(void* p) noexcept {
  if (p) heap::in_use.fetch_sub(malloc_usable_size(p));
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept { operator delete(p); }

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

// A hatch of `lines` lines of 8 mm, 40 µm apart, joined by 40 µm steps: one stroke (G61, 5 g).
std::string hatch_gcode(int lines) {
  std::string g = "G21 G90 G61\nG0 X190 Y-60\nM3 S1000\n";
  double x = 190.0;
  for (int k = 0; k < lines; ++k) {
    const double y = -60.0 + 0.04 * k;
    if (k > 0) g += fmt::format("G1 X{:.3f} Y{:.3f} F120000\n", x, y);
    x = x == 190.0 ? 198.0 : 190.0;
    g += fmt::format("G1 X{:.3f} Y{:.3f} F120000\n", x, y);
  }
  return g + "M5\nM2\n";
}

// The hatch's joint stream (planned at 5 g, inverse kinematics of each 2 kHz sample, no compensation).
std::vector<compensation::JointCommand> hatch_joints(int lines, const kinematics::FiveBar& five_bar) {
  motion::PlanOptions plan;
  plan.limits.max_acceleration_m_s2 = 5 * 9.80665;
  plan.limits.max_jerk_m_s3 = motion::default_jerk_m_s3(plan.limits.max_acceleration_m_s2);
  std::istringstream program(hatch_gcode(lines));
  motion::TrajectoryStream stream(program, "hatch", plan);
  std::vector<compensation::JointCommand> out;
  while (const auto s = stream.next()) {
    compensation::JointCommand c;
    c.t_s = s->t_s;
    c.q_rad = five_bar.inverse(s->position_m);
    c.qd_rad_s = five_bar.jacobian(c.q_rad).inverse() * s->velocity_m_s;
    c.target_m = s->position_m;
    c.laser_on = s->laser_on;
    out.push_back(c);
  }
  return out;
}

// The hatch simulated as `stiffpath simulate` does, each stroke measured while it is marked (the whole
// job is one stroke). Counters: the simulated seconds, and the peak heap the simulation and its metrics
// take above what was in use before (the joints, the robot, its C_true and lattice). Time and memory
// target: 3000 lines within 12× the time and 1.3× the peak heap of 300 lines.
void BM_OneStrokeHatch(benchmark::State& state) {
  const auto spec = kinematics::load_robot("oc-gu");
  const auto truth = simulation::make_true_compliance(spec);
  const auto joints = hatch_joints(static_cast<int>(state.range(0)), spec.five_bar());
  double simulated_s = 0.0, peak_bytes = 0.0;
  for (auto _ : state) {
    const std::size_t base = heap::in_use.load();
    heap::peak.store(base);
    simulation::RunMeter meter(0);
    std::size_t i = 0;
    const auto result = simulation::simulate(
        [&]() -> std::optional<compensation::JointCommand> {
          if (i == joints.size()) return std::nullopt;
          return joints[i++];
        },
        spec, truth, {}, static_cast<simulation::StrokeObserver&>(meter));
    const auto totals = meter.totals(result);
    if (totals.line_strokes != 1) state.SkipWithError("the hatch got no line metrics");
    benchmark::DoNotOptimize(totals.length_m);
    simulated_s = result.duration_s;
    peak_bytes = static_cast<double>(heap::peak.load() - base);
  }
  state.counters["simulated_s"] = simulated_s;
  state.counters["peak_heap_MiB"] = peak_bytes / (1024.0 * 1024.0);
}
BENCHMARK(BM_OneStrokeHatch)->Arg(300)->Arg(3000)->Unit(benchmark::kMillisecond);

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
