"""Loads a dataset folder with LeRobot's own LeRobotDataset (lerobot 0.6.1) and prints what a
test compares: counts, fps, features, robot type, tasks, the metadata's stats, and the frames
asked for (stdin JSON: {"root": DIR, "repo_id": ID, "frames": [global indices]})."""

import json
import sys

from lerobot.datasets.lerobot_dataset import LeRobotDataset

request = json.load(sys.stdin)
ds = LeRobotDataset(request["repo_id"], root=request["root"])
frames = []
for i in request["frames"]:
    item = ds[i]
    frames.append(
        {
            "index": int(item["index"]),
            "frame_index": int(item["frame_index"]),
            "episode_index": int(item["episode_index"]),
            "timestamp": float(item["timestamp"]),
            "task": item["task"],
            "state": [float(v) for v in item["observation.state"]],
            "action": [float(v) for v in item["action"]],
        }
    )
json.dump(
    {
        "num_episodes": ds.num_episodes,
        "num_frames": ds.num_frames,
        "fps": ds.fps,
        "features": {k: {"dtype": v["dtype"], "shape": list(v["shape"]), "names": v["names"]} for k, v in ds.features.items()},
        "robot_type": ds.meta.robot_type,
        "camera_keys": ds.meta.camera_keys,
        "episode_lengths": [int(ep["length"]) for ep in ds.meta.episodes],
        "stats_state_max": [float(v) for v in ds.meta.stats["observation.state"]["max"]],
        "frames": frames,
    },
    sys.stdout,
)
