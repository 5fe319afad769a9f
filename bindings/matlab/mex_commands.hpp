// The commands of the MEX gateway `stiffpath(command, …)`, one function each (mexFunction's arguments).
#pragma once
#include <mex.h>

namespace stiffpath::mex {

void ik(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]);
void fk(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]);
void fit(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]);
void predict(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]);
void compliance_matrices(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]);
void cv(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]);
void plan(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]);
void run(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]);
void compensate(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]);
void simulate(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]);
void help(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]);

//! The help text of a command ("" for the overview), or nullptr for an unknown one.
const char* help_text(const char* command);

}  // namespace stiffpath::mex
