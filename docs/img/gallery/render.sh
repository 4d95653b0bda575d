#!/bin/sh
# Render the gallery views: render.sh SCENES_DIR TAG (before|after). Writes
# docs/img/gallery/<scene>_<room>_<TAG>.png (the 224x224 RGB camera). Run from the repo root.
set -e
SCENES=$1; TAG=$2; XTASK=${XTASK:-target/release/xtask}
for s in tiny_0000 tiny_0001 tiny_0002; do
  ${PY:-python3} docs/img/gallery/views.py "$SCENES/$s" | while read -r room pos yaw; do
    $XTASK render --scene "$SCENES/$s" --position "$pos" --yaw "$yaw" --out /tmp/gallery-view >/dev/null
    cp /tmp/gallery-view/rgb.png "docs/img/gallery/${s}_${room}_${TAG}.png"
  done
done
