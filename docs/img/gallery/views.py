#!/usr/bin/env python3
"""Pick gallery viewpoints: for each room of a scene folder, a navigable cell part-way from the
room centre towards its first corner, looking back across the room. Prints one line per view:
`room_name x,0,z yaw_deg`. Plain Python (no numpy), reads scene.json and navigable.pgm/yaml."""
import json, math, sys

def read_pgm(path):
    data = open(path, "rb").read()
    parts, i = [], 0
    while len(parts) < 4:
        while data[i:i+1].isspace():
            i += 1
        if data[i:i+1] == b"#":
            while data[i:i+1] != b"\n":
                i += 1
            continue
        j = i
        while not data[j:j+1].isspace():
            j += 1
        parts.append(data[i:j]); i = j
    w, h = int(parts[1]), int(parts[2])
    return w, h, data[i+1:i+1+w*h]

def inside(poly, x, z):
    c = False
    for k in range(len(poly)):
        (x1, z1), (x2, z2) = poly[k], poly[k-1]
        if (z1 > z) != (z2 > z) and x < (x2 - x1) * (z - z1) / (z2 - z1) + x1:
            c = not c
    return c

def free_cells(scene_dir):
    """The centres (x, z) of the free cells of the scene's navigable map, in metres."""
    yaml = dict(l.split(":", 1) for l in open(f"{scene_dir}/navigable.yaml") if ":" in l)
    res = float(yaml["resolution"]); ox, oy = json.loads(yaml["origin"])[:2]
    w, h, px = read_pgm(f"{scene_dir}/navigable.pgm")
    for j in range(h):
        for i in range(w):
            if px[j * w + i] == 254:
                yield ox + (i + 0.5) * res, -(oy + (h - j - 0.5) * res)

def main(scene_dir):
    scene = json.load(open(f"{scene_dir}/scene.json"))
    cells = list(free_cells(scene_dir))
    for room in scene["rooms"]:
        poly = room["polygon"]
        cx = sum(p[0] for p in poly) / len(poly); cz = sum(p[1] for p in poly) / len(poly)
        tx = cx + 0.6 * (poly[0][0] - cx); tz = cz + 0.6 * (poly[0][1] - cz)
        best = None
        for x, z in cells:
            if not inside(poly, x, z):
                continue
            d = (x - tx) ** 2 + (z - tz) ** 2
            if best is None or d < best[0]:
                best = (d, x, z)
        if best is None:
            continue
        _, x, z = best
        # yaw 0 looks along -Z, counter-clockwise from above
        yaw = math.degrees(math.atan2(-(cx - x), -(cz - z)))
        print(f"{room['name']} {x:.2f},0,{z:.2f} {yaw:.1f}")

if __name__ == "__main__":
    main(sys.argv[1])
