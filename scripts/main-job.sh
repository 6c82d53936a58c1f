#!/usr/bin/env bash
# The README's first command: installs what is missing, builds rpsd (the command and the libraries
# it links, not the tests: scripts/test.sh builds those), then runs the main job:
# an earthquake RPsD test of the paper's structure on the simulated servo rig under a synthetic
# record, the linear analysis of the seed paper's rig, its Figure 5, 6 and 7 studies, and the RPsD
# delay-compensation study of its Figure 8 (servo model and ideal delay), into ./results.
# Run again, it replaces what an earlier main job wrote there (rpsd run --replace).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
RPSD_BUILD_TARGETS=rpsd bash scripts/build.sh
out=${1:-results}
rig=examples/servo/paper-mts-244.yaml
echo
./build/rpsd analyze "$rig"
mkdir -p "$out"
./build/rpsd analyze "$rig" --json > "$out/servo-analysis.json"
for scenario in synthetic-sdof paper-fig5-sinesweep paper-fig6-frequency-response paper-fig7-max-gain \
                paper-fig8-delay-compensation paper-fig8-ideal-delay; do
  ./build/rpsd run "examples/scenarios/$scenario.yaml" --out "$out/$scenario" --replace
done
echo
echo "Earthquake RPsD test (synthetic record): $out/synthetic-sdof/summary.json, test.png, response.png, record.png"
echo "Plots: $out/paper-fig5-sinesweep/sine_sweep.png, $out/paper-fig6-frequency-response/frequency_response.png,"
echo "       $out/paper-fig7-max-gain/max_gain.png, $out/paper-fig8-delay-compensation/delay_compensation.png,"
echo "       $out/paper-fig8-ideal-delay/delay_compensation.png (data beside them as CSV and summary.json)"
