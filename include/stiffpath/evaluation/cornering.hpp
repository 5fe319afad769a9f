// ISO 9283:1998 §7.8 cornering deviations of an attained path at the sharp corners of its commanded path.
#pragma once

#include <deque>
#include <span>
#include <vector>

#include "stiffpath/evaluation/line_fit.hpp"
#include "stiffpath/evaluation/vertex_finder.hpp"

namespace stiffpath::evaluation {

//! The deviations of one attained path at one sharp corner of the command. SI.
struct CorneringDeviation {
  Point2 corner{0.0, 0.0};    //!< the commanded corner point (m)
  double turn_rad = 0.0;      //!< change of direction at the corner (0 = straight on, π = reversal)
  double round_off_m = 0.0;   //!< CR: distance from the corner point to the nearest point of the attained path
  //! CO: how far the attained path goes outside the outgoing side's line near the corner (0 if never):
  //! the largest offset from that line on the side the incoming motion came from (inertia's side).
  double overshoot_m = 0.0;
  //! Whether the attained path entered the corner's neighbourhood. If not, CR is its distance from
  //! the corner (at least the neighbourhood's radius) and CO is 0: there is no overshoot to measure.
  bool reached = true;
};

//! Options of the cornering evaluation.
struct CorneringOptions {
  //! A vertex of the command is a corner when the direction turns by more than this (rad, 10°).
  double min_turn_rad = 0.17453292519943295;
  //! Points of the command closer together than this are merged before directions are taken (m),
  //! so that the dense samples of a move coming to rest do not make up directions of their own.
  double merge_distance_m = 1e-6;
  //! Vertices of the command joined by segments shorter than this (m), between straight sides at least
  //! this long, form one corner at the sides' intersection: a corner rounded by a few µm (a smoothed
  //! reference at an exact stop, a small G64 blend) is still the corner the sides meet at. Arcs and
  //! fillets wider than this are no corners.
  double max_corner_span_m = 0.5e-3;
  //! The neighbourhood of a corner is this fraction of the shorter adjacent side: the attained
  //! points inside it (in the order marked, from their first entry to their last exit) count.
  double neighbourhood_fraction = 0.5;
};

//! A sharp corner of a commanded path.
struct SharpCorner {
  Point2 at{0.0, 0.0};   //!< the corner point: where the incoming and the outgoing side meet (m)
  Point2 in{1.0, 0.0};   //!< unit direction of the incoming side
  Point2 out{1.0, 0.0};  //!< unit direction of the outgoing side
  double turn_rad = 0.0; //!< change of direction (π: a reversal)
  double reach_m = 0.0;  //!< radius of its neighbourhood: neighbourhood_fraction × the shorter adjacent side
  //! Indices (among the command's points) of the first and the last vertex of the corner: equal for a
  //! sharp vertex, apart for a corner rounded or stepped within max_corner_span_m.
  std::size_t first_index = 0, last_index = 0;
};

//! Finds the sharp corners of a command handed over point by point, in bounded memory: the command's
//! vertices (VertexFinder with merge_distance_m), then runs of vertices within max_corner_span_m between
//! straight sides at least that long, turning by more than min_turn_rad. A corner is known once the
//! vertex after its outgoing side is (two sides late). Endpoints are never corners. The corner point
//! is the intersection of the sides' lines, or for a near reversal (turn within min_turn_rad of π,
//! where that intersection runs off) the vertex farthest along the incoming side.
class CornerFinder {
 public:
  explicit CornerFinder(const CorneringOptions& options = {});
  //! Adds the next command point; appends the vertices it settles and the corners it decides.
  void add(const Point2& p, std::vector<Vertex>& vertices, std::vector<SharpCorner>& corners);
  //! The command has ended: settles the last vertices and corners.
  void finish(std::vector<Vertex>& vertices, std::vector<SharpCorner>& corners);
  //! No vertex with a smaller index than this can be settled any more (VertexFinder::frontier()).
  [[nodiscard]] std::size_t frontier() const noexcept { return finder_.frontier(); }

 private:
  void take(const std::vector<Vertex>& settled, std::size_t from, std::vector<SharpCorner>& corners);
  void decide(std::vector<SharpCorner>& corners);

  CorneringOptions options_;
  VertexFinder finder_;
  std::deque<Vertex> v_;     // vertices from the one before the next corner candidate on
  std::size_t base_ = 0;     // number of vertices before v_.front()
  std::size_t next_ = 1;     // the next corner candidate (a vertex number)
  bool finished_ = false;
};

//! The cornering deviations of `attained` (points in m, in the order marked) at `corner`, searching
//! from `cursor`: its neighbourhood's points from their first entry to their first exit count (CR their
//! polyline's distance from the corner, CO their largest offset outside the outgoing side). When the
//! path reaches the next corner's neighbourhood (`next`, when given) or its end first, the corner is
//! missed (entering the next one from outside it: the path may start inside it, as a hatch's line does
//! beside the next corner): CR is the distance from the corner to the path searched, CO 0, and `cursor` stays; else
//! `cursor` moves past the exit. O(points searched).
CorneringDeviation corner_deviation(const SharpCorner& corner, const SharpCorner* next, std::span<const Point2> attained,
                                    std::size_t& cursor);

//! Finds the sharp corners of `command` (CornerFinder) and measures `attained` (points in m in the
//! order marked) at each, in order along the command (corner_deviation, each search starting where the
//! previous corner's neighbourhood was left and ending at the next's). Endpoints of the command are
//! not corners, even when it closes on itself. Returns no entries for a command without sharp corners.
//! Time linear in the points. Throws stiffpath::Error for fewer than two attained points, a command
//! shorter than two distinct points, or non-finite coordinates.
std::vector<CorneringDeviation> iso9283_cornering(std::span<const Point2> command, std::span<const Point2> attained,
                                                  const CorneringOptions& options = {});

}  // namespace stiffpath::evaluation
