% The README's walkthrough (fit, cv, plan, run, simulate) from Octave, each number against the CLI of the same build
% (`stiffpath … --json`), and the scan against a drawn line of known length.
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

% |a - b| within rel of |b|, element by element (the CLI prints 12 significant digits).
function ok = near(a, b, rel)
  ok = numel(a) == numel(b) && all(abs(a(:) - b(:)) <= rel * max(abs(b(:)), 1e-300));
end

gcode = @(name) fullfile(source_dir, 'examples', name);

% fit: the physical model of the robot's own table, as `stiffpath fit --robot oc-gu --method physical -o oc.json`.
oc_json = fullfile(scratch, 'oc.json');
model = stiffpath('fit', 'oc-gu', struct('method', 'physical', 'output', oc_json));
doc = cli_json(cli, sprintf('fit --robot oc-gu --method physical -o "%s"', fullfile(scratch, 'oc_cli.json')));
failures = check(failures, strcmp(model.method, doc.method) && near(model.D_um_per_N, doc.D_um_per_N, 1e-10), ...
                 sprintf('fit: D(p) coefficients = stiffpath fit (%d of them)', numel(doc.D_um_per_N)));
failures = check(failures, near(model.uncertainty.campaign_sigma_um, doc.uncertainty.campaign_sigma_um, 1e-10), ...
                 'fit: the uncertainty it records = stiffpath fit''s');
written = jsondecode(fileread(oc_json));
failures = check(failures, near(written.D_um_per_N, doc.D_um_per_N, 1e-12), 'fit: the model file written = stiffpath fit''s');

% cv: every method's leave-one-out errors, as `stiffpath cv --robot oc-gu`.
cv = stiffpath('cv', 'oc-gu');
doc = cli_json(cli, 'cv --robot oc-gu');
ok = strcmp(cv.favoured_method, doc.favoured_method);
for k = 1:numel(doc.methods)
  m = doc.methods(k);
  mine = cv.methods.(strrep(m.method, '-', '_'));
  ok = ok && near(mine.mean_error_m * 1e6, m.mean_error_um, 1e-9) && near(mine.max_error_m * 1e6, m.max_error_um, 1e-9) ...
          && near(mine.interior_mean_error_m * 1e6, m.interior_mean_error_um, 1e-9) ...
          && near(mine.common_points_mean_error_m * 1e6, m.common_points_mean_error_um, 1e-9) ...
          && mine.predicted_points == m.predicted_points && mine.band_95.inside == m.band_95.inside;
end
failures = check(failures, ok && numel(fieldnames(cv.methods)) == numel(doc.methods), ...
                 sprintf('cv: %d methods'' errors and the favoured one (%s) = stiffpath cv', numel(doc.methods), doc.favoured_method));
% The README's figures: physical-spline misses the held-out points by 32.0 um on average, bilinear's interior 90.5 um.
failures = check(failures, abs(cv.methods.physical_spline.mean_error_m * 1e6 - 32.0) < 0.05 ...
                 && abs(cv.methods.bilinear.interior_mean_error_m * 1e6 - 90.5) < 0.05, 'cv: the README''s 32.0 and 90.5 um');

% plan: the x motion at 5 g with a 20 kHz rate and a jerk of its own, as `stiffpath plan … -o traj.csv`.
traj_csv = fullfile(scratch, 'traj.csv');
[T, s] = stiffpath('plan', gcode('x_motion.gcode'), struct('accel', '5g', 'jerk', 20000, 'rate_hz', 20000));
doc = cli_json(cli, sprintf('plan "%s" --accel 5g --jerk 20000 --rate 20000 -o "%s"', gcode('x_motion.gcode'), traj_csv));
ref = dlmread(traj_csv, ',', 1, 0);  % t_s,x_mm,y_mm,vx_mm_s,vy_mm_s,ax_mm_s2,ay_mm_s2,jx_mm_s3,jy_mm_s3,laser,power,line
failures = check(failures, s.samples == doc.samples && rows(T.t_s) == rows(ref) && near(s.duration_s, doc.duration_s, 1e-12), ...
                 sprintf('plan: %d samples, %.6f s = stiffpath plan', doc.samples, doc.duration_s));
failures = check(failures, near(s.peak_velocity_m_s, doc.peak_velocity_m_s, 1e-9) && near(s.peak_acceleration_m_s2, doc.peak_acceleration_m_s2, 1e-9) ...
                 && near(s.peak_jerk_m_s3, doc.peak_jerk_m_s3, 1e-9) && s.max_jerk_m_s3 == 20000, 'plan: peaks and limits = stiffpath plan');
failures = check(failures, max(max(abs(T.p_m * 1e3 - ref(:, 2:3)))) < 1e-6 && max(max(abs(T.a_m_s2 * 1e3 - ref(:, 6:7)))) < 1e-3 ...
                 && isequal(double(T.laser), ref(:, 10)) && isequal(T.line, ref(:, 12)), 'plan: every sample = stiffpath plan -o');

% run and simulate: the thesis's triangle at 5 g with and without compensation, marked by the twin (the demo).
triangle = gcode('triangle.gcode');
cases = {struct('accel', '5g'), '--accel 5g', 'compensated'; ...
         struct('accel', '5g', 'compensate', false), '--accel 5g --no-compensation', 'without compensation'; ...
         struct('thesis', true), '--thesis', 'the thesis''s method'};
length_error_mm = zeros(1, rows(cases));
for k = 1:rows(cases)
  [J, summary] = stiffpath('run', triangle, 'oc-gu', cases{k, 1});
  joints_csv = fullfile(scratch, sprintf('joints_%d.csv', k));
  doc = cli_json(cli, sprintf('run "%s" %s -o "%s"', triangle, cases{k, 2}, joints_csv));
  ref = dlmread(joints_csv, ',', 2, 0);
  failures = check(failures, summary.samples == doc.samples && rows(J.t_s) == rows(ref) && max(max(abs(J.q_rad - ref(:, 2:3)))) < 1e-9 ...
                   && isequal(double(J.laser), ref(:, 8)), sprintf('run, %s: %d joint commands = stiffpath run', cases{k, 3}, doc.samples));
  failures = check(failures, strcmp(summary.model, doc.model) && strcmp(summary.method, doc.method) && strcmp(summary.filters, doc.filters) ...
                   && near(summary.peak_deflection_m * 1e6, doc.peak_deflection_um, 1e-9) && near(summary.peak_correction_m * 1e6, doc.peak_correction_um, 1e-9) ...
                   && near(summary.peak_force_N, doc.peak_force_n, 1e-9) && near(summary.duration_s, doc.duration_s, 1e-12), ...
                   sprintf('run, %s: summary (%s, %s) = stiffpath run --json', cases{k, 3}, doc.method, doc.filters));
  % The CSV holds angles to 1e-9 rad, the binary file the doubles: run's struct is simulated against the latter.
  joints_bin = fullfile(scratch, sprintf('joints_%d.bin', k));
  [~, ~] = system(sprintf('"%s" run "%s" %s -o "%s" --format bin', cli, triangle, cases{k, 2}, joints_bin));
  names = {'length', 'commanded_length', 'length_error', 'max_deviation', 'path_accuracy', 'cornering_round_off', ...
           'cornering_overshoot', 'residual_vibration', 'peak_deflection'};
  for route = {{J, joints_bin, 'run''s struct'}, {joints_csv, joints_csv, 'the joint file'}}
    m = stiffpath('simulate', 'oc-gu', route{1}{1});
    sim_doc = cli_json(cli, sprintf('simulate "%s"', route{1}{2}));
    ok = m.corners == sim_doc.corners && m.marked_points == sim_doc.marked_points && m.strokes == sim_doc.strokes ...
         && near(m.deviation_area_m2 * 1e6, sim_doc.deviation_area_mm2, 1e-9) && numel(m.stroke_metrics) == sim_doc.strokes;
    for n = 1:numel(names)
      ok = ok && near(m.([names{n} '_m']) * 1e3, sim_doc.([names{n} '_mm']), 1e-9);
    end
    failures = check(failures, ok && rows(m.marked_m) == sim_doc.marked_points, ...
                     sprintf('simulate, %s, %s: length error %+.4f mm, area %.3f mm^2 = stiffpath simulate', cases{k, 3}, ...
                             route{1}{3}, m.length_error_m * 1e3, m.deviation_area_m2 * 1e6));
  end
  length_error_mm(k) = m.length_error_m * 1e3;
end
% The README's demo line: length error 0.546 -> 0.005 mm.
failures = check(failures, abs(abs(length_error_mm(2)) - 0.546) < 0.0005 && abs(abs(length_error_mm(1)) - 0.005) < 0.0005, ...
                 sprintf('the README''s demo: length error %.3f -> %.3f mm', abs(length_error_mm(2)), abs(length_error_mm(1))));

% compensate on plan's struct = run on the same program where no filter retimes the path (run holds each stop for
% its filters' delay, which only a G-code program's segments tell): the thesis's method and no compensation.
[T, ~] = stiffpath('plan', triangle);
for opts = {struct('thesis', true), struct('compensate', false)}
  [Jc, sc] = stiffpath('compensate', 'oc-gu', '', T, opts{1});
  [Jr, sr] = stiffpath('run', triangle, 'oc-gu', opts{1});
  failures = check(failures, rows(Jc.t_s) == rows(Jr.t_s) && max(max(abs(Jc.q_rad - Jr.q_rad))) < 1e-12 ...
                   && max(max(abs(Jc.command_m - Jr.command_m))) < 1e-12 && strcmp(sc.method, sr.method), ...
                   sprintf('compensate(plan(job)) = run(job), method %s', sr.method));
end

% scan: a drawn capsule (a laser's line: round ends) 40 mm between its end centres, 0.3 mm wide at 600 dpi, measured
% through the second gateway; the centre line runs between the end centres (docs/vision.md), to about a pixel (42 um).
has_scan = exist('stiffpath_scan') == 3;  % built where the vision library is
image = uint8(255 * ones(400, 1200));
if has_scan
  dpi = 600; px = 25.4e-3 / dpi;
  [cols, rws] = meshgrid(1:1200, 1:400);
  ends = [150 200.5; 150 + 0.040 / px, 200.5];  % px, image frame (x right, y down)
  along = min(max(cols, ends(1, 1)), ends(2, 1));
  inside = hypot(cols - along, rws - ends(1, 2)) <= 0.15e-3 / px;
  image = uint8(255 - 235 * inside);
  m = stiffpath('scan', image, struct('dpi', dpi, 'shape', 'line'));
  failures = check(failures, abs(m.length_mm - 40) < 0.05 && rows(m.points_m) > 10 ...
                   && max(abs(m.points_m(:, 2) - (ends(1, 2) - 1) * px)) < px / 2, ...
                   sprintf('scan: a drawn 40 mm line measures %.4f mm, its centre line within half a pixel', m.length_mm));
else
  printf('skip scan: stiffpath_scan.mex is not built here (no vision library)\n');
end

% Refusals: each a MATLAB error with the library's message, never a crash.
bad = {{'run', triangle, 'oc-gu', struct('accel', '2000g')}, 'stiffpath:badInput', 'options.accel'; ...
       {'run', triangle, 'oc-gu', struct('smoth_s', 0)}, 'stiffpath:usage', 'smoth_s'; ...
       {'plan', fullfile(source_dir, 'examples', 'no_such.gcode')}, 'stiffpath:badInput', 'no_such.gcode'; ...
       {'plan', triangle, struct('jerk', 'auto')}, 'stiffpath:badInput', 'auto'; ...
       {'simulate', 'oc-gu', struct('t_s', [0; 1])}, 'stiffpath:usage', 'q_rad'; ...
       {'predict', 'thesis-oc', [0.23 NaN], [1 1]}, 'stiffpath:badInput', 'finite'; ...
       {'compensate', 'oc-gu', '', T, struct('gain', -1)}, 'stiffpath:badInput', 'gain'; ...
       {'cv', 'oc-gu', struct('table', '/nonexistent.csv')}, 'stiffpath:badInput', 'nonexistent'; ...
       {'help', 'nosuch'}, 'stiffpath:usage', 'nosuch'};
if has_scan, bad(end + 1, :) = {{'scan', image, struct('shape', 'line')}, 'stiffpath:badInput', 'dpi'}; end
for k = 1:rows(bad)
  try
    stiffpath(bad{k, 1}{:});
    failures = check(failures, false, sprintf('%s %s is refused', bad{k, 1}{1}, bad{k, 3}));
  catch err
    failures = check(failures, strcmp(err.identifier, bad{k, 2}) && ~isempty(strfind(err.message, bad{k, 3})), ...
                     sprintf('%s refused as %s naming %s: %s', bad{k, 1}{1}, bad{k, 2}, bad{k, 3}, strtok(err.message, "\n")));
  end
end

% Help: the overview names every command, and each command has a text of its own.
overview = evalc('help stiffpath');
commands = {'ik', 'fk', 'fit', 'cv', 'predict', 'compliance', 'plan', 'run', 'compensate', 'simulate', 'scan', 'help'};
ok = true;
for k = 1:numel(commands)
  text = stiffpath('help', commands{k});
  ok = ok && ~isempty(strfind(overview, ['''' commands{k} ''''])) && ~isempty(strfind(text, ['''' commands{k} '''']));
end
failures = check(failures, ok, 'help stiffpath lists every command; stiffpath(''help'', command) explains each');

if failures > 0
  printf('%d check(s) failed\n', failures);
  exit(1);
end
printf('all checks passed\n');
