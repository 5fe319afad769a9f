// measure_sides one side at a time: the metrics of a long chain of sides in memory bounded by a few sides.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "stiffpath/evaluation/path_metrics.hpp"

namespace stiffpath::evaluation {

//! Measures consecutive sides as they come, with exactly measure_sides' numbers. A side's metrics
//! depend on its fitted line after two trimming passes, which depend on the sides up to three before
//! and three after it; so side k is measured when side k + 3 arrives, and only the sides still
//! needed are kept (the first three too, until finish() says whether the path closes). Sides that
//! meet at less than kReversalAngle_rad are joined by a free end on both (no corner). Errors are
//! measure_sides' (stiffpath::Error), thrown by the add() or finish() that needs the failing side.
class SideChain {
 public:
  //! Receives a measured side (sides come out of order: the first three at finish()).
  using SideSink = std::function<void(std::size_t index, SideMetrics&& side)>;
  //! Receives a corner once both its sides are measured.
  using CornerSink = std::function<void(CornerReport&& corner)>;

  SideChain(const PathMetricsOptions& options, SideSink on_side, CornerSink on_corner = {});

  //! The next side: its points in the order marked (m), at least two. The chain keeps a simplified
  //! trace and the arc-length samples, not the points.
  void add(std::span<const Point2> points);
  //! The same with the side already simplified (simplify_path with trace_tolerance_m): kept as it is.
  void add_trace(std::vector<Point2> trace);
  //! No more sides; `closed`: the last side ends where the first begins (needs two sides or more).
  void finish(bool closed);
  [[nodiscard]] std::size_t sides() const noexcept { return n_; }
  //! Reversals found between consecutive sides so far.
  [[nodiscard]] std::size_t reversals() const noexcept { return reversals_; }

 private:
  struct Side {
    std::vector<Point2> trace;    // the side's points within trace_tolerance_m (free ends, corner distances)
    std::vector<Point2> samples;  // arc-length samples (line, spline, area)
    Point2 heading{1.0, 0.0};     // last point − first point
    std::array<std::optional<LineFit>, 3> fit;           // before trimming, after one pass, after two
    std::array<std::optional<std::optional<Point2>>, 3> after;  // junction with the next side, per pass
    std::optional<bool> reversal_after;
    bool measured = false;
    bool corner_reported = false;  // the corner after this side
  };

  Side& at(std::size_t k);
  [[nodiscard]] std::optional<std::size_t> prev(std::size_t k) const;
  [[nodiscard]] std::optional<std::size_t> next(std::size_t k) const;
  bool reversal_after(std::size_t k);
  const LineFit& fit(int pass, std::size_t k);
  const std::optional<Point2>& junction(int pass, std::size_t k);
  std::vector<Point2> kept(std::size_t k);
  void measure(std::size_t k);
  void report_corner(std::size_t k);
  void forget_before(std::size_t k);

  PathMetricsOptions options_;
  SideSink on_side_;
  CornerSink on_corner_;
  std::map<std::size_t, Side> sides_;
  std::size_t n_ = 0;
  std::size_t reversals_ = 0;
  bool closed_ = false;
  bool finished_ = false;
};

}  // namespace stiffpath::evaluation
