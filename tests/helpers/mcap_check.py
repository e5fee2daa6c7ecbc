"""Reads an MCAP file with Foxglove's own Python library (`mcap`, PyPI), which nobody here wrote,
and prints what it found as one JSON object. Used by tests/integration/export-mcap.test.ts.

    python mcap_check.py FILE.mcap [TIP_LINK]

Prints: the library version; the header's library; the summary's message count; per topic its
schema name, message encoding and count; every message of the armtwin.* schemas as
[topic, log_time_ns (a string: JSON numbers lose nanoseconds), payload]; the number of transforms in each foxglove.FrameTransforms message; and, when TIP_LINK
is given, that link's position in the root frame of the last transforms message (transforms composed
here, in plain Python).
"""
import json
import sys
from importlib.metadata import version

from mcap.reader import make_reader


def rotate(q, v):
    x, y, z, w = q
    vx, vy, vz = v
    # v + 2w(q×v) + 2q×(q×v)
    cx, cy, cz = y * vz - z * vy, z * vx - x * vz, x * vy - y * vx
    cx2, cy2, cz2 = y * cz - z * cy, z * cx - x * cz, x * cy - y * cx
    return (vx + 2 * (w * cx + cx2), vy + 2 * (w * cy + cy2), vz + 2 * (w * cz + cz2))


def tip_position(transforms, tip):
    by_child = {t["child_frame_id"]: t for t in transforms}
    p = (0.0, 0.0, 0.0)
    frame = tip
    while frame in by_child:
        t = by_child[frame]
        r = t["rotation"]
        tr = t["translation"]
        q = (r["x"], r["y"], r["z"], r["w"])
        rp = rotate(q, p)
        p = (rp[0] + tr["x"], rp[1] + tr["y"], rp[2] + tr["z"])
        frame = t["parent_frame_id"]
    return {"root": frame, "position": p}


out = {"library": "mcap " + version("mcap"), "topics": {}, "records": [], "tf_sizes": []}
last_tf = None
with open(sys.argv[1], "rb") as f:
    reader = make_reader(f)
    out["header_library"] = reader.get_header().library
    summary = reader.get_summary()
    out["message_count"] = summary.statistics.message_count
    for schema, channel, message in reader.iter_messages(log_time_order=True):
        t = out["topics"].setdefault(
            channel.topic,
            {"schema": schema.name, "encoding": channel.message_encoding, "count": 0},
        )
        t["count"] += 1
        data = json.loads(message.data)
        if schema.name.startswith("armtwin.") or schema.name == "foxglove.Log":
            out["records"].append([channel.topic, str(message.log_time), data])
        elif schema.name == "foxglove.FrameTransforms":
            out["tf_sizes"].append(len(data["transforms"]))
            last_tf = data["transforms"]
        elif schema.name == "foxglove.JointStates" and channel.topic.endswith("/joint_states"):
            out["last_joint_states"] = data
if len(sys.argv) > 2 and last_tf is not None:
    out["tip"] = tip_position(last_tf, sys.argv[2])
print(json.dumps(out))
