% load_results.m: a test's results.h5 in MATLAB, with h5read and h5readatt only (no toolbox).
% Follows the layout of docs/results-format.md: /test and /reference hold the coordinator's,
% each experimental channel's and each recorded DOF's histories, one dataset per CSV column
% with its unit in the attribute 'units'; time is the step index times the run's period_s.
% Not run in CI (MATLAB is not on the build machines); Octave 7+ reads the same calls.
%
%   rpsd run examples/scenarios/elcentro-sdof.yaml --out out/elcentro --format hdf5
%   >> r = load_results('out/elcentro/results.h5');
%   >> plot(r.test.time_s, r.test.ch0.measured_m, r.reference.time_s, r.reference.ch0.measured_m)
function r = load_results(file)
  r.scenario = h5readatt(file, '/global_model', 'scenario');
  r.test = load_run(file, '/test');
  if has_group(file, '/reference')
    r.reference = load_run(file, '/reference');
  end
  % summary.json whole, as text (jsondecode turns it into a struct in MATLAB R2016b+).
  if has_group(file, '/analysis')
    r.summary = jsondecode(char(h5read(file, '/analysis/summary_json')));
  end
end

function run = load_run(file, group)
  run.period_s = h5readatt(file, group, 'period_s');
  run.step = double(h5read(file, [group '/coordinator/step']));
  run.time_s = run.step * run.period_s;
  run.coordinator = load_group(file, [group '/coordinator']);
  info = h5info(file, group);
  for g = info.Groups'
    [~, part] = fileparts(g.Name);  % experimental_substructure, simulation_substructure
    if strcmp(part, 'coordinator')
      continue
    end
    for sub = g.Groups'
      [~, name] = fileparts(sub.Name);  % ch0, held_ch1, dof0
      run.(name) = load_group(file, sub.Name);
    end
  end
end

% Every dataset of a group as a column vector of doubles, and its unit in s.units.<name>.
function s = load_group(file, group)
  info = h5info(file, group);
  for d = info.Datasets'
    s.(d.Name) = double(h5read(file, [group '/' d.Name]));
    s.units.(d.Name) = h5readatt(file, [group '/' d.Name], 'units');
  end
end

function yes = has_group(file, group)
  info = h5info(file);
  yes = any(strcmp({info.Groups.Name}, group));
end
