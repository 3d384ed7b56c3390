#!/usr/bin/env bash
# Installs every Debian package GearSPH needs to build, test and run.
# Idempotent: safe to run again; apt-get skips what is already installed.
set -euo pipefail

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build pkg-config git clang-format ccache
  # libraries (architecture.md: Beast, nlohmann-json, Eigen, HDF5, SQLite, OSMesa)
  libboost-dev nlohmann-json3-dev libeigen3-dev libhdf5-dev hdf5-tools
  # JSON Schema validation of job files (header-only, over nlohmann-json)
  libvalijson-dev
  libsqlite3-dev sqlite3 libosmesa6-dev libpng-dev
  # SHA-256 of the job store's session ids (libcrypto)
  libssl-dev
  # tests and benchmarks
  libgtest-dev libbenchmark-dev python3-pysph curl
  # the official JSON-Schema-Test-Suite, run through the job validator
  json-schema-test-suite
  # results checked with ParaView's own reader (pvpython), rendering fonts
  paraview python3-paraview python3-h5py libfreetype-dev fonts-dejavu-core
  # scale-out (docs/scale-out.md): the PostgreSQL job store's client library,
  # and the engines its tests start on loopback (PostgreSQL, single-node Slurm)
  libpq-dev postgresql slurm-wlm munge
  # the dashboard's browser tests (headless Chromium driven by playwright-core)
  chromium
  # the finite-element check (docs/fe-check.md): gmsh meshes, CalculiX solves;
  # both run as programs, so no development packages are needed
  gmsh calculix-ccx
)
# Node.js for the dashboard's npm packages (uPlot, playwright-core); a newer
# Node.js already installed (e.g. from NodeSource) is kept.
if ! command -v npm >/dev/null; then PACKAGES+=(nodejs npm); fi

export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${PACKAGES[@]}" >/dev/null
echo "setup: Debian packages installed"

# The dashboard's chart library and the browser-test driver, exactly as
# locked in package-lock.json; postinstall copies uPlot to web/vendor/.
cd "$(dirname "$0")/.."
npm ci --no-audit --no-fund --loglevel=error
echo "setup: npm packages installed (web/vendor/ ready)"
