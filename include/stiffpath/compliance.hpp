// The compliance module in one include: the Model contract C(p), the fitted models (bilinear, symmetric, physical, physical-spline, corrected), fitting, model files, cross-validation and prediction uncertainty.
#pragma once

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/uncertainty.hpp"
#include "stiffpath/compliance/corrected_model.hpp"
#include "stiffpath/compliance/model_check.hpp"
