#!/usr/bin/env bash
# Fresh Debian 12 machine -> dependencies, build, every test (unit, verification, stress).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release
cmake --build --preset release
ctest --preset release
