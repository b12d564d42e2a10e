#!/usr/bin/env bash
# Fresh Debian 12 machine -> dependencies, build, default scene with VTK output, series,
# figures and an offscreen render. Usage: bash scripts/setup-and-run.sh [SCENE] [OUTDIR]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-cases/quickstart.toml}
out=${2:-out/quickstart}
bash scripts/install-deps.sh
cmake --preset release
cmake --build --preset release --target dustlift
bash scripts/run-scene.sh "$scene" "$out"
