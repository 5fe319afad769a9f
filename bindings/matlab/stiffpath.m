% STIFFPATH  stiffpath(command, ...): the stiffpath library from MATLAB/Octave. SI units everywhere (m, rad, N, s).
%   Results are structs with named fields; stiffpath('help', command) explains one command.
%
%     q_rad = stiffpath('ik', robot, p_m)                     inverse kinematics, N×2 → N×2
%     p_m   = stiffpath('fk', robot, q_rad)                   forward kinematics
%     model = stiffpath('fit', robot [, options])             fit a compliance model (as stiffpath fit --json)
%     cv    = stiffpath('cv', robot [, options])              leave-one-out cross-validation, a struct per method
%     r     = stiffpath('predict', model, p_m, F_N [, opts])  deflection, compliance and 95 % band
%     C     = stiffpath('compliance', model, p_m [, opts])    2×2×N compliance (m/N)
%     [T, s] = stiffpath('plan', gcode_file [, options])      jerk-limited trajectory (accel, jerk, rate_hz, robot, …)
%     [J, s] = stiffpath('run', gcode_file, robot [, opts])   the main job, exactly as `stiffpath run`
%     [J, s] = stiffpath('compensate', robot, model, T [, o]) the main job on planned samples T
%     m     = stiffpath('simulate', robot, J [, options])     the digital twin's mark and metrics
%     m     = stiffpath('scan', image [, options])            a scanned mark measured (loads OpenCV: stiffpath_scan)
%     stiffpath('help' [, command])                           this text, or one command's
%
%   robot: a preset ('oc-gu', 'sc-gu', …) or a robot file; model: a model file or built-in name ('thesis-oc', …).
%   Errors: stiffpath:badInput (the message names the file, line and value), stiffpath:usage, stiffpath:internal.
function varargout = stiffpath(varargin)
  % stiffpath.mex (built beside this file) takes precedence over this file; this file only holds the help text.
  error('stiffpath:notBuilt', 'stiffpath.mex is not on the path: build it (docs/matlab.md) and addpath its folder');
end
