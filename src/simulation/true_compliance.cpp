// C_true: the physics-based compliance field with a seeded smooth perturbation (the plant's "real" robot).
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <random>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/simulation/structural_fit_store.hpp"
#include "stiffpath/simulation/tabulated_field.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::simulation {
namespace {

using compliance::GridBounds;
using compliance::Mat2;
using compliance::Vec2;

// s(ξ, η) = 1 + ε·Σ aₖ bₖ(ξ, η) / Σ|aₖ| over the basis {ξ, η, ξη, ξ², η²} on [−1, 1]²; |s − 1| ≤ ε.
struct ScaleField {
  std::array<double, 5> a{};
  double epsilon = 0.0;
  [[nodiscard]] double operator()(double xi, double eta) const noexcept {
    const double b[5] = {xi, eta, xi * eta, xi * xi - 0.5, eta * eta - 0.5};
    double sum = 0.0, norm = 0.0;
    for (int k = 0; k < 5; ++k) {
      sum += a[static_cast<std::size_t>(k)] * b[k];
      norm += std::abs(a[static_cast<std::size_t>(k)]);
    }
    return norm > 0.0 ? 1.0 + epsilon * sum / norm : 1.0;
  }
};

class PerturbedModel final : public compliance::Model {
 public:
  PerturbedModel(std::shared_ptr<const compliance::Model> base, ScaleField sx, ScaleField sy, std::uint64_t seed)
      : base_(std::move(base)), sx_(sx), sy_(sy), seed_(seed) {
    set_outside_policy(compliance::OutsidePolicy::extrapolate);
  }
  [[nodiscard]] std::string description() const override { return "perturbed " + base_->description(); }
  [[nodiscard]] Mat2 compliance(const Vec2& p) const noexcept override {
    const GridBounds b = base_->bounds();
    const Vec2 q = b.clamp(p);  // the perturbation is held at its edge value outside the grid
    const double xi = 2.0 * (q.x() - b.x_min) / (b.x_max - b.x_min) - 1.0;
    const double eta = 2.0 * (q.y() - b.y_min) / (b.y_max - b.y_min) - 1.0;
    const Vec2 s(std::sqrt(sx_(xi, eta)), std::sqrt(sy_(xi, eta)));
    return s.asDiagonal() * base_->compliance(p) * s.asDiagonal();
  }
  [[nodiscard]] GridBounds bounds() const noexcept override { return base_->bounds(); }

 private:
  std::shared_ptr<const compliance::Model> base_;
  ScaleField sx_, sy_;
  std::uint64_t seed_;
};

}  // namespace

std::shared_ptr<const compliance::Model> make_true_base(const kinematics::Robot& robot,
                                                        const TrueComplianceOptions& options) {
  if (options.base) return options.base;
  std::shared_ptr<compliance::Model> base;
  if (!options.base_model.empty()) {
    compliance::LoadedModel m = compliance::load_model(options.base_model);
    compliance::check_model_geometry(m, robot, false);
    base = std::move(m.model);
  } else if (!robot.compliance.table.empty()) {
    if (options.family == TrueFamily::structural) {
      // The structure costs an inverse kinematics and a network of arms per point; the plant reads it
      // every 20 kHz step, from a 0.5 mm lattice (within 10⁻⁵ of the structure, tabulated_field.hpp).
      // The built-in robots' fits are stored with the library (the same numbers, without the fit's time).
      return tabulate_true_field(stored_or_fitted_structural_model(robot, compliance::robot_table(robot)));
    }
    base = compliance::fit_model(measurement::load_displacement_table(robot.compliance.table), robot.compliance.rows,
                                 compliance::FitMethod::physical, compliance::ForceConvention::measured, robot)
               .model;
  } else if (!robot.compliance.model.empty()) {
    compliance::LoadedModel m = compliance::load_model_file(robot.compliance.model);
    compliance::check_model_geometry(m, robot, false);
    base = std::move(m.model);
  } else {
    throw Error(SourceLocation{robot.file.label()},
                fmt::format("robot '{}' has no compliance data for the digital twin (compliance.table or .model)",
                            robot.name));
  }
  // The plant must follow the physics beyond the measured rectangle, not freeze it.
  base->set_outside_policy(compliance::OutsidePolicy::extrapolate);
  return base;
}

std::shared_ptr<const compliance::Model> make_true_compliance(const kinematics::Robot& robot,
                                                              const TrueComplianceOptions& options) {
  if (!(options.perturbation >= 0.0 && options.perturbation <= 0.5)) {
    throw Error(fmt::format("perturbation {} outside [0, 0.5]", options.perturbation));
  }
  std::shared_ptr<const compliance::Model> base = make_true_base(robot, options);
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ScaleField sx, sy;
  sx.epsilon = sy.epsilon = options.perturbation;
  for (auto& a : sx.a) a = u(rng);
  for (auto& a : sy.a) a = u(rng);
  return std::make_shared<PerturbedModel>(std::move(base), sx, sy, options.seed);
}

}  // namespace stiffpath::simulation
