// The work a fit or a cross-validation may be asked for, checked before it starts (docs/reliability.md).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/compliance/point_fit.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::compliance {

//! Samples (table rows) one fit takes: 10^5 (the thesis's table has 600); a fit's time and memory grow
//! with them.
inline constexpr std::size_t max_fit_samples = 100'000;
//! Points of a physical-spline fit, whose solve grows faster than linearly with them: 2 000.
inline constexpr std::size_t max_spline_points = 2'000;
//! Leave-one-out cross-validation (`cv`, `fit --method auto`, the report) refits every method once per
//! point, so its work grows as points × samples: at most 400 points and 20 000 samples.
inline constexpr std::size_t max_cv_points = 400;
inline constexpr std::size_t max_cv_samples = 20'000;

//! Refuses (stiffpath::Error at `source`, "LIMIT: …" naming the limit and how to stay within it) a fit
//! by `method` (none: chosen by cross-validation) beyond the budgets above.
void check_fit_budget(const std::vector<PointSamples>& points, std::optional<kinematics::FitMethod> method, const std::string& source);
//! The same for a cross-validation alone.
void check_cv_budget(const std::vector<PointSamples>& points, const std::string& source);

}  // namespace stiffpath::compliance
