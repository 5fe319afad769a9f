// The MATLAB/Octave gateway `stiffpath(command, …)`: kinematics, compliance fits and predictions, planning and
// compensation over matrices. Only the C MEX API (mex.h), so `mkoctfile --mex` and MATLAB's `mex` both build it.
#include <mex.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compensation/run_filters.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/job/prepared_job.hpp"
#include "stiffpath/job/joint_record.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/measurement/displacement_table.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace {

using stiffpath::kinematics::Vec2;

// Bad arguments from the caller (as opposed to stiffpath::Error from the library).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string text_arg(const mxArray* a, const char* what) {
  if (a == nullptr || !mxIsChar(a)) throw UsageError(std::string(what) + " must be a character string");
  char* chars = mxArrayToString(a);
  std::string s(chars != nullptr ? chars : "");
  mxFree(chars);
  return s;
}

// An N×k real double matrix, read column-major.
struct Matrix {
  const double* data;
  std::size_t rows, cols;
  double operator()(std::size_t r, std::size_t c) const { return data[c * rows + r]; }
};

Matrix matrix_arg(const mxArray* a, const char* what, std::size_t min_cols, std::size_t max_cols) {
  if (a == nullptr || !mxIsDouble(a) || mxIsComplex(a) || mxIsSparse(a)) {
    throw UsageError(std::string(what) + " must be a real double matrix");
  }
  const Matrix m{mxGetPr(a), mxGetM(a), mxGetN(a)};
  if (m.cols < min_cols || m.cols > max_cols) {
    throw UsageError(std::string(what) + " must have " + std::to_string(min_cols) +
                     (max_cols > min_cols ? " to " + std::to_string(max_cols) : "") + " columns, not " +
                     std::to_string(m.cols));
  }
  return m;
}

mxArray* new_matrix(std::size_t rows, std::size_t cols) { return mxCreateDoubleMatrix(rows, cols, mxREAL); }

void need(int nrhs, int count, const char* usage) {
  if (nrhs != count) throw UsageError(std::string("usage: ") + usage);
}

// q = stiffpath('ik', robot, P): P N×2 (m) → N×2 θ (rad); every point checked as the CLI's kin ik.
void ik(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 3, "q_rad = stiffpath('ik', robot, p_m)  % p_m: N×2 in m");
  (void)nlhs;
  const auto robot = stiffpath::kinematics::load_robot(text_arg(prhs[1], "robot"));
  const Matrix p = matrix_arg(prhs[2], "p_m", 2, 2);
  plhs[0] = new_matrix(p.rows, 2);
  double* q = mxGetPr(plhs[0]);
  for (std::size_t i = 0; i < p.rows; ++i) {
    const Vec2 angles = robot.inverse(Vec2(p(i, 0), p(i, 1)));
    q[i] = angles.x();
    q[p.rows + i] = angles.y();
  }
}

// P = stiffpath('fk', robot, Q): Q N×2 (rad) → N×2 (m).
void fk(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 3, "p_m = stiffpath('fk', robot, q_rad)  % q_rad: N×2 in rad");
  const auto robot = stiffpath::kinematics::load_robot(text_arg(prhs[1], "robot"));
  const Matrix q = matrix_arg(prhs[2], "q_rad", 2, 2);
  plhs[0] = new_matrix(q.rows, 2);
  double* p = mxGetPr(plhs[0]);
  for (std::size_t i = 0; i < q.rows; ++i) {
    Vec2 point;
    try {
      point = robot.forward(Vec2(q(i, 0), q(i, 1)));  // finite, within the joints' ranges (as `kin fk`)
    } catch (const stiffpath::Error& e) {
      throw stiffpath::Error("q_rad row " + std::to_string(i + 1) + ": " + e.message());
    }
    p[i] = point.x();
    p[q.rows + i] = point.y();
  }
}

// stiffpath('fit', robot, table, method, model_file): fits and writes a model file; returns its JSON text.
void fit(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 5, "json = stiffpath('fit', robot, table_csv, method, model_file)  % table_csv '' = the robot's own");
  const auto robot = stiffpath::kinematics::load_robot(text_arg(prhs[1], "robot"));
  const std::string table_path = text_arg(prhs[2], "table_csv");
  const auto table = table_path.empty() ? stiffpath::compliance::robot_table(robot)
                                        : stiffpath::measurement::load_displacement_table(table_path);
  const std::string rows = table_path.empty() ? "" : robot.compliance.rows;
  const auto fitted = stiffpath::compliance::fit_model(table, rows,
                                                       stiffpath::compliance::parse_fit_method(text_arg(prhs[3], "method")),
                                                       stiffpath::compliance::ForceConvention::measured, robot);
  const std::string out = text_arg(prhs[4], "model_file");
  if (!out.empty()) stiffpath::compliance::save_model(out, *fitted.model, fitted.provenance);
  plhs[0] = mxCreateString(stiffpath::compliance::model_to_json(*fitted.model, fitted.provenance).dump(2).c_str());
}

stiffpath::compliance::LoadedModel model_arg(const mxArray* a) {
  return stiffpath::compliance::load_model(text_arg(a, "model"));
}

// D = stiffpath('predict', model, P, F): Δ (m) at P (m) under F (N), N×2 each (one row of F for all points).
void predict(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 4, "d_m = stiffpath('predict', model, p_m, F_N)  % model: a file or built-in name; N×2 each");
  const auto loaded = model_arg(prhs[1]);
  const Matrix p = matrix_arg(prhs[2], "p_m", 2, 2);
  const Matrix F = matrix_arg(prhs[3], "F_N", 2, 2);
  if (F.rows != p.rows && F.rows != 1) throw UsageError("F_N must have one row or as many rows as p_m");
  plhs[0] = new_matrix(p.rows, 2);
  double* d = mxGetPr(plhs[0]);
  for (std::size_t i = 0; i < p.rows; ++i) {
    const Vec2 point(p(i, 0), p(i, 1));
    if (loaded.model->refuses(point)) {
      throw stiffpath::Error("p_m row " + std::to_string(i + 1) + " is outside model " + loaded.label +
                             "'s measured rectangle");
    }
    const std::size_t k = F.rows == 1 ? 0 : i;
    const Vec2 delta = loaded.model->predict(point, Vec2(F(k, 0), F(k, 1)));
    d[i] = delta.x();
    d[p.rows + i] = delta.y();
  }
}

// C = stiffpath('compliance', model, P): 2×2×N compliance matrices (m/N).
void compliance(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 3, "C = stiffpath('compliance', model, p_m)  % 2×2×N in m/N");
  const auto loaded = model_arg(prhs[1]);
  const Matrix p = matrix_arg(prhs[2], "p_m", 2, 2);
  const mwSize dims[3] = {2, 2, static_cast<mwSize>(p.rows)};
  plhs[0] = mxCreateNumericArray(3, dims, mxDOUBLE_CLASS, mxREAL);
  double* c = mxGetPr(plhs[0]);
  for (std::size_t i = 0; i < p.rows; ++i) {
    const Vec2 point(p(i, 0), p(i, 1));
    if (loaded.model->refuses(point)) {
      throw stiffpath::Error("p_m row " + std::to_string(i + 1) + " is outside model " + loaded.label +
                             "'s measured rectangle");
    }
    const auto C = loaded.model->compliance(point);
    c[4 * i + 0] = C(0, 0);
    c[4 * i + 1] = C(1, 0);
    c[4 * i + 2] = C(0, 1);
    c[4 * i + 3] = C(1, 1);
  }
}

// T = stiffpath('plan', gcode_file): N×10 [t x y vx vy ax ay jx jy laser] (SI), planned and sampled at 2 kHz.
void plan(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 2, "T = stiffpath('plan', gcode_file)  % N×10: t_s x_m y_m vx vy ax ay jx jy laser");
  stiffpath::motion::TrajectoryStream stream(text_arg(prhs[1], "gcode_file"));
  std::vector<stiffpath::motion::TrajectorySample> samples;
  while (auto s = stream.next()) samples.push_back(*s);
  const std::size_t n = samples.size();
  plhs[0] = new_matrix(n, 10);
  double* t = mxGetPr(plhs[0]);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& s = samples[i];
    const double row[10] = {s.t_s, s.position_m.x(), s.position_m.y(), s.velocity_m_s.x(), s.velocity_m_s.y(),
                            s.acceleration_m_s2.x(), s.acceleration_m_s2.y(), s.jerk_m_s3.x(), s.jerk_m_s3.y(),
                            s.laser_on ? 1.0 : 0.0};
    for (std::size_t c = 0; c < 10; ++c) t[c * n + i] = row[c];
  }
}

// The rows of a trajectory matrix as the job's sample source.
// The rows of T as the planned samples of a job.
std::vector<stiffpath::motion::TrajectorySample> samples_of(const Matrix& m) {
  std::vector<stiffpath::motion::TrajectorySample> out(m.rows);
  for (std::size_t i = 0; i < m.rows; ++i) {
    const auto col = [&](std::size_t c) { return c < m.cols ? m(i, c) : 0.0; };
    auto& s = out[i];
    s.t_s = col(0);
    s.position_m = Vec2(col(1), col(2));
    s.velocity_m_s = Vec2(col(3), col(4));
    s.acceleration_m_s2 = Vec2(col(5), col(6));
    s.jerk_m_s3 = Vec2(col(7), col(8));
    s.laser_on = col(9) != 0.0;
    s.line = static_cast<int>(i + 1);
  }
  return out;
}

class MatrixWriter final : public stiffpath::job::JointWriter {
 public:
  void write(const stiffpath::compensation::JointCommand& c) override { commands.push_back(c); }
  void finish() override {}
  std::vector<stiffpath::compensation::JointCommand> commands;
};

// A number or text field of an options struct, or `fallback` when the field is absent.
double number_field(const mxArray* options, const char* name, double fallback) {
  const mxArray* f = options != nullptr ? mxGetField(options, 0, name) : nullptr;
  if (f == nullptr) return fallback;
  if (mxIsLogical(f) && mxGetNumberOfElements(f) == 1) return mxIsLogicalScalarTrue(f) ? 1.0 : 0.0;  // true / false
  if (!mxIsDouble(f) || mxIsComplex(f) || mxGetNumberOfElements(f) != 1) {
    throw UsageError(std::string("options.") + name + " must be a real number");
  }
  return mxGetScalar(f);
}

std::string text_field(const mxArray* options, const char* name, const std::string& fallback) {
  const mxArray* f = options != nullptr ? mxGetField(options, 0, name) : nullptr;
  return f == nullptr ? fallback : text_arg(f, (std::string("options.") + name).c_str());
}

// The joint-file fields (job::kJointFields, by CSV name) in the columns of 'compensate' and 'run', SI: 'compensate'
// adds Δx Δy after its nine; 'run' gives the CSV's joint columns and the line.
using stiffpath::job::joint_field;
constexpr std::array<std::size_t, 9> kCompensateColumns{
    joint_field("t_s"),           joint_field("theta1_rad"),    joint_field("theta2_rad"),
    joint_field("omega1_rad_s"),  joint_field("omega2_rad_s"),  joint_field("alpha1_rad_s2"),
    joint_field("alpha2_rad_s2"), joint_field("xcmd_mm"),       joint_field("ycmd_mm")};
constexpr std::array<std::size_t, 10> kRunColumns{
    joint_field("t_s"),           joint_field("theta1_rad"),    joint_field("theta2_rad"),
    joint_field("omega1_rad_s"),  joint_field("omega2_rad_s"),  joint_field("alpha1_rad_s2"),
    joint_field("alpha2_rad_s2"), joint_field("laser"),         joint_field("power"),
    joint_field("line")};

// Q = stiffpath('compensate', robot, model, T [, options]): T N×7..10 [t x y vx vy ax ay (jx jy laser)] →
// N×11 [t θ1 θ2 ω1 ω2 α1 α2 x_cmd y_cmd Δx Δy] (SI), as `stiffpath run` with its defaults (dynamic compensation,
// reference smoothed over 8 ms); the first refused row is an error. options: a struct with any of gain (1),
// method ('dynamic' or 'quasi-static'), damping_ratio (0.05), smooth_s (0.008; 0 = off), shaper ('none', 'zv',
// 'zvd'), or a number: the gain. The filters lengthen the job by their delay (more rows than T).
void compensate(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  if (nrhs != 4 && nrhs != 5) {
    throw UsageError("usage: Q = stiffpath('compensate', robot, model, T [, options])  % model '' = the robot's own");
  }
  // The job `run` makes, with its defaults (job::JobSpec), from the planned samples T.
  stiffpath::job::JobSpec spec = stiffpath::job::default_job(stiffpath::kinematics::load_robot(text_arg(prhs[1], "robot")));
  spec.model.request.model = text_arg(prhs[2], "model");
  spec.model.request.how_to_force = "set options.force_model = true";
  const mxArray* options = nullptr;
  if (nrhs == 5) {
    if (mxIsStruct(prhs[4]) && mxGetNumberOfElements(prhs[4]) == 1) {
      options = prhs[4];
    } else if (mxIsDouble(prhs[4]) && mxGetNumberOfElements(prhs[4]) == 1) {
      spec.gain = mxGetScalar(prhs[4]);
    } else {
      throw UsageError("options must be a struct (gain, method, damping_ratio, smooth_s, shaper) or the gain");
    }
  }
  spec.gain = number_field(options, "gain", spec.gain);
  spec.model.request.force = number_field(options, "force_model", 0.0) != 0.0;
  spec.method = stiffpath::core::parse_enum<stiffpath::compensation::Method>(
      text_field(options, "method", std::string(stiffpath::core::enum_name(spec.method))));
  if (options != nullptr && mxGetField(options, 0, "damping_ratio") != nullptr) {
    spec.damping_ratio = number_field(options, "damping_ratio", 0.0);
  }
  if (options != nullptr && mxGetField(options, 0, "smooth_s") != nullptr) spec.smooth_s = number_field(options, "smooth_s", 0.0);
  spec.shaper = stiffpath::core::parse_enum<stiffpath::compensation::FilterKind>(text_field(options, "shaper", "none"));
  const Matrix trajectory = matrix_arg(prhs[3], "T", 7, 10);
  const stiffpath::job::PreparedJob prepared =
      stiffpath::job::prepare(std::move(spec), stiffpath::job::Program::samples(samples_of(trajectory), "T"));
  MatrixWriter writer;
  stiffpath::job::run(prepared, &writer);
  const std::size_t n = writer.commands.size();
  plhs[0] = new_matrix(n, kCompensateColumns.size() + 2);
  double* q = mxGetPr(plhs[0]);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = writer.commands[i];
    for (std::size_t k = 0; k < kCompensateColumns.size(); ++k) {
      q[k * n + i] = stiffpath::job::value_of(c, stiffpath::job::kJointFields[kCompensateColumns[k]]);
    }
    const std::size_t d = kCompensateColumns.size();  // then the predicted deflection, which joint files do not hold
    q[d * n + i] = c.deflection_m.x();
    q[(d + 1) * n + i] = c.deflection_m.y();
  }
}

// J = stiffpath('run', gcode_file, robot [, options]): the main job exactly as `stiffpath run` makes it (job::JobSpec,
// the defaults every surface shares) → N×10 [t θ1 θ2 ω1 ω2 α1 α2 laser power line] (SI). options: a struct with any
// of thesis (true: the thesis's method), compensate (false: without compensation), method, gain, damping_ratio,
// smooth_s, shaper, accel_m_s2, jerk_m_s3, rate_hz. The first refused sample is an error naming its G-code line.
void run(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  if (nrhs != 3 && nrhs != 4) throw UsageError("usage: J = stiffpath('run', gcode_file, robot [, options])");
  const std::string file = text_arg(prhs[1], "gcode_file");
  const auto robot = stiffpath::kinematics::load_robot(text_arg(prhs[2], "robot"));
  const mxArray* o = nullptr;
  if (nrhs == 4) {
    if (!mxIsStruct(prhs[3]) || mxGetNumberOfElements(prhs[3]) != 1) throw UsageError("options must be a struct");
    o = prhs[3];
  }
  const auto has = [&](const char* name) { return o != nullptr && mxGetField(o, 0, name) != nullptr; };
  stiffpath::job::JobSpec spec =
      has("thesis") && number_field(o, "thesis", 0.0) != 0.0 ? stiffpath::job::thesis_job(robot) : stiffpath::job::default_job(robot);
  if (has("model")) spec.model.request.model = text_field(o, "model", "");
  spec.model.request.force = number_field(o, "force_model", 0.0) != 0.0;
  spec.model.request.how_to_force = "set options.force_model = true";
  if (has("compensate")) spec.compensate = number_field(o, "compensate", 1.0) != 0.0;
  if (has("method")) spec.method = stiffpath::core::parse_enum<stiffpath::compensation::Method>(text_field(o, "method", ""));
  spec.gain = number_field(o, "gain", spec.gain);
  if (has("damping_ratio")) spec.damping_ratio = number_field(o, "damping_ratio", 0.0);
  if (has("smooth_s")) spec.smooth_s = number_field(o, "smooth_s", 0.0);
  if (has("shaper")) spec.shaper = stiffpath::core::parse_enum<stiffpath::compensation::FilterKind>(text_field(o, "shaper", ""));
  auto& limits = spec.plan.limits;
  limits.max_acceleration_m_s2 = number_field(o, "accel_m_s2", limits.max_acceleration_m_s2);
  limits.max_jerk_m_s3 = number_field(o, "jerk_m_s3", stiffpath::motion::default_jerk_m_s3(limits.max_acceleration_m_s2));
  spec.plan.rate_hz = number_field(o, "rate_hz", spec.plan.rate_hz);
  spec.plan.gcode.home_position_m = robot.home_m;
  const stiffpath::job::PreparedJob prepared = stiffpath::job::prepare(std::move(spec), stiffpath::job::Program::file(file));
  stiffpath::job::check_output(prepared, "-");  // the matrix is kept in memory: the cap of a written job holds
  MatrixWriter writer;
  stiffpath::job::run(prepared, &writer);
  const std::size_t n = writer.commands.size();
  plhs[0] = new_matrix(n, kRunColumns.size());
  double* q = mxGetPr(plhs[0]);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < kRunColumns.size(); ++k) {
      q[k * n + i] = stiffpath::job::value_of(writer.commands[i], stiffpath::job::kJointFields[kRunColumns[k]]);
    }
  }
}

using Command = void (*)(int, mxArray*[], int, const mxArray*[]);

const std::map<std::string, Command>& commands() {
  static const std::map<std::string, Command> table{{"ik", ik},           {"fk", fk},
                                                    {"fit", fit},         {"predict", predict},
                                                    {"compliance", compliance}, {"plan", plan},
                                                    {"compensate", compensate}, {"run", run}};
  return table;
}

// Runs one command; returns the error message ("" on success). Every C++ object is destroyed before the caller
// raises the MATLAB error, which does not return (mexErrMsgIdAndTxt unwinds without running destructors).
std::string dispatch(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[], std::string& id) {
  try {
    if (nrhs < 1) throw UsageError("usage: stiffpath(command, …) with command ik, fk, fit, predict, compliance, plan, compensate, run");
    const std::string name = text_arg(prhs[0], "command");
    const auto found = commands().find(name);
    if (found == commands().end()) throw UsageError("unknown command '" + name + "' (ik, fk, fit, predict, compliance, plan, compensate, run)");
    found->second(nlhs, plhs, nrhs, prhs);
    return {};
  } catch (const stiffpath::Error& e) {
    id = "stiffpath:badInput";
    return e.what();
  } catch (const UsageError& e) {
    id = "stiffpath:usage";
    return e.what();
  } catch (const std::exception& e) {
    id = "stiffpath:internal";
    return std::string("internal error: ") + e.what();
  }
}

}  // namespace

void mexFunction(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  static char message[2048];
  static char id[64];
  {
    std::string error_id;
    const std::string error = dispatch(nlhs, plhs, nrhs, prhs, error_id);
    if (error.empty()) return;
    std::snprintf(message, sizeof message, "%s", error.c_str());
    std::snprintf(id, sizeof id, "%s", error_id.c_str());
  }
  mexErrMsgIdAndTxt(id, "%s", message);
}
