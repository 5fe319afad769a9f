// Biarcs: two tangent-continuous circular arcs joining two points with given tangents.
#pragma once

#include <array>
#include <optional>

#include "stiffpath/motion/path_segment.hpp"

namespace stiffpath::motion {

//! The arc that leaves `from_m` along the unit tangent `tangent` and ends at `to_m` (its signed
//! curvature is 2·(t × c)/|c|², c = to − from, and it turns by twice the angle between t and c).
//! A line when that angle is below 5e-8 rad (the arc would leave the line by less than 1e-8 of
//! its length). nullopt when `to_m` does not lie ahead (t·c ≤ 0) or coincides with `from_m`.
std::optional<PathSegment> arc_from_tangent(const Vec2& from_m, const Vec2& tangent, const Vec2& to_m) noexcept;

//! The biarc from p0 (unit tangent t0) to p1 (unit tangent t1) with equal tangent lengths d: the
//! joint is the midpoint of the control points p0 + d·t0 and p1 − d·t1, which lie 2d apart, so
//! d·d·|t0 − t1|² + 2d·(p1 − p0)·(t0 + t1) − |p1 − p0|² = 0, taken in the form without cancellation
//! d = |v|² / (v·t + sqrt((v·t)² + |t0 − t1|²·|v|²)). The first arc ends at the joint with the
//! direction from one control point to the other, the second leaves it so and ends along t1. Both
//! pieces are lines when the points and tangents are collinear. nullopt when the tangents point
//! away from each other's point (v·(t0 + t1) ≤ 0) or a piece would turn by more than 90°.
std::optional<std::array<PathSegment, 2>> biarc(const Vec2& p0_m, const Vec2& t0, const Vec2& p1_m,
                                                const Vec2& t1) noexcept;

}  // namespace stiffpath::motion
