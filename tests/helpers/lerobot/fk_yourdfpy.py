"""The tool centre's pose by yourdfpy (PyPI), not by armtwin: reads
{"urdf": path, "base": link, "tip": link, "samples": [{joint: radians, ...}, ...]} on stdin and
prints [[16 numbers, column-major, metres], ...] (one 4x4 base->tip transform per sample)."""
import json
import sys

import numpy as np
import yourdfpy

req = json.load(sys.stdin)
robot = yourdfpy.URDF.load(req["urdf"], load_meshes=False, build_collision_scene_graph=False,
                           load_collision_meshes=False)
out = []
for cfg in req["samples"]:
    robot.update_cfg({name: np.float64(value) for name, value in cfg.items()})
    m = robot.get_transform(frame_to=req["tip"], frame_from=req["base"])
    out.append([float(m[r][c]) for c in range(4) for r in range(4)])
json.dump(out, sys.stdout)
