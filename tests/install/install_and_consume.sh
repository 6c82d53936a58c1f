#!/usr/bin/env bash
# Installs the built tree into a temporary prefix, then configures, builds and runs a
# separate project that does find_package(rpsd) and links rpsd::servo and rpsd::output.
set -euo pipefail
build_dir=$1; source_dir=$2
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" >/dev/null
test -x "$work/prefix/bin/rpsd"
test -f "$work/prefix/include/rpsd/servo/servo_hydraulic_plant.h"
# The test's assembly is its own module (docs/migration.md): its headers, not the old ones.
test -f "$work/prefix/include/rpsd/hybrid_test/site_kinds.h"
test ! -e "$work/prefix/include/rpsd/coordinator/test_config.h"
grep -q "rpsd::hybrid_test" "$work/prefix/lib/cmake/rpsd/rpsdTargets.cmake"
# The result writers are their own module too: output/, not studies/.
test -f "$work/prefix/include/rpsd/output/results_files.h"
test ! -e "$work/prefix/include/rpsd/studies/results_files.h"
# A test's output and its Monte Carlo batch belong to the test's assembly, not studies/.
test -f "$work/prefix/include/rpsd/hybrid_test/hybrid_test_output.h"
test -f "$work/prefix/include/rpsd/hybrid_test/hybrid_test_document.h"
test ! -e "$work/prefix/include/rpsd/studies/monte_carlo_output.h"
# The Python module, installed with its package files, imports from there and runs the C++ core.
python_package=$(dirname "$(find "$work/prefix" -name '_rpsd*.so' | head -1)")
test -f "$python_package/__init__.py" && test -f "$python_package/loader.py"
PYTHONPATH=$(dirname "$python_package") /usr/bin/python3 -c \
  "import rpsd, sys; assert rpsd.analyze_servo(sys.argv[1])['cutoff_frequency_hz'] > 1.9" \
  "$source_dir/examples/servo/paper-mts-244.yaml"
cmake -S "$source_dir/tests/install/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
"$work/consumer/consumer"
