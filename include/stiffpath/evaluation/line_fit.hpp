// Total-least-squares straight line through planar points (thesis §4.6 step iv, "line fitting").
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>

namespace stiffpath::evaluation {

using Point2 = Eigen::Vector2d;  //!< a point of a path, (x, y) in m

//! A straight line through `origin` along the unit vector `direction`. The along-line parameter
//! t = (p − origin)·direction and the signed offset u = (p − origin)·normal, normal = direction
//! turned by +90° (x, y) → (−y, x), define the line's frame used by every metric.
struct Line2 {
  Point2 origin{0.0, 0.0};     //!< a point on the line, m (the weighted centroid after a fit)
  Point2 direction{1.0, 0.0};  //!< unit vector along the line

  [[nodiscard]] Point2 normal() const { return {-direction.y(), direction.x()}; }
  //! Along-line parameter t of p (m).
  [[nodiscard]] double along(const Point2& p) const { return (p - origin).dot(direction); }
  //! Signed perpendicular offset u of p from the line (m), positive on the normal's side.
  [[nodiscard]] double offset(const Point2& p) const { return (p - origin).dot(normal()); }
  //! The point at parameter t and offset u.
  [[nodiscard]] Point2 at(double t, double u = 0.0) const { return origin + t * direction + u * normal(); }
};

//! Result of a total-least-squares fit.
struct LineFit {
  Line2 line;                 //!< origin = weighted centroid, direction = principal axis
  double rms_residual_m = 0;  //!< weighted RMS of the perpendicular offsets (m)
  double spread_m = 0;        //!< weighted RMS spread along the line (m); 0 for a single point
};

//! Fits the line minimising the weighted sum of squared perpendicular distances (orthogonal
//! regression: the principal axis of the weighted scatter matrix, solved in closed form). Weights
//! default to 1; they must be ≥ 0 with a positive sum. The direction's sign is chosen so that it
//! points from the first point towards the last (then from lower to higher x for closed sets).
//! Throws stiffpath::Error for fewer than two distinct points or non-finite input.
LineFit fit_line_tls(std::span<const Point2> points, std::span<const double> weights = {});

//! Intersection of two lines, or nullopt when they are parallel within |sin angle| < 1e-9.
std::optional<Point2> intersect(const Line2& a, const Line2& b);

//! Angle between two directions in [0, π] (rad).
double angle_between(const Point2& a, const Point2& b);

}  // namespace stiffpath::evaluation
