"""Writes a LeRobot v3.0 dataset with LeRobot's own writer (LeRobotDataset.create, add_frame,
save_episode, finalize): an SO-101 follower's six motors in LeRobot's units (degrees, the
gripper in 0-100 %), no camera. stdin: JSON {"root", "fps", "episodes": [{"task", "state":
[[6 floats], ...], "action": [[...], ...]}]}; stdout: JSON {"root", "info"} (meta/info.json as
written)."""
import json
import sys
from pathlib import Path

import numpy as np
from lerobot.datasets.lerobot_dataset import LeRobotDataset

MOTORS = ["shoulder_pan", "shoulder_lift", "elbow_flex", "wrist_flex", "wrist_roll", "gripper"]

req = json.load(sys.stdin)
names = [f"{m}.pos" for m in MOTORS]
vector = {"dtype": "float32", "shape": (len(names),), "names": names}
ds = LeRobotDataset.create(
    repo_id="local/armtwin-import-test",
    fps=req["fps"],
    features={"observation.state": vector, "action": vector},
    root=req["root"],
    robot_type="so101_follower",
    use_videos=False,
)
for ep in req["episodes"]:
    for state, action in zip(ep["state"], ep["action"]):
        ds.add_frame(
            {
                "observation.state": np.asarray(state, dtype=np.float32),
                "action": np.asarray(action, dtype=np.float32),
                "task": ep["task"],
            }
        )
    ds.save_episode()
ds.finalize()
info = json.loads((Path(req["root"]) / "meta" / "info.json").read_text())
json.dump({"root": req["root"], "info": info}, sys.stdout)
