#!/usr/bin/env bash
# Installs the Debian 12 packages stiction needs (only those missing), then configures and
# builds it in ./build (Release). Usage: scripts/bootstrap.sh [--peers] [--slurm] [extra cmake args...]
# --peers: also installs the peer engines bench/peers measures stiction against (ODE, Bullet,
# MuJoCo, DART, Siconos) and builds bench_peers with them.
# --slurm: also installs Slurm and munge (slurm-wlm, munge), which tests/cluster uses to run
# docs/sweeps.md's job array on a single-node cluster it starts itself (CI does).
set -euo pipefail
cd "$(dirname "$0")/.."

peers=0
slurm=0
cmake_args=()
for arg in "$@"; do
  case "$arg" in
    --peers) peers=1 ;;
    --slurm) slurm=1 ;;
    *) cmake_args+=("$arg") ;;
  esac
done

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libtomlplusplus-dev libmuparser-dev nlohmann-json3-dev libcli11-dev
  catch2 libbenchmark-dev
  libosmesa6-dev libglm-dev libpng-dev libfreetype-dev libcairo2-dev
  poppler-utils librsvg2-bin
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
  python3
  pybind11-dev python3-dev python3-numpy python3-pandas python3-pytest python3-matplotlib
  python3-nbconvert python3-nbclient python3-ipykernel
  clang-14 libclang-rt-14-dev
  liburdfdom-dev libtinyxml-dev libassimp-dev
)
if [ "$peers" -eq 1 ]; then
  packages+=(libode-dev libbullet-dev libmujoco-dev libdart-dev libsiconos-mechanics-dev)
  cmake_args+=(-DSTICTION_BUILD_BENCH=ON -DSTICTION_PEERS=ON)
fi
if [ "$slurm" -eq 1 ]; then
  packages+=(slurm-wlm munge)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "Installing: ${missing[*]}" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release ${cmake_args[@]+"${cmake_args[@]}"} >&2
cmake --build build -j"$(nproc)" >&2
