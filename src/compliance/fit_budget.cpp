// Budgets of fits and cross-validations: refused before the work starts, naming the limit.
#include "stiffpath/compliance/fit_budget.hpp"

#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::compliance {

namespace {
std::size_t samples_of(const std::vector<PointSamples>& points) {
  std::size_t n = 0;
  for (const auto& p : points) n += p.samples.size();
  return n;
}
}  // namespace

void check_cv_budget(const std::vector<PointSamples>& points, const std::string& source) {
  const std::size_t samples = samples_of(points);
  if (points.size() > max_cv_points || samples > max_cv_samples) {
    throw Error(SourceLocation{source},
                fmt::format("LIMIT: cross-validation refits every method once per point; it takes at most {} points "
                            "and {} samples, this table has {} points and {} samples: name a method (--method) "
                            "instead of auto, or thin the table",
                            max_cv_points, max_cv_samples, points.size(), samples));
  }
}

void check_fit_budget(const std::vector<PointSamples>& points, std::optional<kinematics::FitMethod> method, const std::string& source) {
  const std::size_t samples = samples_of(points);
  if (samples > max_fit_samples) {
    throw Error(SourceLocation{source},
                fmt::format("LIMIT: {} samples ({} points), more than the {} a fit takes: thin the table (a point's "
                            "line fit needs a few load steps, not thousands)",
                            samples, points.size(), max_fit_samples));
  }
  if (method == kinematics::FitMethod::physical_spline && points.size() > max_spline_points) {
    throw Error(SourceLocation{source},
                fmt::format("LIMIT: {} points, more than the {} a physical-spline fit takes: name another method",
                            points.size(), max_spline_points));
  }
  if (!method) check_cv_budget(points, source);
}

}  // namespace stiffpath::compliance
