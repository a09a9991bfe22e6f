#!/usr/bin/env bash
# Rebuilds the kernel's SPIR-V (host/shaders/caustic-kernel.spv, or the path given as $1).
# The builder's target directory is a cache outside the clone: the first build compiles rust-gpu's
# codegen backend (minutes); later builds take seconds.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
export CAUSTIC_CACHE=${CAUSTIC_CACHE:-$HOME/.cache/caustic}
rustup toolchain list | grep -q '^nightly-2026-08-15' ||
  rustup toolchain install nightly-2026-08-15 --profile minimal --component rust-src,rustc-dev,llvm-tools
cd "$here"
export CAUSTIC_ROOT=$(cd "$here/.." && pwd)
CARGO_TARGET_DIR="$CAUSTIC_CACHE/shaders-build-target" cargo run --release --quiet -- "${1:-$here/../host/shaders/caustic-kernel.spv}"
