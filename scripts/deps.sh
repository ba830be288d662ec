#!/usr/bin/env bash
# Installs what dropcheck needs from Debian 12's packages, skipping the apt calls when all are there.
# Sourced by scripts/report.sh and scripts/test.sh; safe to run on its own.
set -euo pipefail

DROPCHECK_PACKAGES=(
  cmake g++ gcc make pkg-config        # build (gcc: the C example engine in examples/c)
  ninja-build                          # the ci preset's generator (scripts/test.sh)
  python3                              # the Python example engines and the bad-engine test doubles
  libeigen3-dev libtomlplusplus-dev    # ours, scene files
  catch2                               # tests
  libcli11-dev                         # command-line parsing (header-only CLI11)
  nlohmann-json3-dev                   # JSON output, every name escaped by construction
  libfmt-dev                           # number formatting (harness/core/number_format.hpp)
  libboost-math-dev                    # Jacobi elliptic functions (harness/oracles/free_rotation)
  libbullet-dev libode-dev libbox2d-dev libmujoco-dev libqhull-dev  # the engines compared
  libchipmunk-dev                      # Chipmunk2D (2-D, double)
  libsimbody-dev                       # Simbody (multibody, semi-explicit Euler)
  libdart-dev                          # DART 6.12 (Gazebo's fourth engine; pulls Boost and Open MPI)
  libwildmagic-dev                     # Wild Magic 5 (RigidBody, fourth-order Runge-Kutta)
  libgl-dev                            # MuJoCo's CMake package requires OpenGL to be findable
  gnuplot-nox                          # report plots (SVG)
  clang-format-14 git                  # scripts/format.sh and the ctest entry `format`
  libbenchmark-dev                     # benchmarks (bench/, scripts/bench.sh)
  slurmctld slurmd slurm-client munge  # sweeps on a localhost Slurm (ctest slurm, scripts/slurm/)
  python3-jsonschema                   # validates sweep records against docs/results.schema.json
)

missing=()
for p in "${DROPCHECK_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "dropcheck: installing ${missing[*]}" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
