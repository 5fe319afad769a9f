// The calibration module in one include: geometry calibration and pose plans, compliance campaign design, and calibration from the robot's own marks (plate, tip response, identification).
#pragma once

#include "stiffpath/calibration/geometry_fit.hpp"
#include "stiffpath/calibration/geometry_plan.hpp"
#include "stiffpath/calibration/campaign_plan.hpp"
#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/calibration/tip_response.hpp"
#include "stiffpath/calibration/identify.hpp"
#include "stiffpath/calibration/calibrated_robot.hpp"
