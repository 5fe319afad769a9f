// Benchmarks of the five-bar kinematics: forward, inverse, Jacobian, J̇, and the real-time inverse for the thesis and a general robot (ns per call).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "stiffpath/kinematics/five_bar.hpp"

namespace {
constexpr double kThesisLink_m = 0.150;  // the thesis robot's four links (§2.2)

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
  const FiveBar robot(kThesisLink_m);
  const auto qs = joint_points(robot);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(robot.forward(qs[i++ & 1023]));
}
BENCHMARK(BM_Forward);

void BM_Inverse(benchmark::State& state) {
  const FiveBar robot(kThesisLink_m);
  const auto ps = workspace_points();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(robot.solve_inverse(ps[i++ & 1023]));
}
BENCHMARK(BM_Inverse);

void BM_Jacobian(benchmark::State& state) {
  const FiveBar robot(kThesisLink_m);
  const auto qs = joint_points(robot);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(robot.jacobian(qs[i++ & 1023]));
}
BENCHMARK(BM_Jacobian);

void BM_JacobianDot(benchmark::State& state) {
  const FiveBar robot(kThesisLink_m);
  const auto qs = joint_points(robot);
  const Vec2 qd{3.0, -4.0};
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(robot.jacobian_dot(qs[i++ & 1023], qd));
}
BENCHMARK(BM_JacobianDot);

void BM_JointAcceleration(benchmark::State& state) {
  const FiveBar robot(kThesisLink_m);
  const auto qs = joint_points(robot);
  const Vec2 qd{3.0, -4.0}, pdd{30.0, -20.0};
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(robot.joint_acceleration(qs[i++ & 1023], qd, pdd));
}
BENCHMARK(BM_JointAcceleration);
}  // namespace

// The real-time inverse (what Compensator::step calls): θ, J and what J̇ needs, for the thesis robot
// (eq. 2.2's closed form) and for a general five-bar (actuators 80 mm apart, links 120/130 + 180/170 mm).
namespace {
using stiffpath::kinematics::FiveBarGeometry;
using stiffpath::kinematics::InverseFrame;

FiveBarGeometry asymmetric() {
  FiveBarGeometry g;
  g.actuator_m = {Vec2(-0.04, 0.0), Vec2(0.04, 0.0)};
  g.proximal_m = {0.120, 0.130};
  g.distal_m = {0.180, 0.170};
  return g;
}

std::vector<Vec2> asymmetric_points() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(-0.06, 0.06), uy(0.17, 0.25);
  std::vector<Vec2> points(1024);
  for (auto& p : points) p = {ux(rng), uy(rng)};
  return points;
}

void BM_RealTimeInverseThesis(benchmark::State& state) {
  const FiveBar robot(kThesisLink_m);
  const auto ps = workspace_points();
  InverseFrame frame;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(robot.solve_inverse(ps[i++ & 1023], frame));
    benchmark::DoNotOptimize(frame);
  }
}
BENCHMARK(BM_RealTimeInverseThesis);

void BM_RealTimeInverseGeneral(benchmark::State& state) {
  const FiveBar robot(asymmetric(), {});
  const auto ps = asymmetric_points();
  InverseFrame frame;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(robot.solve_inverse(ps[i++ & 1023], frame));
    benchmark::DoNotOptimize(frame);
  }
}
BENCHMARK(BM_RealTimeInverseGeneral);

void BM_RealTimeJacobianDotGeneral(benchmark::State& state) {
  const FiveBar robot(asymmetric(), {});
  std::vector<InverseFrame> frames;
  for (const auto& p : asymmetric_points()) {
    InverseFrame f;
    if (robot.solve_inverse(p, f).status == stiffpath::kinematics::Reach::ok) frames.push_back(f);
  }
  const Vec2 qd{3.0, -4.0};
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(robot.jacobian_dot(frames[i++ % frames.size()], qd));
}
BENCHMARK(BM_RealTimeJacobianDotGeneral);
}  // namespace
