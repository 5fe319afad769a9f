// Time-series figures of a joint trajectory from `stiffpath run`: the planned and commanded motion, forces, deflection, joints.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/report/gnuplot.hpp"

namespace stiffpath::report {

//! Settings of plot_run. Documented defaults.
struct RunPlotOptions {
  double gain = 1.0;              //!< the run's compensation gain k: predicted Δ = (p − p_cmd)/k when the file holds no Δ
  std::size_t max_points = 4000;  //!< plotted points per series at most (longer runs are decimated, peaks kept)
  int max_line_markers = 40;      //!< G-code line markers drawn at most (evenly chosen among the line changes)
  Style style = Style::screen;
  //! The robot the file was written for (named in the titles; its joint velocity and acceleration limits
  //! drawn on the joint panels); null: neither.
  const kinematics::Robot* robot = nullptr;
};

//! What plot_run read and drew.
struct RunPlotSummary {
  std::size_t samples = 0, plotted = 0;  //!< samples in the file, points per plotted series
  double duration_s = 0.0;
  double peak_speed_mm_s = 0.0, peak_acceleration_m_s2 = 0.0, peak_jerk_m_s3 = 0.0;  //!< of the planned path
  double peak_force_N = 0.0, peak_correction_um = 0.0;
  double peak_power = 0.0;           //!< largest laser power (fraction of full power, 0..1)
  double laser_on_s = 0.0;           //!< time with the laser on
  std::vector<std::string> figures;  //!< <name>_motion, <name>_joints
};

//! Reads a joint file (CSV or binary, by JointReader) in one pass and draws <name>_motion (planned and
//! commanded x, y; path speed, acceleration and jerk by finite differences of the sampled points;
//! D'Alembert force; predicted deflection Δ = (p − p_cmd)/k and correction p_cmd − p, which holds for the
//! quasi-static and the dynamic method alike; laser power) and <name>_joints (θ, ω and α as the file
//! records them, α by differences of ω for files written before α was recorded; the robot's ±ω and ±α
//! limits dashed) against t, with dotted markers where the G-code line changes. "Planned" p is the
//! reference the compensator was given: the G-code's path, smoothed when the run smoothed it. Writes <name>.tsv (the plotted series), and the figures' SVG, PNG and .gp. Runs longer
//! than max_points are cut into equal buckets of samples and each series keeps, per bucket, its value of
//! largest magnitude, so peaks survive decimation. Throws stiffpath::Error for a bad or empty file.
RunPlotSummary plot_run(const std::filesystem::path& dir, const std::string& name, const std::string& joints,
                        const RunPlotOptions& options = {});

}  // namespace stiffpath::report
