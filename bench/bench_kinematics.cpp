// Benchmarks of the five-bar kinematics: forward, inverse, Jacobian, J̇ and condition number (ns per call).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "stiffpath/kinematics/five_bar.hpp"

namespace {
using stiffpath::kinematics::FiveBar;
using stiffpath::kinematics::Vec2;

std::vector<Vec2> workspace_points() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(0.172132, 0.272132), uy(-0.075, 0.075);
  std::vector<Vec2> points(1024);
  for (auto& p : points) p = {ux(rng), uy(rng)};
  return points;
}

std::vector<Vec2> joint_points(const FiveBar& robot) {
  std::vector<Vec2> q;
  for (const auto& p : workspace_points()) q.push_back(robot.inverse(p));
  return q;
}

void BM_Forward(benchmark::State& state) {
  const FiveBar robot;
  const auto qs = joint_points(robot);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(robot.forward(qs[i++ & 1023]));
}
BENCHMARK(BM_Forward);

void BM_Inverse(benchmark::State& state) {
  const FiveBar robot;
  const auto ps = workspace_points();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(robot.solve_inverse(ps[i++ & 1023]));
}
BENCHMARK(BM_Inverse);

void BM_Jacobian(benchmark::State& state) {
  const FiveBar robot;
  const auto qs = joint_points(robot);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(robot.jacobian(qs[i++ & 1023]));
}
BENCHMARK(BM_Jacobian);

void BM_JacobianDot(benchmark::State& state) {
  const FiveBar robot;
  const auto qs = joint_points(robot);
  const Vec2 qd{3.0, -4.0};
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(robot.jacobian_dot(qs[i++ & 1023], qd));
}
BENCHMARK(BM_JacobianDot);

void BM_JointAcceleration(benchmark::State& state) {
  const FiveBar robot;
  const auto qs = joint_points(robot);
  const Vec2 qd{3.0, -4.0}, pdd{30.0, -20.0};
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(robot.joint_acceleration(qs[i++ & 1023], qd, pdd));
}
BENCHMARK(BM_JointAcceleration);
}  // namespace
