// The evaluation module in one include: a marked path's metrics (length, deviation area, ISO 9283 path accuracy and cornering), measured along the mark.
#pragma once

#include "stiffpath/evaluation/path_metrics.hpp"
#include "stiffpath/evaluation/iso9283.hpp"
#include "stiffpath/evaluation/cornering.hpp"
#include "stiffpath/evaluation/metrics_json.hpp"
