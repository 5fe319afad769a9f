// The simulation module in one include: the digital twin (plant, simulator, metrics), its models and the experiments that compare compensations on it.
#pragma once

#include "stiffpath/simulation/simulator.hpp"
#include "stiffpath/simulation/plant.hpp"
#include "stiffpath/simulation/run_metrics.hpp"
#include "stiffpath/simulation/twin_models.hpp"
#include "stiffpath/simulation/experiment.hpp"
#include "stiffpath/simulation/robustness.hpp"
#include "stiffpath/simulation/compensation_variant.hpp"
