// Checking a compliance model against physics over the region it serves (a lattice and its grid nodes).
#include "stiffpath/compliance/model_check.hpp"

#include <cmath>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "stiffpath/compliance/grid_model.hpp"

namespace stiffpath::compliance {

namespace {
constexpr int lattice = 41;

// The word and reason of a compliance that breaks physics, or nothing.
std::optional<std::pair<std::string, std::string>> defect_of(const Mat2& c) {
  if (!c.allFinite()) return std::make_pair(std::string("RANGE"), std::string("not finite"));
  if (c.cwiseAbs().maxCoeff() > max_compliance_m_per_N) {
    return std::make_pair(std::string("RANGE"), fmt::format("beyond ±{:g} um/N", max_compliance_m_per_N * 1e6));
  }
  // The symmetric part S is positive definite when S11 > 0 and det S > 0 (Sylvester's criterion).
  const double s11 = c(0, 0), s22 = c(1, 1), s12 = 0.5 * (c(0, 1) + c(1, 0));
  const double det = s11 * s22 - s12 * s12;
  if (!(s11 > 0.0 && det > 0.0)) {
    return std::make_pair(std::string("PHYSICS"),
                          fmt::format("not positive definite (its symmetric part has C11 {:.4g} um/N and det {:.4g} "
                                      "(um/N)^2): a load would move the platform against itself",
                                      s11 * 1e6, det * 1e12));
  }
  return std::nullopt;
}
}  // namespace

std::string ModelDefect::describe() const {
  const Mat2 c = compliance_m_per_N * 1e6;
  return fmt::format("{}: the model's compliance at ({:.3f}, {:.3f}) mm is [{:.4g} {:.4g}; {:.4g} {:.4g}] um/N, {}", word,
                     point_m.x() * 1e3, point_m.y() * 1e3, c(0, 0), c(0, 1), c(1, 0), c(1, 1), reason);
}

std::optional<ModelDefect> find_model_defect(const Model& model) {
  const GridBounds b = model.bounds().grown(kOutsideMargin_m);
  std::vector<Vec2> points;
  points.reserve(lattice * lattice);
  for (int i = 0; i < lattice; ++i) {
    for (int j = 0; j < lattice; ++j) {
      const double fx = static_cast<double>(i) / (lattice - 1), fy = static_cast<double>(j) / (lattice - 1);
      points.emplace_back(b.x_min + fx * (b.x_max - b.x_min), b.y_min + fy * (b.y_max - b.y_min));
    }
  }
  // Between its nodes a grid model interpolates; its extremes are at the nodes.
  if (const auto* grid = dynamic_cast<const GridModel*>(&model)) {
    for (const double x : grid->grid().xs) {
      for (const double y : grid->grid().ys) points.emplace_back(x, y);
    }
  }
  for (const Vec2& p : points) {
    const Mat2 c = model.compliance(p);
    if (auto defect = defect_of(c)) return ModelDefect{p, c, defect->first, defect->second};
  }
  return std::nullopt;
}

}  // namespace stiffpath::compliance
