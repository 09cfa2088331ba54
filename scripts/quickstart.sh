#!/usr/bin/env bash
# Quick start: install the dependencies, build repose (release) and run the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)"
build/release/apps/repose/repose info "cylinder:r=0.67,h=0.67" --density 0.96
