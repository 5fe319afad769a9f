// Comparing one job's two routes through LinuxCNC: the commanded tool points at the same place of the laser path.
#pragma once

#include <filesystem>
#include <vector>

#include "cmd_linuxcnc_record.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::cli::linuxcnc {

//! What one route did on the job's laser-on path.
struct RouteSummary {
  double duration_s = 0.0;           //!< recorded time
  double laser_s = 0.0;              //!< time with the laser on
  double laser_path_mm = 0.0;        //!< planned distance travelled with the laser on
  int intervals = 0;                 //!< laser-on stretches (the laser switched on this often)
  double largest_correction_um = 0.0;  //!< max |FK(θ) − planned point| with the laser on
};

struct Comparison {
  RouteSummary routes[2];    //!< [0] LinuxCNC plans, [1] stiffpath plans
  //! Both routes switch the laser on equally often, so their stretches can be paired.
  bool comparable = false;
  //! The largest distance from a commanded tool point FK(θ) of one route to the other route's commanded path
  //! (the polyline of its commanded points in the same laser-on stretch, within 1 mm of planned path length of
  //! the point's place), both ways: how far apart the two routes' drive commands draw the job.
  double largest_difference_um = 0.0;
  double at_path_mm = 0.0;   //!< the s where it occurs
  int at_interval = 0;       //!< in which stretch (0, 1, …)
};

//! Compares the records and writes compare.tsv and the figure compare.svg / .png / .gp into `dir`
//! (when gnuplot is installed and the routes are comparable; else the figure is left out and `figure` is false).
Comparison compare_routes(const std::vector<RecordRow>& linuxcnc, const std::vector<RecordRow>& stiffpath,
                          const kinematics::Robot& robot, double period_s, const std::filesystem::path& dir, bool& figure);

}  // namespace stiffpath::cli::linuxcnc
