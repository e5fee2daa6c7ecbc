"""LeRobot 0.6.1's own replay command (its `replay` function, as `lerobot-replay` runs it) playing
an episode of a dataset recorded through armtwin on an arm driven through armtwin's robot plugin
(`--robot.type=armtwin`, found by register_third_party_plugins). Reads JSON on stdin:
  {"broker", "arm", "user", "repo_id", "root", "episode", "fps"}
and prints JSON: {"frames": n, "first": [...], "last": [...]} (the episode's actions, LeRobot's
units). The plugin logs refusals and e-stops on stderr."""
import json
import sys

from lerobot.datasets.lerobot_dataset import LeRobotDataset
from lerobot.robots import RobotConfig
from lerobot.scripts import lerobot_replay as rep
from lerobot.utils.import_utils import register_third_party_plugins

req = json.load(sys.stdin)
register_third_party_plugins()  # LeRobot's own discovery: imports lerobot_robot_armtwin
robot_cfg = RobotConfig.get_choice_class("armtwin")(broker=req["broker"], arm=req["arm"], user=req["user"])
rep.replay(
    rep.ReplayConfig(
        robot=robot_cfg,
        dataset=rep.DatasetReplayConfig(
            repo_id=req["repo_id"], root=req["root"], episode=req["episode"], fps=req["fps"]
        ),
        play_sounds=False,
    )
)
ds = LeRobotDataset(req["repo_id"], root=req["root"], episodes=[req["episode"]])
json.dump(
    {"frames": ds.num_frames, "first": ds[0]["action"].tolist(), "last": ds[ds.num_frames - 1]["action"].tolist()},
    sys.stdout,
)
