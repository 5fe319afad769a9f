// The parts of the Python module, one source file each, and the Python-side model type they share.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/compliance/model_factory.hpp"

namespace stiffpath::python {

namespace py = pybind11;

//! A compliance model as Python sees it: the model (shared with compensators and the twin), where it came from.
struct PyModel {
  std::shared_ptr<compliance::Model> model;
  compliance::Provenance provenance;
  std::string label;
};

//! Wraps a loaded model.
PyModel to_py_model(compliance::LoadedModel loaded);

void add_kinematics(py::module_& m);   //!< Robot, presets
void add_compliance(py::module_& m);   //!< DisplacementTable, Model, fit, cv, load_model
void add_motion(py::module_& m);       //!< plan
void add_compensation(py::module_& m); //!< Compensator, JointCommand, compensate
void add_twin(py::module_& m);         //!< true_compliance, simulate, run_metrics, path_metrics
void add_job(py::module_& m);          //!< run: the main job as `stiffpath run`
void add_calibration(py::module_& m);  //!< calibration_plate: the plate `stiffpath calibrate plate` lays out

}  // namespace stiffpath::python
