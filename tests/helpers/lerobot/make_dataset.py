"""Writes a LeRobot v3.0 dataset with LeRobot's own writer (LeRobotDataset.create, add_frame,
save_episode, finalize): an SO-101 follower's six motors in LeRobot's units (degrees, the
gripper in 0-100 %), and optionally one camera, `observation.images.<camera>`, encoded by
LeRobot's own video writer: frame k of episode e shows the number 64 e + k as eight black or
white bars, most significant bit left (a picture a test reads back from the decoded video).
stdin: JSON {"root", "fps", "camera"?: {"key", "width", "height"}, "episodes": [{"task",
"state": [[6 floats], ...], "action": [[...], ...]}]}; stdout: JSON {"root", "info"}
(meta/info.json as written)."""
import json
import sys
from pathlib import Path

import numpy as np
from lerobot.datasets.lerobot_dataset import LeRobotDataset

MOTORS = ["shoulder_pan", "shoulder_lift", "elbow_flex", "wrist_flex", "wrist_roll", "gripper"]

req = json.load(sys.stdin)
names = [f"{m}.pos" for m in MOTORS]
vector = {"dtype": "float32", "shape": (len(names),), "names": names}
features = {"observation.state": vector, "action": vector}
camera = req.get("camera")
if camera:
    image = f"observation.images.{camera['key']}"
    shape = (camera["height"], camera["width"], 3)
    features[image] = {"dtype": "video", "shape": shape, "names": ["height", "width", "channels"]}


def bars(number: int) -> np.ndarray:
    """The picture of `number`: eight full-height bars, white for a 1 bit, MSB left."""
    h, w, _ = shape
    img = np.zeros(shape, dtype=np.uint8)
    for bit in range(8):
        if number >> (7 - bit) & 1:
            img[:, bit * w // 8 : (bit + 1) * w // 8] = 255
    return img


ds = LeRobotDataset.create(
    repo_id="local/armtwin-import-test",
    fps=req["fps"],
    features=features,
    root=req["root"],
    robot_type="so101_follower",
    use_videos=bool(camera),
)
for e, ep in enumerate(req["episodes"]):
    for k, (state, action) in enumerate(zip(ep["state"], ep["action"])):
        row = {
            "observation.state": np.asarray(state, dtype=np.float32),
            "action": np.asarray(action, dtype=np.float32),
            "task": ep["task"],
        }
        if camera:
            row[image] = bars(64 * e + k)
        ds.add_frame(row)
    ds.save_episode()
ds.finalize()
info = json.loads((Path(req["root"]) / "meta" / "info.json").read_text())
json.dump({"root": req["root"], "info": info}, sys.stdout)
