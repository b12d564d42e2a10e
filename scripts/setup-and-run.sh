#!/usr/bin/env bash
# Fresh Debian 12 machine -> dependencies, build, default scene with VTK output, series,
# figures and an offscreen render. Usage: bash scripts/setup-and-run.sh [SCENE] [OUTDIR]
# (relative to the current folder; OUTDIR is replaced if it holds an earlier run).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
scene=$(realpath -m "${1:-$root/cases/quickstart.toml}")
out=$(realpath -m "${2:-$root/out/quickstart}")
bash "$root/scripts/install-deps.sh"
cd "$root"
cmake --preset release
cmake --build --preset release --target dustlift
bash scripts/run-scene.sh "$scene" "$out" --overwrite
