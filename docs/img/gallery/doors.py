#!/usr/bin/env python3
"""Render the kinds of doorway (vlnverse-procgen `doors.rs`): for each kind (hinged, sliding,
french, arched) the first few ground-floor doorways of that kind in a scenes folder, seen by the
RGB camera from a navigable cell about 2.3 m in front of the doorway, looking at it (a sliding
door from the room its open panel lies in, aimed between the opening and the panel); then a row
of carpeted rooms. One labelled contact sheet, a row per kind.

    python3 docs/img/gallery/doors.py SCENES_DIR OUT.png [PER_KIND]
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

KINDS = ["hinged", "sliding", "french", "arched"]
XTASK = os.environ.get("XTASK", "target/release/xtask")
TILE = 192


def view_towards(scene_dir, room, ax, az, nx, nz, dist=2.3):
    """A free cell of `room` nearest `dist` m from (ax, az) along (nx, nz), looking at it."""
    tx, tz = ax + nx * dist, az + nz * dist
    best = None
    for x, z in free_cells(scene_dir):
        if not inside(room["polygon"], x, z):
            continue
        d = (x - tx) ** 2 + (z - tz) ** 2
        if best is None or d < best[0]:
            best = (d, x, z)
    if best is None or best[0] > 1.0:
        return None
    _, x, z = best
    return x, z, math.degrees(math.atan2(-(ax - x), -(az - z)))


def doorway_views(scenes, kind, count):
    """Up to `count` views of ground-floor doorways of `kind`, one per home."""
    out = []
    for name in sorted(os.listdir(scenes)):
        scene_dir = f"{scenes}/{name}"
        scene = json.load(open(f"{scene_dir}/scene.json"))
        rooms = {r["id"]: r for r in scene["rooms"]}
        objects = {o["id"]: o for o in scene["objects"]}
        for d in scene["doors"]:
            if d["open_plan"] or d.get("kind", "hinged") != kind or d["position"][1] > 0.1:
                continue
            if kind != "arched" and d.get("leaf") is None:
                continue
            cx, _, cz = d["position"]
            nx, nz = d["normal"]
            ax, az = cx, cz
            sides = [(d["rooms"][1], 1.0), (d["rooms"][0], -1.0)]
            if kind == "sliding":
                leaf = objects[d["leaf"]]
                b = leaf["bbox"]
                lx, lz = (b["min"][0] + b["max"][0]) / 2, (b["min"][2] + b["max"][2]) / 2
                ax, az = (cx + lx) / 2, (cz + lz) / 2
                sides = [s for s in sides if s[0] == leaf["room"]]
            for room, s in sides:
                v = view_towards(scene_dir, rooms[room], ax, az, s * nx, s * nz)
                if v:
                    out.append((scene_dir, name, v))
                    break
            break
        if len(out) >= count:
            break
    return out


def carpet_views(scenes, count):
    """Views across carpeted ground-floor rooms (from views.py's viewpoint rule)."""
    out = []
    for name in sorted(os.listdir(scenes)):
        scene_dir = f"{scenes}/{name}"
        scene = json.load(open(f"{scene_dir}/scene.json"))
        carpeted = {o["room"] for o in scene["objects"]
                    if o["class"] == "floor" and o["material"] == "carpet"
                    and o["bbox"]["max"][1] < 0.05}
        for room in scene["rooms"]:
            if room["id"] not in carpeted:
                continue
            poly = room["polygon"]
            cx = sum(p[0] for p in poly) / len(poly)
            cz = sum(p[1] for p in poly) / len(poly)
            # From near a corner, looking at the room's centre.
            v = view_towards(scene_dir, room, cx, cz, poly[0][0] - cx, poly[0][1] - cz, 0.6)
            if v:
                out.append((scene_dir, name, v))
                break
        if len(out) >= count:
            break
    return out


def render(scene_dir, view, label):
    x, z, yaw = view
    subprocess.run([XTASK, "render", "--scene", scene_dir, "--position", f"{x:.2f},0,{z:.2f}",
                    "--yaw", f"{yaw:.1f}", "--out", "/tmp/doors-view"], check=True,
                   capture_output=True)
    im = Image.open("/tmp/doors-view/rgb.png").convert("RGB").resize((TILE, TILE))
    ImageDraw.Draw(im).text((4, 4), label, fill=(255, 255, 255))
    return im


def main(scenes, out, per_kind):
    rows = []
    for kind in KINDS:
        rows.append([render(s, v, f"{kind} ({n})") for s, n, v in
                     doorway_views(scenes, kind, per_kind)])
    rows.append([render(s, v, f"carpet ({n})") for s, n, v in carpet_views(scenes, per_kind)])
    sheet = Image.new("RGB", (per_kind * TILE, len(rows) * TILE))
    for r, row in enumerate(rows):
        for k, im in enumerate(row):
            sheet.paste(im, (k * TILE, r * TILE))
    # An adaptive palette keeps the sheet a few hundred kB.
    sheet.convert("P", palette=Image.Palette.ADAPTIVE, colors=256).save(out, optimize=True)
    print(f"{sum(len(r) for r in rows)} views -> {out}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else 4)
