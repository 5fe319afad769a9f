// One laser stroke measured while it is marked: cut into sides at its command's corners, in bounded memory.
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/evaluation/cornering.hpp"
#include "stiffpath/evaluation/side_chain.hpp"
#include "stiffpath/evaluation/vertex_finder.hpp"
#include "stiffpath/simulation/run_metrics.hpp"

namespace stiffpath::simulation::detail {

//! Measures one stroke from its command samples and marks, handed over in the order StrokeObserver
//! gives them. The command's sharp corners (evaluation::CornerFinder) cut the stroke into sides: side k
//! holds the marks of the intervals from the corner before it (its last vertex) to the corner after it
//! (its first vertex); the marks while the command turns a corner belong to no side. Each side is
//! measured as it is complete (evaluation::SideChain, the mark's and the command's), AT_p per side
//! (100 normal planes), CR and CO per corner from the marks of its two sides. What is kept: the marks
//! and commands since the last settled vertex (up to VertexFinder's window), the current side and the
//! chains' windows, each side simplified within PathMetricsOptions::trace_tolerance_m.
class StrokeMeter {
 public:
  StrokeMeter(int sides, const evaluation::PathMetricsOptions& options);
  void command(const Vec2& target_m);
  void mark(const Vec2& tip_m);
  //! The stroke has ended: its metrics (index and times are the caller's). `strict`: throw the refusal.
  StrokeMetrics finish(bool strict);

  //! A side's command may run this long (m) without a sharp corner: no five-bar's side is as long, so
  //! the stroke is not straight sides; it is cut there (for AT_p) and its line metrics are refused.
  static constexpr double kMaxSide_m = 2.0;
  //! Points a side's simplified mark may hold before it is cut the same way (memory: 16 MiB).
  static constexpr std::size_t kMaxSidePoints = std::size_t{1} << 20;

 private:
  struct Trace {  // a simplified polyline built point by point
    explicit Trace(double tolerance_m) : tolerance(tolerance_m), finder(tolerance_m, 64) {}
    double tolerance;
    evaluation::VertexFinder finder;
    std::vector<evaluation::Vertex> settled;
    void add(const Vec2& p) { finder.add(p, settled); }
    [[nodiscard]] double finder_tolerance() const noexcept { return tolerance; }
    std::vector<Vec2> take();
  };
  struct Piece {  // the stroke between two consecutive command vertices
    std::size_t start = 0, end = 0;
    std::vector<Vec2> commands, marks;
    double command_length_m = 0.0;
  };
  struct Part {  // a side, or the turn of a corner
    std::vector<Vec2> commands, marks;
  };

  void settle(const std::vector<evaluation::Vertex>& vertices, std::size_t from);
  void assign_until(std::size_t frontier);
  void close_piece(std::size_t end);
  Part take_pieces(std::size_t until);
  void cut(std::size_t first, std::size_t last, const std::optional<evaluation::SharpCorner>& corner);
  void measure_side(Part& side);
  void measure_corner(const evaluation::SharpCorner& corner, const evaluation::SharpCorner* next,
                      const std::vector<Vec2>& window);
  void refuse(const std::string& why);

  int sides_wanted_;
  evaluation::PathMetricsOptions options_;
  evaluation::CornerFinder finder_;
  std::size_t commands_ = 0, marks_ = 0;
  Vec2 first_command_{0, 0}, last_command_{0, 0};
  std::deque<std::pair<std::size_t, Vec2>> pending_commands_, pending_marks_;  // (sample / interval, point)
  std::size_t piece_start_ = 0;
  Trace piece_commands_, piece_marks_;
  double piece_length_m_ = 0.0;
  std::optional<Vec2> piece_last_command_;
  std::deque<Piece> pieces_;         // closed pieces since the current side's start
  std::size_t side_start_ = 0;       // the sample the current side starts at
  double side_length_m_ = 0.0;       // command length of the closed pieces since then
  std::size_t side_points_ = 0;      // simplified marks in them
  // Cornering: the side before the last corner, the corner's turn, and that corner.
  std::optional<Part> before_corner_, turn_;
  std::optional<evaluation::SharpCorner> corner_;
  bool reversal_ = false;  // a corner of the command turns back: the stroke cannot close
  std::size_t sides_ = 0;
  // Line metrics.
  evaluation::SideChain mark_chain_, command_chain_;
  std::string refusal_;
  double length_m_ = 0.0, commanded_m_ = 0.0, area_m2_ = 0.0, max_deviation_m_ = 0.0, command_deviation_m_ = 0.0;
  StrokeMetrics result_;
};

}  // namespace stiffpath::simulation::detail
