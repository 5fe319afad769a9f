// The motion module in one include: G-code to time-optimal jerk-limited samples (TrajectoryStream, plan_gcode, measure_plan), their limits and the account of lost time.
#pragma once

#include "stiffpath/motion/trajectory_stream.hpp"
#include "stiffpath/motion/limits.hpp"
#include "stiffpath/motion/sampler.hpp"
#include "stiffpath/motion/slowdown.hpp"
#include "stiffpath/motion/trajectory_csv.hpp"
