// The kinematics module in one include: a robot from its file, the five-bar's forward and inverse kinematics, Jacobians and workspace checks (thesis eqs. 2.1-2.2).
#pragma once

#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/kinematics/five_bar.hpp"
#include "stiffpath/kinematics/robot_json.hpp"
