#!/usr/bin/env bash
# Reproduces the committed DuskNet model (docs/learned_descriptor.md) in one
# command: builds duskmap, renders the training pairs of configs/dusknet.json's
# "data" section (generated scenes only, never the default dataset), then
# trains with its "train" section and writes slam/features/models/dusknet.onnx,
# its training log and data manifest beside it, and
# docs/figures/dusknet_training.png. The pairs go to DATA (default
# out/dusknet_data). Rebuild afterwards to embed the new model in duskmap.
set -euo pipefail
cd "$(dirname "$0")/.."
DATA="${DATA:-out/dusknet_data}"
bash scripts/build.sh
start=$(date +%s)
./build/experiments/duskmap features training-data --config configs/dusknet.json --out "$DATA" --overwrite
echo "train_dusknet: training data in $(( $(date +%s) - start )) s"
start=$(date +%s)
/usr/bin/python3 scripts/train_descriptor.py --data "$DATA" --config configs/dusknet.json
echo "train_dusknet: training in $(( $(date +%s) - start )) s"
