// The documented bounds the G-code reader checks each value against where it enters (docs/motion.md).
#pragma once

#include <cstddef>

namespace stiffpath::motion {

//! |X|, |Y| as programmed and every point the path reaches in the robot frame, arcs included (m).
//! The thesis's workspace spans 0.3 m; 10 m is far beyond any planar five-bar yet keeps every
//! product of the planner finite. A move of 1e9 mm or a coordinate of 1e157 mm is refused here.
inline constexpr double max_coordinate_m = 10.0;
//! |I|, |J|, |R| and the radius of an arc (m): nearly straight arcs from CAM arc fitting pass.
inline constexpr double max_arc_radius_m = 1000.0;
//! Slowest feed accepted (mm/min): 1 mm/min. Lower feeds (0.001 mm/min) are refused at the F word.
inline constexpr double min_feed_mm_min = 1.0;
//! Fastest feed accepted (mm/min): 1000 m/min, far beyond any speed limit; the planner then caps
//! the speed at MotionLimits::max_velocity_m_s as it does for every feed.
inline constexpr double max_feed_mm_min = 1e6;
//! Longest a single block may take (s): a dwell, or a feed move's length over its feed. Beyond an
//! hour the block is refused: it is a typo or a unit mix-up, and its samples would fill a disk.
inline constexpr double max_block_duration_s = 3600.0;
//! Dwells longer than this (s) are accepted with a warning (G4 P500 is 500 s, or 0.5 s in ms).
inline constexpr double long_dwell_warning_s = 60.0;
//! Default blend tolerance (m): of a G64 without P and of a program that names no mode (20 µm; see
//! GcodeOptions::default_blend_tolerance_m).
inline constexpr double default_blend_tolerance_m = 20e-6;
//! Largest G64 P blend tolerance (m); a corner is never rounded by more than half its shorter line.
inline constexpr double max_blend_tolerance_m = 1.0;
//! Default full-scale S: 1000, GRBL's default $30 (LightBurn's GRBL profile). Marlin uses 255.
inline constexpr double default_s_max = 1000.0;
//! M106 (Marlin's fan output driving a laser) takes S in 0–255.
inline constexpr double fan_s_max = 255.0;
//! Refusals listed one by one before the rest are only counted ("… and N more"); no more are kept,
//! not even of one line (a 16 MB line of `G1G1…` held a refusal per word).
inline constexpr std::size_t max_reported_errors = 20;
//! Longest line read (bytes, without its line end): 64 KiB, 250 times LinuxCNC's and GRBL's 256. A
//! longer line (or a file without line ends, such as /dev/zero) is refused at its column 65 537
//! after reading at most that much, and reading stops there.
inline constexpr std::size_t max_line_bytes = 65536;
//! Highest M-code in GcodeOptions::ignored_m_codes and output number P of GcodeOptions::outputs.
inline constexpr double max_code_number = 1000.0;

}  // namespace stiffpath::motion
