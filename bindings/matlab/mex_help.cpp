// The help texts of the MEX gateway: stiffpath('help') for the overview, stiffpath('help', command) for one command.
#include <cstring>
#include <string>

#include "mex_args.hpp"
#include "mex_commands.hpp"

namespace stiffpath::mex {

namespace {

struct Help {
  const char* command;
  const char* text;
};

// The overview is also bindings/matlab/stiffpath.m's comment (what `help stiffpath` prints); keep both in step.
constexpr Help kHelp[] = {
    {"", R"(stiffpath(command, ...): the stiffpath library from MATLAB/Octave. SI units everywhere (m, rad, N, s).
Results are structs with named fields; stiffpath('help', command) explains one command.

  q_rad = stiffpath('ik', robot, p_m)                     inverse kinematics, N×2 → N×2
  p_m   = stiffpath('fk', robot, q_rad)                   forward kinematics
  model = stiffpath('fit', robot [, options])             fit a compliance model (as stiffpath fit --json)
  cv    = stiffpath('cv', robot [, options])              leave-one-out cross-validation, a struct per method
  r     = stiffpath('predict', model, p_m, F_N [, opts])  deflection, compliance and 95 % band
  C     = stiffpath('compliance', model, p_m [, opts])    2×2×N compliance (m/N)
  [T, s] = stiffpath('plan', gcode_file [, options])      jerk-limited trajectory (accel, jerk, rate_hz, robot, …)
  [J, s] = stiffpath('run', gcode_file, robot [, opts])   the main job, exactly as `stiffpath run`
  [J, s] = stiffpath('compensate', robot, model, T [, o]) the main job on planned samples T
  m     = stiffpath('simulate', robot, J [, options])     the digital twin's mark and metrics
  m     = stiffpath('scan', image [, options])            a scanned mark measured (loads OpenCV: stiffpath_scan)
  stiffpath('help' [, command])                           this text, or one command's

robot: a preset ('oc-gu', 'sc-gu', …) or a robot file; model: a model file or built-in name ('thesis-oc', …).
Errors: stiffpath:badInput (the message names the file, line and value), stiffpath:usage, stiffpath:internal.
)"},
    {"ik", R"(q_rad = stiffpath('ik', robot, p_m)
  Joint angles (N×2, rad) of the points p_m (N×2, m). A point the robot cannot reach is an error naming its row.)"},
    {"fk", R"(p_m = stiffpath('fk', robot, q_rad)
  Points (N×2, m) of the joint angles q_rad (N×2, rad), each within the joints' ranges.)"},
    {"fit", R"(model = stiffpath('fit', robot [, options])
  Fits a compliance model to a displacement table, as `stiffpath fit --json`; returns the model document as a
  struct (method, provenance, nodes or D_um_per_N, uncertainty, …; keys with '-' get '_').
  options: table ('' the robot's own, 'thesis', or a CSV file), method ('auto': the one cross-validation favours;
  'bilinear', 'symmetric', 'physical', 'physical-0', 'physical-2', 'physical-spline'), rows (the table's
  mechanism rows, default the robot's), forces ('measured' | 'nominal'), outside ('error' | 'clamp' |
  'extrapolate'), zero_force ('relative' | 'thesis-raw'), output (write the model file).
  The earlier form stiffpath('fit', robot, table_csv, method, model_file) still works.)"},
    {"cv", R"(cv = stiffpath('cv', robot [, options])
  Leave-one-out cross-validation of every compliance method that can run on the robot's table, as
  `stiffpath cv --json`, in SI: cv.favoured_method, cv.methods.<method> (description, predicted_points,
  mean_error_m, max_error_m, interior_mean_error_m, common_points_mean_error_m, band_95, points) with
  'physical-spline' as physical_spline, cv.could_not_run.<method> = reason.
  options: table ('' the robot's own, 'thesis', or a CSV file), rows, forces, zero_force (as fit).)"},
    {"predict", R"(r = stiffpath('predict', model, p_m, F_N [, options])
  The deflection Δ = C(p)·F at the points p_m (N×2, m) under F_N (N×2 or one row, N): r.d_m (N×2), r.C_m_per_N
  (2×2×N), r.inside, and when the model's uncertainty is known r.d_sigma_m, r.d_band_95_m,
  r.measured_d_band_95_m (N×2, the campaign's scatter added) and r.uncertainty_basis.
  model: a model file or built-in name, or '' with options.robot: the robot's own.
  options: robot, outside ('error' | 'clamp' | 'extrapolate'), force_model (accept another geometry's model).)"},
    {"compliance", R"(C = stiffpath('compliance', model, p_m [, options])
  The 2×2×N compliance matrices (m/N) at the points p_m (N×2, m). options as predict's.)"},
    {"plan", R"([T, summary] = stiffpath('plan', gcode_file [, options])
  Plans a G-code program with look-ahead and jerk-limited profiles, as `stiffpath plan`, sampled at rate_hz.
  T: struct of columns t_s (N×1), p_m, v_m_s, a_m_s2, j_m_s3 (N×2), laser (logical), power (0…1), line.
  summary: duration_s, samples, rate_hz, peak_velocity_m_s, peak_acceleration_m_s2, peak_jerk_m_s3, limits.
  options: robot (default 'oc-gu': its home for G28; every sample checked inside its workspace),
  accel (m/s², or text: '5g'; default 5 g), jerk (m/s³; default accel / 5 ms), max_velocity_m_s (default 2),
  rate_hz (default 2000), work_offset_m, start_m ([x y] m), blend ('on' | 'off' for a program naming neither
  G61 nor G64), blend_tolerance_m (default 2e-5), max_samples (default 2e7).)"},
    {"run", R"([J, summary] = stiffpath('run', gcode_file, robot [, options])
  The main job exactly as `stiffpath run` makes it (job::JobSpec: one set of defaults on every surface): plans,
  compensates every sample and returns the joint commands.
  J: struct of columns t_s, q_rad, qd_rad_s, qdd_rad_s2, target_m, command_m, force_N, deflection_m (N×2),
  laser, outside_grid (logical), power, line (the joint file's fields, then deflection_m, outside_grid). summary: as `run --json` in SI (model, method, gain, filters,
  duration_s, samples, peak_deflection_m, peak_correction_m, peak_force_N, …).
  options: model (file or built-in name; default the robot's own), force_model, thesis (true: the thesis's
  method: bilinear model, quasi-static, no filter), compensate (false: the planned path as it is),
  method ('dynamic' | 'quasi-static'), gain (0…10, default 1), damping_ratio (0…0.9; default the robot
  file's), smooth_s (0…1 s; default 0.008 when compensating, 0 without), shaper ('none' | 'zv' | 'zvd'),
  outside ('error' | 'clamp' | 'extrapolate'), acceleration ('analytic' | 'numeric'), laser_on_delay_s,
  laser_off_delay_s (±0.05 s; default the robot file's), jerk ('auto': accel × the tip's lowest frequency),
  max_samples, and plan's options (accel, jerk, max_velocity_m_s, rate_hz, work_offset_m, start_m, blend,
  blend_tolerance_m). The first refused sample is an error naming its G-code line.)"},
    {"compensate", R"([J, summary] = stiffpath('compensate', robot, model, T [, options])
  The main job on planned samples: T is plan's struct (or the earlier N×7…10 matrix [t x y vx vy ax ay jx jy
  laser]). model '' = the robot's own. Returns J and summary as run's. options: run's compensation options
  (force_model, thesis, compensate, method, gain, damping_ratio, smooth_s, shaper, outside, acceleration,
  laser_on_delay_s, laser_off_delay_s) and rate_hz (T's sample rate, default 2000); a plain number is the gain.)"},
    {"simulate", R"(m = stiffpath('simulate', robot, joints [, options])
  Runs joint commands (run's struct J, or a joint file written by `stiffpath run`) through the digital twin and
  measures the mark, as `stiffpath simulate --json` in SI: duration_s, marked_points, length_m,
  commanded_length_m, length_error_m, deviation_area_m2, max_deviation_m, path_accuracy_m, corners,
  cornering_round_off_m, cornering_overshoot_m ([] when not measured), residual_vibration_m, peak_deflection_m,
  strokes, line_strokes, stroke_metrics (struct array), marked_m (N×2) and stroke_starts (1-based into marked_m).
  options: sides (0: inferred per stroke), truth ('structural' | 'physical'), perturbation (0…0.5, default 0.1),
  seed, servo ('loaded' | 'ideal'), cg_lever (default true), mass_scale, damping_ratio, motor_inertia_kg_m2,
  load_feedforward, load_feedforward_from ('reference' | 'command'), servo_bandwidth_hz, step_rate_hz,
  corner_trim_m (default 0.001), max_steps, force_robot (a joint file written for another robot).)"},
    {"scan", R"(m = stiffpath('scan', image [, options])
  Measures the marked path on a scan as `stiffpath scan --json` (lengths in mm, as its keys say), plus
  m.points_m (N×2, the centre line in m). image: an image file, or a uint8 grey matrix (then options.dpi).
  options: dpi, shape ('line', 'triangle', …), spline_cutoff_m, corner_trim_m, roi_px ([x y w h]).
  Runs in the second gateway stiffpath_scan, which alone loads OpenCV.)"},
    {"help", R"(stiffpath('help') or stiffpath('help', command): the overview, or one command's text; with an output
  argument the text is returned instead of printed.)"},
};

}  // namespace

const char* help_text(const char* command) {
  for (const auto& h : kHelp) {
    if (std::strcmp(h.command, command) == 0) return h.text;
  }
  return nullptr;
}

void help(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 1, 2, "stiffpath('help' [, command])");
  const std::string command = nrhs == 2 ? text_arg(prhs[1], "command") : "";
  const char* text = help_text(command.c_str());
  if (text == nullptr) throw UsageError("no help for '" + command + "': stiffpath('help') lists the commands");
  if (nlhs > 0) {
    plhs[0] = mxCreateString(text);
  } else {
    mexPrintf("%s\n", text);
  }
}

}  // namespace stiffpath::mex
