#!/usr/bin/env bash
# Installs the Debian 12 packages the project needs (only those missing) and builds
# everything (library, lafit, tests, benchmarks) into build/.
set -euo pipefail
cd "$(dirname "$0")/.."

source scripts/packages.sh
installMissing "${LAFAIR_LIBRARY_PACKAGES[@]}" g++ \
  libgtest-dev libgmock-dev libbenchmark-dev \
  qt6-base-dev qt6-qpa-plugins fonts-dejavu-core \
  python3 python3-numpy

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
