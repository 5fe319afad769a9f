// The recordings of `stiffpath linuxcnc run`: halsampler's lines in, one CSV row per servo period out.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::cli::linuxcnc {

//! One servo period of a job: what went to the drives and the laser, and the point it was planned for.
struct RecordRow {
  double t_s = 0.0;
  double theta_rad[2] = {0.0, 0.0};  //!< the commanded joint angles (compensated), as sent to the drives
  bool laser = false;
  double power = 0.0;                //!< 0..1
  double x_mm = 0.0, y_mm = 0.0;     //!< the planned point this period's command realises
};

//! The CSV header of a record: the joint file's names for the same quantities.
inline constexpr const char* kRecordHeader = "t_s,theta1_rad,theta2_rad,laser,power,x_mm,y_mm";

//! halsampler's record of LinuxCNC's route (run's record.hal): sample number, x, y (µm), joint.N.pos-cmd,
//! joint.N.motor-pos-cmd, the drive command (millidegrees), blend, deflection x, y (µm), fault, status, laser,
//! power. θ = drive command − motor offset (motor-pos-cmd − pos-cmd); x, y = the robot's forward kinematics
//! of pos-cmd (motion's uncompensated joint command). t_s from 0 at the first row.
std::vector<RecordRow> read_machine_record(const std::filesystem::path& file, const kinematics::Robot& robot,
                                           double period_s);

//! halsampler's record of the streamed route: period number, stream sample number, θ1, θ2
//! (millidegrees), laser, power. Keeps the periods that played samples 1..N of `joint_file` (checked:
//! each once, in order, one per period — else the stream ran dry); x, y from the joint file's planned points.
std::vector<RecordRow> read_stream_record(const std::filesystem::path& file, const std::filesystem::path& joint_file,
                                          double period_s);

//! Writes the rows as CSV (kRecordHeader; θ to 12 decimals, power 9, mm 9), atomically.
void write_record_csv(const std::filesystem::path& file, const std::vector<RecordRow>& rows);

}  // namespace stiffpath::cli::linuxcnc
