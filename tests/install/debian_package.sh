#!/usr/bin/env bash
# cpack builds rpsd_<version>_amd64.deb from this build tree. The package holds the binary,
# the libraries, headers and CMake package, the examples with the records, servo files and DDS
# configurations they name, and the docs; it depends on the runtime libraries (never a -dev
# package), gnuplot and the Python module's python3, NumPy, h5py and PyYAML; its rpsd, unpacked,
# reads its own example scenarios from share/, and its Python module imports and reads one.
# Usage: debian_package.sh BUILD_DIR VERSION
set -euo pipefail
build=$1 version=$2
work=$(mktemp -d /tmp/rpsd-deb.XXXXXX)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
(cd "$build" && cpack -G DEB -B "$work" > "$work/cpack.log" 2>&1) || { cat "$work/cpack.log"; fail "cpack"; }
deb="$work/rpsd_${version}_amd64.deb"
[ -f "$deb" ] || fail "no $deb: $(ls "$work")"
depends=$(dpkg-deb -f "$deb" Depends)
for runtime in libyaml-cpp libddsc libssl3 libhdf5 libstdc++6 libcpp-httplib gnuplot python3-numpy python3-h5py \
  python3-yaml "python3 (>= "; do
  grep -q "$runtime" <<< "$depends" || fail "Depends lacks $runtime: $depends"
done
! grep -q -- "-dev" <<< "$depends" || fail "Depends names a -dev package: $depends"
contents=$(dpkg-deb -c "$deb" | awk '{print $6}')
for path in ./usr/bin/rpsd ./usr/include/rpsd/servo/plant_factory.h ./usr/lib/cmake/rpsd/rpsdConfig.cmake \
  ./usr/lib/librpsd_servo.a ./usr/include/rpsd/output/results_files.h ./usr/lib/librpsd_output.a \
  ./usr/share/rpsd/examples/scenarios/elcentro-sdof.yaml \
  ./usr/share/rpsd/examples/servo/paper-mts-244.yaml ./usr/share/rpsd/data/ground-motions/I-ELC180.AT2 \
  ./usr/share/rpsd/data/ground-motions/README.md ./usr/share/rpsd/transport/config/loopback.xml \
  ./usr/share/doc/rpsd/README.md ./usr/share/doc/rpsd/safety.md ./usr/share/doc/rpsd/LICENSE \
  ./usr/share/doc/rpsd/python.md ./usr/lib/python3/dist-packages/rpsd/__init__.py \
  ./usr/lib/python3/dist-packages/rpsd/loader.py ./usr/share/rpsd/examples/python/figure8.py; do
  grep -qxF "$path" <<< "$contents" || fail "the package lacks $path"
done
dpkg-deb -x "$deb" "$work/root"
cd "$work"
for scenario in "$work"/root/usr/share/rpsd/examples/scenarios/*.yaml; do
  "$work/root/usr/bin/rpsd" validate "$scenario" > /dev/null || fail "the packaged rpsd refuses $scenario"
done
PYTHONPATH="$work/root/usr/lib/python3/dist-packages" /usr/bin/python3 -c \
  "import rpsd, sys; assert rpsd.validate(sys.argv[1])['kind'] == 'rpsd_test'" \
  "$work/root/usr/share/rpsd/examples/scenarios/elcentro-sdof.yaml" || fail "the packaged Python module"
ls "$work"/root/usr/lib/python3/dist-packages/rpsd/_rpsd*.so > /dev/null || fail "the package lacks the extension _rpsd"
echo "PASS: $(basename "$deb"): $(wc -l <<< "$contents") entries; Depends: $depends"
