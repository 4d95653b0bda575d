#!/usr/bin/env bash
# Reproduces docs/baselines.md: export, offline training, online fine-tuning and evaluation of
# Seq2Seq and CMA on the vlnverse preset (fine-grained), beside the CLI's reference agents.
# Every step resumes where it stopped (run folders, export parts). Times are printed per step.
set -euo pipefail
cd "$(dirname "$0")/../.."
PY=${PY:-.venv/bin/python}
XTASK=${XTASK:-target/release/xtask}
D=${D:-datasets/vlnverse}
R=${R:-runs/baselines}
TRAIN_EPISODES=${TRAIN_EPISODES:-200}
SAMPLE=${SAMPLE:-50}
export OPENBLAS_NUM_THREADS=1
mkdir -p "$R/eval"
[ -d "$D" ] || "$XTASK" generate --preset vlnverse --out "$D"

step() { local t0=$SECONDS; "$@"; echo "step: $((SECONDS - t0)) s: $*" | tee -a "$R/times.txt"; }

# Offline data: the first TRAIN_EPISODES fine-grained training episodes along the teacher path.
step "$XTASK" export --dataset "$D" --task fine --split train --format lerobot \
  --episodes "$TRAIN_EPISODES" --out "$R/export-fine-train"

for m in seq2seq cma; do
  # Offline teacher forcing (lr 1e-3: a few minutes of CPU, not the paper's day at 1e-4).
  step $PY -m vlnverse_baselines train --model "$m" --mode offline --data "$R/export-fine-train" \
    --dataset "$D" --task fine --out "$R/$m-offline" --epochs 10 --batch-size 4 --lr 1e-3
  # Online fine-tuning: imitation with schedule sampling in Tel-Hop, 4 environments.
  step $PY -m vlnverse_baselines train --model "$m" --mode online --init "$R/$m-offline/model.safetensors" \
    --dataset "$D" --task fine --out "$R/$m-online" --epochs 8 --updates-per-epoch 25 \
    --decay-every 2 --num-envs 4 --lr 5e-4
  for v in offline online; do
    for sp in val_unseen/telhop val_unseen/strict test/telhop; do
      step $PY -m vlnverse_baselines evaluate --checkpoint "$R/$m-$v/model.safetensors" \
        --dataset "$D" --task fine --split "${sp%/*}" --setting "${sp#*/}" --sample "$SAMPLE" \
        --seed 0 --name "$m-$v" --out "$R/eval/$m-$v-fine-${sp%/*}-${sp#*/}"
    done
  done
done

for a in random forward semantic oracle; do
  for sp in val_unseen/telhop val_unseen/strict test/telhop; do
    step "$XTASK" evaluate --dataset "$D" --task fine --split "${sp%/*}" --agent "$a" \
      --setting "${sp#*/}" --sample "$SAMPLE" --seed 0 --out "$R/eval/$a-fine-${sp%/*}-${sp#*/}"
  done
done

# Coarse-grained: the same recipe on the first 200 coarse training episodes, then online.
step "$XTASK" export --dataset "$D" --task coarse --split train --format lerobot \
  --episodes "$TRAIN_EPISODES" --out "$R/export-coarse-train"
for m in seq2seq cma; do
  step $PY -m vlnverse_baselines train --model "$m" --mode offline --data "$R/export-coarse-train" \
    --dataset "$D" --task coarse --out "$R/$m-offline-coarse" --epochs 10 --batch-size 4 --lr 1e-3
  step $PY -m vlnverse_baselines evaluate --checkpoint "$R/$m-offline-coarse/model.safetensors" \
    --dataset "$D" --task coarse --split val_unseen --setting telhop --sample "$SAMPLE" --seed 0 \
    --name "$m-offline" --out "$R/eval/$m-offline-coarse-val_unseen-telhop"
  step $PY -m vlnverse_baselines train --model "$m" --mode online \
    --init "$R/$m-offline-coarse/model.safetensors" --dataset "$D" --task coarse \
    --out "$R/$m-online-coarse" --epochs 8 --updates-per-epoch 25 --decay-every 2 --num-envs 4 \
    --lr 5e-4
  step $PY -m vlnverse_baselines evaluate --checkpoint "$R/$m-online-coarse/model.safetensors" \
    --dataset "$D" --task coarse --split val_unseen --setting telhop --sample "$SAMPLE" --seed 0 \
    --name "$m-online" --out "$R/eval/$m-online-coarse-val_unseen-telhop"
done
for a in random forward semantic oracle; do
  step "$XTASK" evaluate --dataset "$D" --task coarse --split val_unseen --agent "$a" \
    --setting telhop --sample "$SAMPLE" --seed 0 --out "$R/eval/$a-coarse-val_unseen-telhop"
done

$PY baselines/bench/results_table.py "$R"/eval/*
