#!/usr/bin/env bash
# Regenerates docs/reference/scene-keys.md: `dustlift info --keys` over every scene of cases/
# (not the sweep studies), in byte order of their paths (tests/unit/test_scene_keys.cpp reads
# the same list and fails when the file is stale). Usage: bash scripts/scene-keys.sh [BUILD_DIR]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build/release}"
mapfile -t scenes < <(find "$root/cases" -name '*.toml' -not -path '*/studies/*' | LC_ALL=C sort)
mkdir -p "$root/docs/reference"
"$build/dustlift" info --keys "${scenes[@]}" > "$root/docs/reference/scene-keys.md"
echo "wrote $root/docs/reference/scene-keys.md (${#scenes[@]} scenes)"
