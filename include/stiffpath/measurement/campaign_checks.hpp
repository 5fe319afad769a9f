// Consistency checks of a whole campaign (series structure), shared by the file loader and the processing.
#pragma once

#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "stiffpath/measurement/campaign.hpp"

namespace stiffpath::measurement {

//! The readings of one (point, direction) series, grouped by load step (ascending) then reading.
struct CampaignSeries {
  std::string point;
  ForceDirection direction = ForceDirection::plus_x;
  std::map<int, std::vector<const CampaignReading*>> steps;  //!< step → its readings
};

//! Groups a campaign into series, in order of first appearance. Pointers refer into `campaign`.
std::vector<CampaignSeries> group_series(const Campaign& campaign);

//! Throws stiffpath::Error (file:line, naming the point and direction) if a series has no step 0, fewer
//! than two loaded steps, a point whose nominal x/y changes between rows, or readings of one step whose
//! forces differ by more than 1e-6 of the force; or if a loaded step's force does not exceed step 0's.
void validate_campaign(const Campaign& campaign);

}  // namespace stiffpath::measurement
