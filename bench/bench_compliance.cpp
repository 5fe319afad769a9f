// Benchmarks of compliance prediction: predict(p, F) per model (targets: bilinear ≤ 20 ns, physical ≤ 100 ns).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/point_fit.hpp"
#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/physical_model.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace {
using stiffpath::compliance::Vec2;

struct Inputs {
  std::vector<Vec2> p, f;
};

const Inputs& inputs() {
  static const Inputs in = [] {
    Inputs r;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> ux(0.172132, 0.272132), uy(-0.075, 0.075), uf(-180.0, 180.0);
    for (int i = 0; i < 1024; ++i) {
      r.p.emplace_back(ux(rng), uy(rng));
      r.f.emplace_back(uf(rng), uf(rng));
    }
    return r;
  }();
  return in;
}

void BM_Predict(benchmark::State& state, const char* model_name) {
  const auto loaded = stiffpath::compliance::load_model(model_name);
  const auto& model = *loaded.model;
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 1023;
    benchmark::DoNotOptimize(model.predict(in.p[k], in.f[k]));
  }
}
BENCHMARK_CAPTURE(BM_Predict, bilinear, "thesis-oc");
BENCHMARK_CAPTURE(BM_Predict, symmetric, "thesis-oc-symmetric");
BENCHMARK_CAPTURE(BM_Predict, physical, "thesis-oc-physical");
BENCHMARK_CAPTURE(BM_Predict, physical_order2, "thesis-oc-physical-2");
// Physical + residual spline: read from its lattice inside the measured rectangle.
BENCHMARK_CAPTURE(BM_Predict, physical_spline, "thesis-oc-physical-spline");

// The physical model of a general (asymmetric) five-bar: U from the general inverse kinematics.
void BM_PredictPhysicalGeneralGeometry(benchmark::State& state) {
  stiffpath::kinematics::FiveBarGeometry g;
  g.actuator_m = {Vec2(-0.04, 0.0), Vec2(0.04, 0.0)};
  g.proximal_m = {0.120, 0.130};
  g.distal_m = {0.180, 0.170};
  const stiffpath::compliance::GridBounds region{-0.06, 0.06, 0.17, 0.25};
  stiffpath::compliance::PhysicalModel model(g, region, 1, {{1.0e-6, 0.1e-6, 1.2e-6}, {0.2e-6, 0.0, -0.1e-6}, {0.0, 0.05e-6, 0.1e-6}},
                                             nlohmann::json::object());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> ux(-0.06, 0.06), uy(0.17, 0.25), uf(-200.0, 200.0);
  std::vector<Vec2> p(1024), f(1024);
  for (std::size_t k = 0; k < p.size(); ++k) {
    p[k] = {ux(rng), uy(rng)};
    f[k] = {uf(rng), uf(rng)};
  }
  std::size_t k = 0;
  for (auto _ : state) {
    k = (k + 1) & 1023;
    benchmark::DoNotOptimize(model.predict(p[k], f[k]));
  }
}
BENCHMARK(BM_PredictPhysicalGeneralGeometry);

void BM_Fit(benchmark::State& state, stiffpath::compliance::FitMethod method) {
  const auto robot = stiffpath::kinematics::load_robot("oc-gu");
  const auto table = stiffpath::measurement::load_displacement_table(robot.compliance.table);
  for (auto _ : state) {
    benchmark::DoNotOptimize(stiffpath::compliance::fit_model(table, "OC", method,
                                                              stiffpath::compliance::ForceConvention::measured, robot));
  }
}
BENCHMARK_CAPTURE(BM_Fit, physical, stiffpath::compliance::FitMethod::physical)->Unit(benchmark::kMillisecond);
// Includes filling the 0.75 mm lattice (about 27 000 nodes and as many cell-centre checks).
BENCHMARK_CAPTURE(BM_Fit, physical_spline, stiffpath::compliance::FitMethod::physical_spline)->Unit(benchmark::kMillisecond);

void BM_CrossValidation(benchmark::State& state) {
  const auto table =
      stiffpath::measurement::load_displacement_table(stiffpath::measurement::thesis_dataset()).filter("OC");
  const auto points = stiffpath::compliance::group_by_point(table, stiffpath::compliance::ForceConvention::measured);
  const auto geometry = stiffpath::kinematics::FiveBarGeometry::thesis(0.150);
  for (auto _ : state) benchmark::DoNotOptimize(stiffpath::compliance::cross_validate(points, geometry, "thesis"));
}
BENCHMARK(BM_CrossValidation)->Unit(benchmark::kMillisecond);
}  // namespace
