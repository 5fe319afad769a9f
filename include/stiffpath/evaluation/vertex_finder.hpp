// Online polyline simplification (vertices of a streamed path within a tolerance) and arc-length resampling.
#pragma once

#include <cstddef>
#include <deque>
#include <span>
#include <vector>

#include "stiffpath/evaluation/line_fit.hpp"

namespace stiffpath::evaluation {

//! A point of a path that a simplification keeps, with its index among the points given.
struct Vertex {
  std::size_t index = 0;
  Point2 point{0.0, 0.0};
};

//! Simplifies a path handed over point by point, in bounded memory: every point lies within about the
//! tolerance of the polyline through the vertices it keeps (within three times it: a cone-intersection
//! test from the last vertex, Sklansky & Gonzalez 1980). When a point leaves the cone, or the path turns
//! back by more than the tolerance (a hairpin, which a cone cannot see), the new vertex is the point
//! farthest from the chord between the last vertex and the new point (as Ramer–Douglas–Peucker picks
//! it), among the last `window` points, or its neighbour (closer than the tolerance) nearer the corner the
//! path turns (where the line from the last vertex through the point before meets the line through the
//! point after and the new point): the sample nearest a sharp corner. Points closer than the tolerance to the last vertex merge into
//! it. The first point is always a vertex, and so is the last (finish()).
class VertexFinder {
 public:
  //! `tolerance_m` > 0; `window` ≥ 2 points may still become a vertex (the cost of one break is O(window)).
  explicit VertexFinder(double tolerance_m, std::size_t window = 512);

  //! Adds the next point (its index is the number of points added before it). Appends the vertices it
  //! settles to `out`, in order. Throws stiffpath::Error for a non-finite point.
  void add(const Point2& p, std::vector<Vertex>& out);
  //! Settles the rest (Ramer–Douglas–Peucker over the points still open) and the last point.
  void finish(std::vector<Vertex>& out);
  //! No vertex with a smaller index than this can be settled any more.
  [[nodiscard]] std::size_t frontier() const noexcept;
  //! Points added so far.
  [[nodiscard]] std::size_t count() const noexcept { return count_; }

 private:
  void consider(const Vertex& v, std::vector<Vertex>& out);
  void settle(const Vertex& v, std::vector<Vertex>& out);

  double tol_;
  std::size_t window_;
  std::size_t count_ = 0;
  bool started_ = false;
  Vertex anchor_;
  Vertex last_;
  std::deque<Vertex> open_;  // points after the anchor, farther than the tolerance from it
  bool cone_ = false;
  Point2 ref_{1.0, 0.0};     // direction the cone's angles are measured from
  double lo_ = 0.0, hi_ = 0.0, d_max_ = 0.0;
};

//! The vertices of `points` (all of them given at once) kept by a VertexFinder of this tolerance.
std::vector<Point2> simplify_path(std::span<const Point2> points, double tolerance_m);

//! The polyline through `points` resampled at equal arc-length steps of at most `step_m`: ⌈S/step⌉ + 1
//! points S/⌈S/step⌉ apart, the first and the last kept. A path of no length gives its first point.
std::vector<Point2> resample_along(std::span<const Point2> points, double step_m);

}  // namespace stiffpath::evaluation
