// The C interface (include/stiffpath/stiffpath.h) over the C++ library: the one file that knows both.
#include "stiffpath/stiffpath.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <utility>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/job/prepared_job.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace sp = stiffpath;

// The robot: its description and the mechanism built from it. When the robot description changes
// type, this struct, load_robot() and robot_info() are what follow it.
struct stiffpath_robot {
  sp::kinematics::Robot spec;
  sp::kinematics::FiveBar mechanism;
  explicit stiffpath_robot(sp::kinematics::Robot s) : spec(std::move(s)), mechanism(spec.five_bar()) {}
};

struct stiffpath_compensator {
  stiffpath_robot robot;
  sp::compensation::Compensator compensator;
  stiffpath_compensator(stiffpath_robot r, std::shared_ptr<const sp::compliance::Model> model,
                        const sp::compensation::CompensatorOptions& options)
      : robot(std::move(r)), compensator(robot.spec, std::move(model), options) {}
};

namespace {

static_assert(static_cast<int>(sp::compensation::Status::ok) == STIFFPATH_OK);
static_assert(static_cast<int>(sp::compensation::Status::not_finite) == STIFFPATH_NOT_FINITE);
static_assert(static_cast<int>(sp::compensation::Status::outside_grid) == STIFFPATH_OUTSIDE_GRID);
static_assert(static_cast<int>(sp::compensation::Status::unreachable) == STIFFPATH_UNREACHABLE);
static_assert(static_cast<int>(sp::compensation::Status::joint_position) == STIFFPATH_JOINT_POSITION);
static_assert(static_cast<int>(sp::compensation::Status::joint_velocity) == STIFFPATH_JOINT_VELOCITY);
static_assert(static_cast<int>(sp::compensation::Status::joint_acceleration) == STIFFPATH_JOINT_ACCELERATION);

// Copies `text` into the caller's buffer, truncated and NUL-terminated; nothing if there is no buffer.
void report(char* error, size_t error_size, const std::string& text) noexcept {
  if (error == nullptr || error_size == 0) return;
  const size_t n = std::min(text.size(), error_size - 1);
  std::memcpy(error, text.data(), n);
  error[n] = '\0';
}

// Runs `make` (which may throw) and turns every exception into NULL plus the message.
template <typename T, typename Make>
T* create_or_report(Make&& make, char* error, size_t error_size) noexcept {
  try {
    report(error, error_size, "");
    return make();
  } catch (const std::bad_alloc&) {
    report(error, error_size, "out of memory");
  } catch (const std::exception& e) {
    report(error, error_size, e.what());
  } catch (...) {
    report(error, error_size, "unknown error");
  }
  return nullptr;
}

sp::kinematics::Robot load_robot(const char* robot) {
  if (robot == nullptr || *robot == '\0') throw sp::Error("no robot given: a preset name or a robot file is needed");
  return sp::kinematics::load_robot(robot);
}

sp::kinematics::Vec2 vec(const double v[2]) noexcept { return {v[0], v[1]}; }
void put(const sp::kinematics::Vec2& v, double out[2]) noexcept {
  out[0] = v.x();
  out[1] = v.y();
}

void put(const sp::compensation::JointCommand& c, stiffpath_joint_command* out) noexcept {
  out->t_s = c.t_s;
  put(c.q_rad, out->q_rad);
  put(c.qd_rad_s, out->qd_rad_s);
  put(c.qdd_rad_s2, out->qdd_rad_s2);
  put(c.target_m, out->target_m);
  put(c.command_m, out->command_m);
  put(c.force_N, out->force_N);
  put(c.deflection_m, out->deflection_m);
  put(c.load_torque_Nm, out->load_torque_Nm);
  out->status = static_cast<int>(c.status);
  out->joint = c.joint;
  out->outside_grid = c.outside_grid ? 1 : 0;
  out->laser = c.laser_on ? 1 : 0;
  out->power = c.power;
  out->line = c.line;
}

sp::compliance::OutsidePolicy outside_policy(int policy) {
  switch (policy) {
    case STIFFPATH_OUTSIDE_CLAMP: return sp::compliance::OutsidePolicy::clamp;
    case STIFFPATH_OUTSIDE_EXTRAPOLATE: return sp::compliance::OutsidePolicy::extrapolate;
    case STIFFPATH_OUTSIDE_ERROR: return sp::compliance::OutsidePolicy::error;
    default: throw sp::Error("outside_policy " + std::to_string(policy) + " is not one of 0..3");
  }
}

sp::compensation::Method method(int method) {
  switch (method) {
    case STIFFPATH_METHOD_QUASI_STATIC: return sp::compensation::Method::quasi_static;
    case STIFFPATH_METHOD_DYNAMIC: return sp::compensation::Method::dynamic;
    default: throw sp::Error("method " + std::to_string(method) + " is not one of 0..1");
  }
}

// The job's commands to the caller's sink; a sink that returns non-zero stops the job.
struct SinkStopped {};
class SinkWriter final : public sp::job::JointWriter {
 public:
  SinkWriter(stiffpath_command_sink sink, void* user) : sink_(sink), user_(user) {}
  void write(const sp::compensation::JointCommand& c) override {
    stiffpath_joint_command out{};
    put(c, &out);
    if (sink_(&out, user_) != 0) throw SinkStopped{};
  }
  void finish() override {}

 private:
  stiffpath_command_sink sink_;
  void* user_;
};

// The job options onto the library's JobSpec (defaults: the JobSpec's, so every surface shares them).
sp::job::JobSpec job_spec(const char* robot, const char* model, const stiffpath_job_options& o) {
  const sp::kinematics::Robot r = load_robot(robot);
  sp::job::JobSpec spec = o.thesis != 0 ? sp::job::thesis_job(r) : sp::job::default_job(r);
  const stiffpath_options& c = o.compensation;
  if (o.thesis == 0) {
    if (model != nullptr) spec.model.request.model = model;
    spec.method = method(c.method);
    if (o.smooth_s >= 0.0) spec.smooth_s = o.smooth_s;
    switch (o.shaper) {
      case STIFFPATH_SHAPER_NONE: break;
      case STIFFPATH_SHAPER_ZV: spec.shaper = sp::compensation::FilterKind::zv; break;
      case STIFFPATH_SHAPER_ZVD: spec.shaper = sp::compensation::FilterKind::zvd; break;
      default: throw sp::Error("shaper " + std::to_string(o.shaper) + " is not one of 0..2");
    }
  }
  if (std::isnan(o.smooth_s)) throw sp::Error("smooth_s is NaN");
  spec.gain = c.gain;
  spec.compensate = c.enabled != 0;
  spec.check_limits = c.check_limits != 0;
  if (c.outside_policy != STIFFPATH_OUTSIDE_MODEL_DEFAULT) spec.outside = outside_policy(c.outside_policy);
  if (std::isnan(c.damping_ratio)) throw sp::Error("damping_ratio is NaN");
  if (c.damping_ratio >= 0.0) spec.damping_ratio = c.damping_ratio;
  auto& limits = spec.plan.limits;
  limits.max_velocity_m_s = o.max_velocity_m_s;
  limits.max_acceleration_m_s2 = o.max_acceleration_m_s2;
  if (o.max_jerk_m_s3 > 0.0) {
    limits.max_jerk_m_s3 = o.max_jerk_m_s3;
  } else {
    limits.max_jerk_m_s3 = sp::motion::default_jerk_m_s3(limits.max_acceleration_m_s2);
    if (o.max_jerk_m_s3 < 0.0) spec.jerk = sp::job::JerkRule::tip_frequency;
  }
  if (std::isnan(o.max_jerk_m_s3)) throw sp::Error("max_jerk_m_s3 is NaN");
  spec.plan.rate_hz = o.rate_hz;
  spec.plan.gcode.home_position_m = r.home_m;
  return spec;
}

}  // namespace

extern "C" {

int stiffpath_c_api_version(void) noexcept { return STIFFPATH_C_API_VERSION; }

const char* stiffpath_status_text(int status) noexcept {
  if (status >= STIFFPATH_OK && status <= STIFFPATH_JOINT_ACCELERATION) {
    return sp::compensation::describe(static_cast<sp::compensation::Status>(status));
  }
  if (status == STIFFPATH_INVALID_ARGUMENT) return "invalid argument (a NULL pointer)";
  return "unknown status";
}

stiffpath_options stiffpath_default_options(void) noexcept {
  const sp::job::JobSpec defaults;
  return {defaults.gain,
          defaults.compensate ? 1 : 0,
          defaults.check_limits ? 1 : 0,
          STIFFPATH_OUTSIDE_MODEL_DEFAULT,
          defaults.method == sp::compensation::Method::dynamic ? STIFFPATH_METHOD_DYNAMIC : STIFFPATH_METHOD_QUASI_STATIC,
          -1.0};
}

stiffpath_job_options stiffpath_default_job_options(void) noexcept {
  const sp::motion::PlanOptions plan;
  return {stiffpath_default_options(), 0,    -1.0, STIFFPATH_SHAPER_NONE, plan.limits.max_velocity_m_s,
          plan.limits.max_acceleration_m_s2, 0.0, plan.rate_hz};
}

stiffpath_robot* stiffpath_robot_load(const char* robot, char* error, size_t error_size) noexcept {
  return create_or_report<stiffpath_robot>([&] { return new stiffpath_robot(load_robot(robot)); }, error, error_size);
}

void stiffpath_robot_free(stiffpath_robot* robot) noexcept { delete robot; }

int stiffpath_robot_get_info(const stiffpath_robot* robot, stiffpath_robot_info* info) noexcept {
  if (robot == nullptr || info == nullptr) return STIFFPATH_INVALID_ARGUMENT;
  *info = stiffpath_robot_info{};
  const std::string& name = robot->spec.name;
  const size_t n = std::min(name.size(), sizeof info->name - 1);
  std::memcpy(info->name, name.data(), n);
  info->name[n] = '\0';
  info->moving_mass_kg = robot->spec.moving_mass_kg;
  for (size_t i = 0; i < 2; ++i) {
    const auto& limit = robot->spec.joints[i];
    info->joints[i] = {limit.min_rad, limit.max_rad, limit.max_velocity_rad_s, limit.max_acceleration_rad_s2};
  }
  return STIFFPATH_OK;
}

int stiffpath_forward(const stiffpath_robot* robot, const double q_rad[2], double p_m[2]) noexcept {
  if (robot == nullptr || q_rad == nullptr || p_m == nullptr) return STIFFPATH_INVALID_ARGUMENT;
  if (!std::isfinite(q_rad[0]) || !std::isfinite(q_rad[1])) return STIFFPATH_NOT_FINITE;
  put(robot->mechanism.forward(vec(q_rad)), p_m);
  return STIFFPATH_OK;
}

int stiffpath_inverse(const stiffpath_robot* robot, const double p_m[2], double q_rad[2]) noexcept {
  if (robot == nullptr || p_m == nullptr || q_rad == nullptr) return STIFFPATH_INVALID_ARGUMENT;
  const sp::kinematics::InverseResult ik = robot->mechanism.solve_inverse(vec(p_m));
  switch (ik.status) {
    case sp::kinematics::Reach::ok: put(ik.q, q_rad); return STIFFPATH_OK;
    case sp::kinematics::Reach::not_finite: return STIFFPATH_NOT_FINITE;
    default: return STIFFPATH_UNREACHABLE;
  }
}

stiffpath_compensator* stiffpath_compensator_create(const char* robot, const char* model,
                                                    const stiffpath_options* options, char* error,
                                                    size_t error_size) noexcept {
  return create_or_report<stiffpath_compensator>(
      [&] {
        const stiffpath_options o = options != nullptr ? *options : stiffpath_default_options();
        stiffpath_robot r(load_robot(robot));
        sp::compliance::ModelRequest request;
        if (model != nullptr) request.model = model;
        auto loaded = sp::compliance::load_robot_model(r.spec, request);
        if (o.outside_policy != STIFFPATH_OUTSIDE_MODEL_DEFAULT) loaded.model->set_outside_policy(outside_policy(o.outside_policy));
        const std::shared_ptr<const sp::compliance::Model> shared(std::move(loaded.model));
        sp::compensation::CompensatorOptions co;
        co.gain = o.gain;
        co.enabled = o.enabled != 0;
        co.check_limits = o.check_limits != 0;
        co.method = method(o.method);
        if (std::isnan(o.damping_ratio)) throw sp::Error("damping_ratio is NaN");
        if (o.damping_ratio >= 0.0) co.damping_ratio = o.damping_ratio;  // negative: the robot file's
        return new stiffpath_compensator(std::move(r), shared, co);
      },
      error, error_size);
}

void stiffpath_compensator_free(stiffpath_compensator* compensator) noexcept { delete compensator; }

const stiffpath_robot* stiffpath_compensator_robot(const stiffpath_compensator* compensator) noexcept {
  return compensator != nullptr ? &compensator->robot : nullptr;
}

int stiffpath_compensator_step(const stiffpath_compensator* compensator, const stiffpath_task_sample* sample,
                               stiffpath_joint_command* out) noexcept {
  if (compensator == nullptr || sample == nullptr || out == nullptr) return STIFFPATH_INVALID_ARGUMENT;
  sp::compensation::TaskSample s;
  s.t_s = sample->t_s;
  s.position_m = vec(sample->p_m);
  s.velocity_m_s = vec(sample->v_m_s);
  s.acceleration_m_s2 = vec(sample->a_m_s2);
  s.jerk_m_s3 = vec(sample->j_m_s3);
  s.snap_m_s4 = vec(sample->s_m_s4);
  put(compensator->compensator.step(s), out);
  return out->status;
}

int stiffpath_run_job(const char* robot, const char* model, const char* gcode_path, const stiffpath_job_options* options,
                      stiffpath_command_sink sink, void* user, char* error, size_t error_size) noexcept {
  report(error, error_size, "");
  if (robot == nullptr || gcode_path == nullptr || sink == nullptr) {
    report(error, error_size, "stiffpath_run_job: robot, gcode_path and sink must not be NULL");
    return STIFFPATH_INVALID_ARGUMENT;
  }
  try {
    const stiffpath_job_options o = options != nullptr ? *options : stiffpath_default_job_options();
    const sp::job::PreparedJob prepared = sp::job::prepare(job_spec(robot, model, o), sp::job::Program::file(gcode_path));
    SinkWriter writer(sink, user);
    try {
      sp::job::run(prepared, &writer);
    } catch (const sp::job::Refusal& refused) {
      report(error, error_size, refused.what());
      return static_cast<int>(refused.status());
    }
    return STIFFPATH_OK;
  } catch (const SinkStopped&) {
    report(error, error_size, "stopped by the sink");
    return STIFFPATH_STOPPED;
  } catch (const std::bad_alloc&) {
    report(error, error_size, "out of memory");
  } catch (const std::exception& e) {
    report(error, error_size, e.what());
  } catch (...) {
    report(error, error_size, "unknown error");
  }
  return STIFFPATH_BAD_INPUT;
}

}  // extern "C"
