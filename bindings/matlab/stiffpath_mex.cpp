// The MATLAB/Octave gateway `stiffpath(command, …)`: kinematics, compliance fits, cross-validation and predictions,
// planning, the main job, the digital twin (and the scan, forwarded to the stiffpath_scan gateway, which alone loads
// OpenCV). Only the C MEX API (mex.h), so `mkoctfile --mex` and MATLAB's `mex` both build it.
#include <mex.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <string>

#include "mex_args.hpp"
#include "mex_commands.hpp"
#include "stiffpath/core/error.hpp"

namespace {

using namespace stiffpath::mex;

const std::map<std::string, Command>& commands() {
  static const std::map<std::string, Command> table{
      {"ik", ik},       {"fk", fk},     {"fit", fit},           {"predict", predict}, {"compliance", compliance_matrices},
      {"cv", cv},       {"plan", plan}, {"run", run},           {"compensate", compensate},
      {"simulate", simulate},           {"help", help}};
  return table;
}

// Runs one command; returns the error message ("" on success). Every C++ object is destroyed before the caller
// raises the MATLAB error, which does not return (mexErrMsgIdAndTxt unwinds without running destructors).
std::string dispatch(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[], std::string& id) {
  try {
    if (nrhs < 1) throw UsageError("usage: stiffpath(command, …); stiffpath('help') lists the commands");
    const std::string name = text_arg(prhs[0], "command");
    const auto found = commands().find(name);
    if (found == commands().end()) {
      throw UsageError("unknown command '" + name + "': ik, fk, fit, cv, predict, compliance, plan, run, compensate, "
                       "simulate, scan, help");
    }
    found->second(nlhs, plhs, nrhs, prhs);
    return {};
  } catch (const stiffpath::Error& e) {
    id = "stiffpath:badInput";
    return e.what();
  } catch (const UsageError& e) {
    id = "stiffpath:usage";
    return e.what();
  } catch (const std::bad_alloc&) {
    id = "stiffpath:outOfMemory";
    return "out of memory: the result does not fit (options.max_samples bounds a job)";
  } catch (const std::exception& e) {
    id = "stiffpath:internal";
    return std::string("internal error: ") + e.what();
  }
}

bool is_scan(int nrhs, const mxArray* prhs[]) {
  if (nrhs < 1 || !mxIsChar(prhs[0])) return false;
  char name[8] = {};
  return mxGetString(prhs[0], name, sizeof name) == 0 && std::strcmp(name, "scan") == 0;
}

}  // namespace

void mexFunction(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  if (is_scan(nrhs, prhs)) {  // the scan needs OpenCV: the second gateway loads it on the first scan only
    mexCallMATLAB(nlhs > 0 ? nlhs : 1, plhs, nrhs - 1, const_cast<mxArray**>(prhs + 1), "stiffpath_scan");
    return;
  }
  static char message[4096];
  static char id[64];
  {
    std::string error_id;
    const std::string error = dispatch(nlhs, plhs, nrhs, prhs, error_id);
    if (error.empty()) return;
    std::snprintf(message, sizeof message, "%s", error.c_str());
    std::snprintf(id, sizeof id, "%s", error_id.c_str());
  }
  mexErrMsgIdAndTxt(id, "%s", message);
}
