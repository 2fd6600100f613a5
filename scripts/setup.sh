#!/usr/bin/env bash
# Installs every Debian package duskmap needs. Idempotent and non-interactive.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config git
  libopencv-dev libeigen3-dev libflann-dev libceres-dev
  nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev
  libsqlite3-dev libcli11-dev libzip-dev
  libhdf5-dev  # hloc-layout feature files, slam/features/h5_feature_file.h
  sweethome3d-furniture  # real furniture models, slam/synthetic/assets/furniture_catalog.h
  python3 python3-matplotlib python3-numpy python3-onnx
  python3-h5py python3-opencv  # tests write h5 files as hloc does; the external-feature example
  clang libclang-rt-14-dev  # libFuzzer targets under tests/fuzz (docs/real_data.md)
  slurm-wlm munge  # the one-node cluster of the slurm tests (scripts/slurm_local.sh)
  python3-torch  # training DuskNet, the learned descriptor (scripts/train_descriptor.py), on the CPU
)

missing=()
for pkg in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
