"""Loads a dataset folder with LeRobot's own LeRobotDataset (lerobot 0.6.1) and prints what a
test compares: counts, fps, features, robot type, tasks, the metadata's stats, and the frames
asked for (stdin JSON: {"root": DIR, "repo_id": ID, "frames": [global indices], "band": ROWS});
for each camera, a frame's picture as LeRobot decodes it: its shape and the bottom ROWS rows
of its first channel (0-255, base64), where the test source's time stripe is."""

import base64
import json
import sys

import torch

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
            "images": {
                key: {
                    "shape": list(item[key].shape),
                    "band": base64.b64encode(
                        (item[key][0, -request.get("band", 0) :, :] * 255).round().to(torch.uint8).numpy().tobytes()
                    ).decode(),
                }
                for key in ds.meta.camera_keys
            },
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
        "video_info": {key: ds.meta.features[key].get("info") for key in ds.meta.camera_keys},
        "episode_lengths": [int(ep["length"]) for ep in ds.meta.episodes],
        "stats_state_max": [float(v) for v in ds.meta.stats["observation.state"]["max"]],
        "stats_camera_mean": {key: ds.meta.stats[key]["mean"].tolist() for key in ds.meta.camera_keys},
        "frames": frames,
    },
    sys.stdout,
)
