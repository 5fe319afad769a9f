// The calibration plate: marks designed to identify a robot's dynamics and laser timing from a scan of what it marked.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::calibration {

using kinematics::Vec2;

//! A ring the robot marks slowly (no deflection), with a cross inside: its centre registers the scan to the
//! robot frame. The shape's numbers are those the scan looks for (vision::FiducialShape).
struct FiducialMark {
  std::string id;                    //!< "F1" …
  Vec2 centre_m = Vec2::Zero();      //!< robot frame
  double ring_radius_m = 3e-3;       //!< radius of the ring's centre line
  double cross_arm_m = 1.5e-3;       //!< half length of each stroke of the cross (stops short of the ring)
};

//! What a stroke shows.
enum class StrokeKind : std::uint8_t {
  ringing,  //!< a fast stroke then, the laser still on, a slow tail at right angles (to its left), on which the
            //!< tip's ringing after the stop draws a wave (wavelength: the tail's speed over the tip's frequency)
  timing,   //!< a fast stroke whose laser switches on and off at speed: the motion runs up to speed before the
            //!< mark and on after it (run_m each side, the laser off, collinear and blended), so a delay of the
            //!< laser moves the mark's ends by the speed times it (0.4 mm per ms at 0.4 m/s)
  arc,      //!< a fast arc about a centre: its centripetal acceleration acts across the mark, so the mark's radius
            //!< shows the deflection along every direction the arc turns through. Straight strokes show only the
            //!< compliance's cross term and the difference of its diagonal (n·Q·u, u ⊥ n); an arc shows n·Q·n,
            //!< and so the field's size itself
};

//! A stroke from rest to rest (exact stops): along a direction, with or without its tail, or along an arc.
struct StrokeMark {
  std::string id;                    //!< "S2-D060-A1-R", "S2-A1-C": station, direction (deg), acceleration level, kind
  StrokeKind kind = StrokeKind::ringing;
  Vec2 start_m = Vec2::Zero();       //!< robot frame
  Vec2 end_m = Vec2::Zero();         //!< end of the stroke (start of the tail; an arc's end)
  Vec2 tail_end_m = Vec2::Zero();    //!< ringing strokes: end of the tail; the others: end_m
  Vec2 centre_m = Vec2::Zero();      //!< arcs: the centre (start and end lie on its circle)
  double sweep_rad = 0.0;            //!< arcs: the angle turned, counter-clockwise positive
  double acceleration_m_s2 = 0.0;    //!< the planner's limit for this mark (M204)
  double feed_m_s = 0.0;             //!< the stroke's programmed speed
  double tail_feed_m_s = 0.0;        //!< the tail's (ringing strokes)
  double run_m = 0.0;                //!< timing strokes: the run-up before start_m and the run-out after end_m, laser off
  //! The commanded path: start, end (and the tail's end for a ringing stroke); an arc every 2° at most.
  [[nodiscard]] std::vector<Vec2> polyline_m() const;
  //! The unit direction of the path where the mark starts, and where it ends.
  [[nodiscard]] Vec2 start_direction() const;
  [[nodiscard]] Vec2 end_direction() const;
  //! Where the tool moves for the mark: the polyline with a timing stroke's run-up and run-out.
  [[nodiscard]] std::vector<Vec2> motion_m() const;
};

//! How a plate is laid out. Documented defaults; every length fits the robot's own measured region.
struct PlateOptions {
  double acceleration_m_s2 = 5.0 * units::standard_gravity_m_s2;  //!< the highest acceleration (5 g); the job's --accel
  //! The accelerations, as fractions of acceleration_m_s2 (at least two: deflection scales with it, laser
  //! timing does not).
  std::vector<double> acceleration_levels{1.0, 0.5};
  std::vector<double> directions_deg{0.0, 60.0, 120.0};  //!< at least three
  int stations_x = 2, stations_y = 2;  //!< places spread over the measured region (at least four)
  double tail_length_m = 4e-3;
  double tail_feed_m_s = 0.02;         //!< 20 mm/s: a 40 Hz ringing draws waves 0.5 mm long
  double arc_sweep_deg = 270.0;        //!< each arc's turn (one per station and acceleration level): 180 … 300°
  double fiducial_feed_m_s = 0.01;     //!< the fiducials' speed (10 mm/s: no deflection to speak of)
  double sheet_long_m = 0.297;         //!< the sheet (A4)
  double sheet_short_m = 0.210;
  double margin_m = 1.5e-3;            //!< kept clear between marks, and inside the region's edge
};

//! A plate: what `calibrate plate` writes as plate.json (and, as G-code, plate.gcode).
struct PlateDesign {
  std::string robot;                  //!< name
  std::string geometry_sha256;        //!< the robot's geometry hash: a plate is for one robot
  compliance::GridBounds area;        //!< where the marks are (robot frame, m)
  compliance::GridBounds sheet;       //!< the sheet's rectangle (robot frame, m)
  std::vector<FiducialMark> fiducials;
  std::vector<StrokeMark> strokes;
  double laser_power = 1.0;           //!< fraction of full power of every mark
};

//! Lays out a plate for `robot` over `region` (its measured region: where its compliance model holds): the
//! sheet centred on it, four fiducials in the corners of the marked area, and stations_x × stations_y
//! stations, each with a ringing stroke per direction and acceleration level and a timing stroke per direction
//! at the highest level, each in a cell of its own, so no two marks cross. Every mark's point is checked against the robot (reach and joint limits). Throws stiffpath::Error
//! for options out of range or a region that cannot hold the plate, naming what does not fit.
PlateDesign design_plate(const kinematics::Robot& robot, const compliance::GridBounds& region,
                         const PlateOptions& options = {});
//! Where the robot's compliance model holds, over which its plate is laid out: its table's points' rectangle, else
//! its model file's. Throws stiffpath::Error naming the robot file when it has neither.
compliance::GridBounds plate_region(const kinematics::Robot& robot);

//! The plate as a G-code program in the robot frame (mm, G21 G90 G61): the fiducials first, then the strokes,
//! each with its acceleration (M204 S, mm/s²), the laser on for every mark (M3) and off between (M5).
std::string plate_gcode(const PlateDesign& plate, const PlateOptions& options = {});

//! Writes / reads plate.json (units in the keys: mm, mm/s, mm/s²). Reading checks every field with its line
//! and column, and refuses unknown keys.
std::string plate_json(const PlateDesign& plate);
PlateDesign load_plate(const std::string& path);

}  // namespace stiffpath::calibration
