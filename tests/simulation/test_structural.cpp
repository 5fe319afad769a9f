// The structural C_true: a virtual-joint model of the five-bar fitted to the thesis's translations and tilts' robot.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <map>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/simulation/structural_compliance.hpp"

namespace stiffpath::simulation {
namespace {

struct Floor {
  int cells = 0, within = 0;
  double rms = 0;
};

// The best any linear compliance can do on the table: a straight line (slope and offset, eq. 4.8) per load
// series of one point, direction and axis. A cell it misses by more than the CMM's ±23 µm is inconsistent
// with every linear model.
Floor per_series_floor(const measurement::DisplacementTable& table) {
  std::map<std::string, std::vector<std::pair<double, double>>> series;
  for (const auto& r : table.rows) {
    const std::string k = r.point + measurement::to_string(r.direction);
    if (r.dx_m) series[k + "x"].emplace_back(r.force_N, *r.dx_m);
    if (r.dy_m) series[k + "y"].emplace_back(r.force_N, *r.dy_m);
  }
  Floor f;
  double ss = 0;
  for (const auto& [key, v] : series) {
    double sf = 0, sd = 0, sff = 0, sfd = 0;
    const double n = static_cast<double>(v.size());
    for (const auto& [F, d] : v) {
      sf += F;
      sd += d;
      sff += F * F;
      sfd += F * d;
    }
    const double slope = n > 1 ? (n * sfd - sf * sd) / (n * sff - sf * sf) : 0.0, offset = (sd - slope * sf) / n;
    for (const auto& [F, d] : v) {
      const double e = d - slope * F - offset;
      ss += e * e;
      ++f.cells;
      f.within += std::abs(e) <= 23e-6;
    }
  }
  f.rms = std::sqrt(ss / f.cells);
  return f;
}

// OC: the structure reproduces the table like the CMM would (RMS below its ±23 µm, nearly every cell within
// it); the per-series straight lines show the data themselves are consistent to a few µm. SC's field is
// rougher than any 17-parameter structure (docs/simulation.md gives its numbers); it is checked to be
// positive definite and to follow the table's scale only.
TEST(Structural, ReproducesTheThesisTablesWithinTheCmmTolerance) {
  for (const char* build : {"oc-gu", "sc-gu"}) {
    const auto robot = kinematics::load_robot(build);
    const auto table = compliance::robot_table(robot);
    StructuralFitReport rep;
    const auto model = fit_structural_model(robot, table, &rep);
    const Floor floor = per_series_floor(table);
    std::printf("%s: %d cells, %d within 23 um, max %.1f um, rms %.1f um; per-series lines: %d within, rms %.1f um\n",
                build, rep.cells, rep.within_23um, rep.max_error_m * 1e6, rep.rms_error_m * 1e6, floor.within,
                floor.rms * 1e6);
    EXPECT_GE(floor.within, floor.cells - 1) << build;  // the table is linear per series (one SC outlier)
    if (std::string(build) == "oc-gu") {
      EXPECT_LT(rep.rms_error_m, 23e-6);
      EXPECT_GE(rep.within_23um, rep.cells * 85 / 100);
    }
    for (double x : {0.172132, 0.2, 0.222132, 0.25, 0.272132}) {
      for (double y : {-0.075, -0.02, 0.0, 0.05, 0.075}) {
        const compliance::Mat2 C = model->compliance({x, y});
        EXPECT_NEAR(C(0, 1), C(1, 0), 1e-12 * C.norm());
        EXPECT_GT(C.determinant(), 0.0);
        EXPECT_GT(C.trace(), 0.0);
      }
    }
  }
}

// The virtual-joint sum reduces to the classical result: with rigid links, free elbows (the distal links are
// two-force members) and actuator springs κ_i only, C = J·diag(κ)·Jᵀ (J of eq. 2.1).
TEST(Structural, ActuatorSpringsAloneGiveJKJt) {
  const auto robot = kinematics::load_robot("oc-gu");
  std::array<ArmCompliance, 2> arms{};
  arms[0].actuator_rad_per_Nm = 2e-4;
  arms[1].actuator_rad_per_Nm = 5e-5;
  for (auto& a : arms) a.elbow_rad_per_Nm = 1e4;  // a free elbow: no moment passes it
  const StructuralModel model(robot, arms, {0.172132, 0.272132, -0.075, 0.075});
  const auto five_bar = robot.five_bar();
  for (const compliance::Vec2& p : {compliance::Vec2(0.2, 0.03), compliance::Vec2(0.26, -0.06)}) {
    const compliance::Mat2 J = five_bar.jacobian(five_bar.inverse(p));
    // Arm i then resists only along its distal link u_i, with compliance d_i = κ_i(l·e_i⊥·u_i)²; the arms in
    // parallel give C = U⁻ᵀ·diag(d)·U⁻¹ = J·diag(κ)·Jᵀ.
    const compliance::Mat2 expected = J * compliance::Vec2(2e-4, 5e-5).asDiagonal() * J.transpose();
    EXPECT_LT((model.compliance(p) - expected).norm(), 1e-3 * expected.norm()) << p.transpose();
  }
}

}  // namespace
}  // namespace stiffpath::simulation
