#!/usr/bin/env bash
# Rebuilds the kernel's SPIR-V (host/shaders/caustic-kernel.spv, or the path given as $1).
# The builder's target directory is a cache outside the clone: the first build compiles rust-gpu's
# codegen backend (minutes); later builds take seconds.
#
# Building the committed module also writes its stamp, host/shaders/caustic-kernel.inputs: the
# SHA-256 of every input of the build (`inputs` below: the kernel's sources and manifest, the lock
# files, the toolchain and the builder) and of the module. The test command checks the stamp
# against the tree (tests/tests/committed_spirv.rs), so a kernel edit without a rebuild fails in
# seconds; CI's full rebuild (`CAUSTIC_CI_REBUILD_SPIRV=1 .ci/run`) remains the check that the
# toolchain still produces the committed bytes.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
export CAUSTIC_CACHE=${CAUSTIC_CACHE:-$HOME/.cache/caustic}
rustup toolchain list | grep -q '^nightly-2026-08-15' ||
  rustup toolchain install nightly-2026-08-15 --profile minimal --component rust-src,rustc-dev,llvm-tools
root=$(cd "$here/.." && pwd)
committed="$root/host/shaders/caustic-kernel.spv"
out="${1:-$committed}"
# The inputs, relative to the repository root, in a fixed order (also what the test hashes).
inputs() {
  (cd "$root" && { printf '%s\n' Cargo.toml Cargo.lock kernel/Cargo.toml shaders-build/Cargo.toml \
    shaders-build/Cargo.lock shaders-build/rust-toolchain.toml shaders-build/src/main.rs shaders-build/build.sh \
    shaders-build/tools/spirv-opt;
    find kernel/src -type f -name '*.rs' | LC_ALL=C sort; })
}
# Hashed before the build, so that an edit made while it runs makes the stamp stale, not wrong.
stamp=$(cd "$root" && inputs | xargs sha256sum)
cd "$here"
export CAUSTIC_ROOT=$root
# spirv-opt without validating its input (tools/spirv-opt says why).
export PATH="$here/tools:$PATH"
CARGO_TARGET_DIR="$CAUSTIC_CACHE/shaders-build-target" cargo run --release --quiet -- "$out"
if [ "$(realpath "$out")" = "$(realpath "$committed")" ]; then
  { echo "$stamp"; (cd "$root" && sha256sum host/shaders/caustic-kernel.spv); } >"$root/host/shaders/caustic-kernel.inputs"
  echo "wrote host/shaders/caustic-kernel.inputs"
fi
