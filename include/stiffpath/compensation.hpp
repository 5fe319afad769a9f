// The compensation module in one include: the real-time step Compensator::step (fig. 4.3), its samples, the reference filters and the tip's modes.
#pragma once

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compensation/samples.hpp"
#include "stiffpath/compensation/reference_filter.hpp"
#include "stiffpath/compensation/run_filters.hpp"
#include "stiffpath/compensation/tip_modes.hpp"
