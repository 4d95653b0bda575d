#!/usr/bin/env python3
"""Render the feature pieces (vlnverse-procgen `pieces.rs`), or the classes named after OUT:
for each class, its first object on a ground floor in a scenes folder, seen by the RGB camera
from a navigable cell of its room about two metres away, and one labelled contact sheet of them.

    python3 docs/img/gallery/pieces.py SCENES_DIR OUT.png [CLASS ... | things2 | things3]
    (needs Pillow; XTASK to override)
"""
import json
import math
import os
import subprocess
import sys

from PIL import Image, ImageDraw

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from views import free_cells, inside

PIECES = ["recliner", "rocking_chair", "chaise_lounge", "pool_table", "ping_pong_table",
          "foosball_table", "grandfather_clock", "guitar", "drum_kit", "statue", "column",
          "birdcage", "cactus", "urn", "china_cabinet", "chandelier", "kitchen_island",
          "console_table", "fire_extinguisher", "dryer", "ladder", "easel", "massage_table",
          "grill", "lounger", "hammock"]
# The second lot of things (classes 195-210, vlnverse-procgen `more_things.rs`):
# `pieces.py SCENES docs/img/gallery/things2.png things2`.
THINGS2 = ["sectional", "buffet", "ceiling_fan", "water_heater", "mini_fridge", "teddy_bear",
           "bust", "saxophone", "basketball_hoop", "whiteboard", "bulletin_board", "chess_table",
           "candelabra", "exercise_ball", "sword", "rocks"]
# The third lot (classes 211-239, vlnverse-procgen `household.rs`):
# `pieces.py SCENES docs/img/gallery/things3.png things3`.
THINGS3 = ["light_switch", "outlet", "thermostat", "air_vent", "smoke_detector", "calendar",
           "air_conditioner", "range_hood", "futon", "daybed", "trophy_case", "amplifier",
           "microphone", "violin", "toolbox", "wheelbarrow", "shovel", "garden_hose", "suitcase",
           "mop_bucket", "broom", "bathroom_scale", "firewood", "spice_rack", "sewing_machine",
           "typewriter", "record_player", "radio", "knife_block"]
# Classes that hang above a metre: their lowest point is higher.
HUNG = ("chandelier", "wall_sconce", "wreath", "deer_head", "dartboard", "ceiling_fan",
        "basketball_hoop", "bulletin_board", "sword", "light_switch", "thermostat",
        "smoke_detector", "calendar", "air_conditioner", "range_hood", "spice_rack",
        "sewing_machine", "typewriter", "record_player", "radio", "knife_block")
XTASK = os.environ.get("XTASK", "target/release/xtask")
TILE = 168


def first_objects(scenes, classes):
    found = {}
    for name in sorted(os.listdir(scenes)):
        scene = json.load(open(f"{scenes}/{name}/scene.json"))
        for o in scene["objects"]:
            c = o["class"]
            # Ground floor only (the navigable map below is the ground floor's); a chandelier
            # hangs from its ceiling, a sconce on a wall.
            low = 2.7 if c == "smoke_detector" else 2.6 if c in HUNG else 1.0
            if c in classes and c not in found and o["bbox"]["min"][1] < low:
                found[c] = (f"{scenes}/{name}", scene, o)
    return found


def viewpoint(scene_dir, scene, o):
    """A free cell of the object's room 1.5-2.8 m from its centre, nearest 2.1 m."""
    room = next(r for r in scene["rooms"] if r["id"] == o["room"])
    b = o["bbox"]; cx = (b["min"][0] + b["max"][0]) / 2; cz = (b["min"][2] + b["max"][2]) / 2
    best = None
    for x, z in free_cells(scene_dir):
        d = math.hypot(x - cx, z - cz)
        near = best is None or abs(d - 2.1) < best[0]
        if 1.5 <= d <= 2.8 and near and inside(room["polygon"], x, z):
            best = (abs(d - 2.1), x, z)
    if best is None:
        return None
    _, x, z = best
    return x, z, math.degrees(math.atan2(-(cx - x), -(cz - z)))


def main(scenes, out, classes):
    tiles = []
    for c, (scene_dir, scene, o) in sorted(first_objects(scenes, classes).items(),
                                           key=lambda kv: classes.index(kv[0])):
        view = viewpoint(scene_dir, scene, o)
        if view is None:
            continue
        x, z, yaw = view
        subprocess.run([XTASK, "render", "--scene", scene_dir, "--position", f"{x:.2f},0,{z:.2f}",
                        "--yaw", f"{yaw:.1f}", "--out", "/tmp/pieces-view"], check=True,
                       capture_output=True)
        im = Image.open("/tmp/pieces-view/rgb.png").convert("RGB").resize((TILE, TILE))
        ImageDraw.Draw(im).text((4, 4), c.replace("_", " "), fill=(255, 255, 255))
        tiles.append(im)
    cols = 7
    sheet = Image.new("RGB", (cols * TILE, -(-len(tiles) // cols) * TILE))
    for k, im in enumerate(tiles):
        sheet.paste(im, ((k % cols) * TILE, (k // cols) * TILE))
    # An adaptive palette keeps the sheet a few hundred kB.
    sheet.convert("P", palette=Image.Palette.ADAPTIVE, colors=256).save(out, optimize=True)
    print(f"{len(tiles)} classes -> {out}")


# What lies on some furniture, a dresser's pulls, a pantry's glass panes (vlnverse-procgen
# `models.rs`), one tile per feature: `pieces.py SCENES docs/img/gallery/features.png features`.
FEATURES = ["folded blanket", "throw pillows", "quilt", "blanket over arm", "blanket on seat",
            "four cushions", "blanket over back", "seat cushion", "knobs", "handles", "flowers",
            "flowers in vase", "glass panes"]
# Small things are seen from nearer.
NEAR = {"flowers in vase": 1.2, "seat cushion": 1.6, "knobs": 1.6, "handles": 1.6}


def features_sheet(scenes, out):
    """Like `main`, but the first object with each feature in FEATURES, labelled with it."""
    found = {}
    for name in sorted(os.listdir(scenes)):
        scene = json.load(open(f"{scenes}/{name}/scene.json"))
        for o in scene["objects"]:
            for f in o.get("features", []):
                if f in FEATURES and f not in found and o["bbox"]["min"][1] < 1.0:
                    found[f] = (f"{scenes}/{name}", scene, o)
    tiles = []
    for f in FEATURES:
        if f not in found:
            continue
        scene_dir, scene, o = found[f]
        room = next(r for r in scene["rooms"] if r["id"] == o["room"])
        b = o["bbox"]; cx = (b["min"][0] + b["max"][0]) / 2; cz = (b["min"][2] + b["max"][2]) / 2
        want = NEAR.get(f, 2.0)
        best = None
        for x, z in free_cells(scene_dir):
            d = math.hypot(x - cx, z - cz)
            if want - 0.6 <= d <= want + 0.8 and inside(room["polygon"], x, z):
                if best is None or abs(d - want) < best[0]:
                    best = (abs(d - want), x, z)
        if best is None:
            continue
        _, x, z = best
        yaw = math.degrees(math.atan2(-(cx - x), -(cz - z)))
        subprocess.run([XTASK, "render", "--scene", scene_dir, "--position", f"{x:.2f},0,{z:.2f}",
                        "--yaw", f"{yaw:.1f}", "--out", "/tmp/pieces-view"], check=True,
                       capture_output=True)
        im = Image.open("/tmp/pieces-view/rgb.png").convert("RGB").resize((TILE * 3 // 2,) * 2)
        ImageDraw.Draw(im).text((4, 4), f"{o['class']}: {f}", fill=(255, 255, 255))
        tiles.append(im)
    cols, t = 4, TILE * 3 // 2
    sheet = Image.new("RGB", (cols * t, -(-len(tiles) // cols) * t))
    for k, im in enumerate(tiles):
        sheet.paste(im, ((k % cols) * t, (k // cols) * t))
    sheet.convert("P", palette=Image.Palette.ADAPTIVE, colors=256).save(out, optimize=True)
    print(f"{len(tiles)} features -> {out}")


if __name__ == "__main__":
    named = sys.argv[3:] or PIECES
    if named == ["features"]:
        features_sheet(sys.argv[1], sys.argv[2])
    else:
        lots = {"things2": THINGS2, "things3": THINGS3}
        main(sys.argv[1], sys.argv[2], lots[named[0]] if named[0] in lots else named)
