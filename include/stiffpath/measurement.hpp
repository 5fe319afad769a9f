// The measurement module in one include: CMM campaigns, their processing into displacement tables (eq. 2.3), data checks, repeatability, virtual campaigns.
#pragma once

#include "stiffpath/measurement/campaign.hpp"
#include "stiffpath/measurement/process_campaign.hpp"
#include "stiffpath/measurement/displacement_table.hpp"
#include "stiffpath/measurement/data_check.hpp"
#include "stiffpath/measurement/repeatability.hpp"
#include "stiffpath/measurement/virtual_campaign.hpp"
