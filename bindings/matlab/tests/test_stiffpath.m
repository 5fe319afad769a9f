% Octave test of the MEX gateway: its numbers against the thesis's closed form and the CLI of the same build.
% Arguments: <folder of stiffpath.mex> <stiffpath CLI> <source folder> <scratch folder>.
1;
args = argv();
mex_dir = args{1}; cli = args{2}; source_dir = args{3}; scratch = args{4};
addpath(mex_dir);
if ~exist(scratch, 'dir'), mkdir(scratch); end
failures = 0;

function failures = check(failures, ok, what)
  if ok
    printf('ok   %s\n', what);
  else
    printf('FAIL %s\n', what);
    failures = failures + 1;
  end
end

function doc = cli_json(cli, args)
  [status, out] = system(sprintf('"%s" %s --json', cli, args));
  if status ~= 0, error('CLI failed: %s', out); end
  doc = jsondecode(out);
end

% Inverse kinematics: eq. 2.2 by hand (four links of 150 mm, elbows +1/-1) and the CLI.
P = [0.222132 0.0375; 0.18 -0.06; 0.265 0.07];
Q = stiffpath('ik', 'oc-gu', P);
r = hypot(P(:,1), P(:,2)); phi = atan2(P(:,2), P(:,1)); alpha = acos(r / 0.3);
failures = check(failures, max(max(abs(Q - [phi + alpha, phi - alpha]))) < 1e-12, 'ik = eq. 2.2');
doc = cli_json(cli, 'kin ik --x-mm 222.132 --y-mm 37.5');
failures = check(failures, max(abs(Q(1,:) - [doc.theta1_rad doc.theta2_rad])) < 1e-11, 'ik = stiffpath kin ik');
failures = check(failures, max(max(abs(stiffpath('fk', 'oc-gu', Q) - P))) < 1e-12, 'fk(ik(p)) = p');
try
  stiffpath('ik', 'oc-gu', [0.299 0]);
  failures = check(failures, false, 'an unreachable point raises an error');
catch err
  failures = check(failures, strcmp(err.identifier, 'stiffpath:badInput') && ~isempty(strfind(err.message, 'refused')), ...
                   'an unreachable point raises stiffpath:badInput');
end

% Compliance: the built-in model against `stiffpath predict`, and a fitted model file read back by the CLI.
r = stiffpath('predict', 'thesis-oc', [0.23 0.02], [30 -120]); D = r.d_m;
doc = cli_json(cli, 'predict --model thesis-oc --x-mm 230 --y-mm 20 --fx-n 30 --fy-n -120');
failures = check(failures, max(abs(D * 1e6 - [doc.dx_um doc.dy_um])) < 1e-6, 'predict = stiffpath predict');
C = stiffpath('compliance', 'thesis-oc', [0.23 0.02]);
failures = check(failures, max(max(abs(C * 1e6 - doc.C_um_per_N))) < 1e-9, 'compliance = C_um_per_N');
failures = check(failures, isequal(r.C_m_per_N, C) && abs(r.d_band_95_m(1) * 1e6 - doc.dx_band_95_um) < 1e-6, ...
                 'predict''s compliance and 95 % band = stiffpath predict');
model_file = fullfile(scratch, 'physical.json');
fitted = stiffpath('fit', 'oc-gu', struct('method', 'physical', 'output', model_file));
failures = check(failures, strcmp(fitted.method, 'physical') && exist(model_file, 'file') == 2, 'fit writes a model file');
D2 = stiffpath('predict', model_file, [0.2 -0.05], [40 -200]).d_m;
doc = cli_json(cli, sprintf('predict --model %s --x-mm 200 --y-mm -50 --fx-n 40 --fy-n -200', model_file));
failures = check(failures, max(abs(D2 * 1e6 - [doc.dx_um doc.dy_um])) < 1e-5, 'fitted model = CLI on the same file');

% The main job of the thesis's y motion against `stiffpath run`'s joint file: first with run's defaults (dynamic
% compensation of a reference smoothed over 8 ms, the filters retiming the planned path), then with the thesis's
% quasi-static method on the bare plan through 'compensate'.
gcode = fullfile(source_dir, 'examples', 'y_motion.gcode');
T = stiffpath('plan', gcode);
J = stiffpath('run', gcode, 'oc-gu');  % columns t_s, q_rad, qd_rad_s, qdd_rad_s2, …, laser, power, line
joints_csv = fullfile(scratch, 'joints.csv');
[status, out] = system(sprintf('"%s" run "%s" -o "%s"', cli, gcode, joints_csv));
% Line 1 records the robot, line 2 names the columns: t_s,theta1_rad,theta2_rad,omega1_rad_s,omega2_rad_s,
% alpha1_rad_s2,alpha2_rad_s2,laser,power,x_mm,y_mm,xcmd_mm,ycmd_mm,fx_n,fy_n,line.
ref = dlmread(joints_csv, ',', 2, 0);
failures = check(failures, status == 0 && rows(J.t_s) == rows(ref) && rows(J.t_s) > rows(T.t_s), ...
                 sprintf('run gives %d samples as the CLI (the smoothing adds %d)', rows(ref), rows(ref) - rows(T.t_s)));
failures = check(failures, max(max(abs(J.q_rad - ref(:, 2:3)))) < 1e-9, 'compensated joints = stiffpath run');
failures = check(failures, isequal(double(J.laser), ref(:, 8)) && max(abs(J.power - ref(:, 9))) < 1e-6, 'laser and power = stiffpath run');
failures = check(failures, max(max(abs(J.qdd_rad_s2 - ref(:, 6:7)))) < 1e-6 * max(max(abs(ref(:, 6:7)))), ...
                 'joint accelerations = stiffpath run');

thesis = struct('method', 'quasi-static', 'smooth_s', 0);
Jq = stiffpath('compensate', 'oc-gu', 'thesis-oc', T, thesis);  % the thesis's bilinear model, as predict's below
quasi_csv = fullfile(scratch, 'joints_quasi.csv');
[status, out] = system(sprintf('"%s" run "%s" --compensation quasi-static --smooth-ms 0 --model thesis-oc -o "%s"', cli, gcode, quasi_csv));
refq = dlmread(quasi_csv, ',', 2, 0);
failures = check(failures, status == 0 && rows(Jq.t_s) == rows(T.t_s) && rows(refq) == rows(T.t_s), 'quasi-static, unsmoothed: one row per sample');
failures = check(failures, max(max(abs(Jq.q_rad - refq(:, 2:3)))) < 1e-9, 'quasi-static joints = run --compensation quasi-static');
% F = -m a (eq. 4.4) and p_cmd = p - C(p) F on every sample.
F = -3.6 * T.a_m_s2;
Dall = stiffpath('predict', 'thesis-oc', T.p_m, F).d_m;
failures = check(failures, max(max(abs(Jq.command_m - (T.p_m - Dall)))) < 1e-12, 'p_cmd = p - C(p)(-m a)');
try
  stiffpath('compensate', 'oc-gu', '', T, struct('method', 'static'));
  failures = check(failures, false, 'an unknown method raises an error');
catch err
  failures = check(failures, strcmp(err.identifier, 'stiffpath:badInput') && ~isempty(strfind(err.message, 'static')), ...
                   'an unknown method raises stiffpath:badInput naming it');
end

if failures > 0
  printf('%d check(s) failed\n', failures);
  exit(1);
end
printf('all checks passed\n');
